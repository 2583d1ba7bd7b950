//! Reading a weather-model file on pressure levels: which variable is which, which dimension
//! is which, the grid cell around the site, and the values of that cell unpacked.
//!
//! The file format (NetCDF-3 classic or 64-bit offset, NetCDF-4 on HDF5) is read by the
//! `netcdf-reader` crate (pure Rust, both layouts, hyperslab reads). What it leaves to a user
//! of it, and this module does, is the meaning: the names the weather services give their
//! variables and dimensions, their units, and the CF rule for packed values
//! (`raw × scale_factor + add_offset`, with `_FillValue` and `missing_value` marking a value
//! that is not there).

use super::{SiteWeather, WeatherError, MAX_COLUMN_VALUES, MAX_MEMBERS, MAX_TIMES};
use crate::atmosphere::G0_M_S2;
use netcdf_reader::{NcFile, NcSliceInfo, NcSliceInfoElem, NcVariable};

/// The highest pressure level read, Pa (1100 hPa: no air at the ground is denser).
const MAX_LEVEL_PA: f64 = 110_000.0;

/// The names each quantity goes by, first the CF standard name, then the variable names of
/// ECMWF's ERA5 (classic and 2024), NOAA's GFS from its THREDDS NetCDF subset and OPeNDAP
/// services, and CMIP-style files.
const TIME: &[&str] = &["valid_time", "time", "time1", "time2"];
const LEVEL: &[&str] = &[
    "pressure_level",
    "level",
    "isobaric",
    "isobaric1",
    "isobaric2",
    "lev",
    "plev",
    "pressure",
];
const LATITUDE: &[&str] = &["latitude", "lat"];
const LONGITUDE: &[&str] = &["longitude", "lon"];
const MEMBER: &[&str] = &["number", "ens", "ensemble", "member", "realization"];

/// A data variable: its standard names and names.
struct Quantity {
    what: &'static str,
    standard_names: &'static [&'static str],
    names: &'static [&'static str],
}

const GEOPOTENTIAL: Quantity = Quantity {
    what: "geopotential",
    standard_names: &["geopotential"],
    names: &["z", "Geopotential", "geopotential"],
};
const GEOPOTENTIAL_HEIGHT: Quantity = Quantity {
    what: "geopotential height",
    standard_names: &["geopotential_height"],
    names: &[
        "gh",
        "hgtprs",
        "Geopotential_height_isobaric",
        "HGT",
        "zg",
        "hgt",
    ],
};
const TEMPERATURE: Quantity = Quantity {
    what: "temperature",
    standard_names: &["air_temperature"],
    names: &["t", "tmpprs", "Temperature_isobaric", "ta", "TMP", "air"],
};
const WIND_EAST: Quantity = Quantity {
    what: "wind's east component",
    standard_names: &["eastward_wind"],
    names: &[
        "u",
        "ugrdprs",
        "u-component_of_wind_isobaric",
        "ua",
        "UGRD",
        "uwnd",
    ],
};
const WIND_NORTH: Quantity = Quantity {
    what: "wind's north component",
    standard_names: &["northward_wind"],
    names: &[
        "v",
        "vgrdprs",
        "v-component_of_wind_isobaric",
        "va",
        "VGRD",
        "vwnd",
    ],
};

/// What each dimension of a data variable is.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Role {
    Member,
    Time,
    Level,
    Latitude,
    Longitude,
    /// A dimension of length 1 the reader does not know (taken at its only index).
    Single,
}

fn attribute_text(v: &NcVariable, name: &str) -> Option<String> {
    v.attribute(name).and_then(|a| a.value.as_string())
}

fn attribute_number(v: &NcVariable, name: &str) -> Option<f64> {
    v.attribute(name).and_then(|a| a.value.as_f64())
}

/// The file's variable `name`, if it has one.
fn variable<'f>(file: &'f NcFile, name: &str) -> Option<&'f NcVariable> {
    file.variables().ok()?.iter().find(|v| v.name() == name)
}

/// The first variable of the file named one of `names` (in that order) that has exactly one
/// dimension, as a coordinate does.
fn coordinate<'f>(file: &'f NcFile, names: &[&str]) -> Option<&'f NcVariable> {
    names
        .iter()
        .filter_map(|n| variable(file, n))
        .find(|v| v.ndim() == 1)
}

/// The data variable of a quantity: one with at least the level, latitude and longitude
/// dimensions, by its standard name first, then by its names.
fn data_variable<'f>(file: &'f NcFile, q: &Quantity, dims: &[&str; 3]) -> Option<&'f NcVariable> {
    let vars = file.variables().ok()?;
    let gridded = |v: &&NcVariable| {
        dims.iter()
            .all(|d| v.dimensions().iter().any(|vd| vd.name == *d))
    };
    vars.iter()
        .filter(gridded)
        .find(|v| {
            attribute_text(v, "standard_name").is_some_and(|s| q.standard_names.contains(&s.trim()))
        })
        .or_else(|| {
            q.names
                .iter()
                .find_map(|n| vars.iter().filter(gridded).find(|v| v.name() == *n))
        })
}

/// A coordinate's values as f64.
fn values(file: &NcFile, v: &NcVariable, what: &str) -> Result<Vec<f64>, WeatherError> {
    let data = file
        .read_variable_as_f64(v.name())
        .map_err(|e| WeatherError::read(v.name(), what, e))?;
    let out: Vec<f64> = data.iter().copied().collect();
    if let Some(bad) = out.iter().find(|x| !x.is_finite()) {
        return Err(WeatherError::Value {
            variable: v.name().to_string(),
            rule: format!("the {what} coordinate holds {bad}: every coordinate must be finite"),
        });
    }
    Ok(out)
}

/// The cell of a sorted coordinate (ascending or descending) around `x`: `i` with `x`
/// between `c[i]` and `c[i + 1]`, and the fraction of the way from `c[i]`. `None` when `x`
/// is outside.
fn cell(c: &[f64], x: f64) -> Option<(usize, f64)> {
    if c.len() < 2 {
        return None;
    }
    (0..c.len() - 1).find_map(|i| {
        let (a, b) = (c[i], c[i + 1]);
        let inside = (a <= x && x <= b) || (b <= x && x <= a);
        inside.then(|| (i, (x - a) / (b - a)))
    })
}

/// Whether a coordinate is strictly monotonic.
fn monotonic(c: &[f64]) -> bool {
    c.windows(2).all(|w| w[1] > w[0]) || c.windows(2).all(|w| w[1] < w[0])
}

/// The CF rule for one variable's values: which raw values are missing, and the unpacking.
struct Packing {
    scale: f64,
    offset: f64,
    fill: Option<f64>,
    missing: Option<f64>,
}

impl Packing {
    fn of(v: &NcVariable) -> Packing {
        Packing {
            scale: attribute_number(v, "scale_factor").unwrap_or(1.0),
            offset: attribute_number(v, "add_offset").unwrap_or(0.0),
            fill: attribute_number(v, "_FillValue"),
            missing: attribute_number(v, "missing_value"),
        }
    }

    /// The value of `raw`: `Ok(None)` if missing, an error if it is not finite and not a
    /// missing value's mark.
    fn unpack(&self, raw: f64, variable: &str) -> Result<Option<f64>, WeatherError> {
        let marks = |m: Option<f64>| m.is_some_and(|m| m == raw || (m.is_nan() && raw.is_nan()));
        if marks(self.fill) || marks(self.missing) {
            return Ok(None);
        }
        let v = raw * self.scale + self.offset;
        if !v.is_finite() {
            return Err(WeatherError::Value {
                variable: variable.to_string(),
                rule: format!(
                    "holds {raw}, which is neither a number nor its fill value: every value \
                     must be finite"
                ),
            });
        }
        Ok(Some(v))
    }
}

/// Read the file's weather over the grid cell around (`latitude_deg`, `longitude_deg`),
/// bilinearly interpolated to the site: see [`SiteWeather::read`].
pub(super) fn site_weather(
    file: &NcFile,
    latitude_deg: f64,
    longitude_deg: f64,
) -> Result<SiteWeather, WeatherError> {
    let missing = |what: &'static str, names: &[&str]| WeatherError::Missing {
        what,
        names: names.join(", "),
    };
    // Coordinates.
    let time_var = coordinate(file, TIME)
        .filter(|v| {
            attribute_text(v, "units").is_some_and(|u| u.to_lowercase().contains(" since "))
        })
        .ok_or_else(|| missing("time coordinate (with units \"... since ...\")", TIME))?;
    let level_var = coordinate(file, LEVEL).ok_or_else(|| missing("pressure level", LEVEL))?;
    let lat_var = coordinate(file, LATITUDE).ok_or_else(|| missing("latitude", LATITUDE))?;
    let lon_var = coordinate(file, LONGITUDE).ok_or_else(|| missing("longitude", LONGITUDE))?;
    let dims = [
        level_var.dimensions()[0].name.as_str(),
        lat_var.dimensions()[0].name.as_str(),
        lon_var.dimensions()[0].name.as_str(),
    ];
    let time_dim = time_var.dimensions()[0].name.as_str();

    // Times, seconds since 1970 UTC.
    let time_ref = time_reference(time_var)
        .map_err(|e| WeatherError::Value {
            variable: time_var.name().to_string(),
            rule: format!("its units can't be read as a time: {e}"),
        })?
        .ok_or_else(|| missing("time coordinate (with units \"... since ...\")", TIME))?;
    let raw_times = values(file, time_var, "time")?;
    if raw_times.is_empty() || raw_times.len() > MAX_TIMES {
        return Err(WeatherError::Value {
            variable: time_var.name().to_string(),
            rule: format!(
                "has {} times: a file may hold 1 to {MAX_TIMES}",
                raw_times.len()
            ),
        });
    }
    let times_s = raw_times
        .iter()
        .map(|&t| {
            netcdf_reader::cf::decode_time(t, &time_ref)
                .map(|d| d.timestamp() as f64 + f64::from(d.timestamp_subsec_nanos()) * 1e-9)
                .map_err(|e| WeatherError::Value {
                    variable: time_var.name().to_string(),
                    rule: format!("its value {t} is not a time: {e}"),
                })
        })
        .collect::<Result<Vec<f64>, _>>()?;
    if !times_s.windows(2).all(|w| w[1] > w[0]) {
        return Err(WeatherError::Value {
            variable: time_var.name().to_string(),
            rule: "its times must increase".into(),
        });
    }

    // Pressure levels, Pa.
    let level_units = attribute_text(level_var, "units").unwrap_or_default();
    let to_pa = match level_units.trim().to_lowercase().as_str() {
        "hpa" | "millibars" | "millibar" | "mbar" | "mb" => 100.0,
        "pa" => 1.0,
        "kpa" => 1000.0,
        other => {
            return Err(WeatherError::Value {
                variable: level_var.name().to_string(),
                rule: format!(
                    "its units are \"{other}\": pressure levels must be in hPa (millibars) or Pa"
                ),
            })
        }
    };
    let levels_pa: Vec<f64> = values(file, level_var, "pressure level")?
        .iter()
        .map(|p| p * to_pa)
        .collect();
    if levels_pa.len() < 2
        || !monotonic(&levels_pa)
        || levels_pa.iter().any(|&p| !(p > 0.0 && p <= MAX_LEVEL_PA))
    {
        return Err(WeatherError::Value {
            variable: level_var.name().to_string(),
            rule: format!(
                "the pressure levels must be two or more, above 0 and at most {} hPa, in \
                 increasing or decreasing order",
                MAX_LEVEL_PA / 100.0
            ),
        });
    }

    // The grid cell around the site.
    let lats = values(file, lat_var, "latitude")?;
    let lons = values(file, lon_var, "longitude")?;
    for (c, v) in [(&lats, lat_var), (&lons, lon_var)] {
        if c.len() < 2 || !monotonic(c) {
            return Err(WeatherError::Value {
                variable: v.name().to_string(),
                rule: "a grid needs two or more values in increasing or decreasing order".into(),
            });
        }
    }
    // The site's longitude in the grid's own convention (0 to 360, or -180 to 180).
    let lon_site = if lons.iter().any(|&l| l > 180.0) {
        longitude_deg.rem_euclid(360.0)
    } else if longitude_deg > 180.0 {
        longitude_deg - 360.0
    } else {
        longitude_deg
    };
    let range = |c: &[f64]| (c[0].min(c[c.len() - 1]), c[0].max(c[c.len() - 1]));
    let (Some((i, fy)), Some((j, fx))) = (cell(&lats, latitude_deg), cell(&lons, lon_site)) else {
        let ((lat0, lat1), (lon0, lon1)) = (range(&lats), range(&lons));
        return Err(WeatherError::Outside {
            latitude_deg,
            longitude_deg,
            lat0,
            lat1,
            lon0,
            lon1,
        });
    };

    // The data variables.
    let height = match data_variable(file, &GEOPOTENTIAL, &dims) {
        Some(v) => (v, 1.0 / G0_M_S2),
        None => (
            data_variable(file, &GEOPOTENTIAL_HEIGHT, &dims).ok_or_else(|| {
                WeatherError::Missing {
                    what: "geopotential or geopotential height",
                    names: [GEOPOTENTIAL.names, GEOPOTENTIAL_HEIGHT.names]
                        .concat()
                        .join(", "),
                }
            })?,
            1.0,
        ),
    };
    let quantity = |q: &Quantity| {
        data_variable(file, q, &dims).ok_or_else(|| WeatherError::Missing {
            what: q.what,
            names: q.names.join(", "),
        })
    };
    let (t_var, u_var, v_var) = (
        quantity(&TEMPERATURE)?,
        quantity(&WIND_EAST)?,
        quantity(&WIND_NORTH)?,
    );
    check_units(height.0, height.1 != 1.0)?;
    let t_to_k = match attribute_text(t_var, "units")
        .unwrap_or_default()
        .trim()
        .to_lowercase()
        .as_str()
    {
        "k" | "kelvin" | "degk" | "" => 0.0,
        "degc" | "c" | "celsius" | "degrees_celsius" | "deg_c" => 273.15,
        other => {
            return Err(WeatherError::Value {
                variable: t_var.name().to_string(),
                rule: format!("its units are \"{other}\": a temperature must be in K or °C"),
            })
        }
    };
    for w in [u_var, v_var] {
        let u = attribute_text(w, "units").unwrap_or_default();
        let u = u.trim().to_lowercase().replace(' ', "");
        if !["m/s", "ms**-1", "ms-1", "m.s-1", "meter/sec", "m/sec", ""].contains(&u.as_str()) {
            return Err(WeatherError::Value {
                variable: w.name().to_string(),
                rule: format!("its units are \"{u}\": a wind must be in m/s"),
            });
        }
    }

    // Every data variable on the same dimensions, in the same order.
    let shape_of =
        |v: &NcVariable| -> Vec<String> { v.dimensions().iter().map(|d| d.name.clone()).collect() };
    let layout = shape_of(t_var);
    for v in [height.0, u_var, v_var] {
        if shape_of(v) != layout {
            return Err(WeatherError::Value {
                variable: v.name().to_string(),
                rule: format!(
                    "its dimensions ({}) are not those of {} ({}): the reader needs every \
                     quantity on one grid",
                    shape_of(v).join(", "),
                    t_var.name(),
                    layout.join(", ")
                ),
            });
        }
    }
    let mut roles = Vec::with_capacity(layout.len());
    let mut members: Vec<f64> = vec![0.0];
    for d in t_var.dimensions() {
        let role = if d.name == time_dim {
            Role::Time
        } else if d.name == dims[0] {
            Role::Level
        } else if d.name == dims[1] {
            Role::Latitude
        } else if d.name == dims[2] {
            Role::Longitude
        } else if MEMBER.contains(&d.name.as_str()) && d.size > 1 {
            members = match coordinate(file, &[d.name.as_str()]) {
                Some(c) => values(file, c, "member")?,
                None => (0..d.size).map(|k| k as f64).collect(),
            };
            if members.len() as u64 != d.size || members.len() > MAX_MEMBERS {
                return Err(WeatherError::Value {
                    variable: d.name.clone(),
                    rule: format!("an ensemble may have up to {MAX_MEMBERS} members"),
                });
            }
            Role::Member
        } else if d.size == 1 {
            Role::Single
        } else {
            return Err(WeatherError::Value {
                variable: t_var.name().to_string(),
                rule: format!(
                    "its dimension \"{}\" ({} long) is none the reader knows: time, pressure \
                     level, latitude, longitude, ensemble member ({}), or one of length 1",
                    d.name,
                    d.size,
                    MEMBER.join(", ")
                ),
            });
        };
        roles.push(role);
    }
    for (role, what) in [
        (Role::Time, "time"),
        (Role::Level, "pressure level"),
        (Role::Latitude, "latitude"),
        (Role::Longitude, "longitude"),
    ] {
        if !roles.contains(&role) {
            return Err(WeatherError::Value {
                variable: t_var.name().to_string(),
                rule: format!("it has no {what} dimension"),
            });
        }
    }
    let selection = NcSliceInfo {
        selections: roles
            .iter()
            .map(|r| match r {
                Role::Latitude => NcSliceInfoElem::Slice {
                    start: i as u64,
                    end: i as u64 + 2,
                    step: 1,
                },
                Role::Longitude => NcSliceInfoElem::Slice {
                    start: j as u64,
                    end: j as u64 + 2,
                    step: 1,
                },
                Role::Single => NcSliceInfoElem::Index(0),
                _ => NcSliceInfoElem::Slice {
                    start: 0,
                    end: u64::MAX,
                    step: 1,
                },
            })
            .collect(),
    };
    // Each quantity's values at the cell's four corners, bilinear at the site, for every
    // member, time and level.
    let (nm, nt, nl) = (members.len(), times_s.len(), levels_pa.len());
    if nm * nt * nl > MAX_COLUMN_VALUES {
        return Err(WeatherError::Value {
            variable: t_var.name().to_string(),
            rule: format!(
                "{nt} times × {nm} members × {nl} levels over the site is more than \
                 {MAX_COLUMN_VALUES} values a quantity: cut the file to the days of the launch"
            ),
        });
    }
    let read = |v: &NcVariable, scale: f64, shift: f64| -> Result<Vec<Option<f64>>, WeatherError> {
        let data = file
            .read_variable_slice_as_f64(v.name(), &selection)
            .map_err(|e| WeatherError::read(v.name(), "values", e))?;
        let packing = Packing::of(v);
        // Indices in the slice's order (roles), with the single dimensions dropped.
        let shape = data.shape().to_vec();
        let kept: Vec<Role> = roles
            .iter()
            .copied()
            .filter(|r| *r != Role::Single)
            .collect();
        if shape.len() != kept.len() {
            return Err(WeatherError::Value {
                variable: v.name().to_string(),
                rule: "its values do not have the shape of its dimensions".into(),
            });
        }
        let mut out = vec![None; nm * nt * nl];
        let mut index = vec![0usize; shape.len()];
        for m in 0..nm {
            for t in 0..nt {
                for l in 0..nl {
                    let mut sum = 0.0;
                    let mut complete = true;
                    for (dy, wy) in [(0, 1.0 - fy), (1, fy)] {
                        for (dx, wx) in [(0, 1.0 - fx), (1, fx)] {
                            for (k, r) in kept.iter().enumerate() {
                                index[k] = match r {
                                    Role::Member => m,
                                    Role::Time => t,
                                    Role::Level => l,
                                    Role::Latitude => dy,
                                    Role::Longitude => dx,
                                    Role::Single => 0,
                                };
                            }
                            let raw = data.get(index.as_slice()).copied().ok_or_else(|| {
                                WeatherError::Value {
                                    variable: v.name().to_string(),
                                    rule: "its values do not have the shape of its dimensions"
                                        .into(),
                                }
                            })?;
                            match packing.unpack(raw, v.name())? {
                                Some(x) => sum += wy * wx * x,
                                None => complete = false,
                            }
                        }
                    }
                    out[(m * nt + t) * nl + l] = complete.then_some(sum * scale + shift);
                }
            }
        }
        Ok(out)
    };
    Ok(SiteWeather {
        latitude_deg,
        longitude_deg,
        times_s,
        members,
        levels_pa,
        geopotential_height_m: read(height.0, height.1, 0.0)?,
        temperature_k: read(t_var, 1.0, t_to_k)?,
        wind_east_m_s: read(u_var, 1.0, 0.0)?,
        wind_north_m_s: read(v_var, 1.0, 0.0)?,
        variables: [
            height.0.name().to_string(),
            t_var.name().to_string(),
            u_var.name().to_string(),
            v_var.name().to_string(),
        ],
    })
}

/// A geopotential's units (m²/s²) or a geopotential height's (geopotential metres).
fn check_units(v: &NcVariable, geopotential: bool) -> Result<(), WeatherError> {
    let u = attribute_text(v, "units").unwrap_or_default();
    let u = u.trim().to_lowercase().replace(' ', "");
    let ok = if geopotential {
        ["m**2s**-2", "m2s-2", "m^2/s^2", "m2/s2", "m**2/s**2", ""].contains(&u.as_str())
    } else {
        ["gpm", "m", "meters", "metres", "m2s-2/9.80665", ""].contains(&u.as_str())
    };
    if ok {
        Ok(())
    } else {
        Err(WeatherError::Value {
            variable: v.name().to_string(),
            rule: format!(
                "its units are \"{u}\": a {} must be in {}",
                if geopotential {
                    "geopotential"
                } else {
                    "geopotential height"
                },
                if geopotential {
                    "m²/s² (m**2 s**-2)"
                } else {
                    "geopotential metres (gpm)"
                }
            ),
        })
    }
}

/// The time coordinate's reference (`<unit> since <date>[ <time>]`), its epoch written as
/// ISO 8601 too (`Hour since 2020-02-22T00:00:00Z`, NOAA's), which the CF parser takes only
/// with a space and no zone letter.
fn time_reference(
    v: &NcVariable,
) -> Result<Option<netcdf_reader::cf::CfTimeRef>, netcdf_reader::Error> {
    use netcdf_reader::cf::{parse_time_units, CfCalendar};
    let Some(units) = attribute_text(v, "units") else {
        return Ok(None);
    };
    let lower = units.to_lowercase();
    let Some(at) = lower.find(" since ") else {
        return Ok(None);
    };
    let (unit, epoch) = (&units[..at], units[at + 7..].trim());
    let epoch = epoch
        .strip_suffix(['Z', 'z'])
        .or_else(|| epoch.strip_suffix(" UTC"))
        .or_else(|| epoch.strip_suffix("+00:00"))
        .unwrap_or(epoch);
    let epoch = match epoch.split_once('T') {
        Some((date, clock)) if date.len() >= 8 => format!("{date} {clock}"),
        _ => epoch.to_string(),
    };
    let calendar = attribute_text(v, "calendar")
        .map(|c| CfCalendar::parse(&c))
        .unwrap_or(CfCalendar::Standard);
    parse_time_units(&format!("{unit} since {epoch}"), calendar).map(Some)
}
