//! Profiles `r(x)` of nose cones and transitions, and the outer radius of any body component.
//!
//! The mass code integrates these profiles and the aerodynamics code reads them (planform
//! areas, volumes, the body radius under the fins), so both use the same functions. The
//! formulas are the standard ones (as in OpenRocket and the usual nose-cone references):
//!
//! | shape | `r(x)`, `0 <= x <= L`, base radius `R`, `ξ = x/L` |
//! |---|---|
//! | conical | `R ξ` |
//! | tangent ogive | `sqrt(ρ² − (L − x)²) + R − ρ`, `ρ = (R² + L²)/(2R)` (for `L < R` the hemisphere is stretched: `x → x R/L`, `L → R`) |
//! | secant ogive `p` | `sqrt(ρ² − (λ − x)²) − sqrt(ρ² − λ²)`, `λ = L/p`, `ρ² = (L² + R²)((2 − p)² L² + p² R²)/(4 p² R²)` (stretched as the tangent ogive for `L < R`; a cone for `p < 0.001`; OpenRocket's `Transition.Shape.OGIVE`) |
//! | Haack series `c` | `R sqrt((θ − sin 2θ / 2 + c sin³θ)/π)`, `θ = acos(1 − 2ξ)` (`c = 0` von Kármán, `1/3` LV-Haack) |
//! | elliptical | `R sqrt(1 − (1 − ξ)²)` |
//! | power series `k` | `R ξᵏ` |
//! | parabolic series `K'` | `R (2ξ − K' ξ²)/(2 − K')` |
//!
//! A transition from fore radius `r₁` to aft radius `r₂` uses the nose profile of height
//! `|r₂ − r₁|` with its tip at the smaller end, as OpenRocket does (unclipped):
//! `r = r₁ + f(x)` when `r₁ < r₂`, `r = r₂ + f(L − x)` otherwise.

use super::model::{ComponentKind, NoseShape, TransitionShape};
use std::f64::consts::PI;

/// Radius of a nose cone of the given shape, length and base radius at `x_m` aft of its tip.
/// `x_m` is clamped to `[0, length_m]`. Returns 0 for a length or radius that is not
/// positive (or not a number).
pub fn profile_radius(shape: NoseShape, length_m: f64, base_radius_m: f64, x_m: f64) -> f64 {
    if !(length_m > 0.0 && base_radius_m > 0.0) {
        return 0.0;
    }
    let x = x_m.clamp(0.0, length_m);
    let big_r = base_radius_m;
    let xi = x / length_m;
    let r = match shape {
        NoseShape::Conical => big_r * xi,
        NoseShape::SecantOgive { p } if p < 0.001 => big_r * xi,
        NoseShape::Ogive | NoseShape::SecantOgive { .. } => {
            // An ogive shorter than its radius does not exist: stretch one as long as it.
            let (l, x) = if length_m < big_r {
                (big_r, x * big_r / length_m)
            } else {
                (length_m, x)
            };
            match shape {
                NoseShape::SecantOgive { p } => {
                    let (l2, r2, pr) = (l * l, big_r * big_r, p * big_r);
                    let rho2 = (l2 + r2) * ((2.0 - p) * (2.0 - p) * l2 + pr * pr) / (4.0 * pr * pr);
                    let lambda = l / p;
                    let y0 = (rho2 - lambda * lambda).max(0.0).sqrt();
                    let d = lambda - x;
                    (rho2 - d * d).max(0.0).sqrt() - y0
                }
                _ => {
                    let rho = (big_r * big_r + l * l) / (2.0 * big_r);
                    let d = l - x;
                    (rho * rho - d * d).max(0.0).sqrt() + big_r - rho
                }
            }
        }
        NoseShape::Haack { c } => {
            let theta = (1.0 - 2.0 * xi).clamp(-1.0, 1.0).acos();
            let s = theta.sin();
            let arg = (theta - (2.0 * theta).sin() / 2.0 + c * s * s * s) / PI;
            big_r * arg.max(0.0).sqrt()
        }
        NoseShape::Elliptical => {
            let u = 1.0 - xi;
            big_r * (1.0 - u * u).max(0.0).sqrt()
        }
        NoseShape::PowerSeries { k } => big_r * xi.powf(k),
        NoseShape::Parabolic { k } => big_r * (2.0 * xi - k * xi * xi) / (2.0 - k),
    };
    r.clamp(0.0, big_r)
}

/// The nose shape a transition shape uses for its profile.
pub fn transition_nose_shape(shape: TransitionShape) -> NoseShape {
    match shape {
        TransitionShape::Conical => NoseShape::Conical,
        TransitionShape::Ogive => NoseShape::Ogive,
        TransitionShape::SecantOgive { p } => NoseShape::SecantOgive { p },
        TransitionShape::Elliptical => NoseShape::Elliptical,
        TransitionShape::PowerSeries { k } => NoseShape::PowerSeries { k },
        TransitionShape::Haack { c } => NoseShape::Haack { c },
        TransitionShape::Parabolic { k } => NoseShape::Parabolic { k },
    }
}

/// Radius of a transition at `x_m` aft of its fore end (`x_m` clamped to `[0, length_m]`);
/// `clip_m` is its [`clip_length`] (0 for the unclipped profile).
pub fn transition_radius(
    shape: TransitionShape,
    length_m: f64,
    fore_radius_m: f64,
    aft_radius_m: f64,
    clip_m: f64,
    x_m: f64,
) -> f64 {
    tapered_radius(
        transition_nose_shape(shape),
        length_m,
        fore_radius_m,
        aft_radius_m,
        clip_m,
        x_m,
    )
}

/// Radius `x_m` aft of the fore end of a part tapering from `fore_radius_m` to
/// `aft_radius_m` along the nose profile `nose` (`x_m` clamped to the part). Unclipped
/// (`clip_m` 0): the nose profile of height `|r₂ − r₁|` on the smaller radius. Clipped
/// (OpenRocket's): the nose of length `clip_m + L` and the larger radius, from `clip_m` on.
pub fn tapered_radius(
    nose: NoseShape,
    length_m: f64,
    fore_radius_m: f64,
    aft_radius_m: f64,
    clip_m: f64,
    x_m: f64,
) -> f64 {
    let x = x_m.clamp(0.0, length_m.max(0.0));
    if fore_radius_m == aft_radius_m {
        return fore_radius_m;
    }
    // From the small end.
    let (small, big, x) = if fore_radius_m < aft_radius_m {
        (fore_radius_m, aft_radius_m, x)
    } else {
        (aft_radius_m, fore_radius_m, length_m - x)
    };
    if clip_m > 0.0 {
        profile_radius(nose, clip_m + length_m, big, clip_m + x)
    } else {
        small + profile_radius(nose, length_m, big - small, x)
    }
}

/// Whether OpenRocket clips a transition of this profile when told to: the elliptical,
/// power-series and Haack ones (for the others it makes no difference, or too little).
pub fn clippable(nose: NoseShape) -> bool {
    matches!(
        nose,
        NoseShape::Elliptical | NoseShape::PowerSeries { .. } | NoseShape::Haack { .. }
    )
}

/// OpenRocket's clip of a transition from `small` to `big` radius over `length_m`: the
/// length `c` at which the nose profile of length `c + L` and base radius `big` is `small`
/// wide, so that the transition is the rest of that nose. Found as OpenRocket finds it
/// (`Transition.calculateClip`): bracketed by doubling from `L`, then bisected until the
/// bracket is under 0.1 mm, its midpoint taken. 0 for a pointed end or no length.
pub fn clip_length(nose: NoseShape, length_m: f64, small: f64, big: f64) -> f64 {
    const PRECISION_M: f64 = 1e-4;
    let (small, big) = if small <= big {
        (small, big)
    } else {
        (big, small)
    };
    if small == 0.0 || length_m <= 0.0 {
        return 0.0;
    }
    let r = |c: f64| profile_radius(nose, c + length_m, big, c);
    let (mut min, mut max) = (0.0, length_m);
    let mut n = 0;
    while r(max) - small < 0.0 {
        min = max;
        max *= 2.0;
        n += 1;
        if n > 10 {
            break;
        }
    }
    // OpenRocket's loop has no bound; a bracket of finite lengths is under 0.1 mm within
    // about 1,100 halvings, and one that is not (an infinite length) must not hang.
    for _ in 0..1200 {
        let c = (min + max) / 2.0;
        if max - min < PRECISION_M {
            return c;
        }
        if r(c) - small > 0.0 {
            max = c;
        } else {
            min = c;
        }
    }
    (min + max) / 2.0
}

/// Outer radius of a body component (nose cone, body tube, transition) `x_m` aft of its fore
/// end (clamped to the component), or `None` for any other kind. Shoulders are not included.
pub fn body_radius(kind: &ComponentKind, length_m: f64, x_m: f64) -> Option<f64> {
    match kind {
        ComponentKind::NoseCone(n) => Some(profile_radius(
            n.shape,
            length_m,
            n.base_diameter_m / 2.0,
            x_m,
        )),
        ComponentKind::BodyTube(b) => Some(b.outer_diameter_m / 2.0),
        ComponentKind::Transition(t) => Some(transition_radius(
            t.shape,
            length_m,
            t.fore_diameter_m / 2.0,
            t.aft_diameter_m / 2.0,
            t.clip_m,
            x_m,
        )),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: [NoseShape; 9] = [
        NoseShape::Conical,
        NoseShape::Ogive,
        NoseShape::SecantOgive { p: 0.5 },
        NoseShape::Haack { c: 0.0 },
        NoseShape::Haack { c: 1.0 / 3.0 },
        NoseShape::Elliptical,
        NoseShape::PowerSeries { k: 0.5 },
        NoseShape::Parabolic { k: 1.0 },
        NoseShape::Parabolic { k: 0.5 },
    ];

    #[test]
    fn every_nose_profile_starts_at_zero_and_ends_at_the_base_radius() {
        for shape in ALL {
            assert_eq!(profile_radius(shape, 0.3, 0.05, 0.0), 0.0, "{shape:?} tip");
            let base = profile_radius(shape, 0.3, 0.05, 0.3);
            assert!((base - 0.05).abs() <= 1e-15, "{shape:?} base {base}");
        }
    }

    #[test]
    fn a_secant_ogive_is_the_arc_through_tip_and_base_centred_at_the_length_over_p() {
        // OpenRocket's secant ogive of parameter p: a circle through the tip (0, 0) and the
        // base (L, R) whose center is at x = λ = L/p, below the axis by y₀. The two points
        // give λ² + y₀² = ρ² = (λ − L)² + (R + y₀)², so y₀ = (2λL − L² − R²)/(2R).
        // L = 0.3, R = 0.05, p = 0.5: λ = 0.6, y₀ = 0.2675/0.1 = 2.675, ρ² = 7.515625.
        let (l, r, p) = (0.3, 0.05, 0.5);
        let (lambda, y0): (f64, f64) = (0.6, 2.675);
        let rho2 = lambda * lambda + y0 * y0;
        for x in [0.03, 0.15, 0.27] {
            let want = (rho2 - (lambda - x) * (lambda - x)).sqrt() - y0;
            let got = profile_radius(NoseShape::SecantOgive { p }, l, r, x);
            assert!((got - want).abs() < 1e-15, "x {x}: {got} vs {want}");
        }
        // At mid-length, by hand: sqrt(7.515625 − 0.2025) − 2.675 = 0.0292790167.
        let mid = profile_radius(NoseShape::SecantOgive { p }, l, r, 0.15);
        assert!((mid - 0.029_279_016_67).abs() < 1e-11, "{mid}");
        // It meets the body at an angle: the slope at the base is (λ − L)/(R + y₀) = 0.1101.
        let h = 1e-6;
        let slope = (r - profile_radius(NoseShape::SecantOgive { p }, l, r, l - h)) / h;
        assert!((slope - 0.3 / 2.725).abs() < 1e-5, "{slope}");
    }

    #[test]
    fn a_secant_ogive_tends_to_the_tangent_ogive_at_one_and_is_the_cone_below_a_thousandth() {
        let (l, r) = (0.4, 0.05);
        for x in [0.05, 0.2, 0.35] {
            let tangent = profile_radius(NoseShape::Ogive, l, r, x);
            let near = profile_radius(NoseShape::SecantOgive { p: 1.0 - 1e-9 }, l, r, x);
            assert!((near - tangent).abs() < 1e-9, "x {x}: {near} vs {tangent}");
            let cone = profile_radius(NoseShape::Conical, l, r, x);
            let flat = profile_radius(NoseShape::SecantOgive { p: 0.0005 }, l, r, x);
            assert!((flat - cone).abs() < 1e-17, "x {x}: {flat} vs {cone}");
            // Between the two, the profile lies between the cone and the tangent ogive.
            let mid = profile_radius(NoseShape::SecantOgive { p: 0.5 }, l, r, x);
            assert!(cone < mid && mid < tangent, "x {x}: {cone} {mid} {tangent}");
        }
        // Shorter than its radius it is stretched, as the tangent ogive: r(L/2) of a 0.03 m
        // long, 0.05 m radius one is r(R/2) of the one as long as its radius.
        let short = profile_radius(NoseShape::SecantOgive { p: 0.5 }, 0.03, 0.05, 0.015);
        let long = profile_radius(NoseShape::SecantOgive { p: 0.5 }, 0.05, 0.05, 0.025);
        assert_eq!(short, long);
    }

    #[test]
    fn the_profiles_match_their_formulas_at_a_quarter_of_the_length() {
        // L = 0.4, R = 0.05, x = 0.1 (ξ = 1/4); values by hand from the formulas.
        let (l, r, x) = (0.4, 0.05, 0.1);
        let cone = profile_radius(NoseShape::Conical, l, r, x);
        assert!((cone - 0.0125).abs() < 1e-17);
        // Tangent ogive: ρ = (0.0025 + 0.16)/0.1 = 1.625; r = sqrt(1.625² − 0.3²) + 0.05 − 1.625.
        let ogive = profile_radius(NoseShape::Ogive, l, r, x);
        let expect = (1.625f64 * 1.625 - 0.09).sqrt() + 0.05 - 1.625;
        assert!((ogive - expect).abs() < 1e-15, "{ogive} vs {expect}");
        // Elliptical: R sqrt(1 − 0.75²) = 0.05 sqrt(0.4375).
        let ell = profile_radius(NoseShape::Elliptical, l, r, x);
        assert!((ell - 0.05 * 0.4375f64.sqrt()).abs() < 1e-16);
        // Von Kármán: θ = acos(0.5) = π/3; r = R sqrt((π/3 − sin(2π/3)/2)/π).
        let vk = profile_radius(NoseShape::Haack { c: 0.0 }, l, r, x);
        let th = PI / 3.0;
        let expect = 0.05 * ((th - (3.0f64).sqrt() / 4.0) / PI).sqrt();
        assert!((vk - expect).abs() < 1e-15, "{vk} vs {expect}");
        // Power series k = 1/2: R sqrt(1/4) = R/2.
        let p = profile_radius(NoseShape::PowerSeries { k: 0.5 }, l, r, x);
        assert!((p - 0.025).abs() < 1e-17);
        // Parabolic K' = 1: R (1/2 − 1/16)/1 = 0.4375 R.
        let q = profile_radius(NoseShape::Parabolic { k: 1.0 }, l, r, x);
        assert!((q - 0.4375 * 0.05).abs() < 1e-17);
    }

    #[test]
    fn a_tangent_ogive_meets_the_body_with_zero_slope() {
        let (l, r) = (0.25, 0.03);
        let h = 1e-6;
        let slope = (profile_radius(NoseShape::Ogive, l, r, l)
            - profile_radius(NoseShape::Ogive, l, r, l - h))
            / h;
        // The slope of a circle at its tangent point falls as h/ρ: ρ ≈ 1.06, so < 1e-5.
        assert!(slope.abs() < 1e-5, "slope {slope}");
    }

    #[test]
    fn a_transition_puts_the_nose_profile_at_its_smaller_end() {
        let s = TransitionShape::PowerSeries { k: 0.5 };
        // Growing 0.02 -> 0.04 over 0.1: at x = 0.025, r = 0.02 + 0.02 sqrt(0.25) = 0.03.
        assert!((transition_radius(s, 0.1, 0.02, 0.04, 0.0, 0.025) - 0.03).abs() < 1e-17);
        // Shrinking 0.04 -> 0.02: mirror image, at x = 0.075 the same 0.03.
        assert!((transition_radius(s, 0.1, 0.04, 0.02, 0.0, 0.075) - 0.03).abs() < 1e-17);
        assert_eq!(transition_radius(s, 0.1, 0.04, 0.02, 0.0, 0.0), 0.04);
        assert_eq!(transition_radius(s, 0.1, 0.04, 0.02, 0.0, 0.1), 0.02);
    }

    #[test]
    fn a_clipped_transition_is_the_rest_of_the_nose_of_its_larger_radius() {
        // Elliptical, 0.02 -> 0.04 over 0.1: the nose of length c + L reaches 0.02 at c when
        // 0.04 sqrt(1 − (L/(c + L))²) = 0.02, c = L (1/sqrt(3/4) − 1); OpenRocket's
        // bisection stops within 0.05 mm of it.
        let nose = NoseShape::Elliptical;
        let exact = 0.1 * (1.0 / 0.75f64.sqrt() - 1.0);
        let c = clip_length(nose, 0.1, 0.02, 0.04);
        assert!((c - exact).abs() < 5e-5, "{c} vs {exact}");
        assert_eq!(clip_length(nose, 0.1, 0.04, 0.02), c);
        let shape = TransitionShape::Elliptical;
        for x in [0.0, 0.03, 0.07, 0.1] {
            let want = 0.04 * (1.0 - ((0.1 - x) / (c + 0.1)).powi(2)).sqrt();
            let grow = transition_radius(shape, 0.1, 0.02, 0.04, c, x);
            assert!((grow - want).abs() < 1e-16, "{x}: {grow} vs {want}");
            // A boattail is its mirror image.
            let shrink = transition_radius(shape, 0.1, 0.04, 0.02, c, 0.1 - x);
            assert!((shrink - want).abs() < 1e-16);
        }
        // Its ends: the larger radius exactly, the smaller within the clip's precision.
        assert_eq!(transition_radius(shape, 0.1, 0.02, 0.04, c, 0.1), 0.04);
        assert!((transition_radius(shape, 0.1, 0.02, 0.04, c, 0.0) - 0.02).abs() < 1e-4);
        // A pointed end has nothing to clip; only three shapes can be clipped.
        assert_eq!(clip_length(nose, 0.1, 0.0, 0.04), 0.0);
        // Absurd sizes return (the bracket of a length of f64::MAX doubles to infinity).
        let c = clip_length(nose, f64::MAX, 1e-300, f64::MAX);
        assert!(!c.is_nan(), "{c}");
        assert!(clippable(NoseShape::Haack { c: 0.0 }) && !clippable(NoseShape::Ogive));
        assert!(!clippable(NoseShape::Conical) && !clippable(NoseShape::Parabolic { k: 1.0 }));
    }
}
