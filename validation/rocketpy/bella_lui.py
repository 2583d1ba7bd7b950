"""Bella Lui (EPFL Rocket Team, Kaltbrunn, 2020-02-22) flown by RocketPy in its day's ERA5
weather, and the flight computer's log read as RocketPy's acceptance test reads it.

The rocket is RocketPy's example notebook's (``docs/examples/bella_lui_flight_sim.ipynb``)
with the motor placed physically: the nozzle exit 2.6776 m aft of the nose tip and the
grains' center 0.3 m forward of it (the acceptance test places the motor twice over,
putting the propellant more than a metre too far aft; see
``validation/real-flights/bella-lui/README.md``). hpr-mc flies the same set-up from
``scenarios/bella_lui.toml`` (``engine/sim/tests/flight_proof/bella_lui.rs``).

Recorded (``bella_lui_reference.json``):

* ``rocketpy``: RocketPy 1.13's flight as it is, and ``corrected``: with its lever arm's
  sign corrected and the true speed of sound sqrt(1.4 R T) in its air (``corrections.py``,
  as every cross-check corrects them), each with the acceptance test's figures and its
  height every 0.05 s to landing (for the picture);
* ``measured``: the log's figures as the acceptance test takes them: the highest height
  and its time, the largest vertical speed, the largest acceleration of the vertical speed's
  difference quotients smoothed by scipy's Savitzky-Golay filter (window 51, order 3), the
  vertical speed where the height first falls below zero (touchdown), and the log's rows.

Run from the repository root:
    .venv/bin/python validation/rocketpy/bella_lui.py
"""

import importlib.metadata
import json
import math
import os
import sys
import warnings

import numpy as np
import scipy
from scipy.signal import savgol_filter

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import corrections  # noqa: E402
from rocketpy import Environment, Flight, Function, Rocket, SolidMotor  # noqa: E402

REPO = os.path.dirname(os.path.dirname(HERE))
DATA = os.path.join(REPO, "validation", "real-flights", "bella-lui")
OUT = os.path.join(HERE, "bella_lui_reference.json")

# The set-up (RocketPy's parameters, positions from the center of dry mass, nose positive).
CG_FROM_TIP_M = 1.542
DRAG = [(0.01, 0.51), (0.02, 0.46), (0.04, 0.43), (0.28, 0.43), (0.29, 0.44), (0.45, 0.44),
        (0.49, 0.46)]
CDS_DROGUE = math.pi / 4
# The canopy hpr-mc flies by default: a hemisphere of radius sqrt(CdS / (1.4 pi)).
CANOPY_RADIUS_M = math.sqrt(CDS_DROGUE / (1.4 * math.pi))


def environment():
    env = Environment(gravity=9.81, latitude=47.213476, longitude=9.003336,
                      date=(2020, 2, 22, 13), elevation=407)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        env.set_atmospheric_model(
            type="Reanalysis", file=os.path.join(DATA, "bella_lui_weather_data_ERA5.nc"),
            dictionary="ECMWF")
    env.max_expected_height = 2000
    return env


def rocket(corrected):
    motor = SolidMotor(
        thrust_source=os.path.join(DATA, "AeroTech_K828FJ.eng"),
        burn_time=2.43,
        dry_mass=0.001,
        dry_inertia=(0, 0, 0),
        center_of_dry_mass_position=0.2895,  # the 579 mm motor's middle, as hpr-mc's default
        grains_center_of_mass_position=0.3,
        grain_number=3,
        grain_separation=3 / 1000,
        grain_density=782.4,
        grain_outer_radius=85.598 / 2000,
        grain_initial_inner_radius=33.147 / 1000,
        grain_initial_height=152.4 / 1000,
        nozzle_radius=44.45 / 1000,
        throat_radius=21.4376 / 1000,
        interpolation_method="linear",
        nozzle_position=0,
        coordinate_system_orientation="nozzle_to_combustion_chamber",
    )
    r = Rocket(radius=156 / 2000, mass=18.226, inertia=(0.78267, 0.78267, 0.064244),
               power_off_drag=0.43, power_on_drag=0.43, center_of_mass_without_motor=0)
    r.set_rail_buttons(0.1, -0.5)
    r.add_motor(motor, position=-1.1356)
    r.add_nose(length=0.242, kind="tangent", position=1.3 + 0.242)
    r.add_trapezoidal_fins(3, span=0.200, root_chord=0.280, tip_chord=0.125, position=-0.75)
    r.add_tail(top_radius=156 / 2000, bottom_radius=135 / 2000, length=0.050,
               position=-1.0856)
    r.power_off_drag = Function(DRAG, "Mach Number", "Drag Coefficient with Power Off",
                                "linear", "constant")
    r.power_on_drag = Function(DRAG, "Mach Number", "Drag Coefficient with Power On",
                               "linear", "constant")
    r.add_parachute("Drogue", cd_s=CDS_DROGUE, trigger="apogee", sampling_rate=105, lag=1,
                    radius=CANOPY_RADIUS_M, height=CANOPY_RADIUS_M, porosity=0.0432)
    if corrected:
        corrections.correct(r)
    return r


def fly(corrected):
    env = environment()
    if corrected:
        corrections.true_speed_of_sound(env)
    flight = Flight(rocket=rocket(corrected), environment=env, rail_length=4.2,
                    inclination=89, heading=45, max_time=200)
    elevation = env.elevation
    t = np.arange(0.0, flight.t_final, 0.05)
    heights = [float(flight.z(x) - elevation) for x in t] + [0.0]
    times = [float(x) for x in t] + [float(flight.t_final)]
    vz = [float(flight.vz(x)) for x in np.arange(0.0, flight.t_final, 0.005)]
    az = [float(flight.az(x)) for x in np.arange(0.0, flight.t_final, 0.005)]
    return {
        "apogee_agl_m": float(flight.apogee - elevation),
        "apogee_time_s": float(flight.apogee_time),
        "max_vertical_speed_m_s": max(vz),
        "max_vertical_acceleration_m_s2": max(az),
        "rail_exit_speed_m_s": float(flight.out_of_rail_velocity),
        "impact_time_s": float(flight.t_final),
        "impact_vertical_speed_m_s": float(flight.vz(flight.t_final)),
        "impact_x_m": float(flight.x_impact),
        "impact_y_m": float(flight.y_impact),
        "static_margin_at_liftoff_cal": float(flight.rocket.static_margin(0)),
        "height_every_50_ms": {"time_s": times, "height_m": heights},
    }


def measured():
    rows = np.loadtxt(os.path.join(DATA, "bella_lui_flight_data_filtered.csv"), skiprows=1,
                      delimiter=",", usecols=(2, 3, 4))
    t, z, v = rows[:, 0], rows[:, 1], rows[:, 2]
    # The acceptance test's acceleration: difference quotients of the vertical speed (0 for
    # the first row), Savitzky-Golay smoothed (51 rows, cubic), over its first 573 rows.
    n = 573
    acc = [0.0] + [(v[i] - v[i - 1]) / (t[i] - t[i - 1]) for i in range(1, n)]
    smooth = savgol_filter(acc, 51, 3)
    k = int(np.argmax(z))
    below = int(np.argmax(z[k:] < 0.0)) + k
    # Touchdown: where the height crosses zero, between the last row above and the first
    # below, linearly.
    t0 = t[below - 1] + (t[below] - t[below - 1]) * z[below - 1] / (z[below - 1] - z[below])
    return {
        "apogee_agl_m": float(z[k]),
        "apogee_time_s": float(t[k]),
        "max_vertical_speed_m_s": float(np.max(v[:n])),
        "max_acceleration_smoothed_m_s2": float(np.max(smooth)),
        "max_acceleration_time_s": float(t[int(np.argmax(smooth))]),
        "touchdown_time_s": float(t0),
        "touchdown_vertical_speed_m_s": float(v[below - 1]),
        "rows_used_for_acceleration": n,
    }


def main():
    record = {
        "about": __doc__.strip().splitlines()[0],
        "rocketpy_version": importlib.metadata.version("rocketpy"),
        "scipy_version": scipy.__version__,
        "measured": measured(),
        "rocketpy": fly(corrected=False),
        "corrected": fly(corrected=True),
    }
    for k in ("rocketpy", "corrected"):
        f = record[k]
        print(f"{k:9s}: apogee {f['apogee_agl_m']:.2f} m at {f['apogee_time_s']:.3f} s, max vz "
              f"{f['max_vertical_speed_m_s']:.2f} m/s, max az "
              f"{f['max_vertical_acceleration_m_s2']:.2f} m/s2, impact {f['impact_time_s']:.2f} s "
              f"at {f['impact_vertical_speed_m_s']:.2f} m/s, margin "
              f"{f['static_margin_at_liftoff_cal']:.3f}")
    m = record["measured"]
    print(f"measured : apogee {m['apogee_agl_m']:.2f} m at {m['apogee_time_s']:.2f} s, max vz "
          f"{m['max_vertical_speed_m_s']:.2f} m/s, max acc {m['max_acceleration_smoothed_m_s2']:.2f}"
          f" m/s2, touchdown {m['touchdown_time_s']:.2f} s at "
          f"{m['touchdown_vertical_speed_m_s']:.2f} m/s")
    with open(OUT, "w") as fh:
        json.dump(record, fh, indent=1)
    print("wrote", OUT)


if __name__ == "__main__":
    main()
