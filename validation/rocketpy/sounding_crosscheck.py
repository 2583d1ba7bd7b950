"""A radiosonde sounding read by RocketPy and by hpr-mc: the same air, the same wind, the same
flight.

RocketPy reads the University of Wyoming's text listing with
``Environment.set_atmospheric_model(type="wyoming_sounding", file=URL)``; it fetches the URL,
so its fetch is handed the bundled file instead
(``validation/soundings/synthetic-wyoming.txt``, a synthetic listing in the server's exact
layout: see its generator). hpr-mc reads the same file (``hpr_sim::sounding``). The record
keeps RocketPy's air and wind at heights over the site (temperature, pressure, density,
speed of sound, wind east and north), which ``engine/sim/tests/flight_proof/
sounding_crosscheck.rs`` compares with hpr-mc's, and RocketPy's flight of
``design_crosscheck.py``'s ``elliptical_fins`` (102 mm, L1115, to 3.9 km) through that air,
built exactly as there with its lever arm corrected (``lever_arm_corrected``: the air is the
sounding's in both, not the standard one ``as_hpr_models`` corrects).

What RocketPy 1.13 does with the heights: the listing's are geopotential metres, and
``process_wyoming_sounding`` converts them to geometric ones only after it has set the
temperature and the pressure, so those two are read at geopotential heights taken as
geometric (the wind at geometric ones): its air at 5 km is the sounding's 4 m higher. The
record keeps RocketPy's air as it reads it, and two flights: ``as_rocketpy_reads_it`` and
``heights_geometric``, where RocketPy's own temperature and pressure functions are read at
the geopotential height of each geometric one (``corrections.set_air``), which is what the
listing means and what hpr-mc reads.

How the two differ, by design: RocketPy interpolates the reported pressures linearly in height
between levels and hpr-mc carries the site's up hydrostatically through the temperatures
(the listing's pressures are the dry air's to their rounding, so hpr-mc's meet them at the
levels and RocketPy's are a little high between them, where the true pressure curves);
RocketPy's site is the station's listed elevation (1400.0 m), hpr-mc is handed the same.

Run from the repository root after ``cargo build --release``:
    .venv/bin/python validation/rocketpy/sounding_crosscheck.py
"""

import importlib.metadata
import os
import sys
from types import SimpleNamespace

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import corrections  # noqa: E402
import design_crosscheck as dc  # noqa: E402  (the rocket and its flight, as there)
import rocketpy.environment.environment as rp_environment  # noqa: E402
from corrections import _R0 as R0  # noqa: E402

OUT = os.path.join(HERE, "sounding_crosscheck_reference.json")
SOUNDING = os.path.join(dc.REPO, "validation", "soundings", "synthetic-wyoming.txt")
ROCKET = "elliptical_fins"
# Heights above the site where the air and the wind are recorded, m.
HEIGHTS = [float(h) for h in range(0, 8001, 50)]


def read_sounding(env):
    """RocketPy's wyoming_sounding, its fetch handed the bundled file."""
    with open(SOUNDING) as fh:
        text = fh.read()
    fetch = rp_environment.fetch_wyoming_sounding
    rp_environment.fetch_wyoming_sounding = lambda _url: SimpleNamespace(text=text)
    try:
        env.set_atmospheric_model(type="wyoming_sounding", file="bundled")
    finally:
        rp_environment.fetch_wyoming_sounding = fetch


def read_sounding_geometric(env):
    """``read_sounding``, then RocketPy's own temperature and pressure read at the
    geopotential height of each geometric one (and its barometric height made geometric)."""
    read_sounding(env)
    temperature, pressure, barometric = env.temperature, env.pressure, env.barometric_height

    def air(z):
        h = R0 * z / (R0 + z)
        return temperature(h), pressure(h)

    def height_of(p):
        h = barometric(p)
        return R0 * h / (R0 - h)

    corrections.set_air(env, air, height_of)


def main():
    spec, geo = dc.rocket(ROCKET)
    env, _, rocket, flight = dc.build(spec, geo, wind="calm", lever_arm=True, air=read_sounding)
    site = env.elevation
    air = [{
        "height_m": h,
        "temperature_k": float(env.temperature(site + h)),
        "pressure_pa": float(env.pressure(site + h)),
        "density_kg_m3": float(env.density(site + h)),
        "speed_of_sound_m_s": float(env.speed_of_sound(site + h)),
        "wind_east_m_s": float(env.wind_velocity_x(site + h)),
        "wind_north_m_s": float(env.wind_velocity_y(site + h)),
    } for h in HEIGHTS]
    out = dc.outputs(env, rocket, flight)
    env_g, _, rocket_g, flight_g = dc.build(spec, geo, wind="calm", lever_arm=True,
                                            air=read_sounding_geometric)
    geometric = dc.outputs(env_g, rocket_g, flight_g)
    for name, o in (("as RocketPy reads it", out), ("heights geometric", geometric)):
        print(f"{name}: site {site} m; apogee {o['apogee_agl_m']:.2f} m at"
              f" {o['apogee_time_s']:.3f} s; impact ({o['impact_x_m']:.1f},"
              f" {o['impact_y_m']:.1f}) at {o['impact_time_s']:.2f} s")
    dc.write_reference(OUT, {
        "generator": "validation/rocketpy/sounding_crosscheck.py",
        "rocketpy_version": importlib.metadata.version("rocketpy"),
        "rocket": ROCKET,
        "sounding": "validation/soundings/synthetic-wyoming.txt",
        "site_elevation_m": site,
        "air": air,
        "as_rocketpy_reads_it": out,
        "heights_geometric": geometric,
    })


if __name__ == "__main__":
    main()
