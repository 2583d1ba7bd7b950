"""A second rocket for the RocketPy cross-check: canted fins, a boattail, a J motor.

Calisto (``calisto.py``, ``calisto_wind.py``) is a 127 mm rocket with four plain fins on an
M motor. This one is what it does not exercise: a 54 mm rocket
(``validation/designs/crosscheck-54mm-canted-boattail.json``) with a von Karman nose, three
trapezoidal fins canted 1 degree, so that it spins up, a conical boattail, and the AeroTech
J350W, a short hard burn (peak 707 N on 1.26 kg), flown in a wind across a rail that leans
toward the north-east (constant, and a profile that turns and grows with height), and in
still air, with a drogue at apogee and a main at 250 m.

The rocket is the one hpr-mc builds from the design file, handed to RocketPy as numbers:

* The structure and the motor's casing, from ``hpr-mc inspect --json`` after burnout (the
  casing is a thin shell at the motor's mid-length in hpr-mc): ``ROCKET``. The casing goes in
  the rocket's mass, so RocketPy's motor carries only propellant.
* The motor: RocketPy's ``GenericMotor``, which is hpr-mc's motor model: the .eng curve with
  (0, 0) prepended, propellant burned in proportion to the impulse delivered, a solid
  cylinder of the motor's length and diameter at its mid-length, nozzle radius 0.88 of the
  motor's radius (hpr-mc's ``NOZZLE_RADIUS_FRACTION``).
* The aerodynamic surfaces from the design's geometry, the drag curve the design gives
  (power on = power off, as the design does not give one), interpolated linearly in Mach as
  hpr-mc does.

What is mapped, not tuned (see the Rust test ``crosscheck.rs`` in
engine/sim/tests/flight_proof):

* hpr-mc's rocket starts with its aft end (the boattail's, 1.28 m) at the rail's foot and
  leaves the rail when its upper guide passes the rail's top; RocketPy measures from the
  nozzle (1.24 m). RocketPy's rail is therefore 0.04 m shorter, so that both travel the same
  distance on it.
* RocketPy's canopies replace one another; hpr-mc's add up: hpr-mc's main is RocketPy's CdS
  less the drogue's.

Each case is flown as RocketPy 1.13 flies it (``outputs``), with its lever-arm sign
corrected (``lever_arm_corrected``; RocketPy issue #1186), and with its speed of sound made
the true one as well (``as_hpr_models``, what hpr-mc models; see corrections.py).

Run:  .venv/bin/python validation/rocketpy/canted_boattail.py
Writes validation/rocketpy/canted_boattail_reference.json next to this file.
"""

import importlib.metadata
import json
import math
import os
import sys

import numpy as np
from rocketpy import Environment, Flight, Function, GenericMotor, Rocket

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import corrections  # noqa: E402  (the lever arm and the speed of sound corrected)
import figures  # noqa: E402  (what each flight records)
from figures import f  # noqa: E402

REPO = os.path.dirname(os.path.dirname(HERE))
OUT = os.path.join(HERE, "canted_boattail_reference.json")
DESIGN = os.path.join(REPO, "validation", "designs",
                      "crosscheck-54mm-canted-boattail.json")
ENG = os.path.join(REPO, "engine", "design", "motors", "AeroTech_J350W.eng")

SITE = {"latitude_deg": 32.990254, "longitude_deg": -106.974998,
        "elevation_m": 1400.0}
# Wind constant with height, from 250 deg (meteorological), 6 m/s.
WIND = {"from_deg": 250.0, "speed_m_s": 6.0}
# A wind profile: (height above the site m, speed m/s, from deg), as hpr-mc's
# `environment.wind_profile` rows; RocketPy gets its components at the heights above sea
# level, interpolated linearly as hpr-mc does (custom_atmosphere's default for lists).
PROFILE = [(0.0, 2.0, 270.0), (500.0, 6.0, 250.0), (1500.0, 12.0, 290.0),
           (3000.0, 15.0, 310.0)]
# hpr-mc's rail: 3 m long, 85 deg up, heading 40 deg (toward the north-east).
RAIL = {"length_m": 3.0, "inclination_deg": 85.0, "heading_deg": 40.0}

# `hpr-mc inspect --json validation/designs/crosscheck-54mm-canted-boattail.json`,
# after burnout: the structure and the motor's casing.
ROCKET = {
    "mass_kg": 0.8844536477269653,
    "cg_m": 0.7359032336724057,
    "inertia_transverse_kg_m2": 0.12003007662486465,
    "inertia_axial_kg_m2": 0.00044897390747555355,
    "radius_m": 0.0563 / 2,
    "aft_end_m": 1.28,
}
MOTOR = {
    "propellant_mass_kg": 0.375872,
    "diameter_m": 0.038,
    "length_m": 0.337,
    "aft_m": 1.24,
    "nozzle_radius_fraction": 0.88,
}
NOSE = {"length_m": 0.28, "kind": "vonKarman", "position_m": 0.0}
FINS = {"n": 3, "root_chord_m": 0.12, "tip_chord_m": 0.05, "span_m": 0.07,
        "sweep_length_m": 0.06, "position_m": 1.10, "cant_angle_deg": 1.0}
TAIL = {"top_radius_m": 0.0563 / 2, "bottom_radius_m": 0.046 / 2,
        "length_m": 0.05, "position_m": 1.23}
BUTTONS = {"upper_m": 0.735, "lower_m": 1.195}
CHUTES = {
    "drogue": {"cd_s_m2": 1.5 * math.pi * 0.15 ** 2, "lag_s": 1.0},
    "main": {"cd_s_m2": 1.5 * math.pi * 0.45 ** 2, "lag_s": 1.0,
             "height_m": 250.0},
}
SAMPLING_HZ = 105.0


def drag_curve():
    """The design's Cd(Mach), interpolated linearly as hpr-mc does. (RocketPy reads a list of
    points with ``Function``'s default, a cubic spline; its CSV reader, which Calisto uses,
    is linear.)"""
    with open(DESIGN) as fh:
        points = [tuple(p) for p in json.load(fh)["drag"]["power_off"]]
    return Function(points, "Mach Number", "Drag Coefficient",
                    interpolation="linear", extrapolation="constant")


def wind_components(speed, from_deg):
    a = math.radians(from_deg)
    return -speed * math.sin(a), -speed * math.cos(a)


def build(lever_arm_corrected=False, wind="wind", sound_corrected=False):
    """The rocket in `wind`: "wind" (constant), "profile" (PROFILE) or "calm";
    RocketPy's lever arm and speed of sound corrected or not (corrections.py)."""
    env = Environment(latitude=SITE["latitude_deg"],
                      longitude=SITE["longitude_deg"],
                      elevation=SITE["elevation_m"])
    if wind == "wind":
        u, v = wind_components(WIND["speed_m_s"], WIND["from_deg"])
    elif wind == "profile":
        rows = [(SITE["elevation_m"] + h, wind_components(speed, frm))
                for h, speed, frm in PROFILE]
        u = [[z, c[0]] for z, c in rows]
        v = [[z, c[1]] for z, c in rows]
    else:
        u, v = 0.0, 0.0
    env.set_atmospheric_model(type="custom_atmosphere", wind_u=u, wind_v=v)
    if sound_corrected:
        corrections.true_speed_of_sound(env)
    m = MOTOR
    half = 0.5 * m["length_m"]
    motor = GenericMotor(
        thrust_source=ENG, burn_time=None,
        chamber_radius=0.5 * m["diameter_m"], chamber_height=m["length_m"],
        chamber_position=half,
        propellant_initial_mass=m["propellant_mass_kg"],
        nozzle_radius=0.5 * m["diameter_m"] * m["nozzle_radius_fraction"],
        dry_mass=0.0, center_of_dry_mass_position=half, dry_inertia=(0, 0, 0),
        nozzle_position=0.0,
        coordinate_system_orientation="nozzle_to_combustion_chamber")
    r = ROCKET
    curve = drag_curve()
    rocket = Rocket(
        radius=r["radius_m"], mass=r["mass_kg"],
        inertia=(r["inertia_transverse_kg_m2"], r["inertia_transverse_kg_m2"],
                 r["inertia_axial_kg_m2"]),
        power_off_drag=curve, power_on_drag=curve,
        center_of_mass_without_motor=r["cg_m"],
        coordinate_system_orientation="nose_to_tail")
    rocket.add_motor(motor, position=m["aft_m"])
    rocket.add_nose(length=NOSE["length_m"], kind=NOSE["kind"],
                    position=NOSE["position_m"])
    rocket.add_trapezoidal_fins(
        n=FINS["n"], root_chord=FINS["root_chord_m"],
        tip_chord=FINS["tip_chord_m"], span=FINS["span_m"],
        position=FINS["position_m"], cant_angle=FINS["cant_angle_deg"],
        sweep_length=FINS["sweep_length_m"])
    rocket.add_tail(top_radius=TAIL["top_radius_m"],
                    bottom_radius=TAIL["bottom_radius_m"],
                    length=TAIL["length_m"], position=TAIL["position_m"])
    rocket.set_rail_buttons(upper_button_position=BUTTONS["upper_m"],
                            lower_button_position=BUTTONS["lower_m"],
                            angular_position=0.0)
    d, mn = CHUTES["drogue"], CHUTES["main"]
    rocket.add_parachute("main", cd_s=mn["cd_s_m2"], trigger=mn["height_m"],
                         sampling_rate=SAMPLING_HZ, lag=mn["lag_s"])
    rocket.add_parachute("drogue", cd_s=d["cd_s_m2"], trigger="apogee",
                         sampling_rate=SAMPLING_HZ, lag=d["lag_s"])
    if lever_arm_corrected:
        corrections.correct(rocket)
    rail = RAIL["length_m"] - (r["aft_end_m"] - m["aft_m"])
    flight = Flight(rocket=rocket, environment=env, rail_length=rail,
                    inclination=RAIL["inclination_deg"],
                    heading=RAIL["heading_deg"])
    return env, motor, rocket, flight


def outputs(env, rocket, flight):
    """The common figures, and the roll rate about the body's axis at burnout and at
    apogee (rad/s)."""
    burn = f(rocket.motor.burn_out_time)
    return {
        **figures.flight_figures(env, flight),
        "burnout_time_s": burn,
        "roll_rate_at_burnout_rad_s": f(flight.w3(burn)),
        "roll_rate_at_apogee_rad_s": f(flight.w3(flight.apogee_time)),
    }


def case(**kw):
    env, _, rocket, flight = build(**kw)
    return outputs(env, rocket, flight)


def main():
    np.random.seed(20261202)  # parachute noise is off; nothing is drawn
    env, motor, rocket, _ = build()
    cases = {}
    for name in ("wind", "profile", "calm"):
        wind = name
        cases[name] = {
            "outputs": case(wind=wind),
            "lever_arm_corrected": case(lever_arm_corrected=True, wind=wind),
            "as_hpr_models": case(lever_arm_corrected=True, wind=wind,
                                  sound_corrected=True),
        }
    u, v = wind_components(WIND["speed_m_s"], WIND["from_deg"])
    ref = {
        "generator": "validation/rocketpy/canted_boattail.py",
        "rocketpy_version": importlib.metadata.version("rocketpy"),
        "inputs": {
            "design": "validation/designs/crosscheck-54mm-canted-boattail.json",
            "site": SITE, "wind": {**WIND, "wind_u_toward_east_m_s": u,
                                   "wind_v_toward_north_m_s": v},
            "wind_profile": [{"height_agl_m": h, "speed_m_s": sp, "from_deg": fr}
                             for h, sp, fr in PROFILE],
            "rail": {**RAIL, "rocketpy_rail_length_m":
                     RAIL["length_m"] - (ROCKET["aft_end_m"] - MOTOR["aft_m"])},
            "rocket_after_burnout": ROCKET, "motor": MOTOR,
            "nose": NOSE, "fins": FINS, "tail": TAIL, "buttons": BUTTONS,
            "parachutes": CHUTES, "sampling_rate_hz": SAMPLING_HZ,
        },
        "checks": {
            "liftoff_mass_kg": f(rocket.total_mass(0)),
            "liftoff_center_of_mass_m": f(rocket.center_of_mass(0)),
            "propellant_mass_kg": f(motor.propellant_initial_mass),
            "total_impulse_ns": f(motor.total_impulse),
            "burn_out_time_s": f(motor.burn_out_time),
            "center_of_pressure_mach0_m": f(rocket.cp_position(0)),
            "static_margin_liftoff_cal": f(rocket.static_margin(0)),
        },
        "cases": cases,
    }
    with open(OUT, "w") as fh:
        json.dump(ref, fh, indent=1, sort_keys=True)
        fh.write("\n")
    for name, c in cases.items():
        o, h = c["outputs"], c["as_hpr_models"]
        print(f"{name}: apogee {o['apogee_agl_m']:.2f} (corrected "
              f"{h['apogee_agl_m']:.2f}) m at {h['apogee_time_s']:.3f} s; "
              f"roll at burnout {h['roll_rate_at_burnout_rad_s']:.3f} rad/s; "
              f"impact ({h['impact_x_m']:.1f}, {h['impact_y_m']:.1f}) at "
              f"{h['impact_time_s']:.2f} s")
    print(json.dumps(ref["checks"], indent=1))


if __name__ == "__main__":
    main()
