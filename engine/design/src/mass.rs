//! Mass properties: mass, center of mass and inertia tensor, and their composition by the
//! parallel-axis theorem.
//!
//! Everything is in the station frame (x aft of the nose tip, see the crate docs). A
//! [`MassProps`] carries its inertia about its **own** center of mass; [`MassProps::inertia_about`]
//! moves it to any point. Shapes have closed forms (thin cylindrical shell, solid cylinder,
//! conical shell, fin plate, ...); a subtree's properties are the sum of its parts' with the
//! design's overrides applied.

use nalgebra::{Matrix3, Vector3};

/// `J(v) = |v|² E − v vᵀ`: the inertia of a unit point mass at `v` about the origin.
#[inline]
pub fn point_inertia(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::identity() * v.norm_squared() - v * v.transpose()
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
    pub const ZERO: MassProps =
        MassProps { mass_kg: 0.0, cg_m: Vector3::new(0.0, 0.0, 0.0), inertia_cg: Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0) };

    /// A point mass.
    pub fn point(mass_kg: f64, at: Vector3<f64>) -> Self {
        MassProps { mass_kg, cg_m: at, inertia_cg: Matrix3::zeros() }
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
        MassProps { mass_kg: m, cg_m: cg, inertia_cg: inertia }
    }

    /// The same body moved rigidly by `delta` (its own inertia goes with it unchanged).
    pub fn translated(&self, delta: &Vector3<f64>) -> MassProps {
        MassProps { cg_m: self.cg_m + delta, ..*self }
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
}
