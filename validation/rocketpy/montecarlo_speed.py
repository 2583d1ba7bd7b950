"""How fast RocketPy flies a Monte Carlo's variants, on this machine, for comparison with
hpr-mc's main job.

The rocket is the 54 mm reference design on its Cesaroni I175 (`design_crosscheck.py`'s
``reference_design``, built as every cross-check builds it: its motor, drag curves, drogue and
main, its canopies opening as there), in a 5 m/s wind, each variant scattered as the main job's scenario scatters its
flights (wind speed ±30 %, drag ±5 %, rail ±0.5° in inclination and ±2° in heading; 1σ,
drawn from a fixed seed). RocketPy 1.13 flies the variants in a pool of worker processes
(``multiprocessing``, as its ``MonteCarlo(parallel=True)`` does), each variant a ``Flight``
built and flown to landing (as hpr-mc flies every variant) or to apogee only
(``terminate_on_apogee``). Building the rocket is inside the timing, as it is in RocketPy's
Monte Carlo; writing results is not (RocketPy's ``MonteCarlo`` would add its JSON files).

Run from the repository root after ``cargo build --release`` (the design's geometry comes
from ``hpr-mc inspect``):
    .venv/bin/python validation/rocketpy/montecarlo_speed.py [FLIGHTS] [WORKERS]
"""

import multiprocessing
import os
import sys
import time
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import design_crosscheck as dc  # noqa: E402
from rocketpy import Environment, Flight  # noqa: E402

SPEC, GEO = None, None


def _init():
    global SPEC, GEO
    warnings.simplefilter("ignore")
    SPEC, GEO = dc.rocket("reference_design")


def fly(args):
    wind_scale, drag_scale, d_inclination, d_heading, to_apogee = args
    spec = dict(SPEC)
    spec["wind"] = dict(SPEC["wind"], speed_m_s=SPEC["wind"]["speed_m_s"] * wind_scale)
    spec["rail"] = dict(SPEC["rail"],
                        inclination_deg=min(90.0, SPEC["rail"]["inclination_deg"] + d_inclination),
                        heading_deg=SPEC["rail"]["heading_deg"] + d_heading)
    geo = dict(GEO)
    geo["drag_power_off"] = [[m, cd * drag_scale] for m, cd in GEO["drag_power_off"]]
    geo["drag_power_on"] = [[m, cd * drag_scale] for m, cd in GEO["drag_power_on"]]
    env = Environment(latitude=dc.SITE["latitude_deg"], longitude=dc.SITE["longitude_deg"],
                      elevation=dc.SITE["elevation_m"])
    u, v = dc.wind_components(spec["wind"]["speed_m_s"], spec["wind"]["from_deg"])
    env.set_atmospheric_model(type="custom_atmosphere", wind_u=u, wind_v=v)
    _, rocket = dc.assemble(spec, geo)
    r, m, rail = geo["rocket_after_burnout"], geo["motor"], spec["rail"]
    flight = Flight(rocket=rocket, environment=env,
                    rail_length=rail["length_m"] - (r["aft_end_m"] - m["aft_m"]),
                    inclination=rail["inclination_deg"], heading=rail["heading_deg"],
                    terminate_on_apogee=to_apogee)
    return float(flight.apogee)


def main():
    flights = int(sys.argv[1]) if len(sys.argv) > 1 else 40
    workers = int(sys.argv[2]) if len(sys.argv) > 2 else 2
    rng = np.random.default_rng(20250601)
    draws = list(zip(1.0 + 0.3 * rng.standard_normal(flights),
                     1.0 + 0.05 * rng.standard_normal(flights),
                     0.5 * rng.standard_normal(flights), 2.0 * rng.standard_normal(flights)))
    for to_apogee in (False, True):
        jobs = [(max(w, 0.0), d, i, h, to_apogee) for w, d, i, h in draws]
        with multiprocessing.Pool(workers, initializer=_init) as pool:
            start = time.perf_counter()
            apogees = pool.map(fly, jobs, chunksize=1)
            wall = time.perf_counter() - start
        what = "to apogee" if to_apogee else "to landing"
        print(f"RocketPy 1.13, {flights} flights {what} in {workers} worker processes: "
              f"{wall:.2f} s, {flights / wall:.2f} flights/s ({wall / flights:.3f} s a flight; "
              f"mean apogee {np.mean(apogees) - dc.SITE['elevation_m']:.1f} m)")


if __name__ == "__main__":
    main()
