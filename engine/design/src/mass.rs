//! Mass properties: mass, center of mass and inertia tensor, and their composition by the
//! parallel-axis theorem.
//!
//! Everything is in the station frame (x aft of the nose tip, see the crate docs). A
//! [`MassProps`] carries its inertia about its **own** center of mass; [`MassProps::inertia_about`]
//! moves it to any point. Shapes have closed forms (thin cylindrical shell, solid cylinder,
//! conical shell, fin plate, ...) in [`solids`]; a design's components, subtrees, stages and
//! dry rocket, with the design's overrides applied, are in [`components`]. [`moved_part`] is
//! the moving-mass update (`docs/moving-mass.md`, "What changes").

pub mod components;
pub mod solids;

pub use components::{apply_override, component_own, dry, mass_table, stage, subtree, MassRow};

use nalgebra::{Matrix3, Vector3};

/// `J(v) = |v|² E − v vᵀ`: the inertia of a unit point mass at `v` about the origin.
#[inline]
pub fn point_inertia(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::identity() * v.norm_squared() - v * v.transpose()
}

/// `Σ J(d_i)` over offsets `[y, z]` across the axis (station frame): what unit point masses
/// there add to the inertia about the axis (a cluster's tubes, motors or nozzles).
pub fn offsets_inertia(offsets_m: &[[f64; 2]]) -> Matrix3<f64> {
    offsets_m
        .iter()
        .map(|o| point_inertia(&Vector3::new(0.0, o[0], o[1])))
        .fold(Matrix3::zeros(), |s, j| s + j)
}

/// Mass, center of mass and inertia about that center.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProps {
    pub mass_kg: f64,
    /// Center of mass in the station frame, m.
    pub cg_m: Vector3<f64>,
    /// Inertia tensor about `cg_m`, station axes, kg·m².
    pub inertia_cg: Matrix3<f64>,
}

impl MassProps {
    /// Nothing: the identity of [`MassProps::combine`].
    pub const ZERO: MassProps = MassProps {
        mass_kg: 0.0,
        cg_m: Vector3::new(0.0, 0.0, 0.0),
        inertia_cg: Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    };

    /// A point mass.
    pub fn point(mass_kg: f64, at: Vector3<f64>) -> Self {
        MassProps {
            mass_kg,
            cg_m: at,
            inertia_cg: Matrix3::zeros(),
        }
    }

    /// Inertia about an arbitrary point `p` (parallel-axis theorem).
    pub fn inertia_about(&self, p: &Vector3<f64>) -> Matrix3<f64> {
        self.inertia_cg + point_inertia(&(self.cg_m - p)) * self.mass_kg
    }

    /// Inertia about the nose tip (the station frame's origin).
    pub fn inertia_about_tip(&self) -> Matrix3<f64> {
        self.inertia_about(&Vector3::zeros())
    }

    /// The whole of two bodies.
    pub fn combine(&self, other: &MassProps) -> MassProps {
        let m = self.mass_kg + other.mass_kg;
        if m == 0.0 {
            return MassProps::ZERO;
        }
        let cg = (self.cg_m * self.mass_kg + other.cg_m * other.mass_kg) / m;
        let inertia = self.inertia_about(&cg) + other.inertia_about(&cg);
        MassProps {
            mass_kg: m,
            cg_m: cg,
            inertia_cg: inertia,
        }
    }

    /// The same body moved rigidly by `delta` (its own inertia goes with it unchanged).
    pub fn translated(&self, delta: &Vector3<f64>) -> MassProps {
        MassProps {
            cg_m: self.cg_m + delta,
            ..*self
        }
    }

    /// Axial (roll) moment of inertia about the center of mass, kg·m².
    pub fn axial_inertia(&self) -> f64 {
        self.inertia_cg[(0, 0)]
    }

    /// Transverse (pitch) moment of inertia about the center of mass, kg·m²: about the
    /// station `y` axis through the center of mass.
    pub fn transverse_inertia(&self) -> f64 {
        self.inertia_cg[(1, 1)]
    }

    /// The same shape with its density multiplied by `factor`: mass and inertia scale, the
    /// center stays.
    pub fn scaled(&self, factor: f64) -> MassProps {
        MassProps {
            mass_kg: self.mass_kg * factor,
            cg_m: self.cg_m,
            inertia_cg: self.inertia_cg * factor,
        }
    }

    /// The same shape with mass `mass_kg` (inertia scaled by the ratio). A massless body
    /// stays massless.
    pub fn with_mass(&self, mass_kg: f64) -> MassProps {
        if self.mass_kg == 0.0 {
            return *self;
        }
        self.scaled(mass_kg / self.mass_kg)
    }

    /// The body turned about the station origin by the rotation matrix `q` (columns: where
    /// the station axes go): `cg → q cg`, `I → q I qᵀ`.
    pub fn rotated(&self, q: &Matrix3<f64>) -> MassProps {
        MassProps {
            mass_kg: self.mass_kg,
            cg_m: q * self.cg_m,
            inertia_cg: q * self.inertia_cg * q.transpose(),
        }
    }

    /// The body spread evenly round the station `x` axis: the average of all its copies
    /// turned about that axis. The mass and the center's `x` stay; the center moves onto the
    /// axis; about it, the axial inertia stays, the two transverse ones become their mean and
    /// the products vanish (`I_yy, I_zz → (I_yy + I_zz)/2` about the point on the axis).
    pub fn spread_about_axis(&self) -> MassProps {
        let on_axis = Vector3::new(self.cg_m.x, 0.0, 0.0);
        let i = self.inertia_about(&on_axis);
        let transverse = 0.5 * (i[(1, 1)] + i[(2, 2)]);
        MassProps {
            mass_kg: self.mass_kg,
            cg_m: on_axis,
            inertia_cg: Matrix3::from_diagonal(&Vector3::new(i[(0, 0)], transverse, transverse)),
        }
    }

    /// Sum of any number of bodies.
    pub fn sum<'a>(parts: impl IntoIterator<Item = &'a MassProps>) -> MassProps {
        parts
            .into_iter()
            .fold(MassProps::ZERO, |acc, p| acc.combine(p))
    }
}

/// The whole after one of its parts moved by `delta` (exactly as `docs/moving-mass.md`, "What
/// changes", says):
/// the mass doesn't change; `cg_new = cg + m δ / M`;
/// `I_new = I_whole(about cg_new) + m [J(c₀ + δ − cg_new) − J(c₀ − cg_new)]`, with `m` and
/// `c₀` the part's mass and center where `whole` has it. The part's own inertia goes with it
/// unchanged, so it does not enter.
pub fn moved_part(whole: &MassProps, part: &MassProps, delta: &Vector3<f64>) -> MassProps {
    let m = part.mass_kg;
    let cg_new = whole.cg_m + delta * (m / whole.mass_kg);
    let c0 = part.cg_m;
    let inertia = whole.inertia_about(&cg_new)
        + (point_inertia(&(c0 + delta - cg_new)) - point_inertia(&(c0 - cg_new))) * m;
    MassProps {
        mass_kg: whole.mass_kg,
        cg_m: cg_new,
        inertia_cg: inertia,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn max_abs(m: &Matrix3<f64>) -> f64 {
        m.iter().fold(0.0f64, |a, v| a.max(v.abs()))
    }

    /// A solid cube of mass 6 kg and side 2 m centered at (1, 0, 0): I = m a²/6 = 4 kg·m² on
    /// every axis. Values are chosen exact in binary.
    fn cube() -> MassProps {
        solids::solid_box(6.0, [2.0, 2.0, 2.0]).translated(&Vector3::new(1.0, 0.0, 0.0))
    }

    #[test]
    fn a_solid_cube_has_a_sixth_of_m_a_squared_on_every_axis() {
        let c = cube();
        assert_eq!(c.inertia_cg, Matrix3::identity() * 4.0);
    }

    #[test]
    fn a_part_moved_inside_a_body_gives_the_hand_computed_whole() {
        // A 2 kg point at c0 = (0.5, 0.25, −0.25) inside the cube; moved by δ = (0.25, 0, 0).
        let point = MassProps::point(2.0, Vector3::new(0.5, 0.25, -0.25));
        let delta = Vector3::new(0.25, 0.0, 0.0);
        let whole = cube().combine(&point);
        // Hand: M = 8, cg = (6·1 + 2·0.5, 2·0.25, −2·0.25)/8 = (7/8, 1/16, −1/16).
        assert_eq!(whole.cg_m, Vector3::new(0.875, 0.0625, -0.0625));

        let moved = moved_part(&whole, &point, &delta);
        // Hand: cg_new = cg + m δ / M = (7/8 + 2·0.25/8, 1/16, −1/16) = (0.9375, 0.0625, −0.0625).
        // Inertia by the two-body formula: μ = m (M − m)/M = 2·6/8 = 1.5; the line from the
        // cube's center to the moved point L = (−0.25, 0.25, −0.25), |L|² = 3/16,
        // J(L) = (1/16) [[2, 1, −1], [1, 2, 1], [−1, 1, 2]];
        // I = 4 E + 1.5 J(L) = 4.1875 on the diagonal, ±0.09375 off it.
        let hand_cg = Vector3::new(0.9375, 0.0625, -0.0625);
        let hand_i = Matrix3::new(
            4.1875, 0.09375, -0.09375, //
            0.09375, 4.1875, 0.09375, //
            -0.09375, 0.09375, 4.1875,
        );
        assert_eq!(moved.mass_kg, 8.0);
        assert!(
            (moved.cg_m - hand_cg).amax() <= 1e-15,
            "{:?}",
            moved.cg_m - hand_cg
        );
        assert!(
            max_abs(&(moved.inertia_cg - hand_i)) <= 1e-15,
            "{}",
            moved.inertia_cg - hand_i
        );

        // And the whole rebuilt from scratch with the point where it went.
        let rebuilt = cube().combine(&point.translated(&delta));
        assert_eq!(rebuilt.mass_kg, moved.mass_kg);
        assert!((moved.cg_m - rebuilt.cg_m).amax() <= 1e-15);
        assert!(max_abs(&(moved.inertia_cg - rebuilt.inertia_cg)) <= 1e-15);
    }

    /// A part with its own full inertia tensor and a rest that is not symmetric either.
    fn part_and_rest() -> (MassProps, MassProps) {
        let part = MassProps {
            mass_kg: 0.2,
            cg_m: Vector3::new(0.375, 0.01, -0.004),
            inertia_cg: Matrix3::new(2e-5, 1e-7, -2e-7, 1e-7, 5e-5, 3e-7, -2e-7, 3e-7, 5.5e-5),
        };
        let rest = MassProps {
            mass_kg: 0.6188,
            cg_m: Vector3::new(0.7628, -0.002, 0.003),
            inertia_cg: Matrix3::new(4e-4, 2e-6, 1e-6, 2e-6, 0.052, -1e-5, 1e-6, -1e-5, 0.0521),
        };
        (part, rest)
    }

    #[test]
    fn the_whole_of_two_bodies_is_their_inertias_plus_the_reduced_mass_term() {
        let (part, rest) = part_and_rest();
        let whole = part.combine(&rest);
        let (m, big_m) = (part.mass_kg, whole.mass_kg);
        let mu = m * (big_m - m) / big_m;
        let l = part.cg_m - rest.cg_m;
        let two_body = part.inertia_cg + rest.inertia_cg + point_inertia(&l) * mu;
        // Values of order 0.05 kg·m²: rounding is a few 1e-18.
        assert!(
            max_abs(&(whole.inertia_cg - two_body)) <= 1e-15,
            "{}",
            whole.inertia_cg - two_body
        );
    }

    #[test]
    fn moving_a_part_changes_only_the_line_of_the_two_body_formula() {
        let (part, rest) = part_and_rest();
        let whole = part.combine(&rest);
        let delta = Vector3::new(0.3, 0.0, 0.0);
        let moved = moved_part(&whole, &part, &delta);
        let (m, big_m) = (part.mass_kg, whole.mass_kg);
        let mu = m * (big_m - m) / big_m;
        let l = part.cg_m + delta - rest.cg_m;
        let two_body = part.inertia_cg + rest.inertia_cg + point_inertia(&l) * mu;
        assert!(
            max_abs(&(moved.inertia_cg - two_body)) <= 1e-15,
            "{}",
            moved.inertia_cg - two_body
        );
        // The center moves by m δ / M.
        let shift = moved.cg_m - whole.cg_m;
        assert!((shift - delta * (m / big_m)).amax() <= 1e-15);
        assert_eq!(moved.mass_kg, whole.mass_kg);
    }

    #[test]
    fn composition_follows_the_parallel_axis_theorem_of_a_hand_calculation() {
        // Two 1 kg solid cylinders (r = 0.1, L = 0.4) end to end on the axis, from 0 to 0.8 m.
        // Each: I_ax = m r²/2 = 0.005; I_tr = m (3 r² + L²)/12 = (0.03 + 0.16)/12.
        // Whole: cg 0.4; I_tr = 2 (0.19/12 + 0.2²) = 0.19/6 + 0.08.
        let a = solids::solid_cylinder(1.0, 0.1, 0.4);
        let b = a.translated(&Vector3::new(0.4, 0.0, 0.0));
        let whole = a.combine(&b);
        assert_eq!(whole.mass_kg, 2.0);
        assert!((whole.cg_m.x - 0.4).abs() < 1e-16);
        assert!((whole.axial_inertia() - 0.01).abs() < 1e-17);
        let hand = 0.19 / 6.0 + 0.08;
        assert!(
            (whole.transverse_inertia() - hand).abs() < 1e-16,
            "{}",
            whole.transverse_inertia() - hand
        );
        // About the nose tip: I_tr + M cg² = hand + 2 · 0.16.
        assert!((whole.inertia_about_tip()[(1, 1)] - (hand + 0.32)).abs() < 1e-15);
    }

    #[test]
    fn a_rotation_turns_the_tensor_and_the_center() {
        // A rod along x (I = diag(0, 1, 1)) turned a quarter turn about z lies along y.
        let rod = MassProps {
            mass_kg: 1.0,
            cg_m: Vector3::new(1.0, 0.0, 0.0),
            inertia_cg: Matrix3::from_diagonal(&Vector3::new(0.0, 1.0, 1.0)),
        };
        let q = Matrix3::new(0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0);
        let turned = rod.rotated(&q);
        assert_eq!(turned.cg_m, Vector3::new(0.0, 1.0, 0.0));
        assert_eq!(
            turned.inertia_cg,
            Matrix3::from_diagonal(&Vector3::new(1.0, 0.0, 1.0))
        );
    }
}
