//! Look-up tables over Mach number, built once before a flight and read every integration
//! step without allocating.
//!
//! [`MachTable`] samples a function on the uniform grid Mach 0, 0.01, ..., 5 (501 nodes) and
//! interpolates linearly; look-up is an index computation, no search. Below Mach 0 the first
//! node is used and above Mach 5 the last (constant extrapolation, as RocketPy's `Function`
//! does with `extrapolation="constant"`). [`Curve`] is a piecewise-linear curve through given
//! points (a design's drag curves), looked up by binary search, with the same constant
//! extrapolation at both ends.

/// Highest Mach number of the grid.
pub const MACH_MAX: f64 = 5.0;
/// Spacing of the grid.
pub const MACH_STEP: f64 = 0.01;
/// Number of grid nodes: Mach 0 to [`MACH_MAX`] inclusive.
pub const MACH_NODES: usize = 501;

/// Mach number of grid node `i`.
#[inline]
pub fn mach_node(i: usize) -> f64 {
    i as f64 * MACH_STEP
}

/// A function of Mach number sampled on the uniform grid 0..=5 step 0.01.
#[derive(Debug, Clone, PartialEq)]
pub struct MachTable {
    /// One value per node (a fixed-size array, so that a look-up needs no length check).
    values: Box<[f64; MACH_NODES]>,
}

/// The boxed node values of a table from exactly [`MACH_NODES`] values.
fn nodes(values: Vec<f64>) -> Box<[f64; MACH_NODES]> {
    values
        .into_boxed_slice()
        .try_into()
        .expect("a Mach table has a value at every node")
}

impl MachTable {
    /// Samples `f` at every node of the grid.
    pub fn from_fn(mut f: impl FnMut(f64) -> f64) -> Self {
        let values: Vec<f64> = (0..MACH_NODES).map(|i| f(mach_node(i))).collect();
        MachTable {
            values: nodes(values),
        }
    }

    /// The same value at every Mach number.
    pub fn constant(value: f64) -> Self {
        MachTable {
            values: Box::new([value; MACH_NODES]),
        }
    }

    /// Node values, Mach 0 first.
    #[inline]
    pub fn values(&self) -> &[f64; MACH_NODES] {
        &self.values
    }

    /// Linear interpolation at `mach`; constant beyond the grid's ends. NaN gives NaN.
    #[inline]
    pub fn at(&self, mach: f64) -> f64 {
        if mach.is_nan() {
            return f64::NAN;
        }
        let u = mach / MACH_STEP;
        if u <= 0.0 {
            return self.values[0];
        }
        let last = MACH_NODES - 1;
        if u >= last as f64 {
            return self.values[last];
        }
        let i = u as usize; // floor, u in (0, last)
        let t = u - i as f64;
        let (a, b) = (self.values[i], self.values[i + 1]);
        a + (b - a) * t
    }

    /// Node-wise combination of two tables.
    pub fn zip_with(&self, other: &MachTable, mut f: impl FnMut(f64, f64) -> f64) -> MachTable {
        let values: Vec<f64> = self
            .values
            .iter()
            .zip(other.values.iter())
            .map(|(&a, &b)| f(a, b))
            .collect();
        MachTable {
            values: nodes(values),
        }
    }
}

/// A piecewise-linear curve `y(x)` through points with strictly increasing `x`.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    xs: Box<[f64]>,
    ys: Box<[f64]>,
}

impl Curve {
    /// A curve through `points` (x strictly increasing, at least one point). Returns `None`
    /// if the points are empty, not finite or not strictly increasing in `x`.
    pub fn new(points: &[(f64, f64)]) -> Option<Self> {
        if points.is_empty() {
            return None;
        }
        let ok_finite = points.iter().all(|(x, y)| x.is_finite() && y.is_finite());
        let ok_order = points.windows(2).all(|w| w[1].0 > w[0].0);
        if !ok_finite || !ok_order {
            return None;
        }
        Some(Curve {
            xs: points.iter().map(|p| p.0).collect(),
            ys: points.iter().map(|p| p.1).collect(),
        })
    }

    /// The curve sampled on the Mach grid.
    pub fn to_mach_table(&self) -> MachTable {
        MachTable::from_fn(|m| self.at(m))
    }

    /// Linear interpolation at `x`; the end values beyond the ends. NaN gives NaN.
    #[inline]
    pub fn at(&self, x: f64) -> f64 {
        if x.is_nan() {
            return f64::NAN;
        }
        let n = self.xs.len();
        if x <= self.xs[0] {
            return self.ys[0];
        }
        if x >= self.xs[n - 1] {
            return self.ys[n - 1];
        }
        // First index with xs[j] > x; 1 <= j <= n-1 here.
        let j = self.xs.partition_point(|&xi| xi <= x);
        let (x0, x1, y0, y1) = (self.xs[j - 1], self.xs[j], self.ys[j - 1], self.ys[j]);
        y0 + (y1 - y0) * (x - x0) / (x1 - x0)
    }

    /// The points' abscissae.
    pub fn xs(&self) -> &[f64] {
        &self.xs
    }

    /// The points' ordinates.
    pub fn ys(&self) -> &[f64] {
        &self.ys
    }
}

/// Natural logarithm of the smallest Reynolds-number scale [`ReynoldsTables`] tabulates (its
/// first table; `k` ≈ 0.011, air about 25 km up).
pub const LN_RE_SCALE_MIN: f64 = -4.5;
/// Spacing of [`ReynoldsTables`] in `ln k`.
pub const LN_RE_SCALE_STEP: f64 = 0.5;
/// Number of tables: `ln k` from [`LN_RE_SCALE_MIN`] to +0.5 (`k` ≈ 1.65, cold dense air);
/// table 9 is `k = 1` exactly.
pub const LN_RE_SCALE_NODES: usize = 11;

/// A function of Mach number and of the Reynolds number's scale `k`, the flight's Reynolds
/// number over that of sea-level standard air at the same Mach number: one [`MachTable`] per
/// `ln k` = [`LN_RE_SCALE_MIN`] + j [`LN_RE_SCALE_STEP`], linear in `ln k` between them
/// (the skin friction, `1/(1.5 ln Re − 5.6)²`, is smooth in `ln Re`), constant beyond the
/// first and the last.
#[derive(Debug, Clone, PartialEq)]
pub struct ReynoldsTables {
    tables: Vec<MachTable>,
}

impl ReynoldsTables {
    /// `ln k` of table `j`.
    pub fn ln_scale_of(j: usize) -> f64 {
        LN_RE_SCALE_MIN + j as f64 * LN_RE_SCALE_STEP
    }

    /// Samples `f(mach, k)` at every Mach node of every table.
    pub fn from_fn(mut f: impl FnMut(f64, f64) -> f64) -> Self {
        let tables = (0..LN_RE_SCALE_NODES)
            .map(|j| {
                let k = Self::ln_scale_of(j).exp();
                MachTable::from_fn(|m| f(m, k))
            })
            .collect();
        ReynoldsTables { tables }
    }

    /// Table `j` (`ln k` = [`ReynoldsTables::ln_scale_of`]`(j)`).
    pub fn table(&self, j: usize) -> &MachTable {
        &self.tables[j]
    }

    /// The value at `mach` and `ln k` = `ln_scale`: the two tables about `ln_scale` read at
    /// `mach` and interpolated; below the first table (or NaN) the first, above the last the
    /// last.
    #[inline]
    pub fn at(&self, mach: f64, ln_scale: f64) -> f64 {
        let v = (ln_scale - LN_RE_SCALE_MIN) / LN_RE_SCALE_STEP;
        if v.is_nan() || v <= 0.0 {
            return self.tables[0].at(mach);
        }
        let last = LN_RE_SCALE_NODES - 1;
        if v >= last as f64 {
            return self.tables[last].at(mach);
        }
        let j = v as usize;
        let w = v - j as f64;
        let (a, b) = (self.tables[j].at(mach), self.tables[j + 1].at(mach));
        a + (b - a) * w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mach_table_of_a_linear_function_interpolates_it_exactly_between_nodes() {
        let t = MachTable::from_fn(|m| 3.0 * m - 1.0);
        for &m in &[0.0, 0.005, 0.337, 1.0, 2.5, 4.999] {
            assert!((t.at(m) - (3.0 * m - 1.0)).abs() < 1e-12, "m={m}");
        }
    }

    #[test]
    fn a_mach_table_holds_its_end_values_beyond_the_grid() {
        let t = MachTable::from_fn(|m| m * m);
        assert_eq!(t.at(-1.0), 0.0);
        assert!((t.at(7.0) - 25.0).abs() < 1e-12);
        assert!(t.at(f64::NAN).is_nan());
    }

    #[test]
    fn a_mach_table_of_a_parabola_is_within_the_linear_interpolation_bound() {
        // Error of linear interpolation of m² is h²/4 at most: 0.01²/4 = 2.5e-5.
        let t = MachTable::from_fn(|m| m * m);
        assert!((t.at(1.005) - 1.005f64.powi(2)).abs() <= 2.5e-5 + 1e-15);
    }

    #[test]
    fn a_curve_interpolates_between_its_points_and_is_constant_outside() {
        let c = Curve::new(&[(0.0, 0.5), (1.0, 0.7), (2.0, 0.4)]).unwrap();
        assert!((c.at(0.25) - 0.55).abs() < 1e-15);
        assert!((c.at(1.5) - 0.55).abs() < 1e-15);
        assert_eq!(c.at(1.0), 0.7);
        assert_eq!(c.at(-3.0), 0.5);
        assert_eq!(c.at(9.0), 0.4);
    }

    #[test]
    fn a_curve_refuses_points_out_of_order_or_empty() {
        assert!(Curve::new(&[]).is_none());
        assert!(Curve::new(&[(0.0, 1.0), (0.0, 2.0)]).is_none());
        assert!(Curve::new(&[(0.0, 1.0), (f64::NAN, 2.0)]).is_none());
    }
}
