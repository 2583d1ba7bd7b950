//! Fin sets of every planform: their planform numbers (RocketPy's names), Barrowman's
//! normal-force slope at Mach 0 and center of pressure, referenced to the area of the design's
//! reference diameter. The Mach dependence of the slope and the roll coefficients are in
//! [`super::mach`]. Sources: those of [`super::barrowman`], RocketPy 1.13's
//! `fins/_geometry.py` and OpenRocket's `FinSetCalc`.
//!
//! **Trapezoidal fin sets** (root chord `C_r`, tip chord `C_t`, semi-span `s`, sweep `X_r` of
//! the tip's leading edge aft of the root's, `N` fins, body radius `r` at the fins, reference
//! diameter `d`):
//! `CNα = K_fb · F(N) · 8 (s/d)² / (1 + sqrt(1 + (2 l_m/(C_r + C_t))²))`,
//! with `l_m = sqrt(s² + (X_r + C_t/2 − C_r/2)²)` the mid-chord line, `K_fb = 1 + r/(s + r)`
//! the body interference factor, and `F(N)` the number-of-fins factor: `N/2` (so that for
//! `N = 3, 4` this is Barrowman's `4N (s/d)²/(…)`), except 2.37, 2.74, 2.99, 3.24 for
//! `N = 5..8` (Niskanen's fin-fin interference reduction 0.948, 0.913, 0.854, 0.81 times
//! `N/2`, as RocketPy's `Fins.fin_num_correction`). The CP is
//! `X_f + X_r (C_r + 2C_t)/(3 (C_r + C_t)) + (C_r + C_t − C_r C_t/(C_r + C_t))/6`
//! aft of the root's leading edge `X_f`.
//! At Mach 0 this equals RocketPy's Diederich-based slope exactly (see [`super::mach`]).
//!
//! **Elliptical fin sets** (half an ellipse on the root, semi-axes `C_r/2` and `s`): the same
//! slope in its general form `2π AR (A_f/A_ref)/(2 + sqrt(4 + (AR/cos γc)²))` per fin with
//! `A_f = π C_r s/4`, `γc = 0`, and RocketPy's `_EllipticalGeometry` for `Y_ma`, `K_d` and
//! `G`. The CP is the quarter point of the mean aerodynamic chord `8 C_r/(3π)` at `Y_ma`,
//! `C_r (1/2 − 2/(3π)) = 0.2878 C_r` aft of the root's leading edge; RocketPy rounds it to
//! `0.288 C_r` (2.1e-4 `C_r` further aft).
//!
//! **Free-form fin sets** (an outline of straight edges): the outline cut by lines across the
//! span, as RocketPy and OpenRocket do, on 4000 lines where RocketPy takes 40 ([`FREE_FORM_LINES`]);
//! an outline of a trapezoid has the trapezoid's numbers to 1e-7.

use super::barrowman::Lift;
use crate::design::{FinPlanform, FinSet};
use std::f64::consts::PI;

/// A set of identical fins of one planform.
#[derive(Debug, Clone, PartialEq)]
pub struct Fins {
    pub count: u32,
    pub root_chord_m: f64,
    /// Semi-span from the body surface.
    pub span_m: f64,
    pub planform: FinPlanform,
    /// Body radius at the fins.
    pub body_radius_m: f64,
    pub cant_rad: f64,
    /// The fin section's lift-curve slope in incompressible 2-D flow, per rad: 2π for a flat
    /// plate (RocketPy's `airfoil=None`), an airfoil table's slope otherwise.
    pub lift_slope_2d_per_rad: f64,
}

/// A flat plate's 2-D lift-curve slope, per rad (thin-airfoil theory).
pub const FLAT_PLATE_LIFT_SLOPE: f64 = 2.0 * PI;

/// Derived planform numbers of a fin (the names of RocketPy's `_TrapezoidalGeometry` and
/// `_EllipticalGeometry`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FinGeometry {
    /// Area of one fin, m² (`Af`).
    pub area_m2: f64,
    /// Aspect ratio `2 s²/Af` (`AR`).
    pub aspect_ratio: f64,
    /// Mid-chord sweep angle, rad (`gamma_c`).
    pub mid_chord_sweep_rad: f64,
    /// Length of the mid-chord line, m (`l_m = s / cos γc`).
    pub mid_chord_length_m: f64,
    /// Leading-edge sweep angle, rad: of the straight edge, or for a curved one the angle
    /// whose cosine is the edge's mean over the span (OpenRocket's `cosGammaLead`).
    pub leading_edge_sweep_rad: f64,
    /// Span-wise position of the mean aerodynamic chord from the root, m (`Yma`).
    pub y_mac_m: f64,
    /// Length of the mean aerodynamic chord, m.
    pub mac_length_m: f64,
    /// Axial position of the mean aerodynamic chord's leading edge aft of the root's, m.
    pub mac_leading_edge_m: f64,
    /// `τ = (s + r)/r`.
    pub tau: f64,
    /// Body interference factor on lift `K_fb = 1 + 1/τ = 1 + r/(s + r)`.
    pub lift_interference: f64,
    /// Roll forcing interference factor `K_f` (Barrowman 1967, in RocketPy's form).
    pub roll_forcing_interference: f64,
    /// Roll damping interference factor `K_d`.
    pub roll_damping_interference: f64,
    /// Roll geometric constant `G = ∫ c(y) (r + y)² dy` over the span, m⁴: for a trapezoid
    /// `[(C_r + 3C_t) s³ + 4 (C_r + 2C_t) r s² + 6 (C_r + C_t) s r²]/12`, for an ellipse
    /// `C_r s (3π s² + 32 r s + 12π r²)/48`.
    pub roll_geometric_constant_m4: f64,
}

/// Barrowman's roll forcing interference factor `K_f(τ)` (RocketPy's form; the same for
/// every planform).
fn roll_forcing_interference(tau: f64) -> f64 {
    let t2 = tau * tau;
    let tm1 = tau - 1.0;
    let asin_term = ((t2 - 1.0) / (t2 + 1.0)).asin();
    (1.0 / (PI * PI))
        * ((PI * PI / 4.0) * ((tau + 1.0).powi(2) / t2)
            + (PI * (t2 + 1.0).powi(2) / (t2 * tm1 * tm1)) * asin_term
            - (2.0 * PI * (tau + 1.0)) / (tau * tm1)
            + ((t2 + 1.0).powi(2) / (t2 * tm1 * tm1)) * asin_term * asin_term
            - (4.0 * (tau + 1.0)) / (tau * tm1) * asin_term
            + (8.0 / (tm1 * tm1)) * ((t2 + 1.0) / (2.0 * tau)).ln())
}

/// The roll damping interference factor `K_d` of an elliptical fin of span `s` on a body of
/// radius `r` (RocketPy's `_EllipticalGeometry`, its three cases).
fn elliptical_roll_damping_interference(s: f64, r: f64) -> f64 {
    if s > r {
        let q = (s * s - r * r).sqrt();
        1.0 + r
            * r
            * (2.0 * r * r * q * ((2.0 * s * q + 2.0 * s * s) / r).ln()
                - 2.0 * r * r * q * (2.0 * s).ln()
                + 2.0 * s.powi(3)
                - PI * r * s * s
                - 2.0 * r * r * s
                + PI * r.powi(3))
            / (2.0 * s * s * (s / 3.0 + PI * r / 4.0) * (s * s - r * r))
    } else if s < r {
        let q = (r * r - s * s).sqrt();
        1.0 - r
            * r
            * (2.0 * s.powi(3) - PI * s * s * r - 2.0 * s * r * r
                + PI * r.powi(3)
                + 2.0 * r * r * q * (s / q).atan()
                - PI * r * r * q)
            / (2.0 * s * (r * r - s * s) * (s * s / 3.0 + PI * s * r / 4.0))
    } else {
        (28.0 - 3.0 * PI) / (4.0 + 3.0 * PI)
    }
}

/// The mean over the span of the cosine of an elliptical fin's leading-edge slope, its
/// semi-axes `a` along the body and `b` along the span: with `y = b sin θ`,
/// `∫₀^{π/2} cos²θ / √(1 − (1 − (a/b)²) sin²θ) dθ`, by Simpson's rule on 256 panels (the
/// integrand is smooth and periodic-like: the rule's error is far below 1e-12).
fn elliptical_mean_leading_edge_cos(a: f64, b: f64) -> f64 {
    let e = 1.0 - (a / b).powi(2);
    let f = |t: f64| t.cos().powi(2) / (1.0 - e * t.sin().powi(2)).sqrt();
    let n = 256;
    let h = 0.5 * PI / n as f64;
    let inner: f64 = (1..n)
        .map(|i| if i % 2 == 1 { 4.0 } else { 2.0 } * f(i as f64 * h))
        .sum();
    (f(0.0) + inner + f(0.5 * PI)) * h / 3.0
}

/// Lines across the span on which a free-form outline is sampled.
const FREE_FORM_LINES: usize = 4000;

/// A free-form fin's planform numbers (RocketPy's `_FreeFormGeometry`, OpenRocket's
/// `FinSetCalc`): the outline cut by [`FREE_FORM_LINES`] lines across the span at their
/// midpoints, each line's chord the length inside the outline between its leading edge (the
/// first crossing) and its trailing edge (the last); the span integrals by the midpoint rule
/// (relative error about 1e-7, where RocketPy's 40 lines give about 1e-2); the mid-chord and
/// leading-edge sweeps as the mean of their slopes' cosines; the area `A_f` the outline's own.
/// `K_d = 1 + ∫ r³ c/(r + y)² dy / ∫ (r + y) c dy` and `G = ∫ c (r + y)² dy`, of which the
/// trapezoid's closed forms are the exact values.
fn free_form_geometry(points: &[[f64; 2]], area: f64, s: f64, r: f64, kf: f64) -> FinGeometry {
    let n = points.len();
    let dy = s / FREE_FORM_LINES as f64;
    let mut crossings: Vec<f64> = Vec::with_capacity(n);
    let (mut a, mut mac, mut y_mac, mut lead_mac) = (0.0, 0.0, 0.0, 0.0);
    let (mut g, mut kd_num, mut kd_den) = (0.0, 0.0, 0.0);
    let (mut cos_mid, mut cos_lead) = (0.0, 0.0);
    let mut previous: Option<(f64, f64)> = None;
    for i in 0..FREE_FORM_LINES {
        let y = (i as f64 + 0.5) * dy;
        crossings.clear();
        for k in 0..n {
            let ([x0, y0], [x1, y1]) = (points[k], points[(k + 1) % n]);
            if (y0 <= y && y < y1) || (y1 <= y && y < y0) {
                crossings.push(x0 + (y - y0) * (x1 - x0) / (y1 - y0));
            }
        }
        crossings.sort_by(f64::total_cmp);
        let c: f64 = crossings.chunks(2).map(|p| p.last().unwrap() - p[0]).sum();
        let (lead, trail) = match (crossings.first(), crossings.last()) {
            (Some(&l), Some(&t)) => (l, t),
            _ => (0.0, 0.0),
        };
        a += c * dy;
        mac += c * c * dy;
        y_mac += y * c * dy;
        lead_mac += lead * c * dy;
        g += c * (r + y) * (r + y) * dy;
        kd_num += r.powi(3) * c / ((r + y) * (r + y)) * dy;
        kd_den += (r + y) * c * dy;
        let mid = 0.5 * (lead + trail);
        if let Some((lead0, mid0)) = previous {
            cos_mid += dy / (mid - mid0).hypot(dy);
            cos_lead += dy / (lead - lead0).hypot(dy);
        }
        previous = Some((lead, mid));
    }
    let gamma_c = (cos_mid / (FREE_FORM_LINES - 1) as f64).min(1.0).acos();
    let tau = (s + r) / r;
    FinGeometry {
        area_m2: area,
        aspect_ratio: 2.0 * s * s / area,
        mid_chord_sweep_rad: gamma_c,
        mid_chord_length_m: s / gamma_c.cos(),
        leading_edge_sweep_rad: (cos_lead / (FREE_FORM_LINES - 1) as f64).min(1.0).acos(),
        y_mac_m: y_mac / a,
        mac_length_m: mac / a,
        mac_leading_edge_m: lead_mac / a,
        tau,
        lift_interference: 1.0 + 1.0 / tau,
        roll_forcing_interference: kf,
        roll_damping_interference: 1.0 + kd_num / kd_den,
        roll_geometric_constant_m4: g,
    }
}

impl Fins {
    /// The aerodynamic view of a design's fin set.
    pub fn of(f: &FinSet) -> Fins {
        Fins {
            count: f.count,
            root_chord_m: f.root_chord_m,
            span_m: f.span_m,
            planform: f.planform.clone(),
            body_radius_m: f.body_radius_m,
            cant_rad: f.cant_deg.to_radians(),
            lift_slope_2d_per_rad: f.lift_slope_2d_per_rad,
        }
    }

    /// The planform numbers (RocketPy `_TrapezoidalGeometry` / `_EllipticalGeometry`
    /// `.evaluate_geometrical_parameters`).
    pub fn geometry(&self) -> FinGeometry {
        let (cr, s, r) = (self.root_chord_m, self.span_m, self.body_radius_m);
        let tau = (s + r) / r;
        let kf = roll_forcing_interference(tau);
        match &self.planform {
            &FinPlanform::Trapezoidal {
                tip_chord_m: ct,
                sweep_m: xr,
            } => {
                let area = self.planform.area_m2(cr, s);
                let gamma_c = ((xr + 0.5 * ct - 0.5 * cr) / s).atan();
                let lambda = ct / cr;
                let tm1 = tau - 1.0;
                let kd = 1.0
                    + (((tau - lambda) / tau) - ((1.0 - lambda) / tm1) * tau.ln())
                        / (((tau + 1.0) * (tau - lambda)) / 2.0
                            - ((1.0 - lambda) * (tau.powi(3) - 1.0)) / (3.0 * tm1));
                let g = ((cr + 3.0 * ct) * s.powi(3)
                    + 4.0 * (cr + 2.0 * ct) * r * s * s
                    + 6.0 * (cr + ct) * s * r * r)
                    / 12.0;
                let y_mac = (s / 3.0) * (cr + 2.0 * ct) / (cr + ct);
                FinGeometry {
                    area_m2: area,
                    aspect_ratio: 2.0 * s * s / area,
                    mid_chord_sweep_rad: gamma_c,
                    mid_chord_length_m: s / gamma_c.cos(),
                    leading_edge_sweep_rad: (xr / s).atan(),
                    y_mac_m: y_mac,
                    mac_length_m: (2.0 / 3.0) * (cr + ct - cr * ct / (cr + ct)),
                    mac_leading_edge_m: xr * y_mac / s,
                    tau,
                    lift_interference: 1.0 + 1.0 / tau,
                    roll_forcing_interference: kf,
                    roll_damping_interference: kd,
                    roll_geometric_constant_m4: g,
                }
            }
            FinPlanform::Elliptical => {
                // Chord c(y) = C_r √(1 − (y/s)²), leading edge (C_r/2)(1 − √(1 − (y/s)²)).
                let area = self.planform.area_m2(cr, s);
                let y_mac = s / (3.0 * PI) * (9.0 * PI * PI - 64.0).sqrt();
                let mac = 8.0 * cr / (3.0 * PI);
                FinGeometry {
                    area_m2: area,
                    aspect_ratio: 2.0 * s * s / area,
                    mid_chord_sweep_rad: 0.0,
                    mid_chord_length_m: s,
                    leading_edge_sweep_rad: elliptical_mean_leading_edge_cos(cr / 2.0, s).acos(),
                    y_mac_m: y_mac,
                    mac_length_m: mac,
                    // At Yma, √(1 − (Yma/s)²) = 8/(3π): the leading edge is (C_r/2)(1 − 8/(3π)).
                    mac_leading_edge_m: 0.5 * cr - 0.5 * mac,
                    tau,
                    lift_interference: 1.0 + 1.0 / tau,
                    roll_forcing_interference: kf,
                    roll_damping_interference: elliptical_roll_damping_interference(s, r),
                    roll_geometric_constant_m4: cr
                        * s
                        * (3.0 * PI * s * s + 32.0 * r * s + 12.0 * PI * r * r)
                        / 48.0,
                }
            }
            FinPlanform::FreeForm { points_m } => {
                free_form_geometry(points_m, self.planform.area_m2(cr, s), s, r, kf)
            }
        }
    }

    /// Center of pressure, m aft of the root's leading edge: the quarter point of the mean
    /// aerodynamic chord. For a trapezoid this is Barrowman's
    /// `X_r (C_r + 2C_t)/(3 (C_r + C_t)) + (C_r + C_t − C_r C_t/(C_r + C_t))/6`; for an
    /// ellipse `C_r (1/2 − 2/(3π)) = 0.2878 C_r` (RocketPy rounds it to `0.288 C_r`).
    pub fn x_cp_m(&self) -> f64 {
        let g = self.geometry();
        g.mac_leading_edge_m + 0.25 * g.mac_length_m
    }

    /// Barrowman's normal-force slope of the whole set at Mach 0, on the area of
    /// `ref_diameter_m`: `K_fb F(N) 2π AR (A_f/A_ref) / (2 + √(4 + (AR/cos γc)²))`, which for a
    /// trapezoid is `K_fb F(N) 8 (s/d)² / (1 + √(1 + (2 l_m/(C_r + C_t))²))`.
    pub fn cn_alpha_mach0(&self, ref_diameter_m: f64) -> f64 {
        let g = self.geometry();
        let a_ref = PI * ref_diameter_m * ref_diameter_m / 4.0;
        let one = super::mach::single_fin_cn_alpha(&g, self.lift_slope_2d_per_rad, 0.0, a_ref);
        g.lift_interference * fin_count_factor(self.count) * one
    }

    /// Lift of the set at Mach 0.
    pub fn lift_mach0(&self, ref_diameter_m: f64) -> Lift {
        Lift {
            cn_alpha: self.cn_alpha_mach0(ref_diameter_m),
            x_cp_m: self.x_cp_m(),
        }
    }
}

/// Number-of-fins factor `F(N)` multiplying a single fin's slope: `N/2`, except RocketPy's
/// (Niskanen's) reduced values 2.37, 2.74, 2.99, 3.24 for 5 to 8 fins.
pub fn fin_count_factor(count: u32) -> f64 {
    match count {
        5 => 2.37,
        6 => 2.74,
        7 => 2.99,
        8 => 3.24,
        n => n as f64 / 2.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The example fin set of docs/design-format (3 fins, 54 mm body).
    fn example_fins() -> Fins {
        Fins {
            count: 3,
            root_chord_m: 0.12,
            span_m: 0.07,
            planform: FinPlanform::Trapezoidal {
                tip_chord_m: 0.05,
                sweep_m: 0.06,
            },
            body_radius_m: 0.0563 / 2.0,
            cant_rad: 0.0,
            lift_slope_2d_per_rad: FLAT_PLATE_LIFT_SLOPE,
        }
    }

    #[test]
    fn a_three_fin_set_matches_a_hand_calculation_of_barrowmans_formulas() {
        // Hand calculation, d = 0.0563, r = 0.02815:
        //   mid-chord offset  = X_r + C_t/2 − C_r/2 = 0.06 + 0.025 − 0.06 = 0.025
        //   l_m = sqrt(0.07² + 0.025²) = sqrt(0.005525) = 0.0743303437
        //   2 l_m/(C_r + C_t) = 0.1486606875/0.17 = 0.8744746320
        //   1 + sqrt(1 + 0.7647058824) = 1 + 1.3284223283 = 2.3284223283
        //   4N (s/d)² = 12 (0.07/0.0563)² = 18.5507100063
        //   K_fb = 1 + 0.02815/(0.07 + 0.02815) = 1.2868059093
        //   CNα = 1.2868059093 · 18.5507100063 / 2.3284223283 = 10.2520762527
        let f = example_fins();
        let sd = 0.07 / 0.0563;
        let lm = (0.07f64 * 0.07 + 0.025 * 0.025).sqrt();
        let want = (1.0 + 0.02815 / 0.09815) * 4.0 * 3.0 * sd * sd
            / (1.0 + (1.0 + (2.0 * lm / 0.17).powi(2)).sqrt());
        let got = f.cn_alpha_mach0(0.0563);
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
        assert!((got - 10.2520762527).abs() < 1e-9, "{got}");
        // CP: X_r (C_r + 2C_t)/(3(C_r + C_t)) + (C_r + C_t − C_r C_t/(C_r + C_t))/6
        //   = 0.06 · 0.22/0.51 + (0.17 − 0.006/0.17)/6 = 0.0258823529 + 0.0224509804 = 0.0483333333
        assert!((f.x_cp_m() - 0.0483333333).abs() < 1e-9, "{}", f.x_cp_m());
    }

    #[test]
    fn four_fins_lift_four_thirds_as_much_as_three_and_five_follow_rocketpys_reduced_factor() {
        let three = example_fins();
        let four = Fins {
            count: 4,
            ..three.clone()
        };
        let five = Fins {
            count: 5,
            ..three.clone()
        };
        let ratio = four.cn_alpha_mach0(0.0563) / three.cn_alpha_mach0(0.0563);
        assert!((ratio - 4.0 / 3.0).abs() < 1e-12);
        let ratio5 = five.cn_alpha_mach0(0.0563) / three.cn_alpha_mach0(0.0563);
        assert!((ratio5 - 2.37 / 1.5).abs() < 1e-12);
    }

    #[test]
    fn the_fin_geometry_matches_rocketpys_definitions_for_calisto() {
        // Calisto fins: C_r 0.12, C_t 0.04, s 0.1, X_r = C_r − C_t = 0.08, r = 0.0635.
        let f = Fins {
            count: 4,
            root_chord_m: 0.12,
            span_m: 0.1,
            planform: FinPlanform::Trapezoidal {
                tip_chord_m: 0.04,
                sweep_m: 0.08,
            },
            body_radius_m: 0.0635,
            cant_rad: 0.0,
            lift_slope_2d_per_rad: FLAT_PLATE_LIFT_SLOPE,
        };
        let g = f.geometry();
        assert!((g.area_m2 - 0.008).abs() < 1e-15);
        assert!((g.aspect_ratio - 2.5).abs() < 1e-12);
        // γc = atan((0.08 + 0.02 − 0.06)/0.1) = atan(0.4)
        assert!((g.mid_chord_sweep_rad - 0.4f64.atan()).abs() < 1e-15);
        // Yma = 0.1/3 · 0.2/0.16 = 0.0416666..
        assert!((g.y_mac_m - 0.1 / 3.0 * 0.2 / 0.16).abs() < 1e-15);
        assert!((g.tau - 0.1635 / 0.0635).abs() < 1e-12);
    }

    /// Three elliptical fins, 0.12 m root on a 0.09 m span, on a 60 mm body.
    fn elliptical_fins() -> Fins {
        Fins {
            count: 3,
            root_chord_m: 0.12,
            span_m: 0.09,
            planform: FinPlanform::Elliptical,
            body_radius_m: 0.03,
            cant_rad: 0.0,
            lift_slope_2d_per_rad: FLAT_PLATE_LIFT_SLOPE,
        }
    }

    #[test]
    fn an_elliptical_fin_s_leading_edge_sweep_is_the_span_mean_of_its_slope_s_cosine() {
        // Semi-axes equal (a circle's quarter): the mean of cos over the span is π/4.
        assert!((elliptical_mean_leading_edge_cos(0.05, 0.05) - PI / 4.0).abs() < 1e-13);
        // Otherwise against the mean taken directly over y (midpoint rule, 10⁶ strips; the
        // slope x'(y) = a (y/b²)/√(1 − (y/b)²), cos = 1/√(1 + x'²)).
        let (a, b) = (0.06, 0.09);
        let n = 1_000_000;
        let direct = (0..n)
            .map(|i| {
                let y = (i as f64 + 0.5) / n as f64 * b;
                let u = y / b;
                let slope = a * (y / (b * b)) / (1.0 - u * u).sqrt();
                1.0 / (1.0 + slope * slope).sqrt()
            })
            .sum::<f64>()
            / n as f64;
        let simpson = elliptical_mean_leading_edge_cos(a, b);
        assert!((simpson - direct).abs() < 1e-8, "{simpson} vs {direct}");
        // The fin's sweep angle is its arccosine (a 0.12 m root on a 0.09 m span).
        let fins = elliptical_fins();
        assert_eq!(fins.geometry().leading_edge_sweep_rad, simpson.acos());
        // The mean aerodynamic chord 8 C_r/(3π) at Yma, its quarter point the CP.
        let g = fins.geometry();
        assert!((g.mac_length_m - 0.32 / PI).abs() < 1e-15);
        assert!((fins.x_cp_m() - 0.12 * (0.5 - 2.0 / (3.0 * PI))).abs() < 1e-15);
    }

    #[test]
    fn a_free_form_outline_of_a_trapezoid_has_the_trapezoid_s_numbers() {
        // The example fin's corners: root 0.12, tip 0.05 swept 0.06, span 0.07.
        let trapezoid = example_fins();
        let outline = Fins {
            planform: FinPlanform::FreeForm {
                points_m: vec![[0.0, 0.0], [0.06, 0.07], [0.11, 0.07], [0.12, 0.0]],
            },
            ..trapezoid.clone()
        };
        let (t, f) = (trapezoid.geometry(), outline.geometry());
        let close = |a: f64, b: f64, tol: f64, what: &str| {
            assert!((a / b - 1.0).abs() < tol, "{what}: {a} vs {b}")
        };
        // The area, the sweep and the factors of τ alone are exact; the span integrals carry
        // the midpoint rule's error on 4000 lines (under 1e-7).
        close(f.area_m2, t.area_m2, 1e-15, "A_f");
        close(f.aspect_ratio, t.aspect_ratio, 1e-15, "AR");
        close(f.mid_chord_sweep_rad, t.mid_chord_sweep_rad, 1e-12, "γc");
        close(
            f.leading_edge_sweep_rad,
            t.leading_edge_sweep_rad,
            1e-12,
            "Λ",
        );
        close(
            f.roll_forcing_interference,
            t.roll_forcing_interference,
            1e-15,
            "K_f",
        );
        close(f.y_mac_m, t.y_mac_m, 1e-7, "Yma");
        close(f.mac_length_m, t.mac_length_m, 1e-7, "MAC");
        close(
            f.mac_leading_edge_m,
            t.mac_leading_edge_m,
            1e-7,
            "MAC's leading edge",
        );
        close(
            f.roll_geometric_constant_m4,
            t.roll_geometric_constant_m4,
            1e-7,
            "G",
        );
        // K_d's integral form is the trapezoid's closed form.
        close(
            f.roll_damping_interference,
            t.roll_damping_interference,
            1e-7,
            "K_d",
        );
        close(outline.x_cp_m(), trapezoid.x_cp_m(), 1e-7, "CP");
        close(
            outline.cn_alpha_mach0(0.0563),
            trapezoid.cn_alpha_mach0(0.0563),
            1e-12,
            "CNα",
        );
    }

    #[test]
    fn a_free_form_outline_of_many_corners_on_an_ellipse_tends_to_the_elliptical_fin() {
        // 200 corners on the half ellipse (semi-axes 0.06 and 0.09): a polygon inside it, its
        // area short by 1 − sin(π/n)/(π/n) = 4.1e-5 of the ellipse's, its other numbers
        // within a few 1e-4.
        let n = 200;
        let points: Vec<[f64; 2]> = (0..=n)
            .map(|k| {
                let t = PI * (1.0 - k as f64 / n as f64);
                [0.06 + 0.06 * t.cos(), 0.09 * t.sin()]
            })
            .map(|[x, y]| [if x.abs() < 1e-15 { 0.0 } else { x }, y.max(0.0)])
            .collect();
        let ellipse = elliptical_fins();
        let polygon = Fins {
            planform: FinPlanform::FreeForm { points_m: points },
            ..ellipse.clone()
        };
        let (e, p) = (ellipse.geometry(), polygon.geometry());
        let close = |a: f64, b: f64, tol: f64, what: &str| {
            assert!((a / b - 1.0).abs() < tol, "{what}: {a} vs {b}")
        };
        let shortfall = 1.0 - (PI / n as f64).sin() / (PI / n as f64);
        close(p.area_m2, e.area_m2 * (1.0 - shortfall), 1e-12, "A_f");
        // A free-form Yma is the chord-weighted mean span, the area's centroid (OpenRocket's
        // and RocketPy's free-form `mac_span`), 4s/(3π) for the ellipse; RocketPy's elliptical
        // Yma is where the chord equals the MAC, s √(9π² − 64)/(3π). The two CPs agree: the
        // leading edge there is the chord-weighted mean leading edge.
        close(p.y_mac_m, 4.0 * 0.09 / (3.0 * PI), 5e-4, "Yma");
        close(p.mac_length_m, e.mac_length_m, 5e-4, "MAC");
        close(
            p.roll_geometric_constant_m4,
            e.roll_geometric_constant_m4,
            5e-4,
            "G",
        );
        close(
            p.roll_damping_interference,
            e.roll_damping_interference,
            5e-4,
            "K_d",
        );
        close(polygon.x_cp_m(), ellipse.x_cp_m(), 5e-4, "CP");
        close(
            p.leading_edge_sweep_rad,
            e.leading_edge_sweep_rad,
            5e-3,
            "Λ",
        );
        assert!(
            p.mid_chord_sweep_rad.abs() < 1e-6,
            "γc {}",
            p.mid_chord_sweep_rad
        );
    }
}
