"""Make the weather files the reader's tests use, from the ERA5 file of Bella Lui's day.

The ERA5 file (``validation/real-flights/bella-lui/bella_lui_weather_data_ERA5.nc``) is the
classic layout: NetCDF-3, ``time``/``level``/``latitude``/``longitude``, values packed as short
integers with ``scale_factor`` and ``add_offset``. Weather-model files reach users in other
layouts too; each one written here holds the same weather (or a stated change of it), so that a
test can ask the reader for the same site and time in every layout and get the same air:

* ``bella_lui_era5_netcdf4.nc``: the layout the Copernicus Climate Data Store has delivered
  since 2024: NetCDF-4 (HDF5 inside, zlib-compressed chunks), ``valid_time`` in seconds since
  1970, ``pressure_level`` in hPa stored from 1000 down to 600 (the classic file stores them
  600 up to 1000), a scalar ``number`` and an ``expver`` string per time, ``z``, ``t``, ``u``,
  ``v`` as unpacked 32-bit floats with NaN as their fill value. The values are the classic
  file's unpacked ones rounded to float32 (1e-7 of themselves).
* ``bella_lui_gfs_like.nc``: a forecast in the names of NOAA's THREDDS NetCDF subset service
  for GFS: ``time`` in "Hour since ...", ``isobaric`` in Pa, ``lat``/``lon``,
  ``Geopotential_height_isobaric`` (geopotential metres: the geopotential over 9.80665),
  ``Temperature_isobaric``, ``u-component_of_wind_isobaric``,
  ``v-component_of_wind_isobaric``; only the three times 12:00, 13:00 and 18:00.
* ``bella_lui_ensemble.nc``: an ensemble on pressure levels with a ``number`` dimension of three
  members (NetCDF-4, the Copernicus names): member k has the ERA5 temperature plus 0.5 k K and
  the ERA5 wind times (1 + 0.1 k); the geopotential is the same in all. Its longitudes are
  relabelled 0-360 east of a meridian 340 degrees away (every longitude plus 340), so that a
  site given at -10.996664 degrees (9.003336 - 20) finds the grid by wrapping to 349.003336.
* ``broken_no_north_wind.nc``, ``broken_nan_temperature.nc``: a 2 x 2 cut of the ERA5 file
  around the site at 12:00 and 13:00 without its ``v``, and with a NaN in ``t`` (at 13:00,
  875 hPa) where its fill value is -9999: files the reader must refuse, naming why.

Run from the repository root (netCDF4 and numpy; the venv of validation/rocketpy has both):
    .venv/bin/python validation/weather/make_weather_files.py
"""

import os

import netCDF4
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
ERA5 = os.path.join(REPO, "validation", "real-flights", "bella-lui",
                    "bella_lui_weather_data_ERA5.nc")
G0 = 9.80665
FIELDS = {
    "z": ("geopotential", "m**2 s**-2", "Geopotential"),
    "t": ("air_temperature", "K", "Temperature"),
    "u": ("eastward_wind", "m s**-1", "U component of wind"),
    "v": ("northward_wind", "m s**-1", "V component of wind"),
}


def read_era5():
    src = netCDF4.Dataset(ERA5)
    src.set_auto_maskandscale(True)
    times = netCDF4.num2date(src["time"][:], src["time"].units,
                             only_use_cftime_datetimes=False,
                             only_use_python_datetimes=True)
    data = {
        "times": [t.replace(tzinfo=None) for t in times],
        "level_hpa": np.asarray(src["level"][:], dtype=np.float64),
        "lat": np.asarray(src["latitude"][:], dtype=np.float64),
        "lon": np.asarray(src["longitude"][:], dtype=np.float64),
    }
    for name in FIELDS:
        data[name] = np.asarray(src[name][:], dtype=np.float64)
    src.close()
    return data


def seconds_since_1970(times):
    import datetime
    epoch = datetime.datetime(1970, 1, 1)
    return np.array([int((t - epoch).total_seconds()) for t in times], dtype=np.int64)


def write_cds2024(era, path, members=0, lon_shift=0.0):
    """The Climate Data Store's NetCDF-4 layout; with ``members``, an ensemble file with a
    ``number`` dimension whose member k holds ``member(k, ...)``."""
    out = netCDF4.Dataset(path, "w", format="NETCDF4")
    out.Conventions = "CF-1.7"
    out.institution = "European Centre for Medium-Range Weather Forecasts"
    out.history = ("Made by hpr-mc's validation/weather/make_weather_files.py from the ERA5 "
                   "file of 2020-02-22 (RocketPy's bella_lui_weather_data_ERA5.nc)")
    nt, nl = len(era["times"]), len(era["level_hpa"])
    if members:
        out.createDimension("number", members)
    out.createDimension("valid_time", nt)
    out.createDimension("pressure_level", nl)
    out.createDimension("latitude", len(era["lat"]))
    out.createDimension("longitude", len(era["lon"]))
    if members:
        number = out.createVariable("number", "i8", ("number",))
        number[:] = np.arange(members)
    else:
        number = out.createVariable("number", "i8", ())
        number.assignValue(0)
    number.long_name = "ensemble member numerical id"
    number.units = "1"
    number.standard_name = "realization"
    vt = out.createVariable("valid_time", "i8", ("valid_time",))
    vt.long_name = "time"
    vt.standard_name = "time"
    vt.units = "seconds since 1970-01-01"
    vt.calendar = "proleptic_gregorian"
    vt[:] = seconds_since_1970(era["times"])
    pl = out.createVariable("pressure_level", "f8", ("pressure_level",))
    pl.long_name = "pressure"
    pl.units = "hPa"
    pl.positive = "down"
    pl.stored_direction = "decreasing"
    pl.standard_name = "air_pressure"
    order = np.argsort(-era["level_hpa"])  # 1000 hPa first
    pl[:] = era["level_hpa"][order]
    la = out.createVariable("latitude", "f8", ("latitude",))
    la.units = "degrees_north"
    la.standard_name = "latitude"
    la.stored_direction = "decreasing"
    la[:] = era["lat"]
    lo = out.createVariable("longitude", "f8", ("longitude",))
    lo.units = "degrees_east"
    lo.standard_name = "longitude"
    lo[:] = era["lon"] + lon_shift
    ex = out.createVariable("expver", str, ("valid_time",))
    for i in range(nt):
        ex[i] = "0001"
    dims = (("number",) if members else ()) + ("valid_time", "pressure_level", "latitude",
                                               "longitude")
    for name, (standard, units, long_name) in FIELDS.items():
        sizes = ([members] if members else []) + [nt, nl, len(era["lat"]), len(era["lon"])]
        # Chunks of at most two times (and one member), as the service chunks in time.
        chunks = tuple(1 if d == "number" else min(2, s) if d == "valid_time" else s
                       for d, s in zip(dims, sizes))
        var = out.createVariable(name, "f4", dims, zlib=True, complevel=1,
                                 fill_value=np.float32(np.nan), chunksizes=chunks)
        var.units = units
        var.long_name = long_name
        var.standard_name = standard
        var.coordinates = "number valid_time pressure_level latitude longitude expver"
        values = era[name][:, order, :, :]
        if members:
            var[:] = np.stack([member(k, name, values)
                               for k in range(members)]).astype(np.float32)
        else:
            var[:] = values.astype(np.float32)
    out.close()


def write_gfs_like(era, path):
    """NOAA's THREDDS subset names for GFS on isobaric levels, three of the times."""
    import datetime
    keep = [i for i, t in enumerate(era["times"]) if t.hour in (12, 13, 18)]
    out = netCDF4.Dataset(path, "w", format="NETCDF4")
    out.Conventions = "CF-1.6"
    out.history = ("Made by hpr-mc's validation/weather/make_weather_files.py from the ERA5 "
                   "file of 2020-02-22, in the names of NOAA's GFS NetCDF subset service")
    out.createDimension("time", len(keep))
    out.createDimension("isobaric", len(era["level_hpa"]))
    out.createDimension("lat", len(era["lat"]))
    out.createDimension("lon", len(era["lon"]))
    t = out.createVariable("time", "f8", ("time",))
    t.units = "Hour since 2020-02-22T00:00:00Z"
    t.standard_name = "time"
    t.long_name = "GRIB forecast or observation time"
    t.calendar = "proleptic_gregorian"
    base = datetime.datetime(2020, 2, 22)
    t[:] = [(era["times"][i] - base).total_seconds() / 3600.0 for i in keep]
    p = out.createVariable("isobaric", "f4", ("isobaric",))
    p.units = "Pa"
    p.long_name = "Isobaric surface"
    p.positive = "down"
    p[:] = era["level_hpa"] * 100.0
    la = out.createVariable("lat", "f4", ("lat",))
    la.units = "degrees_north"
    la[:] = era["lat"]
    lo = out.createVariable("lon", "f4", ("lon",))
    lo.units = "degrees_east"
    lo[:] = era["lon"]
    names = {
        "z": ("Geopotential_height_isobaric", "gpm", "geopotential_height"),
        "t": ("Temperature_isobaric", "K", "air_temperature"),
        "u": ("u-component_of_wind_isobaric", "m/s", "eastward_wind"),
        "v": ("v-component_of_wind_isobaric", "m/s", "northward_wind"),
    }
    for name, (var_name, units, standard) in names.items():
        var = out.createVariable(var_name, "f4", ("time", "isobaric", "lat", "lon"),
                                 fill_value=np.float32(np.nan))
        var.units = units
        var.standard_name = standard
        values = era[name][keep]
        if name == "z":
            values = values / G0
        var[:] = values.astype(np.float32)
    out.close()


def write_broken(era, path, drop=None, nan_at=None):
    """A small NetCDF-4 file of the ERA5 values around the site (2 x 2 grid points, the 12:00
    and 13:00 times) with one thing wrong: the variable `drop` left out, or a NaN written at
    `nan_at` (variable, index) where the fill value is -9999 (a NaN that marks nothing)."""
    out = netCDF4.Dataset(path, "w", format="NETCDF4")
    lat, lon = era["lat"][3:5], era["lon"][4:6]  # 47.25-47.0 N, 9.0-9.25 E
    out.createDimension("valid_time", 2)
    out.createDimension("pressure_level", len(era["level_hpa"]))
    out.createDimension("latitude", 2)
    out.createDimension("longitude", 2)
    vt = out.createVariable("valid_time", "i8", ("valid_time",))
    vt.units = "seconds since 1970-01-01"
    vt[:] = seconds_since_1970(era["times"][2:4])
    pl = out.createVariable("pressure_level", "f8", ("pressure_level",))
    pl.units = "hPa"
    pl[:] = era["level_hpa"]
    out.createVariable("latitude", "f8", ("latitude",))[:] = lat
    out.createVariable("longitude", "f8", ("longitude",))[:] = lon
    for name, (standard, units, _) in FIELDS.items():
        if name == drop:
            continue
        var = out.createVariable(name, "f4", ("valid_time", "pressure_level", "latitude",
                                              "longitude"), fill_value=np.float32(-9999.0))
        var.units = units
        var.standard_name = standard
        values = era[name][2:4, :, 3:5, 4:6].astype(np.float32)
        if nan_at and nan_at[0] == name:
            values[nan_at[1]] = np.nan
        var[:] = values
    out.close()


def member(k, name, values):
    if name == "t":
        return values + 0.5 * k
    if name in ("u", "v"):
        return values * (1.0 + 0.1 * k)
    return values


def main():
    era = read_era5()
    write_cds2024(era, os.path.join(HERE, "bella_lui_era5_netcdf4.nc"))
    write_gfs_like(era, os.path.join(HERE, "bella_lui_gfs_like.nc"))
    write_cds2024(era, os.path.join(HERE, "bella_lui_ensemble.nc"), members=3,
                  lon_shift=340.0)
    write_broken(era, os.path.join(HERE, "broken_no_north_wind.nc"), drop="v")
    write_broken(era, os.path.join(HERE, "broken_nan_temperature.nc"), nan_at=("t", (1, 3, 0, 1)))
    for f in ("bella_lui_era5_netcdf4.nc", "bella_lui_gfs_like.nc", "bella_lui_ensemble.nc",
              "broken_no_north_wind.nc", "broken_nan_temperature.nc"):
        print(f, os.path.getsize(os.path.join(HERE, f)), "bytes")


if __name__ == "__main__":
    main()
