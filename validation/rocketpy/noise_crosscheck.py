"""RocketPy's noisy parachute barometer against hpr-mc's: where the main fires.

RocketPy reads a parachute's pressure at each of its samples with a noise
(``Parachute(noise=(bias, deviation, correlation))``) and fires a height trigger when the
height that noisy pressure means is below the trigger's. hpr-mc models the same
(``hpr_sim::sensor``). The noise is random, so the check is of distributions: the rocket is
``design_crosscheck.py``'s ``reference_design`` (54 mm, I175, to 1.87 km) in still air,
handed to RocketPy exactly as there with its lever arm and its standard air corrected
(``as_hpr_models``), its drogue at apogee and its main at 200 m, both read at 105 Hz; it
is flown ``FLIGHTS`` times for each noise of ``NOISES`` (RocketPy's example, and a biased,
more correlated, larger one), each time after ``np.random.seed(seed)``. The record keeps the
height of the center of mass above the site at each main trigger (RocketPy's
``parachute_events`` time, its ``z`` there), which
``engine/sim/tests/flight_proof/noise_crosscheck.rs`` compares in mean and deviation with
hpr-mc's own flights over as many of its sensor seeds.

Run from the repository root after ``cargo build --release`` (about 6 minutes):
    .venv/bin/python validation/rocketpy/noise_crosscheck.py
"""

import importlib.metadata
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import design_crosscheck as dc  # noqa: E402  (the rocket and its flight, as there)

OUT = os.path.join(HERE, "noise_crosscheck_reference.json")
ROCKET = "reference_design"
FLIGHTS = 200
# (bias Pa, deviation Pa, correlation): RocketPy's example, and a poor, biased barometer.
NOISES = {"rocketpy_example": (0.0, 8.3, 0.5), "biased_correlated": (6.0, 20.0, 0.8)}


def main_trigger(env, flight):
    """The main's trigger time and the center's height above the site then."""
    t = next(t for t, p in flight.parachute_events if p.name == "main")
    return t, float(flight.z(t) - env.elevation)


def main():
    spec, geo = dc.rocket(ROCKET)
    env, _, _, flight = dc.build(spec, geo, wind="calm", lever_arm=True, air=True)
    t0, h0 = main_trigger(env, flight)
    print(f"noiseless: main fires at {t0:.4f} s, {h0:.4f} m")
    runs = {}
    for name, noise in NOISES.items():
        heights = []
        for seed in range(FLIGHTS):
            np.random.seed(seed)
            env, _, _, flight = dc.build(spec, geo, wind="calm", lever_arm=True, air=True,
                                         noise=noise)
            heights.append(main_trigger(env, flight)[1])
        h = np.array(heights)
        print(f"{name} {noise}: main fires at {h.mean():.4f} ± {h.std(ddof=1):.4f} m"
              f" over {FLIGHTS} flights")
        runs[name] = {
            "noise": {"bias_pa": noise[0], "std_pa": noise[1], "correlation": noise[2]},
            "main_trigger_heights_m": [float(x) for x in heights],
        }
    dc.write_reference(OUT, {
        "generator": "validation/rocketpy/noise_crosscheck.py",
        "rocketpy_version": importlib.metadata.version("rocketpy"),
        "rocket": ROCKET,
        "wind": "calm",
        "sampling_rate_hz": dc.SAMPLING_HZ,
        "main_height_m": spec["main_height_m"],
        "noiseless_main_trigger": {"time_s": t0, "height_m": h0},
        "runs": runs,
    })


if __name__ == "__main__":
    main()
