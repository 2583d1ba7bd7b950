"""Fly hpr-mc's own designs in RocketPy: the cross-check of whole flights beyond Calisto.

Calisto (``calisto.py``, ``calisto_wind.py``) is a 127 mm rocket with four plain fins on an
M motor, built from RocketPy's own inputs. Here the rockets are hpr-mc design files, handed
to RocketPy as hpr-mc builds them, so that the two fly the same rocket and only the flight
is compared:

* ``canted_boattail`` (``validation/designs/crosscheck-54mm-canted-boattail.json``): what
  Calisto leaves out: a von Karman nose, three fins canted 1 degree (it spins up to 36
  rad/s), a conical boattail, the AeroTech J350W (peak 707 N on 1.26 kg, Mach 1.38);
* ``four_fin_lug`` (``validation/designs/crosscheck-75mm-four-fin-lug.json``): a 75 mm
  rocket with a conical nose, four fins, a launch lug for its rail guide and a boattail, on
  the AeroTech K1100T (3.6 kg at liftoff, Mach 1.2);
* ``reference_design`` (``validation/designs/synthetic-54mm-three-fin.json``): the moving-mass
  worked example's 54 mm design (``docs/moving-mass.md``), ogive nose, three plain fins, on its Cesaroni I175;
* ``elliptical_fins`` (``validation/designs/crosscheck-102mm-elliptical-fins.json``): a 102 mm
  rocket with an elliptical nose and three elliptical fins (RocketPy's ``EllipticalFins``,
  whose center of pressure it rounds to 0.288 root chords where hpr-mc's quarter-MAC point is
  0.2878), on the Cesaroni L1115 (9.7 kg at liftoff);
* ``free_form_fins`` (``validation/designs/crosscheck-79mm-free-form-fins.json``): a 79 mm
  rocket with an ogive nose and four free-form fins (RocketPy's ``FreeFormFins``: a swept
  leading edge, a tip, a trailing edge notched forward), on the Cesaroni K445. RocketPy
  samples the outline on 40 lines across the span, hpr-mc on 4000, so their fins' center
  of pressure differs by a little (see crosscheck.rs).

Each is flown in a constant wind across its rail, in a wind profile that turns and grows
with height, and in still air, with a drogue at apogee and a main lower down.

What RocketPy is given (``rocketpy_rocket``):

* the structure and the motor's casing from ``hpr-mc inspect --json`` after burnout (mass,
  center of mass, the two inertias); the casing goes in the rocket's mass, so RocketPy's
  motor carries only propellant;
* ``GenericMotor``, which is hpr-mc's motor model: the .eng curve with (0, 0) prepended,
  propellant burned in proportion to the impulse, a solid cylinder of the motor's length
  and diameter at its mid-length, nozzle radius 0.88 of the motor's radius (hpr-mc's
  ``NOZZLE_RADIUS_FRACTION``);
* the nose, the fin sets and the conical transitions from the design's geometry, placed
  where ``inspect`` puts them; the rail guides as RocketPy's two buttons (a lug's two ends);
  the design's drag curve
  (power on = power off when the design gives one), interpolated linearly in Mach as hpr-mc
  does (RocketPy reads a bare list of points as a cubic spline).

Mapped, not tuned (see engine/sim/tests/flight_proof/crosscheck.rs): RocketPy measures its
rail from the nozzle, hpr-mc from the rocket's aft end (the airframe's, or the motor's if it
sticks out), so RocketPy's rail is shorter by their distance; RocketPy's canopies replace one another and hpr-mc's add up, so hpr-mc's
main is RocketPy's less the drogue.

Each case is flown as RocketPy 1.13 flies it (``outputs``), with its lever-arm sign
corrected (``lever_arm_corrected``; RocketPy issue #1186) and with its standard atmosphere
made the true one as well (temperature, pressure, density and speed of sound of the U.S.
Standard Atmosphere 1976: ``as_hpr_models``, what hpr-mc models; see corrections.py).

RocketPy starts the center of dry mass at ground level, where hpr-mc's rocket stands on its
rail with its aft end at the rail's foot, so RocketPy's rocket reads the air and the wind
that much lower than it is; the Rust side (crosscheck.rs) hands hpr-mc the same surroundings.

Run from the repository root after ``cargo build --release``:
    .venv/bin/python validation/rocketpy/design_crosscheck.py [ROCKET ...]
Writes validation/rocketpy/design_crosscheck_reference.json: every rocket, or only the ones
named, keeping the others' records as the file has them.
"""

import importlib.metadata
import json
import math
import os
import subprocess
import sys

import numpy as np
from rocketpy import Environment, Flight, Function, GenericMotor, Rocket
from rocketpy.rocket.aero_surface import Fins

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import corrections  # noqa: E402  (the lever arm and the standard air corrected)
import figures  # noqa: E402  (what each flight records)
from figures import f  # noqa: E402

REPO = os.path.dirname(os.path.dirname(HERE))
OUT = os.path.join(HERE, "design_crosscheck_reference.json")
HPR = os.environ.get("HPR_MC", os.path.join(REPO, "target", "release", "hpr-mc"))

SITE = {"latitude_deg": 32.990254, "longitude_deg": -106.974998,
        "elevation_m": 1400.0}
# A wind profile: (height above the site m, speed m/s, from deg), as hpr-mc's
# `environment.wind_profile` rows; RocketPy gets its components at the heights above sea
# level, interpolated linearly as hpr-mc does (custom_atmosphere's default for lists).
PROFILE = [(0.0, 2.0, 270.0), (500.0, 6.0, 250.0), (1500.0, 12.0, 290.0),
           (3000.0, 15.0, 310.0)]
SAMPLING_HZ = 105.0
NOZZLE_RADIUS_FRACTION = 0.88
# Nose shapes whose Barrowman center of pressure RocketPy computes as hpr-mc does (not its
# LV-Haack, hard-coded at 0.563 L where the volume gives 7/16 L, nor its parabolic).
NOSE_KINDS = {"conical": "conical", "ogive": "ogive", "von_karman": "vonKarman",
              "elliptical": "elliptical"}

ROCKETS = {
    "canted_boattail": {
        "design": "validation/designs/crosscheck-54mm-canted-boattail.json",
        # 3 m long, 85 deg up, heading 40 deg (toward the north-east).
        "rail": {"length_m": 3.0, "inclination_deg": 85.0, "heading_deg": 40.0},
        "wind": {"from_deg": 250.0, "speed_m_s": 6.0},
        "main_height_m": 250.0,
    },
    "four_fin_lug": {
        "design": "validation/designs/crosscheck-75mm-four-fin-lug.json",
        # 3.5 m long, 86 deg up, heading 300 deg (toward the west-north-west).
        "rail": {"length_m": 3.5, "inclination_deg": 86.0, "heading_deg": 300.0},
        "wind": {"from_deg": 20.0, "speed_m_s": 7.0},
        "main_height_m": 300.0,
    },
    "reference_design": {
        "design": "validation/designs/synthetic-54mm-three-fin.json",
        # 2.5 m long, 84 deg up, heading 200 deg (toward the south-south-west).
        "rail": {"length_m": 2.5, "inclination_deg": 84.0, "heading_deg": 200.0},
        "wind": {"from_deg": 120.0, "speed_m_s": 5.0},
        "main_height_m": 200.0,
    },
    "elliptical_fins": {
        "design": "validation/designs/crosscheck-102mm-elliptical-fins.json",
        # 5.2 m long, 85 deg up, heading 130 deg (toward the south-east).
        "rail": {"length_m": 5.2, "inclination_deg": 85.0, "heading_deg": 130.0},
        "wind": {"from_deg": 300.0, "speed_m_s": 8.0},
        "main_height_m": 350.0,
    },
    "free_form_fins": {
        "design": "validation/designs/crosscheck-79mm-free-form-fins.json",
        # 4 m long, 87 deg up, heading 75 deg (toward the east-north-east).
        "rail": {"length_m": 4.0, "inclination_deg": 87.0, "heading_deg": 75.0},
        "wind": {"from_deg": 160.0, "speed_m_s": 6.5},
        "main_height_m": 275.0,
        # Under the drogue RocketPy's LSODA steps grow to 20 s; in the constant wind (its
        # steadiest descent) one step went from 331 m above the ground to below it, and
        # RocketPy checks for the impact before it samples the triggers inside the step, so
        # the main never opened. Its steps are held to 2 s.
        "max_time_step_s": 2.0,
    },
}


def wind_components(speed, from_deg):
    """(u toward east, v toward north) of a wind blowing FROM from_deg."""
    a = math.radians(from_deg)
    return -speed * math.sin(a), -speed * math.cos(a)


def inspect(design_path):
    out = subprocess.run([HPR, "inspect", design_path, "--json"], capture_output=True,
                         text=True, check=True)
    return json.loads(out.stdout)


def walk(components):
    for c in components:
        yield c
        yield from walk(c.get("children", []))


def geometry(design, report):
    """Everything RocketPy needs of a design, from the file and hpr-mc's own report."""
    placed = {c["id"]: c for c in report["components"]}
    parts = list(walk([c for s in design["stages"] for c in s["components"]]))
    radius = report["reference_diameter_m"] / 2
    nose = next(c for c in parts if c["type"] == "nose_cone")
    if nose["shape"] not in NOSE_KINDS or nose["base_diameter_m"] / 2 != radius:
        raise SystemExit(f"nose {nose['shape']} not mapped to RocketPy")
    fins = [c for c in parts if c["type"] == "fin_set"]
    tails = [c for c in parts if c["type"] == "transition"]
    if any(t["shape"] != "conical" for t in tails):
        raise SystemExit("only conical transitions map to RocketPy's Tail")
    # Rail guides as hpr-mc takes them (docs/design-format.md): the first two rail buttons
    # (their centers) or launch lugs (both ends of each); the fore-most and aft-most points.
    guides = [c for c in parts if c["type"] in ("rail_button", "launch_lug")][:2]
    points = []
    for g in guides:
        top = placed[g["id"]]["x_top_m"]
        if g["type"] == "rail_button":
            points.append(top + g["outer_diameter_m"] / 2)
        else:
            points += [top, top + g["length_m"]]
    mount = next(c for c in parts if c["type"] == "inner_tube" and "motor_mount" in c)
    mm = placed[mount["id"]]
    motor = report["motor"]
    motor_aft = mm["x_top_m"] + mm["length_m"] + mount["motor_mount"]["overhang_m"]
    # hpr-mc's rocket stands on the rail's foot with its aft end, the airframe's or the
    # motor's if it sticks out (the reference design's motor overhangs its tube by 10 mm).
    aft_end = max([motor_aft] + [placed[c["id"]]["x_top_m"] + placed[c["id"]]["length_m"]
                                 for c in parts
                                 if c["type"] in ("nose_cone", "body_tube", "transition")])
    dry = report["after_burnout"]
    return {
        "rocket_after_burnout": {
            "mass_kg": dry["mass_kg"], "cg_m": dry["cg_m"],
            "inertia_transverse_kg_m2": dry["inertia_transverse_kg_m2"],
            "inertia_axial_kg_m2": dry["inertia_axial_kg_m2"],
            "radius_m": radius, "aft_end_m": aft_end,
        },
        "motor": {
            "file": motor["file"], "propellant_mass_kg": motor["propellant_mass_kg"],
            "diameter_m": motor["diameter_m"], "length_m": motor["length_m"],
            "aft_m": motor_aft,
            "nozzle_radius_fraction": NOZZLE_RADIUS_FRACTION,
        },
        "nose": {"length_m": nose["length_m"], "kind": NOSE_KINDS[nose["shape"]],
                 "position_m": placed[nose["id"]]["x_top_m"]},
        "fins": [{"n": c["count"], "planform": c.get("planform", "trapezoidal"),
                  "root_chord_m": c.get("root_chord_m"),
                  "tip_chord_m": c.get("tip_chord_m"), "span_m": c.get("span_m"),
                  "sweep_length_m": c.get("sweep_m", 0.0),
                  "points_m": c.get("points_m"),
                  "cant_angle_deg": c.get("cant_deg", 0.0),
                  "position_m": placed[c["id"]]["x_top_m"]} for c in fins],
        "tails": [{"top_radius_m": c["fore_diameter_m"] / 2,
                   "bottom_radius_m": c["aft_diameter_m"] / 2,
                   "length_m": c["length_m"],
                   "position_m": placed[c["id"]]["x_top_m"]} for c in tails],
        "buttons": [min(points), max(points)],
        "drag_power_off": design["drag"]["power_off"],
        "drag_power_on": design["drag"].get("power_on", design["drag"]["power_off"]),
        "canopies": {c["id"]: c["cd"] * math.pi * c["canopy_diameter_m"] ** 2 / 4
                     for c in parts if c["type"] == "parachute"},
    }


def linear(points, name):
    return Function([tuple(p) for p in points], "Mach Number", name,
                    interpolation="linear", extrapolation="constant")


def build(spec, geo, wind="wind", lever_arm=False, air=False, noise=(0, 0, 0)):
    """The rocket in `wind` ("wind", "profile" or "calm"), RocketPy's lever arm and standard
    air corrected or not, its parachutes' barometers read with `noise` (RocketPy's (bias,
    deviation, correlation); none by default)."""
    env = Environment(latitude=SITE["latitude_deg"], longitude=SITE["longitude_deg"],
                      elevation=SITE["elevation_m"])
    if wind == "wind":
        u, v = wind_components(spec["wind"]["speed_m_s"], spec["wind"]["from_deg"])
    elif wind == "profile":
        rows = [(SITE["elevation_m"] + h, wind_components(s, d)) for h, s, d in PROFILE]
        u = [[z, c[0]] for z, c in rows]
        v = [[z, c[1]] for z, c in rows]
    else:
        u, v = 0.0, 0.0
    env.set_atmospheric_model(type="custom_atmosphere", wind_u=u, wind_v=v)
    if callable(air):
        air(env)  # another air, as the caller gives it (profile_crosscheck.py)
    elif air:
        corrections.true_standard_air(env)
    motor, rocket = assemble(spec, geo, lever_arm, noise)
    r, m, rail = geo["rocket_after_burnout"], geo["motor"], spec["rail"]
    flight = Flight(rocket=rocket, environment=env,
                    rail_length=rail["length_m"] - (r["aft_end_m"] - m["aft_m"]),
                    inclination=rail["inclination_deg"], heading=rail["heading_deg"],
                    max_time_step=spec.get("max_time_step_s", np.inf))
    return env, motor, rocket, flight


def assemble(spec, geo, lever_arm=False, noise=(0, 0, 0)):
    """RocketPy's motor and rocket (its canopies included, their barometers read with
    `noise`), its lever arm corrected or not, not yet flown."""
    m = geo["motor"]
    half = 0.5 * m["length_m"]
    eng = os.path.join(REPO, "engine", "design", "motors", m["file"] + ".eng")
    motor = GenericMotor(
        thrust_source=eng, burn_time=None,
        chamber_radius=0.5 * m["diameter_m"], chamber_height=m["length_m"],
        chamber_position=half, propellant_initial_mass=m["propellant_mass_kg"],
        nozzle_radius=0.5 * m["diameter_m"] * m["nozzle_radius_fraction"],
        dry_mass=0.0, center_of_dry_mass_position=half, dry_inertia=(0, 0, 0),
        nozzle_position=0.0, coordinate_system_orientation="nozzle_to_combustion_chamber")
    r = geo["rocket_after_burnout"]
    rocket = Rocket(
        radius=r["radius_m"], mass=r["mass_kg"],
        inertia=(r["inertia_transverse_kg_m2"], r["inertia_transverse_kg_m2"],
                 r["inertia_axial_kg_m2"]),
        power_off_drag=linear(geo["drag_power_off"], "Drag Coefficient with Power Off"),
        power_on_drag=linear(geo["drag_power_on"], "Drag Coefficient with Power On"),
        center_of_mass_without_motor=r["cg_m"], coordinate_system_orientation="nose_to_tail")
    rocket.add_motor(motor, position=m["aft_m"])
    n = geo["nose"]
    rocket.add_nose(length=n["length_m"], kind=n["kind"], position=n["position_m"])
    for k in geo["fins"]:
        if k["planform"] == "elliptical":
            rocket.add_elliptical_fins(
                n=k["n"], root_chord=k["root_chord_m"], span=k["span_m"],
                position=k["position_m"], cant_angle=k["cant_angle_deg"])
        elif k["planform"] == "free_form":
            # RocketPy samples the outline on 40 lines (see barrowman.py's free-form records).
            rocket.add_free_form_fins(
                shape_points=[tuple(p) for p in k["points_m"]], n=k["n"],
                position=k["position_m"], cant_angle=k["cant_angle_deg"])
        else:
            rocket.add_trapezoidal_fins(
                n=k["n"], root_chord=k["root_chord_m"], tip_chord=k["tip_chord_m"],
                span=k["span_m"], position=k["position_m"], cant_angle=k["cant_angle_deg"],
                sweep_length=k["sweep_length_m"])
    for t in geo["tails"]:
        rocket.add_tail(top_radius=t["top_radius_m"], bottom_radius=t["bottom_radius_m"],
                        length=t["length_m"], position=t["position_m"])
    upper, lower = geo["buttons"]
    rocket.set_rail_buttons(upper_button_position=upper, lower_button_position=lower,
                            angular_position=0.0)
    chutes = parachutes(spec, geo)
    rocket.add_parachute("main", cd_s=chutes["main"]["cd_s_m2"],
                         trigger=chutes["main"]["height_m"], sampling_rate=SAMPLING_HZ,
                         lag=chutes["main"]["lag_s"], noise=noise)
    rocket.add_parachute("drogue", cd_s=chutes["drogue"]["cd_s_m2"], trigger="apogee",
                         sampling_rate=SAMPLING_HZ, lag=chutes["drogue"]["lag_s"],
                         noise=noise)
    if lever_arm:
        corrections.correct(rocket)
    return motor, rocket


def parachutes(spec, geo):
    """RocketPy's canopies: the design's drogue and main ("drogue" and "chute"), CdS from
    their diameter and Cd, each opening 1 s after its trigger."""
    return {
        "drogue": {"cd_s_m2": geo["canopies"]["drogue"], "lag_s": 1.0},
        "main": {"cd_s_m2": geo["canopies"]["chute"], "lag_s": 1.0,
                 "height_m": spec["main_height_m"]},
    }


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


def case(spec, geo, **kw):
    env, _, rocket, flight = build(spec, geo, **kw)
    return outputs(env, rocket, flight)


def rocket(name):
    """``ROCKETS[name]`` and its geometry as ``geometry`` gives it."""
    spec = ROCKETS[name]
    design_path = os.path.join(REPO, spec["design"])
    with open(design_path) as fh:
        design = json.load(fh)
    return spec, geometry(design, inspect(design_path))


def one(name, spec, winds=("wind", "profile", "calm")):
    """One rocket's record: its inputs, RocketPy's checks of the rocket and each case of
    `winds`, flown three ways."""
    design_path = os.path.join(REPO, spec["design"])
    with open(design_path) as fh:
        design = json.load(fh)
    geo = geometry(design, inspect(design_path))
    _, motor, rocket, _ = build(spec, geo, wind="calm")
    cases = {}
    for wind in winds:
        cases[wind] = {
            "outputs": case(spec, geo, wind=wind),
            "lever_arm_corrected": case(spec, geo, wind=wind, lever_arm=True),
            "as_hpr_models": case(spec, geo, wind=wind, lever_arm=True, air=True),
        }
        h = cases[wind]["as_hpr_models"]
        print(f"{name} {wind}: apogee {h['apogee_agl_m']:.2f} m at {h['apogee_time_s']:.3f} s"
              f" ({cases[wind]['outputs']['apogee_agl_m']:.2f} as RocketPy is); roll at"
              f" burnout {h['roll_rate_at_burnout_rad_s']:.3f} rad/s; impact"
              f" ({h['impact_x_m']:.1f}, {h['impact_y_m']:.1f}) at {h['impact_time_s']:.2f} s")
    u, v = wind_components(spec["wind"]["speed_m_s"], spec["wind"]["from_deg"])
    r, m = geo["rocket_after_burnout"], geo["motor"]
    return {
        "inputs": {
            **geo,
            "design": spec["design"],
            "site": SITE,
            "wind": {**spec["wind"], "wind_u_toward_east_m_s": u,
                     "wind_v_toward_north_m_s": v},
            "wind_profile": [{"height_agl_m": h, "speed_m_s": s, "from_deg": d}
                             for h, s, d in PROFILE],
            "rail": {**spec["rail"], "rocketpy_rail_length_m":
                     spec["rail"]["length_m"] - (r["aft_end_m"] - m["aft_m"])},
            "parachutes": parachutes(spec, geo),
            "sampling_rate_hz": SAMPLING_HZ,
            **({"rocketpy_max_time_step_s": spec["max_time_step_s"]}
               if "max_time_step_s" in spec else {}),
        },
        "checks": {
            "liftoff_mass_kg": f(rocket.total_mass(0)),
            "liftoff_center_of_mass_m": f(rocket.center_of_mass(0)),
            "propellant_mass_kg": f(motor.propellant_initial_mass),
            "total_impulse_ns": f(motor.total_impulse),
            "burn_out_time_s": f(motor.burn_out_time),
            "center_of_pressure_mach0_m": f(rocket.cp_position(0)),
            "static_margin_liftoff_cal": f(rocket.static_margin(0)),
            # Each fin set's own center of pressure aft of its leading edge and its lift
            # slope at Mach 0, as RocketPy computes them (a free-form set's from its 40 lines).
            "fin_sets": [{"cp_aft_of_leading_edge_m": f(fins.cpz),
                          "clalpha_mach0_per_rad": f(fins.clalpha(0))}
                         for fins in rocket.aerodynamic_surfaces.get_by_type(Fins)],
        },
        "cases": cases,
    }


def write_reference(path, ref):
    """Write a cross-check's reference as every cross-check script does (sorted keys, one
    space of indent, a final newline), so that regenerating gives the same bytes."""
    with open(path, "w") as fh:
        json.dump(ref, fh, indent=1, sort_keys=True)
        fh.write("\n")


def main():
    np.random.seed(20261202)  # parachute noise is off; nothing is drawn
    names = sys.argv[1:] or list(ROCKETS)
    unknown = [n for n in names if n not in ROCKETS]
    if unknown:
        sys.exit(f"unknown rocket(s) {unknown}; known: {list(ROCKETS)}")
    kept = {}
    if len(names) < len(ROCKETS) and os.path.exists(OUT):
        with open(OUT) as fh:
            kept = json.load(fh)["rockets"]
    fresh = {name: one(name, ROCKETS[name]) for name in names}
    ref = {
        "generator": "validation/rocketpy/design_crosscheck.py",
        "rocketpy_version": importlib.metadata.version("rocketpy"),
        "rockets": {name: fresh.get(name, kept.get(name)) for name in ROCKETS
                    if name in fresh or name in kept},
    }
    write_reference(OUT, ref)
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
