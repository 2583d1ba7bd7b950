//! Barrowman's normal-force slopes and centers of pressure of the bodies of revolution (noses,
//! transitions) at Mach 0, referenced to the area of the design's reference diameter; the fin
//! sets' are in [`super::fins`].
//!
//! Sources: J. S. Barrowman, *The Practical Calculation of the Aerodynamic Characteristics of
//! Slender Finned Vehicles*, M.Sc. thesis, Catholic University of America, 1967; J. and J.
//! Barrowman, *The Theoretical Prediction of the Center of Pressure*, NARAM-8, 1966; S.
//! Niskanen, *Development of an Open Source model rocket simulation software*, 2009, §3.2;
//! and, for comparison, RocketPy 1.13 (`rocketpy/rocket/aero_surface/nose_cone.py`,
//! `tail.py`, `fins/_geometry.py`, `fins/trapezoidal_fins.py`).
//!
//! **Bodies of revolution** (slender-body theory): a section whose cross-section grows from
//! `A_fore` to `A_aft` over its length `L` has `CNα = 2 (A_aft − A_fore)/A_ref` and its center
//! of pressure at `x_cp = (L A_aft − V)/(A_aft − A_fore)` aft of its fore end, `V` its volume.
//! For a nose (`A_fore = 0`) this is `x_cp = L − V/A_base`. A boattail (`A_aft < A_fore`) has
//! a negative `CNα`. Closed forms of `x_cp/L` for noses: conical 2/3; tangent ogive
//! `1 − V/(π R² L)` with `V = π (L ρ² − L³/3 − (ρ − R) ρ² asin(L/ρ))`, `ρ = (R² + L²)/(2R)`
//! (→ 7/15 ≈ 0.467 for `L/R` large); elliptical 1/3; power series `r ∝ x^k`: `2k/(2k + 1)`;
//! parabolic series `K`: `1 − (4/3 − K + K²/5)/(2 − K)²` (7/15 for `K = 1`); Haack series
//! `c`: `1/2 − 3c/16` (von Kármán 1/2, LV-Haack 7/16). hpr integrates the volume of the
//! actual profile (see [`super::profile`]); the tests check it against these forms.
//!
//! *Difference from RocketPy*: RocketPy puts the LV-Haack CP at `0.563 L` and the parabolic
//! CP at `0.5 L`; the volume formula gives `7L/16 = 0.4375 L` and `7L/15` (its 0.5 is the
//! power-series-½ value). hpr uses the volume formula for every shape. RocketPy's tail
//! (transition) is always conical; hpr uses the transition's shape (identical for conical).
//!

use super::profile::Section;
use crate::design::NoseShape;
use std::f64::consts::PI;

/// Normal-force slope (per radian, on the reference area) and center of pressure of one
/// component.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lift {
    /// `dCN/dα` at α = 0, 1/rad, referenced to the design's reference area.
    pub cn_alpha: f64,
    /// Center of pressure, m aft of the component's fore end (fin sets: the root's leading
    /// edge).
    pub x_cp_m: f64,
}

/// Slender-body lift of a nose or transition. A section whose ends have equal areas has no
/// lift; its CP is put at its middle.
pub fn body_section_lift(section: &Section, ref_area_m2: f64) -> Lift {
    let a_fore = PI * section.fore_radius_m.powi(2);
    let a_aft = PI * section.aft_radius_m.powi(2);
    let l = section.length_m;
    if a_aft == a_fore {
        return Lift {
            cn_alpha: 0.0,
            x_cp_m: l / 2.0,
        };
    }
    let v = section.volume_m3();
    Lift {
        cn_alpha: 2.0 * (a_aft - a_fore) / ref_area_m2,
        x_cp_m: (l * a_aft - v) / (a_aft - a_fore),
    }
}

/// Lift of a nose cone.
pub fn nose_cone_lift(
    shape: NoseShape,
    length_m: f64,
    base_radius_m: f64,
    ref_area_m2: f64,
) -> Lift {
    body_section_lift(&Section::nose(shape, length_m, base_radius_m), ref_area_m2)
}

#[cfg(test)]
mod tests {
    use super::*;

    const L: f64 = 0.4;
    const R: f64 = 0.05;

    fn cp_over_length(shape: NoseShape) -> f64 {
        nose_cone_lift(shape, L, R, PI * R * R).x_cp_m / L
    }

    fn assert_rel(got: f64, want: f64, tol: f64, what: &str) {
        assert!(
            ((got - want) / want).abs() <= tol,
            "{what}: got {got}, want {want}"
        );
    }

    #[test]
    fn a_conical_nose_has_its_center_of_pressure_at_two_thirds_of_its_length() {
        assert_rel(
            cp_over_length(NoseShape::Conical),
            2.0 / 3.0,
            1e-9,
            "conical",
        );
    }

    #[test]
    fn a_von_karman_nose_has_its_center_of_pressure_at_half_its_length() {
        assert_rel(
            cp_over_length(NoseShape::Haack { c: 0.0 }),
            0.5,
            1e-7,
            "von Karman",
        );
    }

    #[test]
    fn an_lv_haack_nose_has_its_center_of_pressure_at_seven_sixteenths_of_its_length() {
        assert_rel(
            cp_over_length(NoseShape::Haack { c: 1.0 / 3.0 }),
            7.0 / 16.0,
            1e-7,
            "LV-Haack",
        );
    }

    #[test]
    fn a_haack_nose_of_any_parameter_has_its_cp_at_one_half_minus_three_sixteenths_of_c() {
        for c in [0.1, 0.2, 0.5] {
            assert_rel(
                cp_over_length(NoseShape::Haack { c }),
                0.5 - 3.0 * c / 16.0,
                1e-7,
                "Haack",
            );
        }
    }

    #[test]
    fn an_elliptical_nose_has_its_center_of_pressure_at_a_third_of_its_length() {
        assert_rel(
            cp_over_length(NoseShape::Elliptical),
            1.0 / 3.0,
            1e-9,
            "elliptical",
        );
    }

    #[test]
    fn a_power_series_nose_has_its_center_of_pressure_at_2k_over_2k_plus_1() {
        for k in [0.25, 0.5, 0.75, 1.0] {
            assert_rel(
                cp_over_length(NoseShape::PowerSeries { k }),
                2.0 * k / (2.0 * k + 1.0),
                1e-7,
                "power",
            );
        }
    }

    #[test]
    fn a_parabolic_series_nose_matches_its_closed_form_and_the_full_parabola_is_seven_fifteenths() {
        for k in [0.0f64, 0.5, 0.75, 1.0] {
            let want = 1.0 - (4.0 / 3.0 - k + k * k / 5.0) / (2.0 - k).powi(2);
            assert_rel(
                cp_over_length(NoseShape::Parabolic { k }),
                want,
                1e-9,
                "parabolic",
            );
        }
        assert_rel(
            cp_over_length(NoseShape::Parabolic { k: 1.0 }),
            7.0 / 15.0,
            1e-9,
            "parabola",
        );
    }

    #[test]
    fn a_tangent_ogive_matches_its_closed_form_volume_and_tends_to_seven_fifteenths_when_slender() {
        for (l, r) in [(0.4, 0.05), (0.25, 0.0282)] {
            let rho: f64 = (r * r + l * l) / (2.0 * r);
            let v =
                PI * (l * rho * rho - l.powi(3) / 3.0 - (rho - r) * rho * rho * (l / rho).asin());
            let want = 1.0 - v / (PI * r * r * l);
            let got = nose_cone_lift(NoseShape::Ogive, l, r, PI * r * r).x_cp_m / l;
            assert_rel(got, want, 1e-9, "ogive");
        }
        // L/R = 200: the closed form cancels ~8 digits in f64, so the reference is the same
        // formula evaluated with 40 digits (mpmath): 0.466_662_857_158_730.
        let slender = nose_cone_lift(NoseShape::Ogive, 10.0, 0.05, PI * 0.0025).x_cp_m / 10.0;
        assert_rel(slender, 0.466_662_857_158_730, 1e-10, "slender ogive");
        assert!((slender - 7.0 / 15.0).abs() < 1e-5, "{slender}");
        // The 0.4 x 0.05 ogive, closed form with 40 digits: 0.464_291_879_715_363_6.
        assert_rel(
            cp_over_length(NoseShape::Ogive),
            0.464_291_879_715_363_6,
            1e-10,
            "0.4 x 0.05 ogive",
        );
    }

    #[test]
    fn a_secant_ogive_has_its_center_of_pressure_where_its_closed_form_volume_puts_it() {
        // x_cp = L − V/A. The secant ogive of L = 0.3, R = 0.05, p = 0.5 is the arc of
        // radius ρ centred at (λ, −y₀) = (0.6, −2.675) (see `shapes`), so with u = λ − x
        // V/π = ∫ (sqrt(ρ² − u²) − y₀)² du over [λ − L, λ]
        //     = (ρ² + y₀²) L − (λ³ − (λ − L)³)/3 − 2 y₀ [F(λ) − F(λ − L)],
        // F(u) = (u sqrt(ρ² − u²) + ρ² asin(u/ρ))/2. Then x_cp/L = 0.605801543 (between the
        // cone's 2/3 and the tangent ogive's 0.4643).
        let (l, r, lambda, y0): (f64, f64, f64, f64) = (0.3, 0.05, 0.6, 2.675);
        let rho2 = lambda * lambda + y0 * y0;
        let f = |u: f64| (u * (rho2 - u * u).sqrt() + rho2 * (u / rho2.sqrt()).asin()) / 2.0;
        let a = lambda - l;
        let v = PI
            * ((rho2 + y0 * y0) * l
                - (lambda.powi(3) - a.powi(3)) / 3.0
                - 2.0 * y0 * (f(lambda) - f(a)));
        let want = 1.0 - v / (PI * r * r * l);
        assert!((want - 0.605_801_543).abs() < 1e-8, "{want}");
        let got = nose_cone_lift(NoseShape::SecantOgive { p: 0.5 }, l, r, PI * r * r);
        assert_rel(got.x_cp_m / l, want, 1e-8, "secant ogive");
        assert!((got.cn_alpha - 2.0).abs() < 1e-12);
    }

    #[test]
    fn a_nose_smaller_than_the_reference_diameter_lifts_in_proportion_to_its_base_area() {
        // CNα = 2 (A_base/A_ref) = 2 (0.05/0.06)² = 1.388888...
        let lift = nose_cone_lift(NoseShape::Conical, L, R, PI * 0.06 * 0.06);
        assert!((lift.cn_alpha - 2.0 * (0.05f64 / 0.06).powi(2)).abs() < 1e-12);
        assert!((nose_cone_lift(NoseShape::Ogive, L, R, PI * R * R).cn_alpha - 2.0).abs() < 1e-12);
    }

    #[test]
    fn a_conical_boattail_has_negative_lift_at_barrowmans_frustum_cp() {
        // Calisto's tail: 0.0635 -> 0.0435 m over 0.06 m, A_ref on r = 0.0635.
        let s = Section {
            shape: NoseShape::Conical,
            length_m: 0.06,
            fore_radius_m: 0.0635,
            aft_radius_m: 0.0435,
            clip_m: 0.0,
        };
        let lift = body_section_lift(&s, PI * 0.0635 * 0.0635);
        // 2 ((0.0435/0.0635)² − 1) = −1.0614421229
        let want_cn = 2.0 * ((0.0435f64 / 0.0635).powi(2) - 1.0);
        assert!((lift.cn_alpha - want_cn).abs() < 1e-12);
        assert!((lift.cn_alpha - (-1.0614421229)).abs() < 1e-9);
        // Barrowman: x = L/3 (1 + (1 − q)/(1 − q²)), q = r_fore/r_aft = 0.0635/0.0435
        let q: f64 = 0.0635 / 0.0435;
        let want_x = 0.06 / 3.0 * (1.0 + (1.0 - q) / (1.0 - q * q));
        assert!(
            (lift.x_cp_m - want_x).abs() < 1e-12,
            "{} vs {want_x}",
            lift.x_cp_m
        );
        assert!((lift.x_cp_m - 0.0281308411).abs() < 1e-9);
    }
}
