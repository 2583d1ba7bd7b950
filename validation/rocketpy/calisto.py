"""Fly RocketPy's "Calisto" test-fixture rocket and save reference numbers.

The rocket, motor, surfaces, rail buttons and parachutes are those of the
RocketPy repository's test fixtures (``tests/fixtures/rockets/rocket_fixtures.py``
``calisto_robust``, ``tests/fixtures/motor/solid_motor_fixtures.py``
``cesaroni_m1670``, ``tests/fixtures/surfaces/surface_fixtures.py``,
``tests/fixtures/parachutes/parachute_fixtures.py``), flown from the Spaceport
America site of ``tests/fixtures/environment/environment_fixtures.py``
(latitude 32.990254, longitude -106.974998, elevation 1400 m, WGS84) in
RocketPy's ISA ``standard_atmosphere`` (no wind), 5.2 m rail at 85 deg,
heading 0.

Two settings differ from a plain copy of the fixtures, and both are recorded
in the JSON:

* rail buttons at ``angular_position=45`` deg (the ``calisto_rail_buttons``
  fixture and the "First Simulation" docs use 45; ``calisto_robust`` passes 0).
  The angle only sets the initial roll; it moves the apogee by 0.08 m
  through the integrator's path (LSODA, rtol 1e-6), and 45 deg reproduces
  3305.6 m (0 deg gives 3305.67 m).
* parachute pressure noise off (``noise=(0, 0, 0)``) so the main-chute
  deployment, the landing point and the drift are deterministic. The
  fixture's noise (0, 8.3 Pa, 0.5) only moves the main deployment height by
  about a metre; it cannot change the ascent.

Run from anywhere:  .venv/bin/python validation/rocketpy/calisto.py
Writes validation/rocketpy/calisto_reference.json next to this file.
Data files are local copies in validation/rocketpy/data/ (see data/README.md).
"""

import importlib.metadata
import json
import math
import os
import platform

import numpy as np
from rocketpy import Environment, Flight, Parachute, Rocket, SolidMotor

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "data")
OUT = os.path.join(HERE, "calisto_reference.json")

# ---------------------------------------------------------------- inputs (SI)
SITE = {
    "latitude_deg": 32.990254,
    "longitude_deg": -106.974998,
    "elevation_m": 1400.0,
    "datum": "WGS84",
    "atmospheric_model": "standard_atmosphere",
    "gravity": "None -> Somigliana normal gravity at the site latitude with "
    "RocketPy's free-air height correction (Environment.somigliana_gravity)",
    "date": "not set (irrelevant for standard_atmosphere)",
}
RAIL = {"rail_length_m": 5.2, "inclination_deg": 85.0, "heading_deg": 0.0}

MOTOR = {
    "thrust_source": "data/Cesaroni_M1670.eng",
    "burn_time_s": 3.9,
    "dry_mass_kg": 1.815,
    "dry_inertia_kg_m2": [0.125, 0.125, 0.002],
    "center_of_dry_mass_position_m": 0.317,
    "nozzle_position_m": 0.0,
    "grain_number": 5,
    "grain_density_kg_m3": 1815.0,
    "nozzle_radius_m": 0.033,
    "throat_radius_m": 0.011,
    "grain_separation_m": 0.005,
    "grain_outer_radius_m": 0.033,
    "grain_initial_height_m": 0.120,
    "grains_center_of_mass_position_m": 0.397,
    "grain_initial_inner_radius_m": 0.015,
    "interpolation_method": "linear",
    "coordinate_system_orientation": "nozzle_to_combustion_chamber",
}

ROCKET = {
    "radius_m": 0.0635,
    "mass_without_motor_kg": 14.426,
    "inertia_without_motor_kg_m2": [6.321, 6.321, 0.034],
    "center_of_mass_without_motor_m": 0.0,
    "power_off_drag": "data/powerOffDragCurve.csv",
    "power_on_drag": "data/powerOnDragCurve.csv",
    "coordinate_system_orientation": "tail_to_nose",
    "motor_position_m": -1.373,
}
NOSE = {"length_m": 0.55829, "kind": "vonkarman", "base_radius_m": 0.0635,
        "rocket_radius_m": 0.0635, "position_m": 1.160}
TAIL = {"top_radius_m": 0.0635, "bottom_radius_m": 0.0435, "length_m": 0.060,
        "rocket_radius_m": 0.0635, "position_m": -1.313}
FINS = {"n": 4, "span_m": 0.100, "root_chord_m": 0.120, "tip_chord_m": 0.040,
        "rocket_radius_m": 0.0635, "cant_angle_deg": 0.0,
        "sweep_length_m": None, "sweep_angle_deg": None, "airfoil": None,
        "position_m": -1.168}
RAIL_BUTTONS = {"upper_button_position_m": 0.082,
                "lower_button_position_m": -0.618, "angular_position_deg": 45.0}
CHUTES = {
    "main": {"cd_s_m2": 10.0, "trigger": "vz < 0 and height AGL < 800 m",
             "sampling_rate_hz": 105, "lag_s": 1.5, "noise": [0, 0, 0]},
    "drogue": {"cd_s_m2": 1.0, "trigger": "vz < 0",
               "sampling_rate_hz": 105, "lag_s": 1.5, "noise": [0, 0, 0]},
}
NOSE_TIP_Z = NOSE["position_m"]  # rocket frame z of the nose tip


def aft_of_nose(z_rocket):
    """RocketPy 'tail_to_nose' coordinate (m, +towards nose, origin at the
    rocket's center of mass without motor) -> metres aft of the nose tip."""
    return NOSE_TIP_Z - z_rocket


def aft_of_nose_from_motor(z_motor):
    """Motor 'nozzle_to_combustion_chamber' coordinate (m, +towards the
    nose, origin at the nozzle exit) -> metres aft of the nose tip."""
    return aft_of_nose(ROCKET["motor_position_m"] + z_motor)


def drogue_trigger(_p, _h, y):
    return y[5] < 0


def main_trigger(_p, h, y):
    return y[5] < 0 and h < 800


def build(latitude=SITE["latitude_deg"], elevation=SITE["elevation_m"],
          button_angle=RAIL_BUTTONS["angular_position_deg"], chutes=True,
          terminate_on_apogee=False, coriolis=True, wind_u=None, wind_v=None):
    """Build environment, motor, rocket and fly. The keyword arguments exist
    for the sensitivity table and the windy cases (calisto_wind.py); their
    defaults are the reference case. ``wind_u``/``wind_v`` (m/s, toward east
    and toward north, constant with height) switch to RocketPy's
    ``custom_atmosphere`` with the ISA pressure and temperature (what it uses
    when neither is given) and that wind."""
    env = Environment(latitude=latitude, longitude=SITE["longitude_deg"],
                      elevation=elevation, datum=SITE["datum"])
    if wind_u is None and wind_v is None:
        env.set_atmospheric_model(type="standard_atmosphere")
    else:
        env.set_atmospheric_model(type="custom_atmosphere",
                                  wind_u=wind_u or 0.0, wind_v=wind_v or 0.0)
    if not coriolis:
        env.earth_rotation_vector = [0.0, 0.0, 0.0]
    m = MOTOR
    motor = SolidMotor(
        thrust_source=os.path.join(DATA, "Cesaroni_M1670.eng"),
        burn_time=m["burn_time_s"], dry_mass=m["dry_mass_kg"],
        dry_inertia=tuple(m["dry_inertia_kg_m2"]),
        center_of_dry_mass_position=m["center_of_dry_mass_position_m"],
        nozzle_position=m["nozzle_position_m"], grain_number=m["grain_number"],
        grain_density=m["grain_density_kg_m3"],
        nozzle_radius=m["nozzle_radius_m"], throat_radius=m["throat_radius_m"],
        grain_separation=m["grain_separation_m"],
        grain_outer_radius=m["grain_outer_radius_m"],
        grain_initial_height=m["grain_initial_height_m"],
        grains_center_of_mass_position=m["grains_center_of_mass_position_m"],
        grain_initial_inner_radius=m["grain_initial_inner_radius_m"],
        interpolation_method=m["interpolation_method"],
        coordinate_system_orientation=m["coordinate_system_orientation"],
    )
    r = ROCKET
    rocket = Rocket(
        radius=r["radius_m"], mass=r["mass_without_motor_kg"],
        inertia=tuple(r["inertia_without_motor_kg_m2"]),
        power_off_drag=os.path.join(DATA, "powerOffDragCurve.csv"),
        power_on_drag=os.path.join(DATA, "powerOnDragCurve.csv"),
        center_of_mass_without_motor=r["center_of_mass_without_motor_m"],
        coordinate_system_orientation=r["coordinate_system_orientation"],
    )
    rocket.add_motor(motor, position=r["motor_position_m"])
    rocket.add_nose(length=NOSE["length_m"], kind=NOSE["kind"],
                    position=NOSE["position_m"])
    rocket.add_tail(top_radius=TAIL["top_radius_m"],
                    bottom_radius=TAIL["bottom_radius_m"],
                    length=TAIL["length_m"], position=TAIL["position_m"])
    rocket.add_trapezoidal_fins(
        n=FINS["n"], root_chord=FINS["root_chord_m"],
        tip_chord=FINS["tip_chord_m"], span=FINS["span_m"],
        position=FINS["position_m"], cant_angle=FINS["cant_angle_deg"])
    rocket.set_rail_buttons(
        upper_button_position=RAIL_BUTTONS["upper_button_position_m"],
        lower_button_position=RAIL_BUTTONS["lower_button_position_m"],
        angular_position=button_angle)
    for name, trig in (("main", main_trigger), ("drogue", drogue_trigger)):
        if not chutes:
            break
        c = CHUTES[name]
        rocket.parachutes.append(Parachute(
            name=name, cd_s=c["cd_s_m2"], trigger=trig,
            sampling_rate=c["sampling_rate_hz"], lag=c["lag_s"],
            noise=tuple(c["noise"])))
    flight = Flight(rocket=rocket, environment=env,
                    rail_length=RAIL["rail_length_m"],
                    inclination=RAIL["inclination_deg"],
                    heading=RAIL["heading_deg"],
                    terminate_on_apogee=terminate_on_apogee)
    return env, motor, rocket, flight


def sensitivity():
    """Ascent-only flights with one setting changed, showing which settings
    the four published numbers pin down."""
    cases = {
        "reference (lat 32.990254, elevation 1400, buttons 45 deg)": {},
        "rail buttons at 0 deg (as calisto_robust passes)": {
            "button_angle": 0.0},
        "no rail buttons (roll 0, rail exit when the nozzle travels 5.2 m)": {
            "button_angle": None},
        "Coriolis off (earth_rotation_vector = 0)": {"coriolis": False},
        "Coriolis off, rail buttons at 0 deg": {"coriolis": False,
                                                "button_angle": 0.0},
        "latitude 0 (Environment() default)": {"latitude": 0.0},
        "elevation 0 (Environment() default)": {"elevation": 0.0},
        "latitude 0 and elevation 0 (plain Environment())": {
            "latitude": 0.0, "elevation": 0.0},
    }
    rows = {}
    for label, kw in cases.items():
        if kw.get("button_angle", 0.0) is None:
            env, _, rocket, flight = build_without_buttons(**{
                k: v for k, v in kw.items() if k != "button_angle"})
        else:
            env, _, rocket, flight = build(chutes=False,
                                           terminate_on_apogee=True, **kw)
        rows[label] = {
            "apogee_agl_m": f(flight.apogee - env.elevation),
            "apogee_time_s": f(flight.apogee_time),
            "rail_exit_time_s": f(flight.out_of_rail_time),
            "max_speed_m_s": f(flight.max_speed),
            "max_mach": f(flight.max_mach_number),
        }
    return rows


def build_without_buttons(**kw):
    """Reference case with the rail buttons removed."""
    env, motor, rocket, _ = build(chutes=False, terminate_on_apogee=True, **kw)
    rocket.rail_buttons = type(rocket.rail_buttons)()
    flight = Flight(rocket=rocket, environment=env,
                    rail_length=RAIL["rail_length_m"],
                    inclination=RAIL["inclination_deg"],
                    heading=RAIL["heading_deg"], terminate_on_apogee=True)
    return env, motor, rocket, flight


def f(x):
    return float(x)


def mass_state(rocket, t):
    """Mass, center of mass and inertia of the whole rocket at time t."""
    m = f(rocket.total_mass(t))
    com = f(rocket.center_of_mass(t))
    cdm = f(rocket.center_of_dry_mass_position)
    i11_cdm = f(rocket.I_11(t))
    i33 = f(rocket.I_33(t))
    d = com - cdm
    return {
        "time_s": t,
        "total_mass_kg": m,
        "propellant_mass_kg": f(rocket.motor.propellant_mass(t)),
        "center_of_mass_rocketpy_z_m": com,
        "center_of_mass_aft_of_nose_m": aft_of_nose(com),
        "I_11_about_center_of_dry_mass_kg_m2": i11_cdm,
        "I_11_about_center_of_mass_kg_m2": i11_cdm - m * d * d,
        "I_33_kg_m2": i33,
    }


def motor_state(motor, t):
    return {
        "time_s": t,
        "thrust_N": f(motor.thrust(t)),
        "mass_flow_rate_kg_s": f(motor.total_mass_flow_rate(t)),
        "propellant_mass_kg": f(motor.propellant_mass(t)),
        "grain_inner_radius_m": f(motor.grain_inner_radius(t)),
        "grain_height_m": f(motor.grain_height(t)),
        "motor_center_of_mass_motor_z_m": f(motor.center_of_mass(t)),
        "motor_center_of_mass_aft_of_nose_m":
            aft_of_nose_from_motor(f(motor.center_of_mass(t))),
        "motor_I_11_about_motor_com_kg_m2": f(motor.I_11(t)),
        "motor_I_33_kg_m2": f(motor.I_33(t)),
        "propellant_I_11_about_propellant_com_kg_m2":
            f(motor.propellant_I_11(t)),
        "propellant_I_33_kg_m2": f(motor.propellant_I_33(t)),
    }


def first_motion_time(flight):
    """First solver node where the rocket has left its initial position."""
    sol = flight.solution_array
    z0 = sol[0, 3]
    for row in sol:
        if row[3] - z0 > 1e-9 or row[6] > 1e-9:
            return f(row[0])
    return None


def thrust_equals_weight_time(env, rocket):
    """Time at which thrust first equals the weight component along the rail,
    m(t) g(pad) sin(inclination): Flight.udot_rail1 holds the rocket (zero
    acceleration) while (thrust - drag)/m - g sin(incl) <= 0."""
    from scipy.optimize import brentq

    g = env.gravity(env.elevation)
    s_incl = math.sin(math.radians(RAIL["inclination_deg"]))

    def excess(t):
        return f(rocket.motor.thrust(t)) - f(rocket.total_mass(t)) * g * s_incl

    ts = np.linspace(0.0, 0.5, 5001)
    for a, b in zip(ts[:-1], ts[1:]):
        if excess(a) <= 0 < excess(b):
            return f(brentq(excess, a, b, xtol=1e-12))
    return None


def main():
    np.random.seed(20240101)  # only parachute noise draws random numbers
    env, motor, rocket, flight = build()
    burnout = motor.burn_out_time
    version = importlib.metadata.version("rocketpy")
    elev = env.elevation

    events = []
    for ev in flight.parachute_events:
        t_ev, chute = ev[0], ev[1]
        events.append({"parachute": chute.name, "trigger_time_s": f(t_ev),
                       "inflation_time_s": f(t_ev + chute.lag),
                       "altitude_agl_at_trigger_m": f(flight.z(t_ev) - elev)})

    g_heights = [0, 1400, 2000, 3000, 4000, 4705, 10000]
    cp0 = f(rocket.cp_position(0))
    sm_rail = f(flight.out_of_rail_stability_margin)
    nozzle_z = f(rocket.nozzle_position)
    upper_z = RAIL_BUTTONS["upper_button_position_m"]
    out = {
        "generator": "validation/rocketpy/calisto.py",
        "rocketpy_version": version,
        "python_version": platform.python_version(),
        "numpy_version": np.__version__,
        "source_of_inputs": (
            "RocketPy-Team/RocketPy tests/fixtures: rockets/rocket_fixtures.py "
            "(calisto, calisto_robust), motor/solid_motor_fixtures.py "
            "(cesaroni_m1670), surfaces/surface_fixtures.py, "
            "parachutes/parachute_fixtures.py, environment/"
            "environment_fixtures.py (example_spaceport_env), "
            "flight/flight_fixtures.py (flight_calisto_robust)"),
        "coordinate_conversion": (
            "RocketPy rocket frame is 'tail_to_nose': z in metres, positive "
            "towards the nose, origin at the rocket's center of mass without "
            "motor (center_of_mass_without_motor = 0). The nose tip is the "
            "nose cone position z = +1.160. Metres aft of the nose tip: "
            "x = 1.160 - z. Motor frame is 'nozzle_to_combustion_chamber': "
            "origin at the nozzle exit, positive towards the nose, placed at "
            "rocket z = -1.373, so x = 1.160 - (-1.373 + z_motor) = "
            "2.533 - z_motor. Surface positions are: nose = tip, tail = its "
            "top (forward) edge, fins = root chord leading edge."),
        "inputs": {
            "site": SITE,
            "rail": RAIL,
            "motor": MOTOR,
            "motor_aft_of_nose_m": {
                "nozzle_exit": aft_of_nose_from_motor(0.0),
                "center_of_dry_mass": aft_of_nose_from_motor(
                    MOTOR["center_of_dry_mass_position_m"]),
                "grains_center_of_mass": aft_of_nose_from_motor(
                    MOTOR["grains_center_of_mass_position_m"]),
            },
            "rocket": ROCKET,
            "rocket_aft_of_nose_m": {
                "center_of_mass_without_motor": aft_of_nose(0.0),
                "motor_origin_nozzle_exit": aft_of_nose(
                    ROCKET["motor_position_m"]),
            },
            "nose_cone": dict(NOSE, tip_aft_of_nose_m=aft_of_nose(
                NOSE["position_m"])),
            "tail": dict(TAIL, top_aft_of_nose_m=aft_of_nose(
                TAIL["position_m"]), bottom_aft_of_nose_m=aft_of_nose(
                TAIL["position_m"]) + TAIL["length_m"]),
            "fins": dict(FINS, root_leading_edge_aft_of_nose_m=aft_of_nose(
                FINS["position_m"]), sweep_length_used_m=f(
                rocket.fins[0].sweep_length) if hasattr(
                rocket, "fins") and rocket.fins else None),
            "rail_buttons": dict(
                RAIL_BUTTONS,
                upper_aft_of_nose_m=aft_of_nose(upper_z),
                lower_aft_of_nose_m=aft_of_nose(
                    RAIL_BUTTONS["lower_button_position_m"])),
            "parachutes": dict(CHUTES, **{
                "radius_height_porosity": {
                    p.name: {"radius_m": f(p.radius), "height_m": f(p.height),
                             "porosity": f(p.porosity),
                             "added_mass_coefficient":
                                 f(p.added_mass_coefficient)}
                    for p in rocket.parachutes},
                "note": "RocketPy defaults: radius = sqrt(cd_s/(1.4*pi)), "
                        "height = radius, porosity 0.0432; the fixture's "
                        "pressure noise (0, 8.3, 0.5) is switched off here"}),
            "flight": {"terminate_on_apogee": False, "max_time_step": "inf",
                       "rtol": 1e-6, "atol": "RocketPy default",
                       "ode_solver": "LSODA",
                       "equations_of_motion": "standard "
                       "(Flight.u_dot_generalized)"},
        },
        "outputs": {
            "apogee_agl_m": f(flight.apogee - elev),
            "apogee_asl_m": f(flight.apogee),
            "apogee_time_s": f(flight.apogee_time),
            "apogee_x_m": f(flight.apogee_x),
            "apogee_y_m": f(flight.apogee_y),
            "first_motion_time_s": first_motion_time(flight),
            "first_motion_note": "first solver node with the rocket off its "
            "initial position; the exact start is thrust_equals_weight_time",
            "thrust_equals_weight_component_time_s":
                thrust_equals_weight_time(env, rocket),
            "rail_exit_time_s": f(flight.out_of_rail_time),
            "rail_exit_speed_m_s": f(flight.out_of_rail_velocity),
            "rail_exit_stability_margin_cal": sm_rail,
            "max_speed_m_s": f(flight.max_speed),
            "max_speed_time_s": f(flight.max_speed_time),
            "max_mach": f(flight.max_mach_number),
            "max_mach_time_s": f(flight.max_mach_number_time),
            "max_acceleration_m_s2": f(flight.max_acceleration),
            "max_acceleration_time_s": f(flight.max_acceleration_time),
            "max_acceleration_note": "magnitude of the kinematic acceleration "
            "of the center of dry mass (d v / d t in the inertial frame, "
            "gravity included, not the sensed acceleration), at solver nodes",
            "burnout_time_s": f(burnout),
            "motor_total_impulse_N_s": f(motor.total_impulse),
            "motor_exhaust_velocity_m_s": f(
                motor.total_impulse / motor.propellant_initial_mass),
            "motor_propellant_initial_mass_kg": f(
                motor.propellant_initial_mass),
            "motor_average_thrust_N": f(motor.average_thrust),
            "motor_max_thrust_N": f(motor.max_thrust),
            "grain_burn_out_time_s": f(motor.grain_burn_out),
            "static_margin_t0_cal": f(rocket.static_margin(0)),
            "static_margin_after_burnout_cal": f(rocket.static_margin(burnout)),
            "cp_position_mach0_rocketpy_z_m": cp0,
            "cp_position_mach0_aft_of_nose_m": aft_of_nose(cp0),
            "total_clalpha_mach0_per_rad": f(rocket.total_lift_coeff_der(0)),
            "cp_position_vs_mach_aft_of_nose_m": {
                str(M): aft_of_nose(f(rocket.cp_position(M)))
                for M in (0.0, 0.3, 0.6, 0.8, 0.86)},
            "clalpha_vs_mach_per_rad": {
                str(M): f(rocket.total_lift_coeff_der(M))
                for M in (0.0, 0.3, 0.6, 0.8, 0.86)},
            "center_of_dry_mass_rocketpy_z_m": f(
                rocket.center_of_dry_mass_position),
            "center_of_dry_mass_aft_of_nose_m": aft_of_nose(
                f(rocket.center_of_dry_mass_position)),
            "dry_mass_kg": f(rocket.dry_mass),
            "dry_I_11_about_center_of_dry_mass_kg_m2": f(rocket.dry_I_11),
            "dry_I_33_kg_m2": f(rocket.dry_I_33),
            "mass_t0": mass_state(rocket, 0.0),
            "mass_after_burnout": mass_state(rocket, burnout),
            "impact_time_s": f(flight.t_final),
            "impact_x_m": f(flight.x_impact),
            "impact_y_m": f(flight.y_impact),
            "impact_speed_m_s": f(flight.impact_velocity),
            "drift_m": f(math.hypot(flight.x_impact, flight.y_impact)),
            "drift_note": "no wind: the drift is the ballistic downrange of "
            "the 85 deg launch (heading 0 = +y, north) plus Coriolis",
            "parachute_events": events,
        },
        "facts": {
            "gravity_at_pad_m_s2": f(env.gravity(elev)),
            "gravity_vs_height_asl_m_s2": {str(h): f(env.gravity(h))
                                          for h in g_heights},
            "gravity_model": "Somigliana: g0 = 9.7803253359 (1 + 1.931852652458e-3 "
            "sin^2 lat) / sqrt(1 - 6.694379990141e-3 sin^2 lat); g(h) = g0 (1 - "
            "2h/a (1 + f + m - 2 f sin^2 lat) + 3 h^2/a^2), a = 6378137, "
            "f = 1/298.257223563, m = 3.449786506841e-3, h = height above sea "
            "level; tabulated at 100 points on [0, 80000] m and spline "
            "interpolated (Environment.set_gravity_model / somigliana_gravity)",
            "earth_rotation_vector_rad_s": [f(v) for v in
                                            env.earth_rotation_vector],
            "coriolis": "v_dot includes -2 w_earth x v with w_earth = (0, "
            "W cos lat, W sin lat), W = 2 pi / 86164.1 s, in the launch frame "
            "(x east, y north, z up), in both the 6-DOF and parachute phases",
            "density_at_pad_kg_m3": f(env.density(elev)),
            "speed_of_sound_at_pad_m_s": f(env.speed_of_sound(elev)),
            "pressure_at_pad_Pa": f(env.pressure(elev)),
            "rail_exit_rule": "upper-button based. Flight.effective_1rl = "
            "rail_length - |nozzle_z - upper_button_z|; the rocket leaves the "
            "rail when the center of dry mass (the integrated state) has "
            "travelled effective_1rl along the rail (Flight."
            "__check_simulation_events), i.e. when the upper button passes "
            "the rail top, the nozzle starting at the rail's lower end",
            "effective_rail_length_m": f(flight.effective_1rl),
            "nozzle_to_upper_button_m": abs(nozzle_z - upper_z),
            "state_reference_point": "Flight x, y, z, vx, vy, vz are those of "
            "the rocket's center of dry mass (rocket + unloaded motor), "
            "not of the nose tip or the instantaneous center of mass",
            "motor_mass_flow": "m_dot(t) = -T(t) / v_e with constant "
            "v_e = I_total / m_prop0 (Motor.total_mass_flow_rate), so "
            "propellant burned is proportional to impulse delivered: "
            "m_prop(t) = m_prop0 (1 - I(t)/I_total). SolidMotor then "
            "integrates the BATES grain geometry (inner radius, height) from "
            "that mass flow (evaluate_geometry); propellant_mass = n rho "
            "pi (R_out^2 - r_in(t)^2) h(t)",
            "motor_center_of_mass": "propellant center of mass fixed at "
            "grains_center_of_mass_position for all t (SolidMotor."
            "center_of_propellant_mass); motor CoM = (m_prop(t) z_grains + "
            "m_dry z_dry) / (m_prop(t) + m_dry)",
            "motor_inertia": "propellant I_11 about its CoM = n m_g (1/4 "
            "(R^2 + r(t)^2) + 1/12 h(t)^2) + m_g sum d_i^2 with d_i = (i - "
            "(n-1)/2)(h0 + s) (grain spacing fixed at the initial height + "
            "separation), m_g = m_prop(t)/n; I_33 = 1/2 m_prop (R^2 + r^2); "
            "motor I_11 = parallel-axis sum of propellant and dry inertias "
            "about the motor CoM. Rocket inertias are about the rocket's "
            "center of dry mass (Rocket.evaluate_inertias) and the EoM "
            "subtract m r_CM x (r_CM x) to get them about the CoM",
            "motor_samples": [motor_state(motor, t) for t in
                              (0.0, 0.5, 1.0, 2.0, 3.0, 3.5, 3.9)],
        },
        "target_numbers": {
            "apogee_agl_m": 3305.6, "apogee_time_s": 25.885,
            "rail_exit_time_s": 0.3632, "max_speed_m_s": 285.95,
            "max_mach": 0.860},
        "sensitivity_ascent_only": sensitivity(),
    }
    with open(OUT, "w", encoding="utf-8") as fh:
        json.dump(out, fh, indent=2)
        fh.write("\n")
    o = out["outputs"]
    print(f"rocketpy {version}")
    print(f"apogee AGL {o['apogee_agl_m']:.3f} m at {o['apogee_time_s']:.4f} s")
    print(f"rail exit {o['rail_exit_time_s']:.5f} s at "
          f"{o['rail_exit_speed_m_s']:.3f} m/s")
    print(f"max speed {o['max_speed_m_s']:.3f} m/s, max Mach {o['max_mach']:.4f}")
    print(f"impact {o['impact_time_s']:.3f} s, drift {o['drift_m']:.2f} m")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
