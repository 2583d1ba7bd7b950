"""Pure-geometry Barrowman reference numbers from RocketPy.

For each component (nose cones of every kind RocketPy knows, a boattail, three
trapezoidal fin sets, three elliptical ones: span above, below and equal to the
body radius, RocketPy's three cases of the roll damping factor) this computes with RocketPy's own classes:

* the normal-force slope CN_alpha (per rad) as a function of Mach, referenced
  to the area pi * r_ref^2 of the component's ``rocket_radius``;
* the center of pressure in metres aft of the component's leading edge / top,
  both from the component (``cpz``) and from a one-component ``Rocket`` in
  ``nose_to_tail`` orientation with the component at z = 0
  (``Rocket.cp_position(mach)``), which must agree;
* for fins, the intermediate geometry RocketPy derives (area, aspect ratio,
  mid-chord sweep, interference factors) and the roll coefficients.

A composite rocket (ogive nose + 3 fins + boattail) gives a whole-rocket CP,
CN_alpha and ``Rocket.static_margin`` for an integration test.

Run:  .venv/bin/python validation/rocketpy/barrowman.py
Writes validation/rocketpy/barrowman_reference.json next to this file.
"""

import importlib.metadata
import json
import math
import os
import warnings

import numpy as np
from rocketpy import EllipticalFins, FreeFormFins, NoseCone, Rocket, Tail, TrapezoidalFins

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "barrowman_reference.json")
NACA = os.path.join(HERE, "data", "NACA0012-radians.txt")

MACHS = [0.0, 0.3, 0.6, 0.8]
# RocketPy's beta() is clamped to sqrt(1 - 0.8^2) for 0.8 <= M < 1.1 and
# switches to sqrt(M^2 - 1) above; these show that behaviour.
EXTRA_MACHS = [0.9, 1.2]

BODY_RADIUS = 0.02815
NOSE_LENGTH = 0.3
NOSE_KINDS = [
    ("conical", None),
    ("ogive", None),
    ("vonkarman", None),
    ("lvhaack", None),
    ("parabolic", None),
    ("powerseries", 0.5),
    ("elliptical", None),
]
TAIL = {"top_radius_m": 0.02815, "bottom_radius_m": 0.02, "length_m": 0.05,
        "rocket_radius_m": BODY_RADIUS}
FINS3 = {"n": 3, "root_chord_m": 0.12, "tip_chord_m": 0.05, "span_m": 0.07,
         "sweep_length_m": 0.06, "rocket_radius_m": BODY_RADIUS,
         "cant_angle_deg": 0.0, "airfoil": None}
CALISTO_FINS = {"n": 4, "root_chord_m": 0.12, "tip_chord_m": 0.04,
                "span_m": 0.10, "sweep_length_m": None,
                "rocket_radius_m": 0.0635, "cant_angle_deg": 0.0,
                "airfoil": None,
                "note": "tests/fixtures/surfaces/surface_fixtures.py "
                        "calisto_trapezoidal_fins; sweep_length None means "
                        "root - tip = 0.08 m (right trapezoid, trailing edge "
                        "perpendicular to the axis)"}
DOCS_FINS = {"n": 4, "root_chord_m": 0.12, "tip_chord_m": 0.06,
             "span_m": 0.11, "sweep_length_m": None,
             "rocket_radius_m": 0.0635, "cant_angle_deg": 0.5,
             "airfoil": ["data/NACA0012-radians.txt", "radians"],
             "note": "docs/user/first_simulation.rst fin set (NACA 0012 "
                     "table, 0.5 deg cant): shows the airfoil lift slope "
                     "and the roll coefficients"}
ELLIPTICAL_FINS = {
    "fins_elliptical_n3_span_above_radius": {
        "n": 3, "root_chord_m": 0.12, "span_m": 0.07,
        "rocket_radius_m": BODY_RADIUS, "cant_angle_deg": 0.5},
    "fins_elliptical_n4_span_below_radius": {
        "n": 4, "root_chord_m": 0.10, "span_m": 0.04,
        "rocket_radius_m": 0.0635, "cant_angle_deg": 0.0},
    "fins_elliptical_n4_span_equal_radius": {
        "n": 4, "root_chord_m": 0.10, "span_m": 0.05,
        "rocket_radius_m": 0.05, "cant_angle_deg": 1.0},
}
FREE_FORM_FINS = {
    "fins_free_form_n3_notched_delta": {
        "n": 3, "rocket_radius_m": BODY_RADIUS, "cant_angle_deg": 0.5,
        "points_m": [[0.0, 0.0], [0.06, 0.07], [0.09, 0.07], [0.1, 0.04],
                     [0.12, 0.0]]},
    "fins_free_form_n4_trapezoid_calisto": {
        "n": 4, "rocket_radius_m": 0.0635, "cant_angle_deg": 0.0,
        "points_m": [[0.0, 0.0], [0.08, 0.1], [0.12, 0.1], [0.12, 0.0]],
        "note": "Calisto's trapezoid as an outline: RocketPy's free-form numbers "
                "against its own trapezoidal ones show its 40-line sampling"},
}
COMPOSITE = {
    "radius_m": BODY_RADIUS,
    "mass_kg": 1.0,
    "center_of_mass_aft_of_nose_m": 0.55,
    "nose": {"kind": "ogive", "length_m": NOSE_LENGTH, "tip_aft_of_nose_m": 0.0},
    "fins": dict(FINS3, root_leading_edge_aft_of_nose_m=0.80),
    "tail": dict(TAIL, top_aft_of_nose_m=0.95),
    "note": "no motor (RocketPy EmptyMotor); body tube adds no normal force "
            "in RocketPy",
}


def f(x):
    return float(x)


def one_surface_rocket(radius):
    """A Rocket whose z axis points aft with origin at the component's
    leading edge, so cp_position(mach) is the CP aft of that edge."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return Rocket(radius=radius, mass=1.0, inertia=(1.0, 1.0, 0.01),
                      power_off_drag=0.5, power_on_drag=0.5,
                      center_of_mass_without_motor=0.0,
                      coordinate_system_orientation="nose_to_tail")


def curve(fn, machs):
    return {str(m): f(fn(m)) for m in machs}


def surface_record(surface, rocket_radius):
    rocket = one_surface_rocket(rocket_radius)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rocket.add_surfaces(surface, 0.0)
    return {
        "clalpha_per_rad": curve(surface.clalpha, MACHS),
        "clalpha_per_rad_extra_machs": curve(surface.clalpha, EXTRA_MACHS),
        "reference_area_m2": f(surface.reference_area),
        "cp_aft_of_leading_edge_m": f(surface.cpz),
        "cp_from_rocket_cp_position_m": curve(rocket.cp_position, MACHS),
        "rocket_total_clalpha_per_rad": curve(rocket.total_lift_coeff_der,
                                              MACHS),
    }


def nose_records():
    out = {}
    for kind, power in NOSE_KINDS:
        nose = NoseCone(length=NOSE_LENGTH, kind=kind, base_radius=BODY_RADIUS,
                        rocket_radius=BODY_RADIUS, power=power,
                        name=f"nose_{kind}")
        rec = {"kind": kind, "power": power, "length_m": NOSE_LENGTH,
               "base_radius_m": BODY_RADIUS, "rocket_radius_m": BODY_RADIUS,
               "k_cp_over_length": f(nose.k)}
        rec.update(surface_record(nose, BODY_RADIUS))
        label = kind if power is None else f"{kind}_{power}"
        out[label] = rec
    return out


def tail_record():
    tail = Tail(top_radius=TAIL["top_radius_m"],
                bottom_radius=TAIL["bottom_radius_m"],
                length=TAIL["length_m"], rocket_radius=TAIL["rocket_radius_m"],
                name="boattail")
    rec = dict(TAIL)
    rec.update(surface_record(tail, TAIL["rocket_radius_m"]))
    return rec


def make_fins(spec, use_sweep_angle=False):
    kwargs = {}
    if spec["sweep_length_m"] is not None:
        if use_sweep_angle:
            kwargs["sweep_angle"] = math.degrees(
                math.atan(spec["sweep_length_m"] / spec["span_m"]))
        else:
            kwargs["sweep_length"] = spec["sweep_length_m"]
    airfoil = None
    if spec["airfoil"]:
        airfoil = (NACA, spec["airfoil"][1])
    return TrapezoidalFins(
        n=spec["n"], root_chord=spec["root_chord_m"],
        tip_chord=spec["tip_chord_m"], span=spec["span_m"],
        rocket_radius=spec["rocket_radius_m"],
        cant_angle=spec["cant_angle_deg"], airfoil=airfoil, name="fins",
        **kwargs)


def fin_geometry(fins):
    """The planform numbers RocketPy derives for a fin set (any planform)."""
    return {
        "Af_single_fin_area_m2": f(fins.Af),
        "AR_aspect_ratio_2s2_over_Af": f(fins.AR),
        "gamma_c_midchord_sweep_rad": f(fins.gamma_c),
        "Yma_mean_aerodynamic_chord_span_position_m": f(fins.Yma),
        "tau_(s+r)/r": f(fins.tau),
        "lift_interference_factor_1+1/tau": f(fins.lift_interference_factor),
        "roll_forcing_interference_factor": f(
            fins.roll_forcing_interference_factor),
        "roll_damping_interference_factor": f(
            fins.roll_damping_interference_factor),
        "roll_geometrical_constant_m4": f(fins.roll_geometrical_constant),
    }


def roll_record(fins):
    """RocketPy's roll coefficients of a fin set against Mach, and its cant."""
    clf_delta, cld_omega, cant = fins.roll_parameters
    return {
        "roll_forcing_clf_delta_per_rad": curve(clf_delta, MACHS),
        "roll_damping_cld_omega": curve(cld_omega, MACHS),
        "cant_angle_rad": f(cant),
    }


def fin_set_record(fins, spec, *parts):
    """A fin set's record: its spec, its surface's numbers, then `parts` in order."""
    rec = dict(spec)
    rec.update(surface_record(fins, spec["rocket_radius_m"]))
    for part in parts:
        rec.update(part)
    return rec


def fin_record(spec):
    fins = make_fins(spec)
    rec = fin_set_record(fins, spec, {
        "sweep_length_used_m": f(fins.sweep_length),
        "single_fin_clalpha_per_rad": curve(fins.clalpha_single_fin, MACHS),
        "fin_number_factor": f(fins.fin_num_correction(fins.n)),
        "geometry": fin_geometry(fins),
        "airfoil_2d_lift_slope_per_rad": (
            f(fins.airfoil_cl.differentiate(x=1e-3, dx=1e-3))
            if spec["airfoil"] else 2 * math.pi),
    }, roll_record(fins))
    if spec["sweep_length_m"] is not None:
        by_angle = make_fins(spec, use_sweep_angle=True)
        rec["same_fins_given_sweep_angle"] = {
            "sweep_angle_deg": f(math.degrees(math.atan(
                spec["sweep_length_m"] / spec["span_m"]))),
            "clalpha_per_rad": curve(by_angle.clalpha, MACHS),
            "cp_aft_of_leading_edge_m": f(by_angle.cpz),
        }
    return rec


def elliptical_fin_record(spec):
    fins = EllipticalFins(n=spec["n"], root_chord=spec["root_chord_m"],
                          span=spec["span_m"],
                          rocket_radius=spec["rocket_radius_m"],
                          cant_angle=spec["cant_angle_deg"], name="fins")
    return fin_set_record(fins, spec, roll_record(fins), {
        "single_fin_clalpha_per_rad": curve(fins.clalpha_single_fin, MACHS),
        "geometry": fin_geometry(fins),
        "note": "RocketPy puts the CP at 0.288 root chords (rounded); the "
                "quarter point of the mean aerodynamic chord is "
                "C_r (1/2 - 2/(3 pi)) = 0.28779 C_r",
    })


def free_form_fin_record(spec):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fins = FreeFormFins(n=spec["n"],
                            shape_points=[tuple(p) for p in spec["points_m"]],
                            rocket_radius=spec["rocket_radius_m"],
                            cant_angle=spec["cant_angle_deg"], name="fins")
    return fin_set_record(fins, spec, roll_record(fins), {
        "root_chord_m": f(fins.root_chord),
        "span_m": f(fins.span),
        "geometry": dict(fin_geometry(fins), mac_length_m=f(fins.mac_length),
                         mac_lead_m=f(fins.mac_lead)),
        "note": "RocketPy samples the outline on 40 lines across the span "
                "(rectangle rule); hpr on 4000 (midpoint rule)",
    })


def composite_record():
    c = COMPOSITE
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rocket = Rocket(radius=c["radius_m"], mass=c["mass_kg"],
                        inertia=(0.1, 0.1, 0.001), power_off_drag=0.5,
                        power_on_drag=0.5,
                        center_of_mass_without_motor=c[
                            "center_of_mass_aft_of_nose_m"],
                        coordinate_system_orientation="nose_to_tail")
        rocket.add_nose(length=NOSE_LENGTH, kind="ogive", position=0.0)
        fs = c["fins"]
        rocket.add_trapezoidal_fins(
            n=fs["n"], root_chord=fs["root_chord_m"],
            tip_chord=fs["tip_chord_m"], span=fs["span_m"],
            position=fs["root_leading_edge_aft_of_nose_m"],
            sweep_length=fs["sweep_length_m"])
        tl = c["tail"]
        rocket.add_tail(top_radius=tl["top_radius_m"],
                        bottom_radius=tl["bottom_radius_m"],
                        length=tl["length_m"], position=tl["top_aft_of_nose_m"])
    return {
        "inputs": c,
        "cp_aft_of_nose_m": curve(rocket.cp_position, MACHS),
        "clalpha_per_rad": curve(rocket.total_lift_coeff_der, MACHS),
        "static_margin_cal": f(rocket.static_margin(0)),
        "static_margin_definition": "(cp_position(Mach 0) - center_of_mass)"
                                    " / (2 r) in calibers",
        "stability_margin_cal_vs_mach": {
            str(m): f(rocket.stability_margin(m, 0)) for m in MACHS},
    }


def main():
    version = importlib.metadata.version("rocketpy")
    out = {
        "generator": "validation/rocketpy/barrowman.py",
        "rocketpy_version": version,
        "units": "SI; CN_alpha per radian referenced to pi r_ref^2 with "
                 "r_ref the component's rocket_radius; cp in metres aft of "
                 "the component's leading edge (nose tip, tail top, fin root "
                 "leading edge)",
        "machs": MACHS,
        "extra_machs": EXTRA_MACHS,
        "nose_cones": nose_records(),
        "tail": tail_record(),
        "fins_n3": fin_record(FINS3),
        "fins_calisto_n4": fin_record(CALISTO_FINS),
        "fins_calisto_docs_naca0012_cant": fin_record(DOCS_FINS),
        **{k: elliptical_fin_record(v) for k, v in ELLIPTICAL_FINS.items()},
        **{k: free_form_fin_record(v) for k, v in FREE_FORM_FINS.items()},
        "composite_rocket": composite_record(),
    }
    with open(OUT, "w", encoding="utf-8") as fh:
        json.dump(out, fh, indent=2)
        fh.write("\n")
    print(f"rocketpy {version}")
    for name, rec in out["nose_cones"].items():
        print(f"nose {name:16s} CNa {rec['clalpha_per_rad']['0.0']:.4f} "
              f"cp {rec['cp_aft_of_leading_edge_m']:.5f}")
    t = out["tail"]
    print(f"tail CNa {t['clalpha_per_rad']['0.0']:.5f} "
          f"cp {t['cp_aft_of_leading_edge_m']:.5f}")
    for key in ("fins_n3", "fins_calisto_n4", "fins_calisto_docs_naca0012_cant",
                *ELLIPTICAL_FINS, *FREE_FORM_FINS):
        r = out[key]
        print(f"{key} CNa(M) {[round(v, 4) for v in r['clalpha_per_rad'].values()]}"
              f" cp {r['cp_aft_of_leading_edge_m']:.5f}")
    c = out["composite_rocket"]
    print(f"composite cp {c['cp_aft_of_nose_m']} SM {c['static_margin_cal']:.4f}")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
