"""Fly randomly drawn rockets in RocketPy: the cross-check of whole flights on rockets no one
picked.

``design_crosscheck.py`` flies five hand-picked rockets; a simulator could agree with RocketPy
on those and not on the next. Here, from a fixed seed, candidates are drawn at random within
what a high-power rocket is and what RocketPy models as hpr-mc does (``design_crosscheck``'s
``NOSE_KINDS``, conical boattails, trapezoidal, elliptical and free-form fins), written as
hpr-mc designs (``validation/designs/random/``, committed inputs) and flown by RocketPy
exactly as ``design_crosscheck.py`` flies its rockets (its functions, imported): the same
handing-over of hpr-mc's rocket as numbers, the same site, canopies, sampling and
corrections. The first ``KEEP`` candidates that pass the rules below are kept, into
``random_crosscheck_reference.json`` (``design_crosscheck_reference.json``'s layout), and
``engine/sim/tests/flight_proof/random_crosscheck.rs`` flies them in hpr-mc with one set of
tolerances for all.

What is drawn, candidate by candidate (``draw``): the motor's class cycles H, I, J, K, L, M
and the motor is drawn within it; the nose shape cycles conical, ogive, von Karman,
elliptical; the fins' planform cycles trapezoidal, elliptical, free-form; everything else
is drawn: the airframe's diameter (from the motor's: 38 to 130 mm), its lengths, walls and
materials, the payload and nose weight, three or four fins and their size, a boattail or
none, rail buttons or a launch lug, the rail (length, 80 to 90 degrees up, any heading), a
constant wind (0 to 10 m/s from anywhere), the main's height. The canopies are sized from
the burnt-out mass ``hpr-mc inspect`` reports (the mass RocketPy is handed): the drogue for
18 to 30 m/s, the main for 4.5 to 6.5 m/s.

Rules (``REJECT_RULES``), judged on RocketPy's own figures only (never on hpr-mc's flight):
a candidate is rejected, and the script says which rule it broke, if its average thrust is
under 5 times its liftoff weight, if its static margin at Mach 0 is 1 calibre or less at
liftoff or at rail exit, if it leaves the rail below 15 m/s, if its apogee is under 150 m
above the main's height or it flies past Mach 2 (the drag curves' last point), or if in any
case a canopy does not open before the landing (RocketPy's LSODA stepping past the ground
under a drogue, NOTES.md section 14; its steps are held to 2 s for every rocket).

Each kept rocket is flown in ``WINDS`` (a constant wind, the turning profile of
``design_crosscheck.PROFILE``, still air), each as RocketPy is, with its lever arm corrected
and as hpr-mc models (``design_crosscheck.one``). Every case records, besides
``design_crosscheck``'s figures, RocketPy's largest angle of attack between the apogee and
the drogue's opening (``max_angle_of_attack_apogee_to_drogue_deg``): a rocket left with a few
m/s at its apogee falls tail first in the drogue's lag, past the 45 degrees beyond which
hpr-mc leaves RocketPy's loads on purpose (random_crosscheck.rs, ``TUMBLE_DEG``).

Run from the repository root after ``cargo build --release``:
    HPR_MC=target/release/hpr-mc .venv/bin/python validation/rocketpy/random_crosscheck.py
Writes validation/designs/random/*.json and validation/rocketpy/random_crosscheck_reference.json.
"""

import glob
import importlib.metadata
import json
import math
import os
import random
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import design_crosscheck as dc  # noqa: E402  (the handing-over, the flights, the records)

OUT = os.path.join(HERE, "random_crosscheck_reference.json")
DESIGNS = os.path.join(dc.REPO, "validation", "designs", "random")
SEED = 20261203
KEEP = 12
MAX_CANDIDATES = 40
WINDS = ("wind", "profile", "calm")
# RocketPy's LSODA steps are held to this under every canopy (NOTES.md section 14).
MAX_TIME_STEP_S = 2.0
# Air density at the site's elevation (1400 m, standard atmosphere), for sizing canopies.
RHO_SITE = 1.0582
G = 9.80665

# The bundled motors by class (file stem, diameter m, length m), from engine/design/motors.
MOTORS = {
    "H": [("AeroTech_H128W", 0.029, 0.194), ("AeroTech_H238T", 0.029, 0.194),
          ("AeroTech_H148", 0.038, 0.152)],
    "I": [("AeroTech_I161W", 0.038, 0.191), ("AeroTech_I284W", 0.038, 0.297),
          ("AeroTech_I175WS", 0.038, 0.214), ("Cesaroni_I175", 0.038, 0.245),
          ("Cesaroni_I216", 0.038, 0.367)],
    "J": [("AeroTech_J350W", 0.038, 0.337), ("AeroTech_J570W", 0.038, 0.479),
          ("Cesaroni_J295", 0.054, 0.329)],
    "K": [("AeroTech_K550W", 0.054, 0.410), ("AeroTech_K1100T", 0.054, 0.398),
          ("Cesaroni_K445", 0.054, 0.404), ("Cesaroni_K660", 0.054, 0.572),
          ("Loki_K960-LW", 0.054, 0.498), ("Cesaroni_1597K400-14A", 0.054, 0.404)],
    "L": [("AeroTech_L1040DM", 0.075, 0.681), ("AeroTech_L1170FJ", 0.075, 0.665),
          ("Cesaroni_L1115", 0.075, 0.621)],
    "M": [("Cesaroni_M1670", 0.075, 0.757), ("AeroTech_M1939W", 0.098, 0.732)],
}
CLASSES = "HIJKLM"
# Airframe outer diameters (m) for a motor's diameter: from a near minimum-diameter airframe
# to about twice the motor's, within 38 to 130 mm.
DIAMETERS = {0.029: (0.038, 0.060), 0.038: (0.048, 0.080), 0.054: (0.066, 0.102),
             0.075: (0.098, 0.130), 0.098: (0.112, 0.130)}
NOSES = ["conical", "ogive", "von_karman", "elliptical"]
PLANFORMS = ["trapezoidal", "elliptical", "free_form"]
FIBERGLASS = {"name": "fiberglass", "density_kg_m3": 1850.0}
CARDBOARD = {"name": "cardboard", "density_kg_m3": 680.0}
PLYWOOD = {"name": "plywood", "density_kg_m3": 630.0}
PHENOLIC = {"name": "phenolic", "density_kg_m3": 700.0}
POLYPROPYLENE = {"name": "polypropylene", "density_kg_m3": 900.0}
# A typical drag curve's shape (Cd over its value at Mach 0), as the hand-picked designs'.
DRAG_SHAPE = [(0.0, 1.0), (0.1, 0.96), (0.2, 0.93), (0.3, 0.91), (0.4, 0.904), (0.5, 0.91),
              (0.6, 0.93), (0.7, 0.97), (0.8, 1.04), (0.9, 1.2), (1.0, 1.4), (1.1, 1.44),
              (1.2, 1.4), (1.5, 1.26), (2.0, 1.1)]


def mm(x):
    """A length rounded to 0.1 mm, as a drawing gives it."""
    return round(x, 4)


def part(id_, kind, at, **fields):
    return {"id": id_, "type": kind, **fields, "position": {"from": "nose_tip", "offset_m": at}}


def draw_fins(rng, planform, d):
    """A fin set's fields for a body of diameter d."""
    span = mm(rng.uniform(0.6, 1.4) * d)
    root = mm(rng.uniform(1.1, 2.4) * d)
    if planform == "trapezoidal":
        tip = mm(rng.uniform(0.25, 0.6) * root)
        return {"root_chord_m": root, "tip_chord_m": tip, "span_m": span,
                "sweep_m": mm(rng.uniform(0.0, 1.0) * (root - tip) + rng.uniform(0, 0.3) * span)}
    if planform == "elliptical":
        return {"planform": "elliptical", "root_chord_m": root, "span_m": span}
    # Free-form: a swept leading edge to a tip, and a trailing edge with a notch or a kink.
    # (The kink lies aft of the leading edge at its height, so no edge crosses another.)
    x_tip = rng.uniform(0.3, 0.6) * root
    tip = rng.uniform(0.2, 0.35) * root
    points = [[0.0, 0.0], [x_tip, span], [x_tip + tip, span]]
    if rng.random() < 0.5:
        points.append([rng.uniform(x_tip + 0.5 * tip, root), rng.uniform(0.2, 0.5) * span])
    points.append([root, 0.0])
    return {"planform": "free_form", "points_m": [[mm(x), mm(y)] for x, y in points]}


def draw(rng, i):
    """Candidate i: its design (without canopy sizes) and its flight's settings."""
    klass = CLASSES[i % len(CLASSES)]
    motor, dm, lm = rng.choice(MOTORS[klass])
    d = mm(rng.uniform(*DIAMETERS[dm]))
    big = d > 0.07
    wall = mm(rng.uniform(0.0012, 0.0018) if not big else rng.uniform(0.0018, 0.003))
    tube = FIBERGLASS if big or rng.random() < 0.3 else rng.choice([CARDBOARD, PHENOLIC])
    inner = mm(d - 2 * wall)
    mount_wall = 0.0012 if dm < 0.05 else 0.0016
    mount_od = mm(dm + 0.0008 + 2 * mount_wall)
    nose_len = mm(rng.uniform(3.0, 5.5) * d)
    shoulder = mm(rng.uniform(0.8, 1.2) * d)
    boattail = rng.random() < 0.45
    bt_len = mm(rng.uniform(0.4, 1.0) * d) if boattail else 0.0
    overhang = mm(rng.choice([0.0, 0.005, 0.01]) if not boattail
                  else rng.choice([0.0, bt_len]))
    mount_len = mm(lm - overhang + rng.uniform(0.0, 0.04))
    # The bay ahead of the motor: avionics, a bulkhead, the cord and both canopies, packed.
    scale = (d / 0.1) ** 2
    avionics = (mm(rng.uniform(1.2, 2.5) * d),
                round(rng.uniform(0.4, 1.6) * 0.45 * scale + 0.03, 3))
    main_pack, drogue_pack = mm(rng.uniform(1.2, 2.0) * d), mm(rng.uniform(0.5, 0.9) * d)
    top = nose_len + shoulder + 0.01
    bay = avionics[0] + 0.02 + 0.01 + mm(0.8 * d) + main_pack + drogue_pack
    body_len = mm(shoulder + bay + mount_len + rng.uniform(0.05, 0.5) + rng.uniform(3, 7) * d)
    planform = PLANFORMS[i % len(PLANFORMS)]
    fins = draw_fins(rng, planform, d)
    root = fins.get("root_chord_m") or fins["points_m"][-1][0]
    fin_mat = rng.choice([PLYWOOD, FIBERGLASS])
    pack_r = mm(0.4 * inner)
    at = top
    children = [part("avionics", "mass_component", mm(at), mass_kg=avionics[1],
                     length_m=avionics[0], radius_m=pack_r)]
    at += avionics[0] + 0.01
    children.append(part("bulkhead", "bulkhead", mm(at), length_m=0.006,
                         outer_diameter_m=inner, material=PLYWOOD))
    at += 0.01
    children.append(part("shock_cord", "shock_cord", mm(at),
                         mass_kg=round(0.05 * scale + 0.01, 3), length_m=mm(0.8 * d),
                         radius_m=pack_r))
    at += 0.8 * d
    # Canopy diameters are placeholders until the burnt-out mass is known (`size_canopies`).
    children.append(part("chute", "parachute", mm(at), mass_kg=round(0.3 * scale + 0.02, 3),
                         length_m=main_pack, radius_m=pack_r, canopy_diameter_m=1.0, cd=1.5))
    at += main_pack
    children.append(part("drogue", "parachute", mm(at), mass_kg=round(0.06 * scale + 0.01, 3),
                         length_m=drogue_pack, radius_m=pack_r, canopy_diameter_m=0.3, cd=1.5))
    children += [
        {"id": "mmt", "type": "inner_tube", "length_m": mount_len, "outer_diameter_m": mount_od,
         "wall_thickness_m": mount_wall, "motor_mount": {"overhang_m": overhang},
         "material": PHENOLIC, "position": {"from": "bottom", "offset_m": 0.0}},
        {"id": "ring_fore", "type": "centering_ring", "length_m": 0.006,
         "outer_diameter_m": inner, "inner_diameter_m": mount_od, "material": PLYWOOD,
         "position": {"from": "bottom", "offset_m": mm(0.006 - mount_len)}},
        {"id": "ring_aft", "type": "centering_ring", "length_m": 0.006,
         "outer_diameter_m": inner, "inner_diameter_m": mount_od, "material": PLYWOOD,
         "position": {"from": "bottom", "offset_m": 0.0}},
        {"id": "fins", "type": "fin_set", "count": rng.choice([3, 4]), **fins,
         "thickness_m": mm(rng.uniform(0.02, 0.04) * d + 0.001), "cross_section": "rounded",
         "material": fin_mat,
         "position": {"from": "bottom", "offset_m": mm(-rng.uniform(0.0, 0.5) * root)}},
    ]
    if d < 0.07 and rng.random() < 0.4:
        children.append(part("lug", "launch_lug", mm(nose_len + 0.5 * body_len),
                             length_m=mm(rng.uniform(0.05, 0.1)), outer_diameter_m=0.012,
                             wall_thickness_m=0.001, material=PHENOLIC))
    else:
        mass = round(0.002 + 0.008 * min(1.0, scale), 3)
        upper = mm(nose_len + rng.uniform(0.35, 0.6) * body_len)
        children.append(part("button_upper", "rail_button", upper, outer_diameter_m=0.011,
                             height_m=0.009, mass_kg=mass))
        children.append({"id": "button_lower", "type": "rail_button", "outer_diameter_m": 0.011,
                         "height_m": 0.009, "mass_kg": mass,
                         "position": {"from": "bottom", "offset_m": -0.02}})
    nose_mat = FIBERGLASS if big else rng.choice([POLYPROPYLENE, FIBERGLASS])
    nose = {"id": "nose", "type": "nose_cone", "shape": NOSES[i % len(NOSES)],
            "length_m": nose_len, "base_diameter_m": d, "wall_thickness_m": wall,
            "material": nose_mat,
            "shoulder": {"length_m": shoulder, "outer_diameter_m": inner,
                         "wall_thickness_m": wall, "capped": True}}
    weight = round(rng.uniform(0.0, 1.0) * 0.8 * scale, 3)
    if weight > 0.005:
        nose["children"] = [part("nose_weight", "mass_component", nose_len, mass_kg=weight,
                                 length_m=mm(0.5 * shoulder), radius_m=pack_r)]
    components = [nose, {"id": "body", "type": "body_tube", "length_m": body_len,
                         "outer_diameter_m": d, "wall_thickness_m": wall, "material": tube,
                         "children": children}]
    if boattail:
        aft = mm(max(mount_od + 0.004, rng.uniform(0.7, 0.88) * d))
        components.append({"id": "boattail", "type": "transition", "shape": "conical",
                           "length_m": bt_len, "fore_diameter_m": d, "aft_diameter_m": aft,
                           "wall_thickness_m": wall, "material": FIBERGLASS})
    cd0 = rng.uniform(0.42, 0.68) * (0.92 if boattail else 1.0)
    name = f"random-{i:02d}-{round(d * 1000)}mm-{motor.split('_', 1)[1]}"
    design = {
        "name": f"Random cross-check rocket {i:02d} ({round(d * 1000)} mm, {motor})",
        "notes": "Drawn at random by validation/rocketpy/random_crosscheck.py (seed "
                 f"{SEED}, candidate {i}) for the randomized RocketPy cross-check. Made up, "
                 "not a real rocket; its drag curve is a typical shape, not measured.",
        "motor": motor,
        "drag": {"power_off": [[m, round(cd0 * k, 6)] for m, k in DRAG_SHAPE]},
        "stages": [{"id": "sustainer", "components": components}],
    }
    rail_len = round(rng.uniform(1.5, 3.0) if d < 0.07 else rng.uniform(3.0, 6.0), 2)
    spec = {
        "design": os.path.relpath(os.path.join(DESIGNS, name + ".json"), dc.REPO),
        "rail": {"length_m": rail_len, "inclination_deg": round(rng.uniform(80.0, 90.0), 1),
                 "heading_deg": round(rng.uniform(0.0, 360.0), 1)},
        "wind": {"from_deg": round(rng.uniform(0.0, 360.0), 1),
                 "speed_m_s": round(rng.uniform(0.0, 10.0), 2)},
        "main_height_m": float(rng.choice(range(150, 451, 25))),
        "max_time_step_s": MAX_TIME_STEP_S,
    }
    speeds = (rng.uniform(18.0, 30.0), rng.uniform(4.5, 6.5))
    return name, design, spec, speeds


def size_canopies(design, dry_mass_kg, speeds):
    """Canopy diameters for the drogue's and the main's descent speeds at the site."""
    def diameter(v, cd):
        return round(math.sqrt(4 * 2 * dry_mass_kg * G / (RHO_SITE * v * v) / (math.pi * cd)), 3)

    for c in design["stages"][0]["components"][1]["children"]:
        if c["id"] in ("drogue", "chute"):
            c["canopy_diameter_m"] = diameter(speeds[0] if c["id"] == "drogue" else speeds[1],
                                              c["cd"])


def write(path, design):
    with open(path, "w") as fh:
        json.dump(design, fh, indent=1)
        fh.write("\n")


def outputs(env, rocket, flight):
    """``design_crosscheck.outputs`` and RocketPy's largest angle of attack between the apogee
    and the drogue's opening (deg, on 101 instants): past 45 degrees (a rocket with little
    speed left at apogee, in still air, falling tail first before its drogue opens) hpr-mc
    leaves RocketPy's loads on purpose (ARCHITECTURE.md, "RocketPy's model, and where it
    stops"), and the Rust check says so for that case's descent."""
    out = _OUTPUTS(env, rocket, flight)
    drogue = [t + c.lag for t, c in flight.parachute_events if c.name == "drogue"]
    end = drogue[0] if drogue else flight.t_final
    instants = np.linspace(flight.apogee_time, end, 101)
    out["max_angle_of_attack_apogee_to_drogue_deg"] = dc.f(
        max(flight.angle_of_attack(t) for t in instants))
    return out


_OUTPUTS = dc.outputs
dc.outputs = outputs  # every case `design_crosscheck.one` flies records it


def reject_before(spec, geo):
    """The rules judged on RocketPy's rocket, then on its still-air flight as hpr-mc models it
    (an unstable rocket is not flown: RocketPy's LSODA crawls through its tumble); None if it
    passes."""
    motor, rocket = dc.assemble(spec, geo, lever_arm=True)
    thrust_to_weight = motor.total_impulse / motor.burn_out_time / (rocket.total_mass(0) * G)
    liftoff_margin = rocket.static_margin(0)
    if thrust_to_weight < 5.0:
        return f"average thrust {thrust_to_weight:.2f} x liftoff weight < 5"
    if liftoff_margin <= 1.0:
        return f"static margin at liftoff {liftoff_margin:.2f} cal <= 1"
    env, motor, rocket, flight = dc.build(spec, geo, wind="calm", lever_arm=True, air=True)
    out = outputs(env, rocket, flight)
    exit_margin = rocket.static_margin(out["rail_exit_time_s"])
    checks = [
        (exit_margin <= 1.0, f"static margin at rail exit {exit_margin:.2f} cal <= 1"),
        (out["rail_exit_speed_m_s"] < 15.0,
         f"rail exit speed {out['rail_exit_speed_m_s']:.1f} m/s < 15"),
        (out["apogee_agl_m"] < spec["main_height_m"] + 150.0,
         f"apogee {out['apogee_agl_m']:.0f} m < main height {spec['main_height_m']:.0f} + 150 m"),
        (out["max_mach"] > 2.0, f"max Mach {out['max_mach']:.2f} > 2"),
    ]
    return next((why for bad, why in checks if bad), None)


def reject_after(record):
    """Every case must open both canopies, the drogue first, before the landing."""
    for wind, flown in record["cases"].items():
        for variant, out in flown.items():
            names = [e["parachute"] for e in out["parachute_events"]]
            late = [e for e in out["parachute_events"]
                    if e["inflation_time_s"] >= out["impact_time_s"]]
            if names != ["drogue", "main"] or late:
                return f"{wind}/{variant}: canopies opened {names} before the landing"
    return None


def summary(record):
    i = record["inputs"]
    fins = i["fins"][0]
    return (f"{i['motor']['file']}, {2000 * i['rocket_after_burnout']['radius_m']:.0f} mm,"
            f" {fins['n']} {fins['planform']} fins, {i['nose']['kind']} nose,"
            f" {'boattail' if i['tails'] else 'no boattail'}, margin"
            f" {record['checks']['static_margin_liftoff_cal']:.2f} cal")


def main():
    np.random.seed(20261202)  # parachute noise is off; nothing is drawn
    rng = random.Random(SEED)
    os.makedirs(DESIGNS, exist_ok=True)
    for old in glob.glob(os.path.join(DESIGNS, "random-*.json")):
        os.remove(old)
    kept, rejected = {}, []
    for i in range(MAX_CANDIDATES):
        if len(kept) == KEEP:
            break
        name, design, spec, speeds = draw(rng, i)
        path = os.path.join(dc.REPO, spec["design"])
        write(path, design)
        size_canopies(design, dc.inspect(path)["after_burnout"]["mass_kg"], speeds)
        write(path, design)
        geo = dc.geometry(design, dc.inspect(path))
        why = reject_before(spec, geo)
        record = None
        if why is None:
            record = dc.one(name, spec, winds=WINDS)
            why = reject_after(record)
        if why is not None:
            os.remove(path)
            rejected.append({"candidate": i, "name": name, "reason": why})
            print(f"REJECTED candidate {i} ({name}): {why}")
            continue
        key = f"random_{len(kept) + 1:02d}"
        kept[key] = record
        print(f"KEPT {key} = candidate {i} ({name}): {summary(record)}")
    if len(kept) < KEEP:
        sys.exit(f"only {len(kept)} of {MAX_CANDIDATES} candidates passed the rules")
    ref = {
        "generator": "validation/rocketpy/random_crosscheck.py",
        "rocketpy_version": importlib.metadata.version("rocketpy"),
        "seed": SEED,
        "rejected": rejected,
        "rockets": kept,
    }
    dc.write_reference(OUT, ref)
    print(f"wrote {OUT}: {len(kept)} rockets kept, {len(rejected)} rejected")


if __name__ == "__main__":
    main()
