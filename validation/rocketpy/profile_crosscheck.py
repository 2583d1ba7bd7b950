"""Fly one of hpr-mc's cross-checked rockets in RocketPy through a measured temperature
profile (``environment.air_profile``, ``hpr_sim::atmosphere::AirProfile``) instead of the
standard atmosphere: the check that the profile's air reaches the flight as it should.

The rocket is ``design_crosscheck.py``'s ``elliptical_fins`` (102 mm, L1115, Mach 1.2 to
3.9 km), handed to RocketPy exactly as there (its functions, imported). The air is a hot day
with an inversion over the site (``ROWS``: 305 K at the ground, 309 K at 600 m, 292 K at
2.5 km, 262 K at 6 km, isothermal above) at 86.2 kPa, written here from the hydrostatic law
of each row-to-row layer (temperature linear in geopotential altitude; this file's own
implementation of the law ``hpr_sim::atmosphere`` states, each layer by
``corrections``' standard-air layer law) and given to RocketPy as its
temperature, pressure, density and speed of sound functions, and the exact inverse of the
pressure as its barometric height (the main's trigger), as ``corrections.true_standard_air``
does for the standard air. Flown in the constant wind and in still air, with RocketPy's
lever arm corrected (``as_hpr_models``), into ``profile_crosscheck_reference.json``, which
``engine/sim/tests/flight_proof/profile_crosscheck.rs`` compares with hpr-mc's flight under
the same tolerances as the hand-picked cross-check.

Run from the repository root after ``cargo build --release``:
    .venv/bin/python validation/rocketpy/profile_crosscheck.py
"""

import importlib.metadata
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import design_crosscheck as dc  # noqa: E402  (the rocket and its flight, as there)
import corrections  # noqa: E402
from corrections import _R0 as R0  # noqa: E402
from corrections import _temperature_pressure as layer_air  # noqa: E402  (one layer's law)

OUT = os.path.join(HERE, "profile_crosscheck_reference.json")
ROCKET = "elliptical_fins"
# (height above the site m, temperature K): a hot afternoon with an inversion at 600 m.
ROWS = [(0.0, 305.0), (600.0, 309.0), (2500.0, 292.0), (6000.0, 262.0)]
SITE_PRESSURE_PA = 86200.0


def geopotential(z):
    return R0 * z / (R0 + z)


def layers():
    """(base geopotential m, lapse K/m, base temperature K, base pressure Pa) of each layer."""
    site = dc.SITE["elevation_m"]
    bases = [geopotential(site + h) for h, _ in ROWS]
    out, p = [], SITE_PRESSURE_PA
    for i, (base, (_, t)) in enumerate(zip(bases, ROWS)):
        lapse = (ROWS[i + 1][1] - t) / (bases[i + 1] - base) if i + 1 < len(ROWS) else 0.0
        out.append((base, lapse, t, p))
        if i + 1 < len(ROWS):
            p = layer_air(out[-1], bases[i + 1])[1]
    return out


LAYERS = layers()


def profile_air(z):
    """Temperature (K) and pressure (Pa) at geometric height z above sea level."""
    h = geopotential(z)
    layer = [b for b in LAYERS if b[0] <= h][-1] if h >= LAYERS[0][0] else LAYERS[0]
    return layer_air(layer, h)


def profile_height(p_pa):
    """The geometric height above sea level of the pressure p_pa (bisection to 1e-9 m)."""
    lo, hi = -2000.0, 40000.0
    while hi - lo > 1e-9:
        mid = 0.5 * (lo + hi)
        if profile_air(mid)[1] > p_pa:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def apply_profile(env):
    return corrections.set_air(env, profile_air, profile_height)


def main():
    spec = dc.ROCKETS[ROCKET]
    record = dc.one(ROCKET, spec, winds=())
    _, geo = dc.rocket(ROCKET)
    cases = {}
    for wind in ("wind", "calm"):
        h = dc.case(spec, geo, wind=wind, lever_arm=True, air=apply_profile)
        cases[wind] = {"as_hpr_models": h}
        print(f"{ROCKET} {wind} in the profile: apogee {h['apogee_agl_m']:.2f} m at"
              f" {h['apogee_time_s']:.3f} s; impact ({h['impact_x_m']:.1f},"
              f" {h['impact_y_m']:.1f}) at {h['impact_time_s']:.2f} s")
    record["cases"] = cases
    record["inputs"]["air_profile"] = {
        "elevation_m": dc.SITE["elevation_m"],
        "pressure_pa": SITE_PRESSURE_PA,
        "rows": [{"height_m": h, "temperature_k": t} for h, t in ROWS],
    }
    ref = {
        "generator": "validation/rocketpy/profile_crosscheck.py",
        "rocketpy_version": importlib.metadata.version("rocketpy"),
        "rockets": {ROCKET: record},
    }
    dc.write_reference(OUT, ref)
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
