//! Lanes: the number type the shared kernels are written over, so that one copy of each
//! equation serves the single flight (`f64`, one lane) and the batch engine ([`F64x4`], four
//! variants side by side in one register's worth of data).
//!
//! Every operation of [`Real`] is element-wise and exactly the IEEE operation of `f64` on each
//! lane (add, subtract, multiply, divide, square root, comparisons, select). Functions the
//! hardware has no vector form of are written once over [`Real`] from those operations
//! (`atan2`, `ln`, `exp`: [`elementary`]), or read lane by lane (a table's cells), so the
//! four lanes run in vector registers and each is the one-lane result. Rust never fuses a
//! multiply and an add on its own, so lane `i` of a kernel evaluated on `F64x4` is bit for
//! bit the kernel evaluated on that lane's `f64` inputs: the batch engine's lanes equal single
//! flights by construction, not by tolerance.
//!
//! [`V3`] and [`M3`] are the small vector and matrix types of the generic kernels (nalgebra's
//! types need a full `RealField`, which a lane bundle is not).

use hpr_design::aero::table::{MachTable, MACH_NODES, MACH_STEP};
use std::ops::{Add, Div, Mul, Neg, Sub};

pub mod elementary;
pub use elementary::{atan2_upper, exp, ln};

/// A number, or a bundle of numbers (lanes) operated on together.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// A truth value per lane.
    type Mask: Copy;
    /// Number of lanes.
    const LANES: usize;
    /// Every lane `v`.
    fn splat(v: f64) -> Self;
    /// Lane `i`.
    fn lane(self, i: usize) -> f64;
    /// `f(i, lane i)` on every lane.
    fn map(self, f: impl FnMut(usize, f64) -> f64) -> Self;
    fn sqrt(self) -> Self;
    fn abs(self) -> Self;
    /// Lane-wise [`f64::max`] (a NaN lane gives the other operand).
    fn max(self, other: Self) -> Self;
    /// Lane-wise `self > other`.
    fn gt(self, other: Self) -> Self::Mask;
    /// Lane-wise `self == other`.
    fn eq(self, other: Self) -> Self::Mask;
    /// Lane-wise `self != other` (true for a NaN lane).
    fn ne(self, other: Self) -> Self::Mask;
    fn or(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Lane-wise `if m { a } else { b }`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// Lane `i` of a mask.
    fn mask_lane(m: Self::Mask, i: usize) -> bool;
    /// Set lane `i` of a mask.
    fn set_mask_lane(m: &mut Self::Mask, i: usize, v: bool);
    /// Lane `i`, to write.
    fn lane_mut(&mut self, i: usize) -> &mut f64;
    /// `table` at Mach `mach`, lane by lane exactly [`MachTable::at`].
    fn mach_table(table: &MachTable, mach: Self) -> Self;
}

impl Real for f64 {
    type Mask = bool;
    const LANES: usize = 1;
    #[inline(always)]
    fn splat(v: f64) -> f64 {
        v
    }
    #[inline(always)]
    fn lane(self, _: usize) -> f64 {
        self
    }
    #[inline(always)]
    fn map(self, mut f: impl FnMut(usize, f64) -> f64) -> f64 {
        f(0, self)
    }
    #[inline(always)]
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> f64 {
        f64::abs(self)
    }
    #[inline(always)]
    fn max(self, other: f64) -> f64 {
        f64::max(self, other)
    }
    #[inline(always)]
    fn gt(self, other: f64) -> bool {
        self > other
    }
    #[inline(always)]
    fn eq(self, other: f64) -> bool {
        self == other
    }
    #[inline(always)]
    fn ne(self, other: f64) -> bool {
        self != other
    }
    #[inline(always)]
    fn or(a: bool, b: bool) -> bool {
        a || b
    }
    #[inline(always)]
    fn select(m: bool, a: f64, b: f64) -> f64 {
        if m {
            a
        } else {
            b
        }
    }
    #[inline(always)]
    fn mask_lane(m: bool, _: usize) -> bool {
        m
    }
    #[inline(always)]
    fn set_mask_lane(m: &mut bool, _: usize, v: bool) {
        *m = v;
    }
    #[inline(always)]
    fn lane_mut(&mut self, _: usize) -> &mut f64 {
        self
    }
    #[inline(always)]
    fn mach_table(table: &MachTable, mach: f64) -> f64 {
        table.at(mach)
    }
}

/// `[e(0), e(1), e(2), e(3)]` for `four!(i => e(i))`, each lane's expression spelled out in
/// line (with `i` a constant). The table look-ups gather their cells with it: written with
/// `std::array::from_fn` and `map`, the compiler stopped inlining those calls when unrelated
/// code moved (+1 % of the batch's instructions); spelled out they stay in line (−1.2 %). The
/// arithmetic of [`F64x4`] keeps `from_fn` and `map`, which it vectorises better than spelled-out
/// lanes (those cost +4.3 %, measured again on 2026-12-02, 48cb63e).
macro_rules! four {
    ($i:ident => $e:expr) => {
        [
            {
                let $i: usize = 0;
                $e
            },
            {
                let $i: usize = 1;
                $e
            },
            {
                let $i: usize = 2;
                $e
            },
            {
                let $i: usize = 3;
                $e
            },
        ]
    };
}
pub(crate) use four;

/// Four `f64` lanes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(C, align(32))]
pub struct F64x4(pub [f64; 4]);

macro_rules! lanewise {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for F64x4 {
            type Output = F64x4;
            #[inline(always)]
            fn $f(self, o: F64x4) -> F64x4 {
                let (a, b) = (self.0, o.0);
                F64x4(std::array::from_fn(|i| a[i] $op b[i]))
            }
        }
    };
}
lanewise!(Add, add, +);
lanewise!(Sub, sub, -);
lanewise!(Mul, mul, *);
lanewise!(Div, div, /);

impl Neg for F64x4 {
    type Output = F64x4;
    #[inline(always)]
    fn neg(self) -> F64x4 {
        F64x4(self.0.map(|a| -a))
    }
}

impl Real for F64x4 {
    type Mask = [bool; 4];
    const LANES: usize = 4;
    #[inline(always)]
    fn splat(v: f64) -> F64x4 {
        F64x4([v; 4])
    }
    #[inline(always)]
    fn lane(self, i: usize) -> f64 {
        self.0[i]
    }
    #[inline(always)]
    fn map(self, mut f: impl FnMut(usize, f64) -> f64) -> F64x4 {
        let a = self.0;
        F64x4(std::array::from_fn(|i| f(i, a[i])))
    }
    #[inline(always)]
    fn sqrt(self) -> F64x4 {
        F64x4(self.0.map(f64::sqrt))
    }
    #[inline(always)]
    fn abs(self) -> F64x4 {
        F64x4(self.0.map(f64::abs))
    }
    #[inline(always)]
    fn max(self, o: F64x4) -> F64x4 {
        let (a, b) = (self.0, o.0);
        F64x4(std::array::from_fn(|i| a[i].max(b[i])))
    }
    #[inline(always)]
    fn gt(self, o: F64x4) -> [bool; 4] {
        let (a, b) = (self.0, o.0);
        std::array::from_fn(|i| a[i] > b[i])
    }
    #[inline(always)]
    fn eq(self, o: F64x4) -> [bool; 4] {
        let (a, b) = (self.0, o.0);
        std::array::from_fn(|i| a[i] == b[i])
    }
    #[inline(always)]
    fn ne(self, o: F64x4) -> [bool; 4] {
        let (a, b) = (self.0, o.0);
        std::array::from_fn(|i| a[i] != b[i])
    }
    #[inline(always)]
    fn or(a: [bool; 4], b: [bool; 4]) -> [bool; 4] {
        std::array::from_fn(|i| a[i] || b[i])
    }
    #[inline(always)]
    fn select(m: [bool; 4], a: F64x4, b: F64x4) -> F64x4 {
        let (x, y) = (a.0, b.0);
        F64x4(std::array::from_fn(|i| if m[i] { x[i] } else { y[i] }))
    }
    #[inline(always)]
    fn mask_lane(m: [bool; 4], i: usize) -> bool {
        m[i]
    }
    #[inline(always)]
    fn set_mask_lane(m: &mut [bool; 4], i: usize, v: bool) {
        m[i] = v;
    }
    #[inline(always)]
    fn lane_mut(&mut self, i: usize) -> &mut f64 {
        &mut self.0[i]
    }
    /// The four lanes' look-ups without a branch, so that they run in vector registers but
    /// for the eight loads: the same division, truncation, subtraction and interpolation as
    /// [`MachTable::at`], and its end values and NaN chosen afterwards by select.
    #[inline(always)]
    fn mach_table(table: &MachTable, mach: F64x4) -> F64x4 {
        const LAST: usize = MACH_NODES - 1;
        let v = table.values();
        let u = mach.0.map(|m| m / MACH_STEP);
        let (i, t) = grid_cells(u, LAST);
        let a: [f64; 4] = std::array::from_fn(|l| v[i[l]]);
        let b: [f64; 4] = std::array::from_fn(|l| v[i[l] + 1]);
        let x = F64x4(std::array::from_fn(|l| a[l] + (b[l] - a[l]) * t[l]));
        let below: [bool; 4] = std::array::from_fn(|l| u[l] <= 0.0);
        let above: [bool; 4] = std::array::from_fn(|l| u[l] >= LAST as f64);
        let x = F64x4::select(below, F64x4::splat(v[0]), x);
        let x = F64x4::select(above, F64x4::splat(v[LAST]), x);
        F64x4::select(mach.ne(mach), F64x4::splat(f64::NAN), x)
    }
}

/// Four look-ups' cells on a uniform grid of `cells` cells, the positions `u` given in grid
/// steps: each cell's index, `u` truncated, and the fraction `u − index` across it, as a
/// one-lane look-up computes them for `u` inside the grid. A `u` outside (or NaN) is held in
/// `[0, cells − 1]` first, so every lane's index reads inside the table; the caller chooses
/// what such a lane gives. Written without branches, so that four lanes run in vector registers.
#[inline(always)]
pub fn grid_cells(u: [f64; 4], cells: usize) -> ([usize; 4], [f64; 4]) {
    let top = cells - 1;
    // f64::max returns 0 for NaN; the integer clamp lets the compiler drop bounds checks.
    let held: [f64; 4] = std::array::from_fn(|l| u[l].max(0.0).min(top as f64));
    // SAFETY: every `held` lane is finite and in [0, top], so truncating it fits an `i32`.
    let k: [i32; 4] = std::array::from_fn(|l| unsafe { held[l].to_int_unchecked::<i32>() });
    let i: [usize; 4] = four!(l => (k[l] as usize).min(top));
    (i, std::array::from_fn(|l| u[l] - f64::from(k[l])))
}

impl F64x4 {
    /// Lanes from a function of the lane index.
    #[inline(always)]
    pub fn from_fn(f: impl FnMut(usize) -> f64) -> F64x4 {
        F64x4(std::array::from_fn(f))
    }
}

/// A 3-vector of lanes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct V3<S> {
    pub x: S,
    pub y: S,
    pub z: S,
}

impl<S: Real> V3<S> {
    #[inline(always)]
    pub fn new(x: S, y: S, z: S) -> V3<S> {
        V3 { x, y, z }
    }
    #[inline(always)]
    pub fn zero() -> V3<S> {
        let z = S::splat(0.0);
        V3 { x: z, y: z, z }
    }
    /// The same `f64` vector in every lane.
    #[inline(always)]
    pub fn splat(v: &nalgebra::Vector3<f64>) -> V3<S> {
        V3::new(S::splat(v.x), S::splat(v.y), S::splat(v.z))
    }
    #[inline(always)]
    pub fn dot(&self, o: &V3<S>) -> S {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    #[inline(always)]
    pub fn cross(&self, o: &V3<S>) -> V3<S> {
        V3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }
    #[inline(always)]
    pub fn scale(&self, s: S) -> V3<S> {
        V3::new(self.x * s, self.y * s, self.z * s)
    }
    #[inline(always)]
    pub fn norm_squared(&self) -> S {
        self.dot(self)
    }
    /// Each component over `s`.
    #[inline(always)]
    pub fn div(&self, s: S) -> V3<S> {
        V3::new(self.x / s, self.y / s, self.z / s)
    }
    /// Lane-wise `if m { a } else { b }`.
    #[inline(always)]
    pub fn select(m: S::Mask, a: &V3<S>, b: &V3<S>) -> V3<S> {
        V3::new(
            S::select(m, a.x, b.x),
            S::select(m, a.y, b.y),
            S::select(m, a.z, b.z),
        )
    }
}

/// Whether any lane of `m` is true.
#[inline(always)]
pub fn any<S: Real>(m: S::Mask) -> bool {
    (0..S::LANES).any(|i| S::mask_lane(m, i))
}

impl V3<f64> {
    #[inline(always)]
    pub fn from_na(v: &nalgebra::Vector3<f64>) -> V3<f64> {
        V3::new(v.x, v.y, v.z)
    }
    #[inline(always)]
    pub fn to_na(self) -> nalgebra::Vector3<f64> {
        nalgebra::Vector3::new(self.x, self.y, self.z)
    }
}

impl<S: Real> Add for V3<S> {
    type Output = V3<S>;
    #[inline(always)]
    fn add(self, o: V3<S>) -> V3<S> {
        V3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<S: Real> Sub for V3<S> {
    type Output = V3<S>;
    #[inline(always)]
    fn sub(self, o: V3<S>) -> V3<S> {
        V3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<S: Real> Neg for V3<S> {
    type Output = V3<S>;
    #[inline(always)]
    fn neg(self) -> V3<S> {
        V3::new(-self.x, -self.y, -self.z)
    }
}

impl V3<F64x4> {
    /// Write `v` into lane `l`.
    #[inline(always)]
    pub fn set_lane(&mut self, l: usize, v: &V3<f64>) {
        self.x.0[l] = v.x;
        self.y.0[l] = v.y;
        self.z.0[l] = v.z;
    }
}

/// A 3×3 matrix of lanes, rows first.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct M3<S> {
    pub m: [[S; 3]; 3],
}

impl<S: Real> M3<S> {
    /// The diagonal matrix `diag(a, b, c)`.
    #[inline(always)]
    pub fn diag(a: S, b: S, c: S) -> M3<S> {
        let z = S::splat(0.0);
        M3 {
            m: [[a, z, z], [z, b, z], [z, z, c]],
        }
    }
    /// `a bᵀ`.
    #[inline(always)]
    pub fn outer(a: &V3<S>, b: &V3<S>) -> M3<S> {
        let (a, b) = ([a.x, a.y, a.z], [b.x, b.y, b.z]);
        let mut m = [[a[0]; 3]; 3];
        for (r, row) in m.iter_mut().enumerate() {
            for (c, e) in row.iter_mut().enumerate() {
                *e = a[r] * b[c];
            }
        }
        M3 { m }
    }
    /// `J(v) = |v|² E − v vᵀ`: what a unit point mass at `v` adds to the inertia about the
    /// origin.
    #[inline(always)]
    pub fn point_inertia(v: &V3<S>) -> M3<S> {
        let n = v.norm_squared();
        M3::diag(n, n, n).sub(&M3::outer(v, v))
    }
    /// Element-wise `f(self, other)`.
    #[inline(always)]
    fn zip(&self, o: &M3<S>, f: impl Fn(S, S) -> S) -> M3<S> {
        // Plain loops (`array::from_fn` and `map` are sometimes left as calls).
        let mut m = self.m;
        for (row, o_row) in m.iter_mut().zip(&o.m) {
            for (e, &b) in row.iter_mut().zip(o_row) {
                *e = f(*e, b);
            }
        }
        M3 { m }
    }
    #[inline(always)]
    #[allow(clippy::should_implement_trait)]
    pub fn add(&self, o: &M3<S>) -> M3<S> {
        self.zip(o, |a, b| a + b)
    }
    #[inline(always)]
    #[allow(clippy::should_implement_trait)]
    pub fn sub(&self, o: &M3<S>) -> M3<S> {
        self.zip(o, |a, b| a - b)
    }
    /// Every element times `s`.
    #[inline(always)]
    pub fn scale(&self, s: S) -> M3<S> {
        let mut m = self.m;
        for row in m.iter_mut() {
            for e in row.iter_mut() {
                *e = *e * s;
            }
        }
        M3 { m }
    }
    /// Lane-wise `if m { a } else { b }`.
    #[inline(always)]
    pub fn select(m: S::Mask, a: &M3<S>, b: &M3<S>) -> M3<S> {
        a.zip(b, |x, y| S::select(m, x, y))
    }
    #[inline(always)]
    pub fn mul_v(&self, v: &V3<S>) -> V3<S> {
        let m = &self.m;
        V3::new(
            m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z,
        )
    }
    /// `selfᵀ v`.
    #[inline(always)]
    pub fn tr_mul_v(&self, v: &V3<S>) -> V3<S> {
        let m = &self.m;
        V3::new(
            m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z,
            m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
            m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z,
        )
    }
    /// The inverse by the adjugate over the determinant (infinite or NaN entries when the
    /// matrix is singular, which the drivers report as a non-finite derivative).
    #[inline(always)]
    pub fn inverse(&self) -> M3<S> {
        let m = &self.m;
        let c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
        let c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
        let c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
        let det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
        let inv = S::splat(1.0) / det;
        M3 {
            m: [
                [
                    c00 * inv,
                    (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * inv,
                    (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * inv,
                ],
                [
                    c01 * inv,
                    (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * inv,
                    (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * inv,
                ],
                [
                    c02 * inv,
                    (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * inv,
                    (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * inv,
                ],
            ],
        }
    }
}

impl M3<f64> {
    #[inline(always)]
    pub fn from_na(a: &nalgebra::Matrix3<f64>) -> M3<f64> {
        M3 {
            m: [
                [a[(0, 0)], a[(0, 1)], a[(0, 2)]],
                [a[(1, 0)], a[(1, 1)], a[(1, 2)]],
                [a[(2, 0)], a[(2, 1)], a[(2, 2)]],
            ],
        }
    }
    pub fn to_na(&self) -> nalgebra::Matrix3<f64> {
        let m = &self.m;
        nalgebra::Matrix3::new(
            m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2],
        )
    }
}

/// Gather lanes: `[V3<f64>; 4]` → `V3<F64x4>`.
#[inline(always)]
pub fn pack_v3(v: [&V3<f64>; 4]) -> V3<F64x4> {
    V3::new(
        F64x4::from_fn(|i| v[i].x),
        F64x4::from_fn(|i| v[i].y),
        F64x4::from_fn(|i| v[i].z),
    )
}

/// Gather lanes: `[M3<f64>; 4]` → `M3<F64x4>`.
#[inline(always)]
pub fn pack_m3(a: [&M3<f64>; 4]) -> M3<F64x4> {
    M3 {
        m: std::array::from_fn(|r| std::array::from_fn(|c| F64x4::from_fn(|i| a[i].m[r][c]))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A xorshift source of uniform numbers in [0, 1) (the lane tests' inputs).
    pub(super) fn uniform(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    #[test]
    fn the_four_lane_mach_table_look_up_is_the_one_lane_look_up_bit_for_bit() {
        use hpr_design::aero::table::MACH_MAX;
        // A table whose neighbouring values differ (so a wrong cell or weight shows).
        let table = MachTable::from_fn(|m| 0.3 + 0.1 * (7.0 * m).sin() + 0.02 * m * m);
        let mut next = uniform(0x9e37_79b9_7f4a_7c15);
        let node = |i: usize| i as f64 * MACH_STEP;
        let mut machs = vec![
            0.0,
            -0.0,
            -1e-300,
            1e-300,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            MACH_MAX,
            node(MACH_NODES - 1),
            node(MACH_NODES - 2),
            MACH_MAX - 1e-12,
            MACH_MAX + 1e-12,
            -3.0,
            60.0,
        ];
        machs.extend((0..MACH_NODES).map(node));
        machs.extend((0..20_000).map(|_| -0.2 + 5.6 * next()));
        for w in machs.chunks(4) {
            let mut four = [0.0; 4];
            four[..w.len()].copy_from_slice(w);
            let got = F64x4::mach_table(&table, F64x4(four));
            for (&mach, &got) in four.iter().zip(&got.0) {
                let want = table.at(mach);
                assert!(
                    got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
                    "Mach {mach}: four lanes {got} against one {want}"
                );
            }
        }
    }

    #[test]
    fn the_inverse_times_the_matrix_is_the_identity() {
        let a = M3 {
            m: [[2.0, 0.3, -0.1], [0.3, 1.5, 0.2], [-0.1, 0.2, 0.9]],
        };
        let inv = a.inverse().to_na();
        let err = (inv * a.to_na() - nalgebra::Matrix3::identity())
            .abs()
            .max();
        assert!(err < 1e-15, "{err}");
        let na = a.to_na().try_inverse().unwrap();
        assert!((inv - na).abs().max() < 1e-15);
    }

    #[test]
    fn four_lanes_compute_what_four_numbers_do_bit_for_bit() {
        let xs = [0.3, -1.7, 1e-300, 7.25];
        let ys = [2.0, 0.1, 3.0, -0.0];
        let (x, y) = (F64x4(xs), F64x4(ys));
        let r = ((x * y + x / y - y).sqrt() - x).map(|_, v| v.atan2(0.5));
        for i in 0..4 {
            let s = ((xs[i] * ys[i] + xs[i] / ys[i] - ys[i]).sqrt() - xs[i]).atan2(0.5);
            assert_eq!(r.0[i].to_bits(), s.to_bits(), "lane {i}");
        }
        let m = F64x4::gt(x, y);
        assert_eq!(m, [false, false, false, true]);
        let s = F64x4::select(m, x, y);
        assert_eq!(s.0, [2.0, 0.1, 3.0, 7.25]);
    }
}
