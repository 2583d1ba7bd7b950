//! Horizontal wind as a function of height above the launch site.
//!
//! Two models: a constant wind, or a table of (height above ground, speed, direction) rows.
//! Directions follow the meteorological convention: the direction the wind blows **from**, in
//! degrees clockwise from true north (a "north wind", 0°, blows toward the south). The velocity
//! returned is the air's velocity over the ground in (east, north) components, m/s.
//!
//! A table is converted once, at construction, into (east, north) components; between rows
//! the **components** are interpolated linearly in height (not the speed and angle: this keeps
//! a veering wind continuous through north and gives the physically meaningful mean vector).
//! Below the first row and above the last the end row's wind is used (clamped).
//!
//! [`Wind::velocity_en`] is pure and allocation-free (binary search over the heights); it is
//! called per derivative evaluation and can be shared between threads.

use thiserror::Error;

/// One row of a wind table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindRow {
    /// Height above the launch site, m.
    pub height_agl_m: f64,
    /// Wind speed, m/s (≥ 0).
    pub speed_m_s: f64,
    /// Direction the wind blows from, degrees clockwise from north.
    pub from_deg: f64,
}

/// Invalid wind settings. `row` is the 0-based index in the table (`None` for a constant wind).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum WindError {
    /// A table must have at least one row.
    #[error("wind table: no rows (at least one is needed)")]
    EmptyTable,
    /// Negative or non-finite speed.
    #[error("wind{}: `speed_m_s` = {value}: must be finite and >= 0", row_label(*.row))]
    Speed {
        /// Table row, if any.
        row: Option<usize>,
        /// The rejected value.
        value: f64,
    },
    /// Non-finite direction.
    #[error("wind{}: `from_deg` = {value}: must be finite", row_label(*.row))]
    Direction {
        /// Table row, if any.
        row: Option<usize>,
        /// The rejected value.
        value: f64,
    },
    /// A turbulence intensity outside 0 to 1 ([`Wind::with_turbulence`]).
    #[error("wind: turbulence intensity = {value}: must be between 0 and 1 (the speed's standard deviation over its mean)")]
    Turbulence {
        /// The rejected value.
        value: f64,
    },
    /// A negative or non-finite scale of the speeds ([`Wind::transformed`]).
    #[error("wind: scale = {value}: must be finite and >= 0")]
    Scale {
        /// The rejected value.
        value: f64,
    },
    /// Non-finite height, or heights not strictly increasing.
    #[error(
        "wind table row {row}: `height_agl_m` = {value}: {}",
        height_rule(*previous)
    )]
    Height {
        /// Table row.
        row: usize,
        /// The rejected value.
        value: f64,
        /// Height of the previous row (−∞ for the first row).
        previous: f64,
    },
}

fn height_rule(previous: f64) -> String {
    if previous.is_finite() {
        format!("must be finite and greater than the previous row's {previous}")
    } else {
        "must be finite and not below the site (>= 0)".into()
    }
}

fn row_label(row: Option<usize>) -> String {
    match row {
        Some(r) => format!(" table row {r}"),
        None => String::new(),
    }
}

#[derive(Debug, Clone, PartialEq)]
enum Profile {
    Constant([f64; 2]),
    Table {
        heights_m: Vec<f64>,
        velocity_en: Vec<[f64; 2]>,
    },
}

/// A wind profile.
#[derive(Debug, Clone, PartialEq)]
pub struct Wind {
    /// The wind as given (constant or table), before any [`Wind::transformed`].
    given: Profile,
    /// The transformation applied to `given`: speed scale, clockwise turn in degrees.
    scale: f64,
    rotation_deg: f64,
    /// The wind blowing: `given` with its speeds scaled and its directions turned.
    profile: Profile,
    /// The turbulence intensity (OpenRocket's: the speed's standard deviation over its mean;
    /// 0: none). The flight draws the gusts ([`crate::turbulence`]).
    turbulence: f64,
}

impl Default for Wind {
    fn default() -> Self {
        Self::calm()
    }
}

impl Wind {
    /// Speed (m/s) and from-direction (degrees clockwise from north) of a constant wind as
    /// given (before [`Wind::transformed`]); `None` for a table.
    pub fn constant_parts(&self) -> Option<(f64, f64)> {
        match self.given {
            Profile::Constant([e, n]) => {
                let speed = e.hypot(n);
                let from = if speed == 0.0 {
                    0.0
                } else {
                    (-e).atan2(-n).to_degrees().rem_euclid(360.0)
                };
                Some((speed, from))
            }
            _ => None,
        }
    }

    /// Whether the wind changes with height (a table), or is one constant everywhere.
    #[inline]
    pub fn varies_with_height(&self) -> bool {
        self.constant_en().is_none()
    }

    /// The east and north components of a wind that is the same at every height (as it
    /// blows: scaled and turned), m/s; `None` for a table.
    #[inline]
    pub fn constant_en(&self) -> Option<[f64; 2]> {
        match self.profile {
            Profile::Constant(v) => Some(v),
            Profile::Table { .. } => None,
        }
    }

    /// No wind.
    pub fn calm() -> Self {
        Self::of(Profile::Constant([0.0, 0.0]))
    }

    /// The same wind at every height: `speed_m_s` blowing from `from_deg` (clockwise from
    /// north).
    pub fn constant(speed_m_s: f64, from_deg: f64) -> Result<Self, WindError> {
        check_speed_direction(None, speed_m_s, from_deg)?;
        Ok(Self::of(Profile::Constant(components_en(
            speed_m_s, from_deg,
        ))))
    }

    /// A wind table: heights strictly increasing. Built once; lookups do not allocate.
    pub fn table(rows: &[WindRow]) -> Result<Self, WindError> {
        if rows.is_empty() {
            return Err(WindError::EmptyTable);
        }
        let mut heights_m = Vec::with_capacity(rows.len());
        let mut velocity_en = Vec::with_capacity(rows.len());
        let mut previous = f64::NEG_INFINITY;
        for (i, r) in rows.iter().enumerate() {
            if !r.height_agl_m.is_finite() || r.height_agl_m <= previous || r.height_agl_m < 0.0 {
                return Err(WindError::Height {
                    row: i,
                    value: r.height_agl_m,
                    previous,
                });
            }
            check_speed_direction(Some(i), r.speed_m_s, r.from_deg)?;
            previous = r.height_agl_m;
            heights_m.push(r.height_agl_m);
            velocity_en.push(components_en(r.speed_m_s, r.from_deg));
        }
        Ok(Self::of(Profile::Table {
            heights_m,
            velocity_en,
        }))
    }

    fn of(profile: Profile) -> Self {
        Self {
            given: profile.clone(),
            scale: 1.0,
            rotation_deg: 0.0,
            profile,
            turbulence: 0.0,
        }
    }

    /// This wind with turbulence of intensity `intensity` (OpenRocket's turbulence intensity:
    /// the speed's standard deviation over its mean, 0 to
    /// [`crate::turbulence::MAX_TURBULENCE_INTENSITY`]); see [`crate::turbulence`].
    pub fn with_turbulence(mut self, intensity: f64) -> Result<Self, WindError> {
        if !(0.0..=crate::turbulence::MAX_TURBULENCE_INTENSITY).contains(&intensity) {
            return Err(WindError::Turbulence { value: intensity });
        }
        self.turbulence = intensity;
        Ok(self)
    }

    /// The turbulence intensity (0: none).
    pub fn turbulence_intensity(&self) -> f64 {
        self.turbulence
    }

    /// The transformation of the wind as given: (speed scale, clockwise turn in degrees);
    /// (1, 0) for a wind as given.
    pub fn transformation(&self) -> (f64, f64) {
        (self.scale, self.rotation_deg)
    }

    /// The wind as given, every speed multiplied by `scale` (≥ 0) and every direction turned
    /// `rotation_deg` clockwise (seen from above): how a campaign scatters a wind profile, as
    /// RocketPy's Monte Carlo scales its wind components. Applied to the wind as given, never
    /// on top of an earlier transformation; `(1, 0)` gives the wind as given back, bit for bit.
    pub fn transformed(&self, scale: f64, rotation_deg: f64) -> Result<Self, WindError> {
        if !scale.is_finite() || scale < 0.0 {
            return Err(WindError::Scale { value: scale });
        }
        if !rotation_deg.is_finite() {
            return Err(WindError::Direction {
                row: None,
                value: rotation_deg,
            });
        }
        if scale == 1.0 && rotation_deg == 0.0 {
            return Self::of(self.given.clone()).with_turbulence(self.turbulence);
        }
        // Clockwise by θ in (east, north): north (0, 1) turns toward east (sin θ, cos θ).
        let (sin, cos) = rotation_deg.to_radians().sin_cos();
        let turn = |[e, n]: [f64; 2]| [scale * (e * cos + n * sin), scale * (n * cos - e * sin)];
        let profile = match &self.given {
            Profile::Constant(v) => Profile::Constant(turn(*v)),
            Profile::Table {
                heights_m,
                velocity_en,
            } => Profile::Table {
                heights_m: heights_m.clone(),
                velocity_en: velocity_en.iter().map(|&v| turn(v)).collect(),
            },
        };
        Ok(Self {
            given: self.given.clone(),
            scale,
            rotation_deg,
            profile,
            turbulence: self.turbulence,
        })
    }

    /// Where `height_agl_m` falls: on a constant wind or an end row of the table (the
    /// velocity there), or between two rows (theirs, the fraction of the way and the height
    /// between them).
    #[inline(always)]
    fn locate(&self, height_agl_m: f64) -> Located {
        match &self.profile {
            Profile::Constant(v) => Located::Flat(*v),
            Profile::Table {
                heights_m,
                velocity_en,
            } => {
                // Number of rows at or below h: 0 → below the table, n → above it.
                let i = heights_m.partition_point(|&z| z <= height_agl_m);
                if i == 0 {
                    return Located::Flat(velocity_en[0]);
                }
                if i == heights_m.len() {
                    return Located::Flat(velocity_en[i - 1]);
                }
                let (z0, z1) = (heights_m[i - 1], heights_m[i]);
                Located::Between {
                    a: velocity_en[i - 1],
                    b: velocity_en[i],
                    s: (height_agl_m - z0) / (z1 - z0),
                    dz: z1 - z0,
                }
            }
        }
    }

    /// [`Wind::velocity_en`] and its rate of change with height there, `[east, north]` per
    /// metre (the slope of the table's segment holding the height; zero for a constant wind
    /// and below or above the table).
    #[inline(always)]
    pub fn velocity_and_shear_en(&self, height_agl_m: f64) -> ([f64; 2], [f64; 2]) {
        match self.locate(height_agl_m) {
            Located::Flat(v) => (v, [0.0, 0.0]),
            Located::Between { a, b, s, dz } => {
                let (de, dn) = (b[0] - a[0], b[1] - a[1]);
                ([a[0] + s * de, a[1] + s * dn], [de / dz, dn / dz])
            }
        }
    }

    /// Air velocity over the ground at `height_agl_m` above the launch site, as
    /// `[east, north]` m/s.
    #[inline(always)]
    pub fn velocity_en(&self, height_agl_m: f64) -> [f64; 2] {
        match self.locate(height_agl_m) {
            Located::Flat(v) => v,
            Located::Between { a, b, s, .. } => {
                [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])]
            }
        }
    }
}

/// Where a height falls in a wind ([`Wind::locate`]).
enum Located {
    Flat([f64; 2]),
    Between {
        a: [f64; 2],
        b: [f64; 2],
        s: f64,
        dz: f64,
    },
}

fn check_speed_direction(row: Option<usize>, speed: f64, from_deg: f64) -> Result<(), WindError> {
    if !speed.is_finite() || speed < 0.0 {
        return Err(WindError::Speed { row, value: speed });
    }
    if !from_deg.is_finite() {
        return Err(WindError::Direction {
            row,
            value: from_deg,
        });
    }
    Ok(())
}

/// (east, north) velocity of a wind of `speed` blowing from `from_deg`: it moves toward
/// `from_deg + 180°`.
pub(crate) fn components_en(speed: f64, from_deg: f64) -> [f64; 2] {
    let (s, c) = from_deg.to_radians().sin_cos();
    [-speed * s, -speed * c]
}

#[cfg(test)]
mod tests {
    use super::*;

    const TOL: f64 = 1e-12;

    fn close(a: [f64; 2], b: [f64; 2]) -> bool {
        (a[0] - b[0]).abs() < TOL && (a[1] - b[1]).abs() < TOL
    }

    #[test]
    fn a_north_wind_blows_toward_the_south() {
        let v = Wind::constant(7.0, 0.0).unwrap().velocity_en(123.0);
        eprintln!("north wind 7 m/s: {v:?}");
        assert!(close(v, [0.0, -7.0]));
    }

    #[test]
    fn an_east_wind_blows_toward_the_west_and_a_southwest_wind_toward_the_northeast() {
        let v = Wind::constant(4.0, 90.0).unwrap().velocity_en(0.0);
        assert!(close(v, [-4.0, 0.0]), "{v:?}");
        let v = Wind::constant(2.0, 225.0).unwrap().velocity_en(0.0);
        let c = 2.0 * std::f64::consts::FRAC_1_SQRT_2;
        assert!(close(v, [c, c]), "{v:?}");
    }

    #[test]
    fn a_transformed_wind_is_the_given_one_scaled_and_turned_clockwise() {
        // A west wind (toward the east) at 4 m/s, doubled and turned 90° clockwise: from the
        // north, toward the south, at 8 m/s.
        let west = Wind::constant(4.0, 270.0).unwrap();
        let v = west.transformed(2.0, 90.0).unwrap().velocity_en(10.0);
        assert!(close(v, [0.0, -8.0]), "{v:?}");
        // Each row of a table is turned the same way; heights are kept.
        let t = north_then_east().transformed(0.5, 180.0).unwrap();
        let (a, b) = (t.velocity_en(0.0), t.velocity_en(1000.0));
        let (a0, b0) = (
            north_then_east().velocity_en(0.0),
            north_then_east().velocity_en(1000.0),
        );
        assert!(close(a, [-0.5 * a0[0], -0.5 * a0[1]]), "{a:?}");
        assert!(close(b, [-0.5 * b0[0], -0.5 * b0[1]]), "{b:?}");
        // A transformation applies to the wind as given, never on top of another.
        let twice = west
            .transformed(3.0, 10.0)
            .unwrap()
            .transformed(2.0, 90.0)
            .unwrap();
        assert_eq!(twice, west.transformed(2.0, 90.0).unwrap());
        assert_eq!(
            west.transformed(3.0, 10.0)
                .unwrap()
                .transformed(1.0, 0.0)
                .unwrap(),
            west
        );
        // Scale 0 is calm.
        assert_eq!(
            west.transformed(0.0, 33.0).unwrap().velocity_en(5.0),
            [0.0, -0.0]
        );
    }

    #[test]
    fn a_transformation_refuses_a_negative_scale_and_a_non_finite_turn() {
        let w = Wind::constant(4.0, 270.0).unwrap();
        assert_eq!(
            w.transformed(-0.1, 0.0).unwrap_err().to_string(),
            "wind: scale = -0.1: must be finite and >= 0"
        );
        assert!(w.transformed(1.0, f64::NAN).is_err());
        assert!(w.transformed(f64::INFINITY, 0.0).is_err());
    }

    #[test]
    fn calm_is_zero_everywhere() {
        assert_eq!(Wind::calm().velocity_en(500.0), [0.0, 0.0]);
        assert_eq!(Wind::default(), Wind::calm());
    }

    fn north_then_east() -> Wind {
        Wind::table(&[
            WindRow {
                height_agl_m: 0.0,
                speed_m_s: 10.0,
                from_deg: 0.0,
            },
            WindRow {
                height_agl_m: 100.0,
                speed_m_s: 10.0,
                from_deg: 90.0,
            },
        ])
        .unwrap()
    }

    #[test]
    fn halfway_between_rows_the_components_are_averaged() {
        // (0, −10) and (−10, 0) → (−5, −5): speed 7.07 m/s, not the 10 m/s that
        // interpolating speed and angle would give.
        let v = north_then_east().velocity_en(50.0);
        eprintln!("halfway: {v:?}");
        assert!(close(v, [-5.0, -5.0]));
        let v = north_then_east().velocity_en(25.0);
        assert!(close(v, [-2.5, -7.5]), "{v:?}");
    }

    #[test]
    fn the_rows_themselves_are_returned_exactly_and_the_ends_are_clamped() {
        let w = north_then_east();
        assert!(close(w.velocity_en(0.0), [0.0, -10.0]));
        assert!(close(w.velocity_en(100.0), [-10.0, 0.0]));
        assert!(close(w.velocity_en(-20.0), [0.0, -10.0]));
        assert!(close(w.velocity_en(5_000.0), [-10.0, 0.0]));
    }

    #[test]
    fn the_shear_is_the_slope_of_the_segment_and_zero_off_the_table_and_in_a_constant_wind() {
        let w = north_then_east();
        // (0, −10) at 0 m to (−10, 0) at 100 m: (−0.1, +0.1) per metre between them.
        for h in [0.0, 37.5, 99.9] {
            let (v, shear) = w.velocity_and_shear_en(h);
            assert_eq!(
                v,
                w.velocity_en(h),
                "the same value as velocity_en at {h} m"
            );
            assert!(close(shear, [-0.1, 0.1]), "{shear:?} at {h} m");
        }
        for h in [-20.0, 100.0, 5_000.0] {
            assert_eq!(w.velocity_and_shear_en(h).1, [0.0, 0.0], "{h} m");
        }
        let c = Wind::constant(7.0, 30.0).unwrap();
        assert_eq!(
            c.velocity_and_shear_en(55.0),
            (c.velocity_en(55.0), [0.0, 0.0])
        );
        assert!(w.varies_with_height() && !c.varies_with_height());
    }

    #[test]
    fn a_table_of_many_rows_is_interpolated_in_the_right_interval() {
        let rows: Vec<WindRow> = (0..50)
            .map(|i| WindRow {
                height_agl_m: 10.0 * i as f64,
                speed_m_s: i as f64,
                from_deg: 180.0, // from the south: north component = +speed
            })
            .collect();
        let w = Wind::table(&rows).unwrap();
        for k in 0..490 {
            let h = k as f64 + 0.5;
            let v = w.velocity_en(h);
            assert!((v[1] - h / 10.0).abs() < 1e-12, "h {h}: {v:?}");
            assert!(v[0].abs() < 1e-12);
        }
    }

    #[test]
    fn bad_wind_input_is_a_typed_error_naming_the_row_and_field() {
        assert_eq!(Wind::table(&[]), Err(WindError::EmptyTable));
        assert!(matches!(
            Wind::constant(-1.0, 0.0),
            Err(WindError::Speed { row: None, .. })
        ));
        assert!(matches!(
            Wind::constant(1.0, f64::NAN),
            Err(WindError::Direction { row: None, .. })
        ));
        let row = |h: f64, s: f64| WindRow {
            height_agl_m: h,
            speed_m_s: s,
            from_deg: 0.0,
        };
        let err = Wind::table(&[row(-5.0, 1.0), row(10.0, 1.0)]).unwrap_err();
        assert!(matches!(err, WindError::Height { row: 0, .. }));
        assert!(err.to_string().contains(">= 0"), "{err}");
        let err = Wind::table(&[row(0.0, 1.0), row(0.0, 1.0)]).unwrap_err();
        assert!(matches!(err, WindError::Height { row: 1, .. }));
        assert!(err.to_string().contains("row 1") && err.to_string().contains("height_agl_m"));
        let err = Wind::table(&[row(0.0, 1.0), row(10.0, f64::INFINITY)]).unwrap_err();
        assert!(matches!(err, WindError::Speed { row: Some(1), .. }));
        assert!(err.to_string().contains("table row 1") && err.to_string().contains("speed_m_s"));
    }
}
