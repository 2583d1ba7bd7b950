//! The individual drag formulas of OpenRocket's method (S. Niskanen, *Development of an Open
//! Source model rocket simulation software*, M.Sc. thesis, Helsinki University of Technology,
//! 2009, §3.4 and appendix B; equation numbers are the thesis'), each a pure function of the
//! Mach number (and Reynolds number for skin friction). [`super::drag_estimate`] sums them
//! over a design.
//!
//! Coefficients marked "per own area" are referenced to the area of the part that causes
//! them (the thesis' `C_D•`), and are scaled by `A_part/A_ref` when summed.

use crate::design::FinCrossSection;

/// Ratio of specific heats of air.
pub const GAMMA_AIR: f64 = 1.4;

/// Which branch of the skin-friction formula applies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrictionRegime {
    /// `R < 10⁴`: the value at `R = 10⁴`, 1.48e-2.
    LowReynolds,
    /// Fully turbulent, smooth: `1/(1.50 ln R − 5.6)²` (eq. 3.78).
    Turbulent,
    /// Above the roughness-critical Reynolds number `51 (R_s/L)^−1.039` (eq. 3.79):
    /// `0.032 (R_s/L)^0.2` (eq. 3.80).
    RoughnessLimited,
}

/// Incompressible skin-friction coefficient on the wetted area, for a Reynolds number `re`
/// (on the rocket's length `L`) and relative roughness `R_s/L`, with the branch used.
pub fn skin_friction_incompressible(re: f64, relative_roughness: f64) -> (f64, FrictionRegime) {
    let re_crit = 51.0 * relative_roughness.powf(-1.039);
    if re < 1.0e4 {
        (1.48e-2, FrictionRegime::LowReynolds)
    } else if re < re_crit {
        (turbulent_cf(re), FrictionRegime::Turbulent)
    } else {
        (
            0.032 * relative_roughness.powf(0.2),
            FrictionRegime::RoughnessLimited,
        )
    }
}

/// Smooth turbulent skin friction `1/(1.50 ln R − 5.6)²` (eq. 3.78).
pub fn turbulent_cf(re: f64) -> f64 {
    1.0 / (1.50 * re.ln() - 5.6).powi(2)
}

/// Compressibility factor of the turbulent (and low-Reynolds) skin friction: `1 − 0.1 M²`
/// subsonic (eq. 3.82), `(1 + 0.15 M²)^−0.58` supersonic (eq. 3.83).
pub fn turbulent_compressibility(mach: f64) -> f64 {
    if mach < 1.0 {
        1.0 - 0.1 * mach * mach
    } else {
        (1.0 + 0.15 * mach * mach).powf(-0.58)
    }
}

/// Compressibility factor of the roughness-limited skin friction: `1 − 0.1 M²` subsonic,
/// `1/(1 + 0.18 M²)` supersonic (eq. 3.84).
pub fn roughness_compressibility(mach: f64) -> f64 {
    if mach < 1.0 {
        1.0 - 0.1 * mach * mach
    } else {
        1.0 / (1.0 + 0.18 * mach * mach)
    }
}

/// Skin-friction coefficient with the compressibility corrections; a corrected
/// roughness-limited value below the corrected turbulent one is replaced by the latter (§3.4.2).
pub fn skin_friction(re: f64, mach: f64, relative_roughness: f64) -> f64 {
    let (cf, regime) = skin_friction_incompressible(re, relative_roughness);
    match regime {
        FrictionRegime::LowReynolds | FrictionRegime::Turbulent => {
            cf * turbulent_compressibility(mach)
        }
        FrictionRegime::RoughnessLimited => {
            let rough = cf * roughness_compressibility(mach);
            let smooth = turbulent_cf(re) * turbulent_compressibility(mach);
            rough.max(smooth)
        }
    }
}

/// Stagnation-pressure drag of a blunt cylinder face, per own area: `0.85 q_stag/q` with
/// `q_stag/q = 1 + M²/4 + M⁴/40` (M < 1) or `1.84 − 0.76/M² + 0.166/M⁴ + 0.035/M⁶` (eqs. B.1, B.2).
pub fn stagnation_cd(mach: f64) -> f64 {
    let m2 = mach * mach;
    let q = if mach < 1.0 {
        1.0 + m2 / 4.0 + m2 * m2 / 40.0
    } else {
        1.84 - 0.76 / m2 + 0.166 / (m2 * m2) + 0.035 / (m2 * m2 * m2)
    };
    0.85 * q
}

/// Base drag per base area: `0.12 + 0.13 M²` (M < 1), `0.25/M` (M ≥ 1) (eq. 3.94).
pub fn base_cd(mach: f64) -> f64 {
    if mach < 1.0 {
        0.12 + 0.13 * mach * mach
    } else {
        0.25 / mach
    }
}

/// Pressure drag of a rounded leading edge perpendicular to the flow, per frontal area
/// (eq. 3.89): `(1 − M²)^−0.417 − 1` (M < 0.9), `1 − 1.785 (M − 0.9)` (0.9 ≤ M < 1),
/// `1.214 − 0.502/M² + 0.1095/M⁴` (M ≥ 1). (The middle piece is written as in the thesis; it
/// joins the outer two continuously at 0.9 and 1.)
pub fn rounded_leading_edge_cd(mach: f64) -> f64 {
    if mach < 0.9 {
        (1.0 - mach * mach).powf(-0.417) - 1.0
    } else if mach < 1.0 {
        1.0 - 1.785 * (mach - 0.9)
    } else {
        let m2 = mach * mach;
        1.214 - 0.502 / m2 + 0.1095 / (m2 * m2)
    }
}

/// Fin pressure drag per fin frontal area `t s` (eqs. 3.89–3.93): leading edge
/// (stagnation for a square profile, the rounded-edge formula for rounded and airfoil
/// profiles) times `cos² Γ_L`, plus trailing edge (base drag for square, half of it for
/// rounded, none for an airfoil's tapered trailing edge).
pub fn fin_pressure_cd(
    mach: f64,
    cross_section: FinCrossSection,
    leading_edge_sweep_rad: f64,
) -> f64 {
    let le_perp = match cross_section {
        FinCrossSection::Square => stagnation_cd(mach),
        FinCrossSection::Rounded | FinCrossSection::Airfoil => rounded_leading_edge_cd(mach),
    };
    let te = match cross_section {
        FinCrossSection::Square => base_cd(mach),
        FinCrossSection::Rounded => base_cd(mach) / 2.0,
        FinCrossSection::Airfoil => 0.0,
    };
    le_perp * leading_edge_sweep_rad.cos().powi(2) + te
}

/// Pressure drag of a launch guide of length `l` and outer diameter `d` per its reference
/// area [`launch_guide_area_m2`]: `max(1.3 − 0.3 l/d, 1) · C_D,stag` (eq. 3.95).
pub fn launch_guide_cd(mach: f64, length_m: f64, outer_diameter_m: f64) -> f64 {
    (1.3 - 0.3 * length_m / outer_diameter_m).max(1.0) * stagnation_cd(mach)
}

/// Reference area of a launch guide: `π r_ext² − π r_int² max(1 − l/d, 0)` (eq. 3.96).
pub fn launch_guide_area_m2(length_m: f64, outer_diameter_m: f64, inner_diameter_m: f64) -> f64 {
    let (re, ri) = (outer_diameter_m / 2.0, inner_diameter_m / 2.0);
    std::f64::consts::PI * (re * re - ri * ri * (1.0 - length_m / outer_diameter_m).max(0.0))
}

/// Boattail pressure drag per its frontal area `π (r_fore² − r_aft²)` (eq. 3.88): the base
/// drag times 1 for `γ = L/(d_fore − d_aft) < 1`, `(3 − γ)/2` for `1 ≤ γ ≤ 3`, 0 above.
pub fn boattail_cd(mach: f64, length_to_height: f64) -> f64 {
    let g = length_to_height;
    let f = if g < 1.0 {
        1.0
    } else if g <= 3.0 {
        (3.0 - g) / 2.0
    } else {
        0.0
    };
    base_cd(mach) * f
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turbulent_skin_friction_at_a_million_matches_the_formula_by_hand() {
        // 1.5 ln(1e6) − 5.6 = 1.5 · 13.815510558 − 5.6 = 15.123265837; 1/that² = 0.0043722887
        let (cf, regime) = skin_friction_incompressible(1.0e6, 1e-7);
        assert_eq!(regime, FrictionRegime::Turbulent);
        assert!((cf - 0.0043722887).abs() < 1e-10, "{cf}");
    }

    #[test]
    fn skin_friction_below_ten_thousand_is_the_value_at_ten_thousand() {
        let (cf, regime) = skin_friction_incompressible(5.0e3, 1e-5);
        assert_eq!(regime, FrictionRegime::LowReynolds);
        assert_eq!(cf, 1.48e-2);
        assert!((turbulent_cf(1.0e4) - 1.48e-2).abs() < 1e-4);
    }

    #[test]
    fn rough_skin_friction_is_capped_by_roughness_above_the_critical_reynolds_number() {
        // R_s/L = 20e-6/2 = 1e-5: R_crit = 51 · 1e5^1.039 = 7.9904e6;
        // C_f = 0.032 · 1e-5^0.2 = 0.032 · 0.1 = 0.0032.
        let rel = 1e-5;
        let (cf, regime) = skin_friction_incompressible(1.0e7, rel);
        assert_eq!(regime, FrictionRegime::RoughnessLimited);
        assert!((cf - 0.0032).abs() < 1e-12);
        let (_, below) = skin_friction_incompressible(7.0e6, rel);
        assert_eq!(below, FrictionRegime::Turbulent);
    }

    #[test]
    fn compressibility_reduces_skin_friction_by_the_thesis_factors() {
        // M = 0.5 turbulent: × (1 − 0.025) = 0.975
        let smooth = skin_friction(1.0e6, 0.5, 1e-9);
        assert!((smooth - 0.0043722887 * 0.975).abs() < 1e-10);
        // M = 2 rough (Re 1e8, R_s/L 1e-5): 0.0032/(1 + 0.72) = 0.0018605;
        // turbulent at 1e8: 1/(1.5 · 18.420681 − 5.6)² = 0.0020603 × 1.6^−0.58 = 0.0015687,
        // smaller, so the rough value stands.
        let rough = skin_friction(1.0e8, 2.0, 1e-5);
        assert!((rough - 0.0032 / 1.72).abs() < 1e-9, "{rough}");
    }

    #[test]
    fn stagnation_and_base_drag_match_their_formulas_at_hand_picked_mach_numbers() {
        // M 0.5: 0.85 (1 + 0.0625 + 0.0015625) = 0.9045781
        assert!((stagnation_cd(0.5) - 0.85 * 1.0640625).abs() < 1e-15);
        // M 2: 0.85 (1.84 − 0.19 + 0.010375 + 0.000546875) = 1.4117836
        assert!((stagnation_cd(2.0) - 0.85 * 1.660921875).abs() < 1e-14);
        assert!((base_cd(0.5) - 0.1525).abs() < 1e-15);
        assert!((base_cd(2.0) - 0.125).abs() < 1e-15);
    }

    #[test]
    fn the_rounded_leading_edge_drag_is_continuous_across_its_three_pieces() {
        let below = rounded_leading_edge_cd(0.9 - 1e-9);
        let at = rounded_leading_edge_cd(0.9);
        assert!((below - at).abs() < 2e-3, "{below} {at}");
        let sub = rounded_leading_edge_cd(1.0 - 1e-12);
        let sup = rounded_leading_edge_cd(1.0);
        assert!((sub - sup).abs() < 1e-9, "{sub} {sup}");
        // M 0.5: 0.75^−0.417 − 1 = 0.1274556
        assert!((rounded_leading_edge_cd(0.5) - (0.75f64.powf(-0.417) - 1.0)).abs() < 1e-15);
        assert!((rounded_leading_edge_cd(0.5) - 0.1274556).abs() < 1e-7);
    }

    #[test]
    fn an_airfoil_fin_has_no_trailing_edge_drag_and_a_square_one_the_full_base_drag() {
        let sweep = 0.5f64;
        let airfoil = fin_pressure_cd(0.3, FinCrossSection::Airfoil, sweep);
        assert!((airfoil - rounded_leading_edge_cd(0.3) * sweep.cos().powi(2)).abs() < 1e-15);
        let square = fin_pressure_cd(0.3, FinCrossSection::Square, 0.0);
        assert!((square - (stagnation_cd(0.3) + base_cd(0.3))).abs() < 1e-15);
        let rounded = fin_pressure_cd(0.3, FinCrossSection::Rounded, 0.0);
        assert!((rounded - (rounded_leading_edge_cd(0.3) + base_cd(0.3) / 2.0)).abs() < 1e-15);
    }

    #[test]
    fn a_boattail_drag_fades_from_full_base_drag_at_ratio_one_to_none_at_three() {
        assert_eq!(boattail_cd(0.5, 0.5), base_cd(0.5));
        assert!((boattail_cd(0.5, 2.0) - base_cd(0.5) / 2.0).abs() < 1e-15);
        assert_eq!(boattail_cd(0.5, 3.5), 0.0);
    }

    #[test]
    fn a_long_launch_lug_counts_its_bore_and_the_stagnation_drag() {
        // l/d = 2: factor max(0.7, 1) = 1, area = π r_ext² (bore closed off).
        let a = launch_guide_area_m2(0.02, 0.01, 0.008);
        assert!((a - std::f64::consts::PI * 0.005 * 0.005).abs() < 1e-18);
        assert_eq!(launch_guide_cd(0.3, 0.02, 0.01), stagnation_cd(0.3));
        // l = 0: factor 1.3, area is the ring only.
        let ring = launch_guide_area_m2(0.0, 0.01, 0.008);
        assert!(
            (ring - std::f64::consts::PI * (0.005f64.powi(2) - 0.004f64.powi(2))).abs() < 1e-18
        );
        assert!((launch_guide_cd(0.3, 0.0, 0.01) - 1.3 * stagnation_cd(0.3)).abs() < 1e-15);
    }
}
