"""Write ``synthetic-wyoming.txt``: a made-up radiosonde sounding in the University of
Wyoming's text listing (``TEXT:LIST``), for hpr-mc's sounding reader and the RocketPy
cross-check of it. It is not a measurement: the machine this project is built on cannot reach
the University of Wyoming's server, so the file is written here from stated formulas, in the
exact layout of that server's pages (fixed columns of 7 characters, heights in geopotential
metres, wind in knots, blank fields below the ground and where the air is too dry for a dew
point).

The air: a station at 1400 m (as high as Spaceport America's) at 860.0 hPa; the temperature
linear in geopotential height between the breakpoints ``TEMPERATURE`` (a hot afternoon:
a superadiabatic layer at the ground, an inversion at 2.2 km, the tropopause at 12 km, warming
above 20 km), the pressure carried up between levels by the dry hydrostatic law of each
linear piece (g0 = 9.80665, R = 287.05287, as the U.S. Standard Atmosphere 1976), so the
file's pressures are the dry air's, rounded as the server rounds them (0.1 hPa, 1 m, 0.1 °C).
Two mandatory levels below the ground (1000 and 925 hPa) carry only a pressure and a
height, as real listings do; above 12 km there is no dew point (RocketPy drops those
levels, hpr-mc keeps their temperatures and winds). The wind veers and grows to a jet at 10
km (``WIND``). Dew points, humidities and potential temperatures fill the other columns
plausibly; neither reader uses them.

Run: python3 validation/soundings/synthetic_sounding.py (no dependencies).
"""

import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "synthetic-wyoming.txt")
G0, R = 9.80665, 287.05287
SURFACE_M, SURFACE_HPA = 1400.0, 860.0
# (geopotential m, temperature C): linear between these.
TEMPERATURE = [(1400.0, 33.0), (1550.0, 30.8), (2200.0, 25.0), (2500.0, 27.5),
               (6000.0, 1.0), (12000.0, -55.0), (20000.0, -56.0), (30000.0, -46.0)]
# (geopotential m, from deg, knots): linear between these.
WIND = [(1400.0, 200.0, 8.0), (3000.0, 230.0, 20.0), (10000.0, 280.0, 60.0),
        (16000.0, 270.0, 25.0), (30000.0, 90.0, 15.0)]


def interp(table, h, k):
    for (h0, *a), (h1, *b) in zip(table, table[1:]):
        if h0 <= h <= h1:
            return a[k] + (h - h0) / (h1 - h0) * (b[k] - a[k])
    raise ValueError(h)


def temperature_k(h):
    return interp(TEMPERATURE, h, 0) + 273.15


def pressure_pa(h):
    """Dry hydrostatic from the surface up through the linear pieces."""
    p, base = SURFACE_HPA * 100.0, SURFACE_M
    for (h0, _), (h1, _) in zip(TEMPERATURE, TEMPERATURE[1:]):
        if h <= h0:
            break
        top = min(h, h1)
        t0, t1 = temperature_k(h0), temperature_k(top)
        lapse = (temperature_k(h1) - t0) / (h1 - h0)
        if lapse == 0.0:
            p *= math.exp(-G0 * (top - h0) / (R * t0))
        else:
            p *= (t1 / t0) ** (-G0 / (R * lapse))
        base = top
    assert base == h or h == SURFACE_M
    return p


def heights():
    """Every 150 m to 3 km, every 400 m to 12 km, every km above, and each breakpoint."""
    hs = set(int(h) for h, _ in TEMPERATURE)
    hs |= set(range(1400, 3000, 150)) | set(range(3000, 12000, 400)) | set(range(12000, 30001, 1000))
    return sorted(hs)


def row(p_hpa, h, t_c=None, td_c=None, wind=None):
    fields = [f"{p_hpa:7.1f}", f"{h:7d}"]
    if t_c is None:
        return "".join(fields).ljust(77)
    theta = (t_c + 273.15) * (1000.0 / p_hpa) ** 0.2857
    if td_c is None:
        fields += [f"{t_c:7.1f}", " " * 7, " " * 7, " " * 7]
        mixr = 0.0
    else:
        e = 6.112 * math.exp(17.67 * td_c / (td_c + 243.5))
        es = 6.112 * math.exp(17.67 * t_c / (t_c + 243.5))
        mixr = 622.0 * e / (p_hpa - e)
        fields += [f"{t_c:7.1f}", f"{td_c:7.1f}", f"{round(100 * e / es):7d}", f"{mixr:7.2f}"]
    d, s = wind
    theta_e = theta * math.exp(2.5e3 * mixr / 1000.0 / (1.004 * (t_c + 273.15)))
    theta_v = theta * (1.0 + 0.61 * mixr / 1000.0)
    fields += [f"{round(d) % 360:7d}", f"{round(s):7d}", f"{theta:7.1f}", f"{theta_e:7.1f}",
               f"{theta_v:7.1f}"]
    return "".join(fields)


def main():
    lines = [
        "<HTML>",
        "<TITLE>University of Wyoming - Radiosonde Data</TITLE>",
        '<BODY BGCOLOR="white">',
        "<H2>00000 SYN Synthetic Station Observations at 00Z 03 Dec 2026</H2>",
        "<PRE>",
        "-" * 77,
        "   PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SKNT   THTA   THTE   THTV",
        "    hPa     m      C      C      %    g/kg    deg   knot     K      K      K ",
        "-" * 77,
    ]
    # Below the ground: the surface air extrapolated down, as the server lists them.
    t0 = temperature_k(SURFACE_M)
    for p_hpa in (1000.0, 925.0):
        h = SURFACE_M + R * t0 / G0 * math.log(SURFACE_HPA / p_hpa)
        lines.append(row(p_hpa, round(h)))
    for h in heights():
        t_c = temperature_k(h) - 273.15
        td_c = None if h > 12000 else t_c - (8.0 + 2.5 * (h - SURFACE_M) / 1000.0)
        wind = (interp(WIND, h, 0), interp(WIND, h, 1))
        lines.append(row(pressure_pa(h) / 100.0, h, round(t_c, 1), td_c, wind))
    lines += [
        "</PRE><H3>Station information and sounding indices</H3><PRE>",
        "                         Station identifier: SYN",
        "                             Station number: 00000",
        "                           Observation time: 261203/0000",
        "                           Station latitude: 32.99",
        "                          Station longitude: -106.97",
        "                          Station elevation: 1400.0",
        "</PRE>",
        "</BODY></HTML>",
    ]
    with open(OUT, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print(f"wrote {OUT}: {len(lines)} lines")


if __name__ == "__main__":
    main()
