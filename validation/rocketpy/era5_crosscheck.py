"""The ERA5 file of Bella Lui's day read by RocketPy, and by a second reader written here,
for hpr-mc's weather reader to be checked against (``engine/sim/src/weather/tests.rs``).

RocketPy 1.13 reads the file with ``Environment(...).set_atmospheric_model(type="Reanalysis",
file=..., dictionary="ECMWF")`` over the launch site of Bella Lui (47.213476 N, 9.003336 E,
407 m) at 2020-02-22 13:00 UTC, one of the file's own times. The record keeps its air and wind
every 100 m from the ground to the file's top level: temperature, pressure, density, speed of
sound, wind speed and direction, east and north components. It reads the NetCDF-4 copy of the
same file (``validation/weather/bella_lui_era5_netcdf4.nc``, Copernicus's 2024 layout) too,
which RocketPy must find the same.

The second reader (``independent_levels``) is numpy on netCDF4's unpacked values: each level's
geopotential height, temperature and wind bilinear in latitude and longitude at the site,
linear in time between the file's two times around the launch, the heights made geometric
with the WGS 84 radius at the site's latitude. It records the levels at 13:00 (a file time)
and at 12:30 and 15:24 (between times), which RocketPy cannot give (it takes the nearest time).

Run from the repository root:
    .venv/bin/python validation/rocketpy/era5_crosscheck.py
"""

import datetime
import importlib.metadata
import json
import math
import os
import warnings

import netCDF4
import numpy as np
from rocketpy import Environment

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
CLASSIC = "validation/real-flights/bella-lui/bella_lui_weather_data_ERA5.nc"
NETCDF4 = "validation/weather/bella_lui_era5_netcdf4.nc"
OUT = os.path.join(HERE, "era5_crosscheck_reference.json")
SITE = {"latitude_deg": 47.213476, "longitude_deg": 9.003336, "elevation_m": 407.0}
LAUNCH = datetime.datetime(2020, 2, 22, 13, 0)
G0 = 9.80665


def wgs84_radius(lat_deg):
    a, f = 6378137.0, 1.0 / 298.257223563
    b = a * (1.0 - f)
    p = math.radians(lat_deg)
    c, s = math.cos(p), math.sin(p)
    return math.sqrt(((a * a * c) ** 2 + (b * b * s) ** 2) / ((a * c) ** 2 + (b * s) ** 2))


def rocketpy_profile(path):
    env = Environment(date=(LAUNCH.year, LAUNCH.month, LAUNCH.day, LAUNCH.hour),
                      latitude=SITE["latitude_deg"], longitude=SITE["longitude_deg"],
                      elevation=SITE["elevation_m"])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        env.set_atmospheric_model(type="Reanalysis", file=os.path.join(REPO, path),
                                  dictionary="ECMWF")
    top = float(max(env.height))
    rows = []
    h = 0.0
    while SITE["elevation_m"] + h <= top:
        z = SITE["elevation_m"] + h
        rows.append({
            "height_m": h,
            "temperature_k": float(env.temperature(z)),
            "pressure_pa": float(env.pressure(z)),
            "density_kg_m3": float(env.density(z)),
            "speed_of_sound_m_s": float(env.speed_of_sound(z)),
            "wind_speed_m_s": float(env.wind_speed(z)),
            "wind_from_deg": float(env.wind_direction(z)),
            "wind_east_m_s": float(env.wind_velocity_x(z)),
            "wind_north_m_s": float(env.wind_velocity_y(z)),
        })
        h += 100.0
    # At each level: where RocketPy's speed and direction (interpolated as themselves
    # between levels, not as the components it flies) are the levels' own.
    levels = [{"height_msl_m": float(hh), "pressure_pa": float(p),
               "wind_speed_m_s": float(env.wind_speed(hh)),
               "wind_from_deg": float(env.wind_direction(hh)),
               "temperature_k": float(env.temperature(hh))}
              for hh, p in zip(env.height, env.levels)]
    return {"earth_radius_m": float(env.earth_radius), "top_msl_m": top, "rows": rows,
            "levels": levels}


def independent_levels(path, when):
    d = netCDF4.Dataset(os.path.join(REPO, path))
    d.set_auto_maskandscale(True)
    tname = "valid_time" if "valid_time" in d.variables else "time"
    lname = "pressure_level" if "pressure_level" in d.variables else "level"
    times = netCDF4.num2date(d[tname][:], d[tname].units, only_use_cftime_datetimes=False,
                             only_use_python_datetimes=True)
    times = [t.replace(tzinfo=None) for t in times]
    k = max(i for i, t in enumerate(times) if t <= when)
    k = min(k, len(times) - 2)
    w = (when - times[k]).total_seconds() / (times[k + 1] - times[k]).total_seconds()
    lat = np.asarray(d["latitude"][:], dtype=float)
    lon = np.asarray(d["longitude"][:], dtype=float)

    def around(c, x):
        for i in range(len(c) - 1):
            if min(c[i], c[i + 1]) <= x <= max(c[i], c[i + 1]):
                return i, (x - c[i]) / (c[i + 1] - c[i])
        raise ValueError("outside")

    i, fy = around(lat, SITE["latitude_deg"])
    j, fx = around(lon, SITE["longitude_deg"])

    def site(name, t):
        v = np.asarray(d[name][t, :, i:i + 2, j:j + 2], dtype=float)
        return ((1 - fy) * (1 - fx) * v[:, 0, 0] + (1 - fy) * fx * v[:, 0, 1]
                + fy * (1 - fx) * v[:, 1, 0] + fy * fx * v[:, 1, 1])

    def at(name):
        a, b = site(name, k), site(name, k + 1)
        return a if w == 0.0 else a + w * (b - a)

    r = wgs84_radius(SITE["latitude_deg"])
    hgt = at("z") / G0
    out = []
    for n, p in enumerate(np.asarray(d[lname][:], dtype=float)):
        out.append({
            "pressure_pa": p * 100.0,
            "height_msl_m": r * hgt[n] / (r - hgt[n]),
            "temperature_k": float(at("t")[n]),
            "wind_east_m_s": float(at("u")[n]),
            "wind_north_m_s": float(at("v")[n]),
        })
    d.close()
    return sorted(out, key=lambda lv: -lv["pressure_pa"])


def main():
    record = {
        "about": __doc__.strip().splitlines()[0],
        "rocketpy_version": importlib.metadata.version("rocketpy"),
        "netcdf4_version": importlib.metadata.version("netCDF4"),
        "site": SITE,
        "launch_utc": "2020-02-22T13:00:00Z",
        "classic_file": CLASSIC,
        "netcdf4_file": NETCDF4,
        "rocketpy_classic": rocketpy_profile(CLASSIC),
        "rocketpy_netcdf4": rocketpy_profile(NETCDF4),
        "independent": {
            label: independent_levels(CLASSIC, when) for label, when in [
                ("2020-02-22T13:00:00Z", LAUNCH),
                ("2020-02-22T12:30:00Z", datetime.datetime(2020, 2, 22, 12, 30)),
                ("2020-02-22T15:24:00Z", datetime.datetime(2020, 2, 22, 15, 24)),
            ]
        },
    }
    a, b = record["rocketpy_classic"]["rows"], record["rocketpy_netcdf4"]["rows"]
    worst = max(abs(x["temperature_k"] - y["temperature_k"]) for x, y in zip(a, b))
    print(f"RocketPy, classic against NetCDF-4: temperatures within {worst:.2e} K over "
          f"{len(a)} heights")
    with open(OUT, "w") as fh:
        json.dump(record, fh, indent=1)
    print("wrote", OUT)


if __name__ == "__main__":
    main()
