//! Body sections (noses, tubes, transitions) and the integrals the aerodynamics needs from
//! their profiles: volume, wetted area, the slope at the joint.
//!
//! The profiles `r(x)` themselves are [`crate::design::shapes`] (shared with the mass code);
//! transitions use OpenRocket's adaptation, the nose profile of height
//! `|R_aft − R_fore|` with its tip at the smaller end.
//!
//! Integrals are computed by adaptive Simpson quadrature (hand-written: 30 lines, no crate in
//! the workspace offers it, and it runs once per design) after the substitution
//! `x = L (1 − cos θ)/2`, which makes the Haack profiles smooth and softens the tip
//! singularity of power series with small `k`.

use crate::design::shapes::tapered_radius;
pub use crate::design::shapes::{profile_radius, transition_nose_shape as nose_shape_of};
use crate::design::{NoseShape, Transition};
use std::f64::consts::PI;

/// An axially symmetric body section: a nose (fore radius 0) or a transition, of one shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    pub shape: NoseShape,
    pub length_m: f64,
    pub fore_radius_m: f64,
    pub aft_radius_m: f64,
    /// A transition's clip length ([`crate::design::shapes::clip_length`]); 0 unclipped.
    pub clip_m: f64,
}

impl Section {
    /// A nose cone.
    pub fn nose(shape: NoseShape, length_m: f64, base_radius_m: f64) -> Self {
        Section {
            shape,
            length_m,
            fore_radius_m: 0.0,
            aft_radius_m: base_radius_m,
            clip_m: 0.0,
        }
    }

    /// A transition `length_m` long.
    pub fn transition(length_m: f64, t: &Transition) -> Self {
        Section {
            shape: nose_shape_of(t.shape),
            length_m,
            fore_radius_m: t.fore_diameter_m / 2.0,
            aft_radius_m: t.aft_diameter_m / 2.0,
            clip_m: t.clip_m,
        }
    }

    /// A cylinder (body tube).
    pub fn tube(length_m: f64, radius_m: f64) -> Self {
        Section {
            shape: NoseShape::Conical,
            length_m,
            fore_radius_m: radius_m,
            aft_radius_m: radius_m,
            clip_m: 0.0,
        }
    }

    /// Radius at `x_m` aft of the section's fore end (OpenRocket's transition profile,
    /// clipped or not).
    pub fn radius(&self, x_m: f64) -> f64 {
        tapered_radius(
            self.shape,
            self.length_m,
            self.fore_radius_m,
            self.aft_radius_m,
            self.clip_m,
            x_m,
        )
    }

    /// Enclosed volume `∫ π r² dx`, m³.
    pub fn volume_m3(&self) -> f64 {
        if self.fore_radius_m == self.aft_radius_m {
            return PI * self.fore_radius_m * self.fore_radius_m * self.length_m;
        }
        integrate_along(self.length_m, |x| {
            let r = self.radius(x);
            PI * r * r
        })
    }

    /// Wetted (lateral) area `∫ 2π r ds`, m², summed over frusta of 4096 slices whose ends
    /// are spaced as `x = L (1 − cos θ)/2` (exact for cones and tubes; relative error below
    /// 1e-6 for the smooth shapes).
    pub fn wetted_area_m2(&self) -> f64 {
        let (r1, r2, l) = (self.fore_radius_m, self.aft_radius_m, self.length_m);
        if r1 == r2 {
            return 2.0 * PI * r1 * l;
        }
        const N: usize = 4096;
        let mut area = 0.0;
        let mut x0 = 0.0;
        let mut y0 = self.radius(0.0);
        for i in 1..=N {
            let theta = PI * i as f64 / N as f64;
            let x1 = l * (1.0 - theta.cos()) / 2.0;
            let y1 = self.radius(x1);
            let slant = (x1 - x0).hypot(y1 - y0);
            area += PI * (y0 + y1) * slant;
            x0 = x1;
            y0 = y1;
        }
        area
    }

    /// Sine of the angle between the profile and the axis at the aft joint, from the radius at
    /// 99 % of the length, as OpenRocket's `SymmetricComponentCalc` takes it (positive when
    /// the section widens aft).
    pub fn sin_joint_angle(&self) -> f64 {
        let l = self.length_m;
        let dr = self.aft_radius_m - self.radius(0.99 * l);
        dr / dr.hypot(0.01 * l)
    }
}

/// `∫₀ᴸ f(x) dx` with the substitution `x = L (1 − cos θ)/2`, adaptive Simpson in `θ`.
pub fn integrate_along(length_m: f64, f: impl Fn(f64) -> f64) -> f64 {
    let l = length_m;
    let g = |theta: f64| f(l * (1.0 - theta.cos()) / 2.0) * (l / 2.0) * theta.sin();
    adaptive_simpson(&g, 0.0, PI, 1e-13)
}

/// Adaptive Simpson quadrature of `f` over `[a, b]` to absolute tolerance `tol` (scaled by
/// the magnitude of the first estimate), at most 32 bisections deep.
pub fn adaptive_simpson(f: &impl Fn(f64) -> f64, a: f64, b: f64, tol: f64) -> f64 {
    let (fa, fb, fm) = (f(a), f(b), f((a + b) / 2.0));
    let whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
    let scale = whole.abs().max(f64::MIN_POSITIVE);
    simpson_step(f, a, b, fa, fm, fb, whole, tol * scale, 32)
}

#[allow(clippy::too_many_arguments)]
fn simpson_step(
    f: &impl Fn(f64) -> f64,
    a: f64,
    b: f64,
    fa: f64,
    fm: f64,
    fb: f64,
    whole: f64,
    tol: f64,
    depth: u32,
) -> f64 {
    let m = (a + b) / 2.0;
    let (lm, rm) = ((a + m) / 2.0, (m + b) / 2.0);
    let (flm, frm) = (f(lm), f(rm));
    let left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
    let right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    let delta = left + right - whole;
    // Keep splitting at least 6 levels deep so that a lucky coarse estimate is not accepted.
    // An integrand that overflows (a profile 1e300 m wide) gives no finite estimate at any
    // depth: return it as it is at once, where splitting on would take 2³² evaluations.
    if depth == 0 || !delta.is_finite() || (depth < 27 && delta.abs() <= 15.0 * tol) {
        return left + right + delta / 15.0;
    }
    simpson_step(f, a, m, fa, flm, fm, left, tol / 2.0, depth - 1)
        + simpson_step(f, m, b, fm, frm, fb, right, tol / 2.0, depth - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    const L: f64 = 0.3;
    const R: f64 = 0.05;

    #[test]
    fn a_cone_volume_is_a_third_of_its_cylinder() {
        let v = Section::nose(NoseShape::Conical, L, R).volume_m3();
        let exact = PI * R * R * L / 3.0;
        assert!((v / exact - 1.0).abs() < 1e-12, "{v} vs {exact}");
    }

    #[test]
    fn a_conical_frustum_has_the_textbook_volume_and_lateral_area() {
        let s = Section {
            shape: NoseShape::Conical,
            length_m: 0.1,
            fore_radius_m: 0.03,
            aft_radius_m: 0.05,
            clip_m: 0.0,
        };
        let v_exact = PI * 0.1 / 3.0 * (0.03f64.powi(2) + 0.03 * 0.05 + 0.05f64.powi(2));
        assert!((s.volume_m3() / v_exact - 1.0).abs() < 1e-12);
        let a_exact = PI * (0.03 + 0.05) * (0.1f64.hypot(0.02));
        assert!((s.wetted_area_m2() / a_exact - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_boattail_is_the_mirror_image_of_the_matching_shoulder() {
        let fore = Section {
            shape: NoseShape::Elliptical,
            length_m: 0.1,
            fore_radius_m: 0.03,
            aft_radius_m: 0.05,
            clip_m: 0.0,
        };
        let aft = Section {
            shape: NoseShape::Elliptical,
            length_m: 0.1,
            fore_radius_m: 0.05,
            aft_radius_m: 0.03,
            clip_m: 0.0,
        };
        for &x in &[0.0, 0.013, 0.05, 0.09, 0.1] {
            assert!((fore.radius(x) - aft.radius(0.1 - x)).abs() < 1e-15);
        }
        assert!((fore.volume_m3() / aft.volume_m3() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_hemispherical_nose_has_the_area_of_a_half_sphere() {
        // Elliptical with L = R is a hemisphere: lateral area 2πR².
        let a = Section::nose(NoseShape::Elliptical, R, R).wetted_area_m2();
        assert!((a / (2.0 * PI * R * R) - 1.0).abs() < 1e-6, "{a}");
    }

    #[test]
    fn the_joint_angle_of_a_cone_is_its_half_apex_angle() {
        let s = Section::nose(NoseShape::Conical, L, R);
        let exact = (R / L).atan().sin();
        assert!((s.sin_joint_angle() - exact).abs() < 1e-12);
    }

    #[test]
    fn adaptive_simpson_gives_up_at_once_on_an_integrand_that_overflows() {
        // r² of a 1e300 m profile: infinite everywhere. Splitting on could never converge
        // (2³² evaluations, the fuzzed design that hung `inspect`): the first level says so.
        let calls = std::cell::Cell::new(0u32);
        let v = adaptive_simpson(
            &|x: f64| {
                calls.set(calls.get() + 1);
                (1e300 * (1.0 + x)).powi(2)
            },
            0.0,
            1.0,
            1e-12,
        );
        assert!(!v.is_finite(), "{v}");
        assert_eq!(calls.get(), 5);
    }

    #[test]
    fn adaptive_simpson_integrates_a_square_root_singularity() {
        // ∫₀¹ sqrt(x) dx = 2/3
        let v = adaptive_simpson(&|x: f64| x.sqrt(), 0.0, 1.0, 1e-12);
        assert!((v - 2.0 / 3.0).abs() < 1e-9);
    }
}
