"""Build validation/designs/synthetic-54mm-three-fin.json.

The reference design is synthetic: a believable 54 mm three-fin rocket whose after-burnout
mass properties and static margin are those of the moving-mass worked example
(docs/moving-mass.md, "The worked example": mass 0.8188 kg,
center of mass 0.6681 m aft of the tip, transverse inertia 0.09556 kg m^2, static margin
4.297 calibres). Four free parameters are solved so that hpr-mc's own mass and Barrowman code
give those numbers: the nose weight's mass, the body tube's length, the body tube's density
and the fins' span. The drag curve's scale is then solved (by flying it) so that the apogee
is 1750 m on the Cesaroni I175, as the worked example has it. Run from the repository root after
`cargo build --release`:  python3 validation/designs/tools/make_reference.py
"""
import json, math, subprocess, sys

OUT = "validation/designs/synthetic-54mm-three-fin.json"
HPR = "./target/release/hpr-mc"

# Targets (docs/moving-mass.md, "The worked example").
# The example prints 4 or 5 digits; its table of the moving ballast (rows at 5.25 to 7.00 s)
# pins the unrounded center of mass to [0.668112, 0.668128] m and the inertia to
# [0.0955609, 0.095565] kg m^2, so the targets are the middle of those windows.
M_T, CG_T, I_T, SM_T = 0.8188, 0.66812, 0.095563, 4.2973

# A drag shape typical of a small fin-stabilised rocket (Cd on the body's cross-section),
# scaled as a whole by `drag_scale`.
DRAG_SHAPE = [(0.0, 0.50), (0.1, 0.48), (0.2, 0.465), (0.3, 0.455), (0.4, 0.452), (0.5, 0.455),
              (0.6, 0.465), (0.7, 0.485), (0.8, 0.52), (0.9, 0.60), (1.0, 0.70), (1.1, 0.72),
              (1.2, 0.70), (1.5, 0.63), (2.0, 0.55)]


def design(p):
    nose_w, body_len, rho_body, span, drag_scale = p
    nose_x = 0.12
    avionics = 0.03
    d = 0.0563
    return {
        "name": "Synthetic 54 mm three-fin (hpr-mc reference design)",
        "notes": ("Synthetic reference design of the moving-mass worked example "
                  "(docs/moving-mass.md). Its nose weight, avionics "
                  "mass, body-tube density and fin span were solved (validation/designs/tools/"
                  "make_reference.py) so that after burnout it has the example's mass 0.8188 kg, center "
                  "of mass 0.6681 m, transverse inertia 0.09556 kg m^2 and static margin 4.297 cal; "
                  "its drag curve is a typical shape scaled by %.6f so that it reaches 1750 m on the "
                  "Cesaroni I175. Not a real rocket: tuned, not measured." % drag_scale),
        "motor": "Cesaroni_I175",
        "drag": {"power_off": [[m, round(cd * drag_scale, 6)] for m, cd in DRAG_SHAPE]},
        "stages": [{
            "id": "sustainer",
            "components": [
                {"id": "nose", "type": "nose_cone", "shape": "ogive", "length_m": 0.25,
                 "base_diameter_m": d, "wall_thickness_m": 0.0015,
                 "material": {"name": "polypropylene", "density_kg_m3": 900.0},
                 "shoulder": {"length_m": 0.05, "outer_diameter_m": 0.0533, "wall_thickness_m": 0.002, "capped": True},
                 "children": [
                     {"id": "nose_weight", "type": "mass_component", "mass_kg": round(nose_w, 9),
                      "length_m": 0.03, "radius_m": 0.009,
                      "position": {"from": "nose_tip", "offset_m": round(nose_x, 9)}}]},
                {"id": "body", "type": "body_tube", "length_m": round(body_len, 9), "outer_diameter_m": d,
                 "wall_thickness_m": 0.0015,
                 "material": {"name": "kraft paper", "density_kg_m3": round(rho_body, 6)},
                 "children": [
                     {"id": "avionics", "type": "mass_component", "mass_kg": avionics,
                      "length_m": 0.04, "radius_m": 0.025,
                      "position": {"from": "nose_tip", "offset_m": 0.305}},
                     {"id": "ballast", "type": "mass_component", "mass_kg": 0.2,
                      "length_m": 0.05, "radius_m": 0.02,
                      "position": {"from": "nose_tip", "offset_m": 0.35}},
                     {"id": "bulkhead", "type": "bulkhead", "length_m": 0.006,
                      "outer_diameter_m": 0.0533, "material": {"name": "plywood", "density_kg_m3": 630.0},
                      "position": {"from": "nose_tip", "offset_m": 0.71}},
                     {"id": "shock_cord", "type": "shock_cord", "mass_kg": 0.02, "length_m": 0.04,
                      "radius_m": 0.02, "position": {"from": "nose_tip", "offset_m": 0.72}},
                     {"id": "chute", "type": "parachute", "mass_kg": 0.045, "length_m": 0.08,
                      "radius_m": 0.022, "canopy_diameter_m": 0.9, "cd": 1.5,
                      "position": {"from": "nose_tip", "offset_m": 0.76}},
                     {"id": "drogue", "type": "parachute", "mass_kg": 0.015, "length_m": 0.03,
                      "radius_m": 0.02, "canopy_diameter_m": 0.3, "cd": 1.5,
                      "position": {"from": "nose_tip", "offset_m": 0.84}},
                     {"id": "mmt", "type": "inner_tube", "length_m": 0.26, "outer_diameter_m": 0.0404,
                      "wall_thickness_m": 0.001, "motor_mount": {"overhang_m": 0.01},
                      "material": {"name": "phenolic", "density_kg_m3": 700.0},
                      "position": {"from": "bottom", "offset_m": 0.0}},
                     {"id": "ring_fore", "type": "centering_ring", "length_m": 0.006,
                      "outer_diameter_m": 0.0533, "inner_diameter_m": 0.0404,
                      "material": {"name": "plywood", "density_kg_m3": 630.0},
                      "position": {"from": "bottom", "offset_m": -0.254}},
                     {"id": "ring_aft", "type": "centering_ring", "length_m": 0.006,
                      "outer_diameter_m": 0.0533, "inner_diameter_m": 0.0404,
                      "material": {"name": "plywood", "density_kg_m3": 630.0},
                      "position": {"from": "bottom", "offset_m": 0.0}},
                     {"id": "fins", "type": "fin_set", "count": 3, "root_chord_m": 0.12,
                      "tip_chord_m": 0.05, "span_m": round(span, 9), "sweep_m": 0.06, "thickness_m": 0.003,
                      "cross_section": "rounded",
                      "material": {"name": "plywood", "density_kg_m3": 630.0},
                      "position": {"from": "bottom", "offset_m": 0.0}},
                     {"id": "button_fore", "type": "rail_button", "outer_diameter_m": 0.01,
                      "height_m": 0.008, "mass_kg": 0.002, "position": {"from": "top", "offset_m": 0.45}},
                     {"id": "button_aft", "type": "rail_button", "outer_diameter_m": 0.01,
                      "height_m": 0.008, "mass_kg": 0.002, "position": {"from": "bottom", "offset_m": -0.02}},
                 ]},
            ]}],
    }


def inspect(p):
    with open(OUT, "w") as f:
        json.dump(design(p), f, indent=1)
    out = subprocess.run([HPR, "inspect", OUT, "--json"], capture_output=True, text=True)
    if out.returncode:
        sys.exit(out.stderr)
    r = json.loads(out.stdout)["after_burnout"]
    return r["mass_kg"], r["cg_m"], r["inertia_transverse_kg_m2"], r["static_margin_cal"]


def apogee(p):
    inspect(p)
    out = subprocess.run([HPR, "fly", OUT, "--json", "--rail-length-m", "1.5"], capture_output=True, text=True)
    if out.returncode:
        sys.exit(out.stderr)
    return json.loads(out.stdout)["metrics"]["apogee_m"]


def solve():
    p = [0.04, 0.95, 700.0, 0.06, 1.0]
    scale = [0.01, 0.01, 100.0, 0.01]
    targets = [M_T, CG_T, I_T, SM_T]
    for it in range(30):
        f = [a - b for a, b in zip(inspect(p), targets)]
        if max(abs(x) for x in f) < 1e-12:
            break
        J = []
        for j in range(4):
            q = list(p)
            q[j] += 1e-6 * scale[j]
            fj = [a - b for a, b in zip(inspect(q), targets)]
            J.append([(fj[i] - f[i]) / (1e-6 * scale[j]) for i in range(4)])
        # Solve J^T x = -f (J stored by columns).
        A = [[J[j][i] for j in range(4)] + [-f[i]] for i in range(4)]
        for c in range(4):
            piv = max(range(c, 4), key=lambda r: abs(A[r][c]))
            A[c], A[piv] = A[piv], A[c]
            for r in range(4):
                if r != c:
                    k = A[r][c] / A[c][c]
                    A[r] = [x - k * y for x, y in zip(A[r], A[c])]
        dx = [A[i][4] / A[i][i] for i in range(4)]
        p = [p[i] + dx[i] for i in range(4)] + [p[4]]
        print(it, p, f, file=sys.stderr)
    # Drag scale for 1750 m apogee (secant).
    a0, s0 = apogee(p), p[4]
    s1 = s0 * 1.1
    p[4] = s1
    a1 = apogee(p)
    for _ in range(20):
        s2 = s1 + (1750.0 - a1) * (s1 - s0) / (a1 - a0)
        s0, a0, s1 = s1, a1, s2
        p[4] = s1
        a1 = apogee(p)
        print("drag", s1, a1, file=sys.stderr)
        if abs(a1 - 1750.0) < 0.01:
            break
    print(inspect(p), apogee(p), p)


if __name__ == "__main__":
    solve()
