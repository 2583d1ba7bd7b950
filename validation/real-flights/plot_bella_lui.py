"""The picture of Bella Lui's flight: height against time as its flight computer logged it,
as hpr-mc flies it (scenarios/bella_lui.toml) and as RocketPy flies it
(validation/rocketpy/bella_lui_reference.json); beside it, the apogees of the scenario's
1,000 Monte Carlo variants with the measured one marked. Writes bella_lui.png here.

Run from the repository root after `cargo build --release`:
    .venv/bin/python validation/real-flights/plot_bella_lui.py
"""

import csv
import json
import os
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pyarrow.parquet as pq  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
HPR = os.path.join(REPO, "target", "release", "hpr-mc")


def log():
    rows = np.loadtxt(os.path.join(HERE, "bella-lui", "bella_lui_flight_data_filtered.csv"),
                      skiprows=1, delimiter=",", usecols=(2, 3, 4))
    return rows[:, 0], rows[:, 1]


def hpr_flight(tmp):
    path = os.path.join(tmp, "flight.csv")
    subprocess.run([HPR, "fly", "--scenario", "scenarios/bella_lui.toml", "--trajectory", path],
                   cwd=REPO, check=True, capture_output=True)
    with open(path) as fh:
        rows = list(csv.DictReader(fh))
    t = np.array([float(r["time_s"]) for r in rows])
    z = np.array([float(r["altitude_m"]) for r in rows])
    return t, z - z[0], z[0]


def hpr_campaign(tmp):
    out = os.path.join(tmp, "mc")
    subprocess.run([HPR, "scenarios/bella_lui.toml", "--quiet", "--out", out], cwd=REPO,
                   check=True, capture_output=True)
    return pq.read_table(os.path.join(out, "variants.parquet")).column("apogee_m").to_numpy()


def main():
    ref = json.load(open(os.path.join(REPO, "validation", "rocketpy", "bella_lui_reference.json")))
    with tempfile.TemporaryDirectory() as tmp:
        t_hpr, z_hpr, start_m = hpr_flight(tmp)
        apogees = hpr_campaign(tmp)
    t_log, z_log = log()
    rp = ref["rocketpy"]["height_every_50_ms"]
    # The clocks aligned where the rocket has risen the log's first height (0.201 m).
    offset = float(np.interp(z_log[0], z_hpr[: np.argmax(z_hpr)], t_hpr[: np.argmax(z_hpr)]))

    fig, (ax, hist) = plt.subplots(1, 2, figsize=(13, 5.2),
                                   gridspec_kw={"width_ratios": [1.7, 1.0]})
    ax.plot(t_log + offset, z_log, color="black", lw=2.2, label="measured (flight computer)")
    ax.plot(t_hpr, z_hpr, color="tab:blue", lw=1.4, label="hpr-mc")
    ax.plot(rp["time_s"], rp["height_m"], color="tab:orange", lw=1.2, ls="--",
            label="RocketPy 1.13")
    ax.set_xlabel("time since ignition, s (the log aligned at 0.2 m of rise)", fontsize=11)
    ax.set_ylabel("height above the pad, m", fontsize=11)
    ax.set_title("Bella Lui, Kaltbrunn, 2020-02-22 13:00 UTC, in its ERA5 weather", fontsize=12)
    ax.set_xlim(0, 38)
    ax.set_ylim(-10, 500)
    ax.grid(alpha=0.3)
    ax.legend(loc="center right", fontsize=10)
    m = ref["measured"]
    ax.annotate(f"apogee: measured {m['apogee_agl_m']:.1f} m\nhpr-mc {z_hpr.max():.1f} m, "
                f"RocketPy {ref['rocketpy']['apogee_agl_m']:.1f} m",
                xy=(10.6, 459), xytext=(14.5, 462), fontsize=10,
                arrowprops={"arrowstyle": "->", "color": "gray"})

    # The campaign's apogee is the center of mass's above the ground: less its start, a rise.
    rise = apogees - start_m
    hist.hist(rise, bins=40, color="tab:blue", alpha=0.75)
    p5, p95 = np.percentile(rise, [5, 95])
    hist.axvspan(p5, p95, color="tab:blue", alpha=0.08, label="5 to 95 % of the variants")
    hist.axvline(m["apogee_agl_m"], color="black", lw=2.2,
                 label=f"measured {m['apogee_agl_m']:.1f} m "
                       f"({100 * np.mean(rise < m['apogee_agl_m']):.0f} % below it)")
    hist.set_xlabel("apogee above the pad, m", fontsize=11)
    hist.set_ylabel("variants", fontsize=11)
    hist.set_title(f"Monte Carlo: {len(rise)} variants (team's dispersions,\nlaunch within "
                   "an hour of 13:00 UTC)", fontsize=12)
    counts, _ = np.histogram(rise, bins=40)
    hist.set_ylim(0, 1.35 * counts.max())
    hist.legend(loc="upper left", fontsize=9)
    hist.grid(alpha=0.3)
    fig.tight_layout()
    out = os.path.join(HERE, "bella_lui.png")
    fig.savefig(out, dpi=110)
    print("wrote", out)


if __name__ == "__main__":
    main()
