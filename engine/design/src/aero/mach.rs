//! Mach dependence of the lift and roll coefficients, as RocketPy 1.13 computes them, so that
//! hpr's flight margin and roll agree with RocketPy's.
//!
//! **Model** (RocketPy `AeroSurface._beta`, `_BaseFin.evaluate_single_fin_lift_coefficient`,
//! `Fins.evaluate_lift_coefficient`, `Fins.evaluate_roll_parameters`):
//! - compressibility factor `β(M) = sqrt(1 − M²)` for `M < 0.8`, `sqrt(1 − 0.8²) = 0.6` for
//!   `0.8 <= M < 1.1`, `sqrt(M² − 1)` for `M >= 1.1` (RocketPy cites Barrowman, AIAA 79-504).
//!   The step at Mach 1.1 (0.6 → 0.458) is RocketPy's; on hpr's 0.01-step tables it is a
//!   ramp between Mach 1.09 and 1.10.
//! - one flat-plate fin (2-D slope `2π/β`, Prandtl–Glauert) with Diederich's planform
//!   correlation `F_D = 2π AR/(c_lα,2D cos γc) = AR β/cos γc`:
//!   `(CNα)₁ = c_lα,2D F_D (A_f/A_ref) cos γc / (2 + F_D sqrt(1 + (2/F_D)²))`
//!   `= 2π AR (A_f/A_ref) / (2 + sqrt(4 + (AR β/cos γc)²))`.
//!   At Mach 0 this is exactly Barrowman's slope of [`super::barrowman`]. RocketPy applies the
//!   same expression above Mach 1.1 with `β = sqrt(M² − 1)`; hpr follows it (it is
//!   RocketPy's choice, not supersonic thin-airfoil theory, and it keeps the two codes in
//!   step).
//! - fin set: `CNα = F(N) K_fb (CNα)₁` (see [`super::fins::fin_count_factor`]).
//! - noses and transitions: constant `CNα` (slender-body theory has no Mach dependence;
//!   RocketPy's `NoseCone`/`Tail` `clalpha` are constant too).
//! - roll forcing per radian of cant: `C_lf,δ = K_f N (Y_ma + r) (CNα)₁ / d`;
//!   roll damping: `C_ld,ω = 2 K_d N (CNα)₁,r cos δ · G / (A_ref d²)`, where `(CNα)₁,r` is the
//!   single-fin slope referenced to the body area at the fins `π r²` (RocketPy references it
//!   to its `Fins.rocket_radius`, which one sets to the body radius at the fins). Both are
//!   referenced here to the design's `A_ref` and `d`, and RocketPy's roll moment is then
//!   `M = q A_ref d (C_lf,δ δ − C_ld,ω ω d/(2V))` about the axis pointing to the nose (see
//!   [`super::FinRoll`]). The damping expression is RocketPy's; Barrowman's uses a 2-D
//!   sectional slope instead of `(CNα)₁`.

#[cfg(test)]
use super::fins::FLAT_PLATE_LIFT_SLOPE;
use super::fins::{fin_count_factor, FinGeometry, Fins};
use std::f64::consts::PI;

/// RocketPy's compressibility factor `β(M)`.
pub fn beta(mach: f64) -> f64 {
    let m = mach.abs();
    if m < 0.8 {
        (1.0 - m * m).sqrt()
    } else if m < 1.1 {
        (1.0f64 - 0.64).sqrt()
    } else {
        (m * m - 1.0).sqrt()
    }
}

/// Slope of one fin at `mach`, on the reference area `ref_area_m2`, its section's 2-D slope
/// `cla0` per rad (2π for a flat plate): RocketPy's
/// `cla FD (A_f/A_ref) cos γc / (2 + FD √(1 + (2/FD)²))` with `cla = cla0/β` and Diederich's
/// `FD = 2π AR/(cla cos γc)`, which is `2π AR (A_f/A_ref)/(2 + √(4 + FD²))`.
pub fn single_fin_cn_alpha(g: &FinGeometry, cla0: f64, mach: f64, ref_area_m2: f64) -> f64 {
    let fd = 2.0 * PI / cla0 * g.aspect_ratio * beta(mach) / g.mid_chord_sweep_rad.cos();
    2.0 * PI * g.aspect_ratio * (g.area_m2 / ref_area_m2) / (2.0 + (4.0 + fd * fd).sqrt())
}

/// Slope of a fin set at `mach`, on the reference area `ref_area_m2`.
pub fn fin_set_cn_alpha(fins: &Fins, g: &FinGeometry, mach: f64, ref_area_m2: f64) -> f64 {
    fin_count_factor(fins.count)
        * g.lift_interference
        * single_fin_cn_alpha(g, fins.lift_slope_2d_per_rad, mach, ref_area_m2)
}

/// Roll forcing coefficient per radian of cant, `C_lf,δ(M)`, on `A_ref` and `d_ref`.
pub fn roll_forcing_per_cant(
    fins: &Fins,
    g: &FinGeometry,
    mach: f64,
    ref_area_m2: f64,
    ref_diameter_m: f64,
) -> f64 {
    g.roll_forcing_interference
        * fins.count as f64
        * (g.y_mac_m + fins.body_radius_m)
        * single_fin_cn_alpha(g, fins.lift_slope_2d_per_rad, mach, ref_area_m2)
        / ref_diameter_m
}

/// Roll damping coefficient `C_ld,ω(M)`, on `A_ref` and `d_ref` (RocketPy's expression with
/// the single-fin slope referenced to the body area at the fins).
pub fn roll_damping(
    fins: &Fins,
    g: &FinGeometry,
    mach: f64,
    ref_area_m2: f64,
    ref_diameter_m: f64,
) -> f64 {
    let local_area = PI * fins.body_radius_m * fins.body_radius_m;
    2.0 * g.roll_damping_interference
        * fins.count as f64
        * single_fin_cn_alpha(g, fins.lift_slope_2d_per_rad, mach, local_area)
        * fins.cant_rad.cos()
        * g.roll_geometric_constant_m4
        / (ref_area_m2 * ref_diameter_m * ref_diameter_m)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn calisto_fins() -> Fins {
        Fins {
            count: 4,
            root_chord_m: 0.12,
            span_m: 0.1,
            planform: crate::design::FinPlanform::Trapezoidal {
                tip_chord_m: 0.04,
                sweep_m: 0.08,
            },
            body_radius_m: 0.0635,
            cant_rad: 0.0,
            lift_slope_2d_per_rad: FLAT_PLATE_LIFT_SLOPE,
        }
    }

    #[test]
    fn beta_follows_rocketpys_three_pieces() {
        assert!((beta(0.0) - 1.0).abs() < 1e-15);
        assert!((beta(0.6) - 0.8).abs() < 1e-15);
        assert!((beta(0.9) - 0.6).abs() < 1e-15);
        assert!((beta(1.09) - 0.6).abs() < 1e-15);
        assert!((beta(1.1) - 0.21f64.sqrt()).abs() < 1e-12);
        assert!((beta(2.0) - 3.0f64.sqrt()).abs() < 1e-15);
    }

    #[test]
    fn the_diederich_slope_at_mach_zero_is_barrowmans() {
        let f = calisto_fins();
        let g = f.geometry();
        let a_ref = PI * 0.0635 * 0.0635;
        let diederich = fin_set_cn_alpha(&f, &g, 0.0, a_ref);
        let barrowman = f.cn_alpha_mach0(0.127);
        assert!(
            (diederich / barrowman - 1.0).abs() < 1e-13,
            "{diederich} vs {barrowman}"
        );
    }

    #[test]
    fn the_fin_slope_grows_by_hand_calculated_amount_at_mach_point_six() {
        // Calisto fins, M = 0.6: β = 0.8, AR = 2.5, cos γc = cos(atan 0.4) = 0.9284766909.
        // F_D = 2.5 · 0.8 / 0.9284766909 = 2.1540659229; sqrt(4 + F_D²) = 2.9393876913
        // (CNα)₁ = 2π · 2.5 · (0.008/0.0126676681) / (2 + 2.9393876913) = 2.0087658..
        let f = calisto_fins();
        let g = f.geometry();
        let a_ref = PI * 0.0635 * 0.0635;
        let one = single_fin_cn_alpha(&g, FLAT_PLATE_LIFT_SLOPE, 0.6, a_ref);
        let fd: f64 = 2.5 * 0.8 / (0.4f64.atan().cos());
        let want = 2.0 * PI * 2.5 * (0.008 / a_ref) / (2.0 + (4.0 + fd * fd).sqrt());
        assert!((one - want).abs() < 1e-12);
        assert!((fd - 2.1540659229).abs() < 1e-9);
        let ratio = single_fin_cn_alpha(&g, FLAT_PLATE_LIFT_SLOPE, 0.6, a_ref)
            / single_fin_cn_alpha(&g, FLAT_PLATE_LIFT_SLOPE, 0.0, a_ref);
        // Mach 0: F_D = 2.6925824036, sqrt(4 + F_D²) = 3.3541019662
        let want_ratio = (2.0 + 3.3541019662) / (2.0 + (4.0 + fd * fd).sqrt());
        assert!((ratio - want_ratio).abs() < 1e-9, "{ratio}");
        assert!(ratio > 1.0);
    }

    #[test]
    fn roll_damping_is_reduced_by_the_cosine_of_the_cant() {
        let f = calisto_fins();
        let canted = Fins {
            cant_rad: 0.1,
            ..f.clone()
        };
        let a = PI * 0.0635f64.powi(2);
        let r0 = roll_damping(&f, &f.geometry(), 0.3, a, 0.127);
        let r1 = roll_damping(&canted, &canted.geometry(), 0.3, a, 0.127);
        assert!((r1 / r0 - 0.1f64.cos()).abs() < 1e-14);
        assert!(r0 > 0.0);
    }
}
