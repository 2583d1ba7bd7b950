"""Fly RocketPy's Calisto in a constant wind and save reference numbers.

The rocket, motor, parachutes (noise off), site and rail are exactly those of
``calisto.py`` (its ``build``), and the air is RocketPy's
``custom_atmosphere`` with no pressure or temperature given, which RocketPy
fills with the same ISA functions as ``standard_atmosphere``
(``Environment.process_custom_atmosphere``: ``self.pressure =
self.pressure_ISA``, ``self.temperature = self.temperature_ISA``), plus a
wind constant with height:

* ``west``: 5 m/s from the west (meteorological direction 270 deg), i.e.
  wind_u = +5 (toward east), wind_v = 0. A crosswind to the rail, which
  leans north (heading 0).
* ``northeast``: 5 m/s from the north-east (direction 45 deg), i.e.
  wind_u = wind_v = -5/sqrt(2) (toward the south-west): a head wind and a
  crosswind at once, so that a swapped axis or a flipped sign shows.

RocketPy's convention (``environment/environment.py``
``process_custom_atmosphere`` docstring: "wind-u ... the wind speed heading
East", "wind-v ... heading North"; ``simulation/flight.py`` ``u_dot_generalized``
and ``u_dot_parachute``: free stream = (wind_u, wind_v, 0) - v in the launch
frame, x east, y north) is checked numerically here too: the script records
RocketPy's own ``wind_heading`` and ``wind_direction`` (from) for each case.

A calm case (the same custom atmosphere, no wind) is flown alongside, and a
calm run checks that the switch of atmosphere type alone changes nothing
against ``calisto_reference.json``.

Each case is flown as RocketPy 1.13 flies it (``outputs``, the reference) and
with three things switched off, one at a time, so that each difference's worth
is RocketPy's own number: Coriolis (``earth_rotation_vector = 0``), the
canopies' added mass (each Parachute's ``added_mass_coefficient`` set to 0
before the Flight reads it), and RocketPy 1.13's sign of the center of mass's
and the nozzle's positions in its equations of motion (``LEVER_ARM`` below:
RocketPy issue #1186). Then as hpr-mc models the flight, the lever arm corrected:
on the turning Earth (``as_hpr_models``, what hpr-mc flies with the site's
latitude given) and with Coriolis off (``as_hpr_models_inertial``, what it
flies without a latitude). hpr-mc's canopies carry RocketPy's added mass: its
main is RocketPy's less the drogue, in CdS and in air (see NOTES.md, Canopies).

Run from anywhere:  .venv/bin/python validation/rocketpy/calisto_wind.py
Writes validation/rocketpy/calisto_wind_reference.json next to this file.
"""

import importlib.metadata
import json
import math
import os
import platform
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import calisto  # noqa: E402  (the shared set-up: rocket, motor, chutes, site, rail)
import corrections  # noqa: E402  (the lever arm and the standard air corrected)
import figures  # noqa: E402  (what each flight records)

OUT = os.path.join(HERE, "calisto_wind_reference.json")

SPEED_M_S = 5.0
CASES = {
    "calm": {"from_deg": 0.0, "speed_m_s": 0.0},
    "west": {"from_deg": 270.0},
    "northeast": {"from_deg": 45.0},
}


def components(speed, from_deg):
    """(u toward east, v toward north) of a wind blowing FROM from_deg."""
    a = math.radians(from_deg)
    u, v = -speed * math.sin(a), -speed * math.cos(a)
    # Exact zeros where the trigonometry leaves 1e-16.
    return (0.0 if abs(u) < 1e-12 else u), (0.0 if abs(v) < 1e-12 else v)


def fly(u, v, coriolis=True, added_mass=True, lever_arm_corrected=False,
        air_corrected=False):
    """One flight in wind (u, v). The options switch off, one by one, what
    hpr-mc does not model: Coriolis, the canopies' added mass, RocketPy
    1.13's sign of r_CM and r_NOZ in Flight.u_dot_generalized (see
    LEVER_ARM below) and its standard atmosphere, whose temperature, pressure
    and speed of sound are chords or splines of the true ones (corrections.py)."""
    env, _, rocket, flight = calisto.build(wind_u=u, wind_v=v,
                                           coriolis=coriolis)
    if added_mass and not lever_arm_corrected and not air_corrected:
        return env, rocket, flight
    if air_corrected:
        corrections.true_standard_air(env)
    if not added_mass:
        for chute in rocket.parachutes:
            chute.added_mass_coefficient = 0.0
    if lever_arm_corrected:
        corrections.correct(rocket)
    flight = calisto.Flight(
        rocket=rocket, environment=env,
        rail_length=calisto.RAIL["rail_length_m"],
        inclination=calisto.RAIL["inclination_deg"],
        heading=calisto.RAIL["heading_deg"])
    return env, rocket, flight


LEVER_ARM = (
    "RocketPy 1.13's Flight.u_dot_generalized takes r_CM = "
    "Rocket.com_to_cdm_function and r_NOZ = Rocket.nozzle_to_cdm as the "
    "center of mass's and the nozzle's positions from the center of dry mass, "
    "but both are defined the other way round (CM to CDM, nozzle to CDM; "
    "RocketPy-Team/RocketPy issue #1186, open, fix proposed in pull request "
    "#1196). With Calisto's propellant aft of the CDM the equations put the "
    "center of mass 0.122 m forward of the CDM at rail exit instead of aft, "
    "so the lever arm of the normal forces about the center of mass is "
    "2 x 0.122 m = 1.9 calibres too long while the motor burns (it vanishes at "
    "burnout): at rail exit in the west wind its angular acceleration is "
    "0.2798 rad/s^2 against 0.148 with the arm as the mass model gives. In "
    "still air the angle of attack is tiny and the apogee moves by under 1 m; "
    "in a crosswind the rocket turns into the wind far more. The "
    "'lever_arm_corrected' flights negate both attributes before the Flight "
    "is built, and add 2 K (r_CM x w_dot) back to the acceleration: the one "
    "term written for the attribute as it is, v_dot = K (T20/m - r_CM x w_dot), "
    "needs + r_CM x w_dot with r_CM from the CDM (corrections.py). The nozzle's "
    "sign cancels in the jet-damping terms, whose products of r_CM and r_NOZ "
    "keep their sign")


def outputs(env, flight):
    return figures.flight_figures(env, flight)


def ascent_only(u, v, coriolis=True):
    """Apogee figures with the same wind and no parachutes."""
    env, _, _, flight = calisto.build(wind_u=u, wind_v=v, coriolis=coriolis,
                                      chutes=False, terminate_on_apogee=True)
    f = calisto.f
    return {"apogee_agl_m": f(flight.apogee - env.elevation),
            "apogee_time_s": f(flight.apogee_time),
            "apogee_x_m": f(flight.apogee_x),
            "apogee_y_m": f(flight.apogee_y)}


def main():
    np.random.seed(20240101)  # only parachute noise draws, and it is off
    version = importlib.metadata.version("rocketpy")
    cases = {}
    for name, c in CASES.items():
        speed = c.get("speed_m_s", SPEED_M_S)
        u, v = components(speed, c["from_deg"])
        env, rocket, flight = fly(u, v)
        h = env.elevation + 1000.0
        cases[name] = {
            "inputs": {
                "speed_m_s": speed,
                "from_deg": c["from_deg"],
                "wind_u_toward_east_m_s": u,
                "wind_v_toward_north_m_s": v,
                "rocketpy_wind_heading_deg": calisto.f(env.wind_heading(h)),
                "rocketpy_wind_direction_deg": calisto.f(
                    env.wind_direction(h)),
                "rocketpy_wind_speed_m_s": calisto.f(env.wind_speed(h)),
                "hpr_mc": f"Wind::constant({speed}, {c['from_deg']})",
            },
            "outputs": outputs(env, flight),
            "coriolis_off": outputs(*fly(u, v, coriolis=False)[::2]),
            "parachute_added_mass_off": outputs(
                *fly(u, v, added_mass=False)[::2]),
            "lever_arm_corrected": outputs(
                *fly(u, v, lever_arm_corrected=True)[::2]),
            "as_hpr_models": outputs(
                *fly(u, v, lever_arm_corrected=True,
                     air_corrected=True)[::2]),
            "as_hpr_models_inertial": outputs(
                *fly(u, v, coriolis=False, lever_arm_corrected=True,
                     air_corrected=True)[::2]),
        }
        print(f"{name}: u {u:+.4f} v {v:+.4f}; "
              f"apogee {cases[name]['outputs']['apogee_agl_m']:.3f} m at "
              f"({cases[name]['outputs']['apogee_x_m']:.2f}, "
              f"{cases[name]['outputs']['apogee_y_m']:.2f}); impact "
              f"{cases[name]['outputs']['impact_time_s']:.3f} s at "
              f"({cases[name]['outputs']['impact_x_m']:.2f}, "
              f"{cases[name]['outputs']['impact_y_m']:.2f})")

    env_c, _, flight_c = fly(0.0, 0.0)
    calm = outputs(env_c, flight_c)
    with open(os.path.join(HERE, "calisto_reference.json"),
              encoding="utf-8") as fh:
        still = json.load(fh)["outputs"]
    calm_check = {
        "what": "custom_atmosphere with wind_u = wind_v = 0 against "
                "calisto_reference.json (standard_atmosphere): the change of "
                "atmosphere type alone",
        "apogee_agl_m": calm["apogee_agl_m"],
        "reference_apogee_agl_m": still["apogee_agl_m"],
        "impact_time_s": calm["impact_time_s"],
        "reference_impact_time_s": still["impact_time_s"],
        "impact_x_m": calm["impact_x_m"],
        "reference_impact_x_m": still["impact_x_m"],
        "impact_y_m": calm["impact_y_m"],
        "reference_impact_y_m": still["impact_y_m"],
    }
    out = {
        "generator": "validation/rocketpy/calisto_wind.py",
        "rocketpy_version": version,
        "python_version": platform.python_version(),
        "numpy_version": np.__version__,
        "set_up": "calisto.py build(): the rocket, motor, parachutes (noise "
                  "off), site, rail and flight settings of "
                  "calisto_reference.json's inputs, with "
                  "custom_atmosphere(wind_u, wind_v) instead of "
                  "standard_atmosphere",
        "wind_convention": {
            "rocketpy": "wind_u = air velocity toward east (+x), wind_v = "
                        "toward north (+y), m/s (Environment."
                        "process_custom_atmosphere; Flight.u_dot_generalized "
                        "and u_dot_parachute take the free stream as (wind_u, "
                        "wind_v, 0) - v). wind_heading = where it blows to, "
                        "wind_direction = where it blows from, degrees "
                        "clockwise from north",
            "hpr_mc": "Wind::constant(speed, from_deg): from_deg = where it "
                      "blows FROM, clockwise from north; velocity (east, "
                      "north) = (-speed sin from, -speed cos from)",
        },
        "parachute_drag_in_rocketpy": "each opening replaces the canopy "
            "drag: after the main opens, CdS = 10 m^2 (the main's), the "
            "drogue's 1 m^2 no longer counts (Flight: parachute_cd_s set per "
            "event); under canopy the added mass C_a rho 2/3 pi R^2 H of the "
            "last canopy opened is added to the dry mass",
        "variants": {
            "outputs": "RocketPy 1.13 as it is (the reference)",
            "coriolis_off": "earth_rotation_vector = 0 (hpr-mc without a "
                            "latitude has no Coriolis)",
            "parachute_added_mass_off": "each Parachute's "
                "added_mass_coefficient = 0 (its worth)",
            "lever_arm_corrected": "r_CM and r_NOZ with the sign the "
                "equations of motion v1 define (see lever_arm_note)",
            "as_hpr_models": "lever arm and standard air corrected: the "
                             "physics hpr-mc models, with the site's "
                             "latitude",
            "as_hpr_models_inertial": "lever arm and standard air "
                                      "corrected, Coriolis off: hpr-mc "
                                      "without a latitude",
        },
        "lever_arm_note": LEVER_ARM,
        "cases": cases,
        "ascent_only_no_coriolis": {
            name: ascent_only(*components(c.get("speed_m_s", SPEED_M_S),
                                          c["from_deg"]), coriolis=False)
            for name, c in CASES.items()},
        "calm_custom_atmosphere_check": calm_check,
    }
    with open(OUT, "w", encoding="utf-8") as fh:
        json.dump(out, fh, indent=2)
        fh.write("\n")
    print(f"calm check: apogee {calm['apogee_agl_m']:.4f} m "
          f"(standard_atmosphere {still['apogee_agl_m']:.4f}), impact "
          f"{calm['impact_time_s']:.3f} s ({still['impact_time_s']:.3f})")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
