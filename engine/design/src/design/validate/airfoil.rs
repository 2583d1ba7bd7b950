//! A fin's section lift (`airfoil`): the 2-D lift-curve slope Diederich's correlation takes,
//! given, or read from a lift table as RocketPy reads its `airfoil` file.

use super::files::two_columns;
use super::Builder;
use crate::design::raw::RawAirfoil;
use crate::error::{DesignError, Location, Rule};

impl Builder<'_> {
    /// A fin's `airfoil`: its 2-D lift-curve slope per rad, given, or read from its lift
    /// table as RocketPy reads it (`Function.differentiate(1e-3)` of the linearly
    /// interpolated table: the slope of the segment holding 0.001 in the table's own unit,
    /// the first or last segment outside it; × 180/π for a table in degrees).
    pub(super) fn airfoil_lift_slope(
        &self,
        at: &Location,
        a: &RawAirfoil,
    ) -> Result<f64, DesignError> {
        let why =
            |field: &str, why: &'static str| self.invalid(at, Some(field), Rule::Airfoil { why });
        match (a.lift_slope_per_rad, &a.csv) {
            (Some(slope), None) => {
                if a.angles.is_some() {
                    return Err(why("airfoil.angles", "goes with a lift table (\"csv\")"));
                }
                self.positive(at, "airfoil.lift_slope_per_rad", slope)
            }
            (None, Some(name)) => {
                let per_unit = match a.angles.as_deref() {
                    Some("radians") => 1.0,
                    Some("degrees") => 180.0 / std::f64::consts::PI,
                    _ => {
                        return Err(why(
                            "airfoil.angles",
                            "a lift table's angles are \"radians\" or \"degrees\"",
                        ))
                    }
                };
                let (file, text) = self.read_beside(name, at, "airfoil.csv")?;
                let (rows, lines) = two_columns(&text, &file, "angle,cl")?;
                let bad = |line: usize, message: String| DesignError::Csv {
                    file: file.clone(),
                    line,
                    message,
                };
                if rows.len() < 2 {
                    return Err(bad(0, "a lift table needs at least two rows".to_owned()));
                }
                for (i, w) in rows.windows(2).enumerate() {
                    if w[1][0].partial_cmp(&w[0][0]) != Some(std::cmp::Ordering::Greater) {
                        return Err(bad(
                            lines[i + 1],
                            "the angles must increase strictly".to_owned(),
                        ));
                    }
                }
                // RocketPy's bisect_left of 0.001, held to the table's segments.
                let k = rows
                    .partition_point(|r| r[0] < 1e-3)
                    .clamp(1, rows.len() - 1)
                    - 1;
                let slope = (rows[k + 1][1] - rows[k][1]) / (rows[k + 1][0] - rows[k][0]);
                let slope = slope * per_unit;
                if slope > 0.0 && slope.is_finite() {
                    Ok(slope)
                } else {
                    Err(bad(
                        lines[k + 1],
                        format!(
                            "the lift table's slope at zero angle must be positive (got {slope} per rad)"
                        ),
                    ))
                }
            }
            _ => Err(why(
                "airfoil",
                "give exactly one of \"lift_slope_per_rad\" and \"csv\"",
            )),
        }
    }
}
