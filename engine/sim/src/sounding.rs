//! A radiosonde sounding read from a file: the air and the wind over a launch site as a
//! balloon measured them (RocketPy's `Environment(type="wyoming_sounding")`).
//!
//! **The file** is the University of Wyoming's text listing (`TEXT:LIST`, the page saved as it
//! is, or only its table): a header naming the columns (`PRES HGHT TEMP DWPT ... DRCT SKNT
//! ...`), a line of units, a line of dashes, then one level per line in fixed-width columns,
//! each column's field ending where its name ends in the header. A field may be blank (the
//! levels below the ground carry only a pressure and a height, the driest levels no dew point):
//! each quantity is read wherever it is given. The wind's speed is in knots (`SKNT`) or in m/s
//! (`SPED`, the newer pages); its direction (`DRCT`) is where it blows from, degrees clockwise
//! from north. Heights (`HGHT`) are geopotential metres above sea level and are converted to
//! geometric ones ([`geometric_altitude_m`]). Everything else in the file (station
//! information, indices, HTML) is ignored.
//!
//! **What a flight gets** ([`Sounding::air_profile`], [`Sounding::wind_rows`]): the launch
//! site is at `elevation_m` above sea level, within the sounding (or up to
//! [`BELOW_LOWEST_LEVEL_M`] below its lowest level). The air is an
//! [`AirProfile`]: the temperature at each level above the site (linear in height between
//! levels, as the profile's layers are, and at the site interpolated between the two levels
//! around it), and the site's pressure interpolated between the two measured levels around
//! it (those with a temperature too) with the logarithm of the pressure linear in height
//! (hydrostatic at a constant temperature). The
//! pressure aloft is then the profile's own, carried up hydrostatically from the site's
//! through the measured temperatures (dry air: no humidity), not the sounding's reported
//! pressures; the two agree to the sounding's rounding and the humidity's effect on density
//! (a few parts in a thousand in humid air; see the tests). The wind is a table of rows by
//! height above the site, interpolated as every wind table is (`crate::wind`), with a row at
//! the site interpolated between the levels around it.
//!
//! RocketPy reads the same file differently in two ways, both said here so that a comparison
//! is fair: it keeps only the levels where every column is given (a level without a dew point
//! loses its temperature and wind too), and it interpolates the reported pressures linearly
//! in height. `validation/rocketpy/sounding_crosscheck.py` flies both on one sounding.

use crate::atmosphere::{geometric_altitude_m, AirProfile, AirRow};
use crate::wind::{components_en, WindRow};
use thiserror::Error;

/// Knots to m/s (1852 m an hour).
const KNOT_M_S: f64 = 1852.0 / 3600.0;

/// How far below the sounding's lowest level a site may be, m: its air is then the lowest
/// two levels' extrapolated (the temperature and the logarithm of the pressure linear in
/// height) and its wind the lowest level's. A station listed at "1400.0 m" is 1400 m
/// geopotential, 0.31 m below its lowest level's geometric height; a launch site near the
/// station may be a little lower.
pub const BELOW_LOWEST_LEVEL_M: f64 = 100.0;

/// One level of a sounding: its geometric height above sea level and what was measured there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Level {
    /// Geometric height above mean sea level, m (from the file's geopotential height).
    pub height_msl_m: f64,
    pub pressure_pa: Option<f64>,
    pub temperature_k: Option<f64>,
    /// Wind speed, m/s, and the direction it blows from, degrees clockwise from north.
    pub wind: Option<(f64, f64)>,
}

/// A sounding's levels, lowest first.
#[derive(Debug, Clone, PartialEq)]
pub struct Sounding {
    pub levels: Vec<Level>,
}

/// What is wrong with a sounding; `line` is 1-based in the file.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SoundingError {
    #[error("no table of levels: no header line naming the columns PRES, HGHT, TEMP, DRCT and SKNT (or SPED), as the University of Wyoming's text listing has")]
    NoTable,
    #[error("line {line}: column {column}: \"{text}\" is not a number")]
    Number {
        line: usize,
        column: &'static str,
        text: String,
    },
    #[error("line {line}: the level at {height_m} m (geopotential) is not above the one before ({previous_m} m): levels go up, lowest first")]
    Order {
        line: usize,
        height_m: f64,
        previous_m: f64,
    },
    #[error("line {line}: column {column}: {value} is out of range ({rule})")]
    Range {
        line: usize,
        column: &'static str,
        value: f64,
        rule: &'static str,
    },
    #[error("the site at {elevation_m} m is outside the sounding's {what} ({low_m:.1} to {high_m:.1} m above sea level; a site may be up to {below_m} m below the lowest)")]
    Site {
        elevation_m: f64,
        what: &'static str,
        low_m: f64,
        high_m: f64,
        /// How far below the lowest level a site may be, m.
        below_m: f64,
    },
    #[error("the sounding has fewer than two levels with a {what}")]
    TooFew { what: &'static str },
    #[error(
        "no level has both a temperature and a pressure: the sounding has no ground to launch from"
    )]
    NoGround,
}

/// A sounding's air and wind over one launch site.
#[derive(Debug, Clone, PartialEq)]
pub struct SiteAir {
    /// The site's elevation above sea level, m.
    pub elevation_m: f64,
    pub air: AirProfile,
    /// The wind's rows by height above the site.
    pub wind: Vec<WindRow>,
}

impl SiteAir {
    /// The air a flight reads: the profile.
    pub fn air_model(&self) -> crate::atmosphere::AirModel {
        crate::atmosphere::AirModel::Profile(std::sync::Arc::new(self.air.clone()))
    }

    /// The wind a flight reads: the rows' table.
    pub fn wind(&self) -> Result<crate::wind::Wind, crate::wind::WindError> {
        crate::wind::Wind::table(&self.wind)
    }
}

/// The columns read, by their header names.
const PRES: &str = "PRES";
const HGHT: &str = "HGHT";
const TEMP: &str = "TEMP";
const DRCT: &str = "DRCT";

impl Sounding {
    /// Read a sounding from the text of a University of Wyoming listing (see the module docs).
    pub fn parse(text: &str) -> Result<Sounding, SoundingError> {
        let lines: Vec<&str> = text.lines().collect();
        // The header: the first line whose words include the columns needed.
        let (head, speed_name) = lines
            .iter()
            .enumerate()
            .find_map(|(i, l)| {
                let words: Vec<&str> = l.split_whitespace().collect();
                let has = |w: &str| words.contains(&w);
                if !(has(PRES) && has(HGHT) && has(TEMP) && has(DRCT)) {
                    return None;
                }
                let speed = ["SKNT", "SPED"].into_iter().find(|s| has(s))?;
                Some((i, speed))
            })
            .ok_or(SoundingError::NoTable)?;
        let header = lines[head];
        // Each column ends where its name ends and starts after the previous one's end.
        let mut spans: Vec<(&str, usize, usize)> = Vec::new();
        let (bytes, mut at, mut start) = (header.as_bytes(), 0, 0);
        while at < bytes.len() {
            if bytes[at].is_ascii_whitespace() {
                at += 1;
                continue;
            }
            let word_start = at;
            while at < bytes.len() && !bytes[at].is_ascii_whitespace() {
                at += 1;
            }
            spans.push((&header[word_start..at], start, at));
            start = at;
        }
        let span = |name: &str| {
            spans
                .iter()
                .find(|(n, _, _)| *n == name)
                .map(|&(_, s, e)| (s, e))
        };
        let (pres, hght, temp, drct, speed) = (
            span(PRES).unwrap(),
            span(HGHT).unwrap(),
            span(TEMP).unwrap(),
            span(DRCT).unwrap(),
            span(speed_name).unwrap(),
        );
        let knots = speed_name == "SKNT";
        let mut levels: Vec<Level> = Vec::new();
        let mut previous_h = f64::NEG_INFINITY;
        // The data start after the units and the dashes (lines that do not start with a
        // number); they end at the first such line after them (a blank line, the end of the
        // table, the station information).
        for (i, line) in lines.iter().enumerate().skip(head + 1) {
            let n = i + 1;
            let trimmed = line.trim();
            if trimmed.chars().all(|c| c == '-') && !trimmed.is_empty() {
                continue;
            }
            if trimmed.is_empty() || !trimmed.starts_with(|c: char| c.is_ascii_digit()) {
                if levels.is_empty() {
                    continue;
                }
                break;
            }
            let field = |(s, e): (usize, usize), column: &'static str| {
                let text = line.get(s..e.min(line.len())).unwrap_or("").trim();
                if text.is_empty() {
                    return Ok(None);
                }
                text.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .map(Some)
                    .ok_or_else(|| SoundingError::Number {
                        line: n,
                        column,
                        text: text.to_string(),
                    })
            };
            let range = |v: Option<f64>, column, ok: fn(f64) -> bool, rule| match v {
                Some(v) if !ok(v) => Err(SoundingError::Range {
                    line: n,
                    column,
                    value: v,
                    rule,
                }),
                v => Ok(v),
            };
            let Some(h) = field(hght, HGHT)? else {
                continue; // a level without a height says nothing a flight can use
            };
            let p = range(
                field(pres, PRES)?,
                PRES,
                |p| p > 0.0 && p <= 1100.0,
                "0 to 1100 hPa",
            )?;
            let t = range(
                field(temp, TEMP)?,
                TEMP,
                |t| (-150.0..=80.0).contains(&t),
                "-150 to 80 °C",
            )?;
            let d = range(
                field(drct, DRCT)?,
                DRCT,
                |d| (0.0..=360.0).contains(&d),
                "0 to 360 degrees",
            )?;
            let s = range(
                field(speed, if knots { "SKNT" } else { "SPED" })?,
                if knots { "SKNT" } else { "SPED" },
                |s| (0.0..=400.0).contains(&s),
                "0 to 400",
            )?;
            if h <= previous_h {
                return Err(SoundingError::Order {
                    line: n,
                    height_m: h,
                    previous_m: previous_h,
                });
            }
            previous_h = h;
            levels.push(Level {
                height_msl_m: geometric_altitude_m(h),
                pressure_pa: p.map(|p| p * 100.0),
                temperature_k: t.map(|t| t + 273.15),
                wind: d
                    .zip(s)
                    .map(|(d, s)| (if knots { s * KNOT_M_S } else { s }, d % 360.0)),
            });
        }
        if levels.is_empty() {
            return Err(SoundingError::NoTable);
        }
        Ok(Sounding { levels })
    }

    /// The lowest level with a temperature and a pressure: the ground the balloon left
    /// from (its station's elevation), m above sea level.
    pub fn surface_m(&self) -> Option<f64> {
        self.levels
            .iter()
            .find(|l| l.temperature_k.is_some() && l.pressure_pa.is_some())
            .map(|l| l.height_msl_m)
    }

    /// The air and the wind over a site `elevation_m` above sea level, or over the sounding's
    /// ground ([`Sounding::surface_m`]) when `None`: [`Sounding::air_profile`] and
    /// [`Sounding::wind_rows`] there.
    pub fn over_site(&self, elevation_m: Option<f64>) -> Result<SiteAir, SoundingError> {
        let elevation_m = match elevation_m {
            Some(e) => e,
            None => self.surface_m().ok_or(SoundingError::NoGround)?,
        };
        self.over_site_within(elevation_m, BELOW_LOWEST_LEVEL_M)
    }

    /// The air and the wind over a site `elevation_m` above sea level that may be up to
    /// `below_m` below the lowest level ([`Sounding::over_site`] allows
    /// [`BELOW_LOWEST_LEVEL_M`]; a weather model's levels, `crate::weather`, allow more).
    pub fn over_site_within(
        &self,
        elevation_m: f64,
        below_m: f64,
    ) -> Result<SiteAir, SoundingError> {
        Ok(SiteAir {
            elevation_m,
            air: self.air_profile_within(elevation_m, below_m)?,
            wind: self.wind_rows_within(elevation_m, below_m)?,
        })
    }

    /// The levels with a value `get` gives, as (height above sea level, value).
    fn series<T>(&self, get: impl Fn(&Level) -> Option<T>) -> Vec<(f64, T)> {
        self.levels
            .iter()
            .filter_map(|l| get(l).map(|v| (l.height_msl_m, v)))
            .collect()
    }

    /// The index `i` of the levels of `series` around `elevation_m` (`series[i]` at or below
    /// it, `series[i + 1]` above) and the fraction of the way up.
    fn around<T>(
        series: &[(f64, T)],
        elevation_m: f64,
        what: &'static str,
        below_m: f64,
    ) -> Result<(usize, f64), SoundingError> {
        if series.len() < 2 {
            return Err(SoundingError::TooFew { what });
        }
        let (low, high) = (series[0].0, series[series.len() - 1].0);
        if !(elevation_m >= low - below_m && elevation_m < high) {
            return Err(SoundingError::Site {
                elevation_m,
                what,
                low_m: low,
                high_m: high,
                below_m,
            });
        }
        // Below the lowest level: from the lowest two, extrapolated (f < 0).
        let i = series
            .partition_point(|(h, _)| *h <= elevation_m)
            .saturating_sub(1);
        let f = (elevation_m - series[i].0) / (series[i + 1].0 - series[i].0);
        Ok((i, f))
    }

    /// The air over a site `elevation_m` above sea level (see the module docs).
    pub fn air_profile(&self, elevation_m: f64) -> Result<AirProfile, SoundingError> {
        self.air_profile_within(elevation_m, BELOW_LOWEST_LEVEL_M)
    }

    /// [`Sounding::air_profile`] for a site that may be up to `below_m` below the lowest level.
    pub fn air_profile_within(
        &self,
        elevation_m: f64,
        below_m: f64,
    ) -> Result<AirProfile, SoundingError> {
        let temps = self.series(|l| l.temperature_k);
        let (i, f) = Sounding::around(&temps, elevation_m, "temperatures", below_m)?;
        let site_t = temps[i].1 + f * (temps[i + 1].1 - temps[i].1);
        let mut rows = vec![AirRow {
            height_m: 0.0,
            temperature_k: site_t,
            pressure_pa: None,
        }];
        rows.extend(
            temps[i..]
                .iter()
                .filter(|(h, _)| *h > elevation_m)
                .map(|&(h, t)| AirRow {
                    height_m: h - elevation_m,
                    temperature_k: t,
                    pressure_pa: None,
                }),
        );
        // The measured levels' pressures (a level below the ground listed with a pressure and
        // a height only is the surface air extrapolated down, not a measurement).
        let pressures = self.series(|l| l.temperature_k.and(l.pressure_pa));
        let (j, g) = Sounding::around(&pressures, elevation_m, "pressures", below_m)?;
        let (p0, p1) = (pressures[j].1, pressures[j + 1].1);
        Ok(AirProfile {
            elevation_m,
            pressure_pa: p0 * (p1 / p0).powf(g),
            rows,
        })
    }

    /// The wind over a site `elevation_m` above sea level, rows by height above it (see the
    /// module docs).
    pub fn wind_rows(&self, elevation_m: f64) -> Result<Vec<WindRow>, SoundingError> {
        self.wind_rows_within(elevation_m, BELOW_LOWEST_LEVEL_M)
    }

    /// [`Sounding::wind_rows`] for a site that may be up to `below_m` below the lowest level.
    pub fn wind_rows_within(
        &self,
        elevation_m: f64,
        below_m: f64,
    ) -> Result<Vec<WindRow>, SoundingError> {
        let winds = self.series(|l| l.wind);
        let (i, f) = Sounding::around(&winds, elevation_m, "winds", below_m)?;
        let f = f.max(0.0); // below the lowest level: its wind
                            // At the site: the components interpolated, as the table interpolates them.
        let en = |(s, d): (f64, f64)| components_en(s, d);
        let (a, b) = (en(winds[i].1), en(winds[i + 1].1));
        let (e, n) = (a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]));
        let site = WindRow {
            height_agl_m: 0.0,
            speed_m_s: e.hypot(n),
            from_deg: (e.atan2(n).to_degrees() + 180.0).rem_euclid(360.0),
        };
        let mut rows = vec![site];
        rows.extend(
            winds[i..]
                .iter()
                .filter(|(h, _)| *h > elevation_m)
                .map(|&(h, (s, d))| WindRow {
                    height_agl_m: h - elevation_m,
                    speed_m_s: s,
                    from_deg: d,
                }),
        );
        Ok(rows)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::{geopotential_altitude_m, AirModel, Atmosphere};

    fn synthetic() -> Sounding {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../validation/soundings/synthetic-wyoming.txt"
        );
        Sounding::parse(&std::fs::read_to_string(path).unwrap()).unwrap()
    }

    #[test]
    fn a_wyoming_listing_reads_into_levels_in_si_units_and_geometric_heights() {
        let s = synthetic();
        // 2 levels below the ground, 56 above: 1400 m and every 150 m to 3 km (11), every
        // 400 m from 3 to 12 km (23), every km from 12 to 30 km (19), and the temperature's
        // breakpoints between (2200, 2500 and 6000 m).
        assert_eq!(s.levels.len(), 58);
        // " 1000.0     48" : a pressure and a height only.
        let below = s.levels[0];
        assert_eq!(below.pressure_pa, Some(100_000.0));
        assert_eq!(below.temperature_k, None);
        assert_eq!(below.wind, None);
        // "  860.0   1400   33.0   25.0     63  23.78    200      8": the surface.
        let surface = s.levels[2];
        let z = 6_356_766.0 * 1400.0 / (6_356_766.0 - 1400.0);
        assert!((surface.height_msl_m - z).abs() < 1e-9 && (z - 1400.308).abs() < 1e-3);
        assert_eq!(surface.pressure_pa, Some(86_000.0));
        assert!((surface.temperature_k.unwrap() - 306.15).abs() < 1e-12);
        let (speed, from) = surface.wind.unwrap();
        assert!((speed - 8.0 * 1852.0 / 3600.0).abs() < 1e-12 && from == 200.0);
        assert_eq!(s.surface_m(), Some(z));
        // "   13.3  30000  -46.0                          90     15": no dew point, but a
        // temperature and a wind.
        let top = s.levels.last().unwrap();
        assert!((top.temperature_k.unwrap() - 227.15).abs() < 1e-12);
        assert_eq!(top.wind.map(|w| w.1), Some(90.0));
        assert!((geopotential_altitude_m(top.height_msl_m) - 30_000.0).abs() < 1e-8);
    }

    #[test]
    fn the_newer_listing_s_speed_in_metres_per_second_and_a_bare_table_read_too() {
        let text = [
            "   PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SPED   THTA   THTE   THTV",
            "    hPa      m      C      C      %   g/kg    deg    m/s      K      K      K",
            " 1013.0     10   15.2   10.0     71   7.70    350    3.5  288.2  310.1  289.6",
            "  900.0   1000    9.0                          10     12  297.1  297.1  297.1",
        ]
        .join("\n");
        let s = Sounding::parse(&text).unwrap();
        assert_eq!(s.levels.len(), 2);
        assert_eq!(s.levels[0].wind, Some((3.5, 350.0)));
        assert_eq!(s.levels[1].wind, Some((12.0, 10.0)));
        assert!((s.levels[1].temperature_k.unwrap() - 282.15).abs() < 1e-12);
    }

    #[test]
    fn a_bad_listing_names_the_line_and_the_column() {
        assert_eq!(
            Sounding::parse("no table here\n"),
            Err(SoundingError::NoTable)
        );
        let head = "   PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SKNT\n";
        let bad = format!("{head}  900.0   1000    x.0                          10     12\n");
        assert_eq!(
            Sounding::parse(&bad),
            Err(SoundingError::Number {
                line: 2,
                column: "TEMP",
                text: "x.0".into()
            })
        );
        let down = format!(
            "{head}  900.0   1000    9.0                          10     12\n  950.0    500   12.0                          10     12\n"
        );
        assert!(matches!(
            Sounding::parse(&down),
            Err(SoundingError::Order { line: 3, .. })
        ));
        let hot = format!("{head}  900.0   1000  190.0                          10     12\n");
        assert!(matches!(
            Sounding::parse(&hot),
            Err(SoundingError::Range {
                line: 2,
                column: "TEMP",
                ..
            })
        ));
    }

    #[test]
    fn a_site_between_levels_gets_their_temperature_wind_and_pressure_interpolated() {
        let s = synthetic();
        let below = s.levels[0]; // a pressure and a height only
        let (a, b) = (s.levels[2], s.levels[3]); // 1400 and 1550 m geopotential
        let site = a.height_msl_m + 0.4 * (b.height_msl_m - a.height_msl_m);
        let air = s.air_profile(site).unwrap();
        let (ta, tb) = (a.temperature_k.unwrap(), b.temperature_k.unwrap());
        assert!((air.rows[0].temperature_k - (ta + 0.4 * (tb - ta))).abs() < 1e-9);
        // ln p linear in height: p_a (p_b / p_a)^0.4.
        let (pa, pb) = (a.pressure_pa.unwrap(), b.pressure_pa.unwrap());
        assert!((air.pressure_pa - pa * (pb / pa).powf(0.4)).abs() < 1e-8);
        assert!((air.rows[1].height_m - 0.6 * (b.height_msl_m - a.height_msl_m)).abs() < 1e-9);
        assert_eq!(air.rows.len(), 56); // the site, then the 55 levels with a temperature above
        let wind = s.wind_rows(site).unwrap();
        let en = |(sp, d): (f64, f64)| components_en(sp, d);
        let (ea, eb) = (en(a.wind.unwrap()), en(b.wind.unwrap()));
        let at = components_en(wind[0].speed_m_s, wind[0].from_deg);
        for k in 0..2 {
            assert!((at[k] - (ea[k] + 0.4 * (eb[k] - ea[k]))).abs() < 1e-12);
        }
        // At a level exactly: that level's own values.
        let air = s.air_profile(a.height_msl_m).unwrap();
        assert_eq!(air.pressure_pa, 86_000.0);
        assert_eq!(air.rows[0].temperature_k, ta);
        // Just below the lowest level (the station's listed 1400 m, 0.31 m below the level's
        // geometric height): the lowest two levels extrapolated, the lowest level's wind.
        let low = s.air_profile(1400.0).unwrap();
        let f = (1400.0 - a.height_msl_m) / (b.height_msl_m - a.height_msl_m);
        assert!(f < 0.0);
        assert!((low.rows[0].temperature_k - (ta + f * (tb - ta))).abs() < 1e-9);
        assert!((low.pressure_pa - pa * (pb / pa).powf(f)).abs() < 1e-8);
        assert!((low.rows[1].height_m - (a.height_msl_m - 1400.0)).abs() < 1e-12);
        let w = s.wind_rows(1400.0).unwrap()[0];
        let lowest = a.wind.unwrap();
        assert!((w.speed_m_s - lowest.0).abs() < 1e-12 && (w.from_deg - lowest.1).abs() < 1e-9);
        // Over the sounding's ground unless told otherwise; none without a ground.
        let ground = s.over_site(None).unwrap();
        assert_eq!(ground.elevation_m, a.height_msl_m);
        assert_eq!(ground.air, s.air_profile(a.height_msl_m).unwrap());
        assert_eq!(ground.wind, s.wind_rows(a.height_msl_m).unwrap());
        let bare = Sounding {
            levels: vec![below, below],
        };
        assert_eq!(bare.over_site(None), Err(SoundingError::NoGround));
        // Further outside the sounding's temperatures: refused, naming them.
        assert!(matches!(
            s.air_profile(1000.0),
            Err(SoundingError::Site {
                what: "temperatures",
                ..
            })
        ));
    }

    #[test]
    fn the_profile_s_hydrostatic_pressure_meets_the_sounding_s_to_its_rounding() {
        // The synthetic sounding's pressures are the dry air's, rounded to 0.1 hPa at heights
        // rounded to 1 m: the profile carried up from the site through its temperatures
        // (rounded to 0.1 °C) finds each within 5 Pa plus half a metre of the air's weight
        // plus the temperatures' rounding (1e-4 of the pressure). Seen: every level within
        // 5.2 Pa, scattered in sign (the file's heights are whole metres exactly, so the
        // pressure's rounding is all there is).
        let s = synthetic();
        let site = s.surface_m().unwrap();
        let air = s.air_profile(site).unwrap();
        let atmosphere =
            Atmosphere::new(site, &AirModel::Profile(std::sync::Arc::new(air))).unwrap();
        let mut worst: f64 = 0.0;
        for l in s.levels.iter().filter(|l| l.height_msl_m >= site) {
            let here = atmosphere.at_msl(l.height_msl_m);
            let reported = l.pressure_pa.unwrap();
            let bound = 5.0 + 0.5 * here.density_kg_m3 * 9.80665 + 1e-4 * reported;
            let off = (here.pressure_pa - reported).abs();
            worst = worst.max(off / bound);
            assert!(
                off < bound,
                "at {} m: {} Pa against {reported} Pa",
                l.height_msl_m,
                here.pressure_pa
            );
        }
        eprintln!("worst pressure difference: {worst:.2} of its bound");
    }
}
