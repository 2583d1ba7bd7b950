//! Pressure (wave) drag of nose cones and shoulders against Mach, per the frontal area of the
//! growing section (Niskanen 2009, §3.4.3 and appendix B; OpenRocket's
//! `SymmetricComponentCalc.calculateNoseInterpolator`).
//!
//! - Conical: above Mach 1.3, `2.1 sin²ε + 0.5 sin ε/sqrt(M² − 1)` (eq. B.4, ε the half-apex
//!   angle); between 1 and 1.3 the cubic through the values at 1 (`sin ε`, eq. B.6) and 1.3 and
//!   the slopes at 1 (`4/(γ+1) (1 − 0.5 C_D,M=1)`, eq. B.5) and 1.3 (`−1.1341 sin ε`, the
//!   derivative of B.4).
//! - Tangent ogive: the cone of the same length and base (appendix B.4; the shape factor
//!   `0.72 (κ − 0.5)² + 0.82` is 1 for a tangent ogive). OpenRocket's code passes the joint
//!   angle, near zero for a tangent ogive, instead of the cone's; hpr follows the thesis.
//! - Elliptical, power series, parabolic series and Haack series: measured curves at
//!   fineness 3 (NASA TR-R-100, Stoney 1961, p. 16, as tabulated in OpenRocket), blended
//!   linearly between neighbouring shape parameters, and carried to the actual fineness `f`
//!   by `C = C_stag (C₃/C_stag)^log₄(f + 1)` (eq. B.9).
//! - Below the first transonic point the curve is `a M^b + 0.8 sin²φ` (eqs. 3.86, 3.87), `φ`
//!   the joint angle with the body, with `a` and `b` matching the value and slope there
//!   (skipped, as in OpenRocket, when the transonic value is below 0.001 or the fit would be
//!   ill-posed; the curve is then constant below that point).
//!
//! The shape parameter of a Haack series is clamped to [0, 1/3] for this look-up (no data
//! beyond LV-Haack).

use super::drag_formulas::{stagnation_cd, GAMMA_AIR};
use super::table::Curve;
use crate::design::NoseShape;

/// Fineness-3 curves (Mach, C_D) of NASA TR-R-100 p. 16.
const ELLIPSOID: &[(f64, f64)] = &[
    (1.2, 0.110),
    (1.25, 0.128),
    (1.3, 0.140),
    (1.4, 0.148),
    (1.6, 0.152),
    (2.0, 0.159),
    (2.4, 0.162),
];
const POWER_1_4: &[(f64, f64)] = &[
    (1.2, 0.140),
    (1.3, 0.156),
    (1.4, 0.169),
    (1.6, 0.192),
    (1.8, 0.206),
    (2.2, 0.227),
    (2.6, 0.241),
    (3.0, 0.249),
    (3.6, 0.252),
];
const POWER_1_2: &[(f64, f64)] = &[
    (0.925, 0.0),
    (0.95, 0.014),
    (1.0, 0.050),
    (1.05, 0.060),
    (1.1, 0.059),
    (1.2, 0.081),
    (1.3, 0.084),
    (1.7, 0.085),
    (2.0, 0.078),
];
const POWER_3_4: &[(f64, f64)] = &[
    (0.8, 0.0),
    (0.9, 0.015),
    (1.0, 0.078),
    (1.06, 0.121),
    (1.2, 0.110),
    (1.4, 0.098),
    (1.6, 0.090),
    (2.0, 0.084),
    (2.8, 0.078),
    (3.4, 0.074),
];
const VON_KARMAN: &[(f64, f64)] = &[
    (0.9, 0.0),
    (0.95, 0.010),
    (1.0, 0.027),
    (1.05, 0.055),
    (1.1, 0.070),
    (1.2, 0.081),
    (1.4, 0.095),
    (1.6, 0.097),
    (2.0, 0.091),
    (3.0, 0.083),
];
const LV_HAACK: &[(f64, f64)] = &[
    (0.9, 0.0),
    (0.95, 0.010),
    (1.0, 0.024),
    (1.05, 0.066),
    (1.1, 0.084),
    (1.2, 0.100),
    (1.4, 0.114),
    (1.6, 0.117),
    (2.0, 0.113),
];
const PARABOLIC: &[(f64, f64)] = &[
    (0.95, 0.0),
    (0.975, 0.016),
    (1.0, 0.041),
    (1.05, 0.092),
    (1.1, 0.109),
    (1.2, 0.119),
    (1.4, 0.113),
    (1.7, 0.108),
];
const PARABOLIC_1_2: &[(f64, f64)] = &[
    (0.8, 0.0),
    (0.9, 0.016),
    (0.95, 0.042),
    (1.0, 0.100),
    (1.05, 0.126),
    (1.1, 0.125),
    (1.3, 0.100),
    (1.5, 0.090),
    (1.8, 0.088),
];
const PARABOLIC_3_4: &[(f64, f64)] = &[
    (0.9, 0.0),
    (0.95, 0.023),
    (1.0, 0.073),
    (1.05, 0.098),
    (1.1, 0.107),
    (1.2, 0.106),
    (1.4, 0.089),
    (1.7, 0.082),
];

/// A base curve of the blend.
#[derive(Debug, Clone, Copy)]
enum Base {
    Data(&'static [(f64, f64)]),
    /// Blunt cylinder face (fineness 0).
    Blunt,
    /// Cone with this `sin ε`.
    Cone(f64),
}

impl Base {
    fn xs(&self) -> Vec<f64> {
        match self {
            Base::Data(d) => d.iter().map(|p| p.0).collect(),
            Base::Blunt => (0..60).map(|i| i as f64 * 0.05).collect(),
            Base::Cone(_) => (0..=400).map(|i| 1.0 + i as f64 * 0.01).collect(),
        }
    }

    fn at(&self, mach: f64) -> f64 {
        match self {
            Base::Data(d) => linear_clamped(d, mach),
            Base::Blunt => stagnation_cd(mach),
            Base::Cone(s) => conical_wave_cd(mach, *s),
        }
    }
}

fn linear_clamped(d: &[(f64, f64)], x: f64) -> f64 {
    if x <= d[0].0 {
        return d[0].1;
    }
    for w in d.windows(2) {
        if x <= w[1].0 {
            let t = (x - w[0].0) / (w[1].0 - w[0].0);
            return w[0].1 + (w[1].1 - w[0].1) * t;
        }
    }
    d[d.len() - 1].1
}

/// Transonic and supersonic pressure drag of a cone with half-apex sine `sin_eps` (eqs.
/// B.4–B.6); below Mach 1 the Mach-1 value.
pub fn conical_wave_cd(mach: f64, sin_eps: f64) -> f64 {
    let s = sin_eps;
    let m = mach.max(1.0);
    if m > 1.3 {
        return 2.1 * s * s + 0.5 * s / (m * m - 1.0).sqrt();
    }
    // Cubic Hermite on [1, 1.3].
    let (y0, y1) = (s, 2.1 * s * s + 0.5 * s / 0.69f64.sqrt());
    let (d0, d1) = (4.0 / (GAMMA_AIR + 1.0) * (1.0 - 0.5 * y0), -1.1341 * s);
    let h = 0.3;
    let t = (m - 1.0) / h;
    let (t2, t3) = (t * t, t * t * t);
    (2.0 * t3 - 3.0 * t2 + 1.0) * y0
        + (t3 - 2.0 * t2 + t) * h * d0
        + (-2.0 * t3 + 3.0 * t2) * y1
        + (t3 - t2) * h * d1
}

/// Pressure drag coefficient against Mach of a nose (or shoulder) of `shape`, fineness
/// `f = L/(2 ΔR)` and joint-angle sine `sin_phi`, per the section's frontal area.
#[derive(Debug, Clone)]
pub struct NosePressureDrag {
    transonic: Curve,
    /// `(first Mach point, a, b, C_D at Mach 0)` of the subsonic fit, if used.
    subsonic: Option<(f64, f64, f64, f64)>,
}

impl NosePressureDrag {
    pub fn new(shape: NoseShape, fineness: f64, sin_phi: f64) -> Self {
        // A tangent ogive meets the body at no angle: OpenRocket sets its joint angle to
        // zero ("special case: tangent ogive"), so it has no pressure drag below Mach 1 and
        // only the conical formula's transonic bump of a zero angle above.
        let sin_phi = if shape == NoseShape::Ogive {
            0.0
        } else {
            sin_phi
        };
        let sin_eps = 1.0 / (1.0 + 4.0 * fineness * fineness).sqrt();
        let blend = |a: Base, b: Base, p: f64| (a, Some(b), p.clamp(0.0, 1.0));
        // OpenRocket's ogive family (`calculateOgiveNoseInterpolator`): the conical formula
        // at the joint's angle, times 0.72 (p − 0.5)² + 0.82 (1 for the cone, p = 0, and the
        // tangent ogive, p = 1; 0.82 at p = 0.5).
        let ogive_mul = match shape {
            NoseShape::SecantOgive { p } => 0.72 * (p - 0.5) * (p - 0.5) + 0.82,
            _ => 1.0,
        };
        let (one, two, p, direct) = match shape {
            NoseShape::Conical | NoseShape::Ogive | NoseShape::SecantOgive { .. } => {
                (Base::Cone(sin_phi), None, 0.0, true)
            }
            NoseShape::Elliptical => (Base::Data(ELLIPSOID), None, 0.0, false),
            NoseShape::PowerSeries { k } => {
                let (a, b, p) = if k <= 0.25 {
                    blend(Base::Blunt, Base::Data(POWER_1_4), k * 4.0)
                } else if k <= 0.5 {
                    blend(
                        Base::Data(POWER_1_4),
                        Base::Data(POWER_1_2),
                        (k - 0.25) * 4.0,
                    )
                } else if k <= 0.75 {
                    blend(
                        Base::Data(POWER_1_2),
                        Base::Data(POWER_3_4),
                        (k - 0.5) * 4.0,
                    )
                } else {
                    blend(Base::Data(POWER_3_4), Base::Cone(sin_eps), (k - 0.75) * 4.0)
                };
                (a, b, p, false)
            }
            NoseShape::Parabolic { k } => {
                let (a, b, p) = if k <= 0.5 {
                    blend(Base::Cone(sin_eps), Base::Data(PARABOLIC_1_2), k * 2.0)
                } else if k <= 0.75 {
                    blend(
                        Base::Data(PARABOLIC_1_2),
                        Base::Data(PARABOLIC_3_4),
                        (k - 0.5) * 4.0,
                    )
                } else {
                    blend(
                        Base::Data(PARABOLIC_3_4),
                        Base::Data(PARABOLIC),
                        (k - 0.75) * 4.0,
                    )
                };
                (a, b, p, false)
            }
            NoseShape::Haack { c } => {
                let (a, b, p) = blend(Base::Data(VON_KARMAN), Base::Data(LV_HAACK), c * 3.0);
                (a, b, p, false)
            }
        };
        let mut xs = one.xs();
        if let Some(b) = two {
            xs.extend(b.xs());
        }
        xs.sort_by(|a, b| a.total_cmp(b));
        xs.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        let blended = |m: f64| match two {
            Some(b) => p * b.at(m) + (1.0 - p) * one.at(m),
            None => one.at(m),
        };
        let exponent = (fineness + 1.0).ln() / 4.0f64.ln();
        let points: Vec<(f64, f64)> = xs
            .iter()
            .map(|&m| {
                let v = blended(m);
                if direct {
                    (m, ogive_mul * v)
                } else {
                    let stag = stagnation_cd(m);
                    (m, stag * (v / stag).powf(exponent))
                }
            })
            .collect();
        let transonic = Curve::new(&points).expect("grid points are finite and increasing");
        let min = points[0].0;
        let min_value = points[0].1;
        let cd0 = 0.8 * sin_phi * sin_phi;
        let deriv = (transonic.at(min + 0.01) - min_value) / 0.01;
        let subsonic = if min_value < 0.001 || cd0 >= min_value - 0.01 || deriv <= 0.01 {
            None
        } else {
            let b = min * deriv / (min_value - cd0);
            let a = (min_value - cd0) / min.powf(b);
            Some((min, a, b, cd0))
        };
        NosePressureDrag {
            transonic,
            subsonic,
        }
    }

    /// Pressure drag per the section's frontal area at `mach`.
    pub fn at(&self, mach: f64) -> f64 {
        match self.subsonic {
            Some((min, a, b, cd0)) if mach < min => a * mach.max(0.0).powf(b) + cd0,
            _ => self.transonic.at(mach),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cone_above_mach_one_point_three_follows_hoerners_formula() {
        // Fineness 3: sin ε = 1/sqrt(37) = 0.1643990; at M 2:
        // 2.1 · 0.0270270 + 0.5 · 0.1643990/sqrt(3) = 0.0567568 + 0.0474579 = 0.1042147
        let s = 1.0 / 37f64.sqrt();
        let d = NosePressureDrag::new(NoseShape::Conical, 3.0, s);
        assert!((d.at(2.0) - 0.1042147).abs() < 1e-6, "{}", d.at(2.0));
    }

    #[test]
    fn the_conical_cubic_meets_its_end_conditions() {
        let s = 0.2;
        assert!((conical_wave_cd(1.0, s) - s).abs() < 1e-15);
        let at13 = 2.1 * s * s + 0.5 * s / 0.69f64.sqrt();
        assert!((conical_wave_cd(1.3, s) - at13).abs() < 1e-12);
        let slope1 = (conical_wave_cd(1.0 + 1e-7, s) - s) / 1e-7;
        assert!((slope1 - 4.0 / 2.4 * (1.0 - 0.1)).abs() < 1e-5, "{slope1}");
    }

    #[test]
    fn a_cone_has_the_joint_angle_drag_at_mach_zero_and_rises_toward_mach_one() {
        let s = 1.0 / 37f64.sqrt();
        let d = NosePressureDrag::new(NoseShape::Conical, 3.0, s);
        assert!((d.at(0.0) - 0.8 * s * s).abs() < 1e-12);
        assert!(d.at(0.5) > d.at(0.0) && d.at(0.9) > d.at(0.5) && d.at(0.99) < d.at(1.0) + 1e-9);
    }

    #[test]
    fn a_tangent_ogive_has_no_pressure_drag_but_the_zero_angle_cones_transonic_bump() {
        // OpenRocket's tangent ogive: joint angle zero whatever the profile says, so nothing
        // below Mach 1 or above 1.3, and between them the conical cubic through 0 at both ends
        // with slope 4/(γ + 1) at Mach 1 and 0 at 1.3: 0.3 · (5/3) (t³ − 2t² + t), t = (M − 1)/0.3
        // (at M 1.16, t = 0.5333: 0.0580741).
        let n = NosePressureDrag::new(NoseShape::Ogive, 2.5, 0.3);
        for m in [0.0, 0.3, 0.9, 0.99, 1.4, 2.0] {
            assert_eq!(n.at(m), 0.0, "Mach {m}");
        }
        let t: f64 = 0.16 / 0.3;
        let want = 0.3 * (4.0 / 2.4) * (t * t * t - 2.0 * t * t + t);
        assert!(
            (n.at(1.16) - want).abs() < 1e-12,
            "{} vs {want}",
            n.at(1.16)
        );
        assert!((want - 0.0580741).abs() < 1e-7);
    }

    #[test]
    fn a_secant_ogive_has_the_cone_s_drag_at_its_joint_angle_times_openrocket_s_factor() {
        // OpenRocket's ogive family above Mach 1: the conical formula at the joint's sine,
        // times 0.72 (p − 0.5)² + 0.82: 0.82 at p = 0.5, 0.8362 at p = 0.35. Below Mach 1
        // the same fit toward 0.8 sin²φ at Mach 0.
        let s = 0.11;
        let cone = NosePressureDrag::new(NoseShape::Conical, 3.0, s);
        for (p, mul) in [(0.5, 0.82), (0.35, 0.8362)] {
            let ogive = NosePressureDrag::new(NoseShape::SecantOgive { p }, 3.0, s);
            for m in [1.0, 1.1, 1.3, 1.5, 2.5] {
                let want = mul * cone.at(m);
                assert!((ogive.at(m) - want).abs() < 1e-15, "p {p}, Mach {m}");
            }
            assert!((ogive.at(0.0) - 0.8 * s * s).abs() < 1e-15);
            assert!(ogive.at(0.6) > ogive.at(0.0) && ogive.at(0.6) < cone.at(0.6));
        }
    }

    #[test]
    fn a_von_karman_nose_of_fineness_three_reproduces_the_measured_curve() {
        // At fineness 3 the extrapolation exponent log₄(4) is 1: the data themselves.
        let d = NosePressureDrag::new(NoseShape::Haack { c: 0.0 }, 3.0, 0.0);
        assert!((d.at(1.2) - 0.081).abs() < 1e-12);
        assert!((d.at(1.3) - 0.088).abs() < 1e-12);
        assert_eq!(d.at(0.5), 0.0);
    }

    #[test]
    fn a_finer_nose_has_less_wave_drag() {
        let stubby = NosePressureDrag::new(NoseShape::Haack { c: 0.0 }, 2.0, 0.0);
        let slim = NosePressureDrag::new(NoseShape::Haack { c: 0.0 }, 5.0, 0.0);
        assert!(slim.at(1.5) < stubby.at(1.5));
    }
}
