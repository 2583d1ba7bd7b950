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

/// Smooth skin friction before its compressibility correction, for a Reynolds number `re`
/// on the rocket's length: fully turbulent `1/(1.50 ln R − 5.6)²` (eq. 3.78), and below
/// `R = 10⁴` the value there, 1.48e-2 (OpenRocket's `calculateFrictionCoefficient` for a
/// finish that is not "perfect").
pub fn smooth_cf(re: f64) -> f64 {
    if re < 1.0e4 {
        1.48e-2
    } else {
        turbulent_cf(re)
    }
}

/// Smooth turbulent skin friction `1/(1.50 ln R − 5.6)²` (eq. 3.78).
pub fn turbulent_cf(re: f64) -> f64 {
    1.0 / (1.50 * re.ln() - 5.6).powi(2)
}

/// Roughness-limited skin friction `0.032 (R_s/L)^0.2` (eq. 3.80), before its compressibility
/// correction.
pub fn roughness_limited_cf(relative_roughness: f64) -> f64 {
    0.032 * relative_roughness.powf(0.2)
}

/// `sub` below Mach 0.9, `sup` above 1.1, and between them the two weighted linearly across
/// the band, as OpenRocket joins its subsonic and supersonic corrections.
fn across_mach_one(mach: f64, sub: f64, sup: f64) -> f64 {
    if mach < 0.9 {
        sub
    } else if mach < 1.1 {
        sup * (mach - 0.9) / 0.2 + sub * (1.1 - mach) / 0.2
    } else {
        sup
    }
}

/// Compressibility factor of the smooth skin friction: `1 − 0.1 M²` subsonic (eq. 3.82),
/// `(1 + 0.15 M²)^−0.58` supersonic (eq. 3.83), both taken at `M` and blended over Mach
/// 0.9–1.1.
pub fn turbulent_compressibility(mach: f64) -> f64 {
    let m2 = mach * mach;
    across_mach_one(mach, 1.0 - 0.1 * m2, (1.0 + 0.15 * m2).powf(-0.58))
}

/// Compressibility factor of the roughness-limited skin friction: `1 − 0.1 M²` subsonic,
/// `1/(1 + 0.18 M²)` supersonic (eq. 3.84), and over Mach 0.9–1.1 a straight line between
/// their values at 0.9 and 1.1 (OpenRocket's `calculateRoughnessCorrection`).
pub fn roughness_compressibility(mach: f64) -> f64 {
    if mach < 0.9 {
        1.0 - 0.1 * mach * mach
    } else if mach > 1.1 {
        1.0 / (1.0 + 0.18 * mach * mach)
    } else {
        across_mach_one(mach, 1.0 - 0.1 * 0.81, 1.0 / (1.0 + 0.18 * 1.21))
    }
}

/// Skin-friction coefficient on the wetted area: the larger of the smooth and the
/// roughness-limited values, each with its compressibility correction (OpenRocket's
/// `calculateFrictionCD`: "actual Cf is maximum of Cf and the roughness-limited value"; the
/// thesis' critical Reynolds number `51 (R_s/L)^−1.039` is not used). `relative_roughness` is
/// `R_s/L`, `re` on the rocket's length.
pub fn skin_friction(re: f64, mach: f64, relative_roughness: f64) -> f64 {
    let smooth = smooth_cf(re) * turbulent_compressibility(mach);
    let rough = roughness_limited_cf(relative_roughness) * roughness_compressibility(mach);
    smooth.max(rough)
}

/// Stagnation-pressure drag of a blunt cylinder face, per own area: `0.85 q_stag/q` with
/// `q_stag/q = 1 + M²/4 + M⁴/40` (M ≤ 1) or `1.84 − 0.76/M² + 0.166/M⁴ + 0.035/M⁶` (eqs. B.1, B.2).
pub fn stagnation_cd(mach: f64) -> f64 {
    let m2 = mach * mach;
    let q = if mach <= 1.0 {
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

/// Drag of a launch lug (a tube along the body) per `A_ref`, as OpenRocket's `TubeCalc`:
/// the bore's pipe friction `f (l/d_i)` on the bore's area, with the Darcy friction factor of
/// the Swamee–Jain equation `f = 0.25 / log10(ε/(3.7 d_i) + 5.74/Re^0.9)²` (`Re = v d_i/ν`,
/// `ε` the surface roughness), plus `0.7 (C_D,stag + C_D,base)` on the wall's ring. A lug
/// without a bore is the ring alone. `reynolds_per_m` is `v/ν`.
pub fn launch_lug_cd(
    mach: f64,
    reynolds_per_m: f64,
    roughness_m: f64,
    length_m: f64,
    outer_diameter_m: f64,
    inner_diameter_m: f64,
    ref_area_m2: f64,
) -> f64 {
    use std::f64::consts::PI;
    let inner_area = PI * inner_diameter_m * inner_diameter_m / 4.0;
    let ring = PI * outer_diameter_m * outer_diameter_m / 4.0 - inner_area;
    let bore = if inner_diameter_m > 0.0 {
        let re = reynolds_per_m * inner_diameter_m;
        let f = 0.25
            / (roughness_m / (3.7 * inner_diameter_m) + 5.74 / re.powf(0.9))
                .log10()
                .powi(2);
        f * length_m / inner_diameter_m * inner_area
    } else {
        0.0
    };
    (bore + 0.7 * (stagnation_cd(mach) + base_cd(mach)) * ring) / ref_area_m2
}

/// The drag coefficients OpenRocket's `RailButtonCalc` reads for a circular cylinder across
/// the flow against the Mach number of the air it meets (Gowen and Perkins, NACA TN 2960,
/// fig. 7): (Mach, C_D) corners, linear between them.
const CYLINDER_CD: [(f64, f64); 12] = [
    (0.0, 1.2),
    (0.2, 1.22),
    (0.3, 1.25),
    (0.4, 1.3),
    (0.5, 1.4),
    (0.6, 1.5),
    (0.7, 1.6),
    (1.0, 2.1),
    (1.6, 1.5),
    (2.0, 1.45),
    (2.8, 1.33),
    (100.0, 1.33),
];

/// [`CYLINDER_CD`] at `mach`, linear between its corners (and its end values beyond them).
fn cylinder_cd(mach: f64) -> f64 {
    let (first, last) = (CYLINDER_CD[0], CYLINDER_CD[CYLINDER_CD.len() - 1]);
    if mach <= first.0 {
        return first.1;
    }
    for w in CYLINDER_CD.windows(2) {
        let ((m0, c0), (m1, c1)) = (w[0], w[1]);
        if mach <= m1 {
            return c0 + (c1 - c0) * (mach - m0) / (m1 - m0);
        }
    }
    last.1
}

/// Drag of a rail button per `A_ref`, as OpenRocket's `RailButtonCalc`: a cylinder of height
/// `h` and diameter `D` standing in the body's boundary layer, whose thickness where the
/// button stands, `x` aft of the tip, is `δ = 0.37 x / Re_x^0.2`. The air crossing the button
/// is taken to move at its mean speed over the height: `M_b = M (h − δ/2)/h` if the button
/// stands out of the layer, `M h/(2δ)` inside it. The button's drag is then the cylinder's
/// `C_D(M_b)` at that speed, `C_D(M_b) (M_b/M)²` at the rocket's, times the stagnation
/// pressure's factor, on the frontal area `D h`. `reynolds_per_m` is `v/ν`.
pub fn rail_button_cd(
    mach: f64,
    reynolds_per_m: f64,
    station_m: f64,
    outer_diameter_m: f64,
    height_m: f64,
    ref_area_m2: f64,
) -> f64 {
    let x = station_m.max(1e-6);
    let delta = 0.37 * x / (reynolds_per_m * x).powf(0.2);
    let h = height_m;
    // M_b / M.
    let ratio = if h > delta {
        (h - 0.5 * delta) / h
    } else {
        h / 2.0 / delta
    };
    cylinder_cd(ratio * mach) * ratio * ratio * stagnation_cd(mach) * outer_diameter_m * h
        / ref_area_m2
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
        let cf = smooth_cf(1.0e6);
        assert!((cf - 0.0043722887).abs() < 1e-10, "{cf}");
    }

    #[test]
    fn skin_friction_below_ten_thousand_is_the_value_at_ten_thousand() {
        assert_eq!(smooth_cf(5.0e3), 1.48e-2);
        assert!((turbulent_cf(1.0e4) - 1.48e-2).abs() < 1e-4);
    }

    #[test]
    fn skin_friction_is_the_larger_of_the_smooth_and_the_roughness_limited_values() {
        // R_s/L = 1e-5: 0.032 · 1e-5^0.2 = 0.0032. At Re 7e6 the smooth value is
        // 1/(1.5 ln 7e6 − 5.6)² = 0.0030720, so the rough one stands, as in OpenRocket (the
        // thesis' critical Reynolds number, 51 · 1e5^1.039 = 7.99e6, would have kept 0.0030720).
        let rel = 1e-5;
        assert!((roughness_limited_cf(rel) - 0.0032).abs() < 1e-15);
        assert!((skin_friction(7.0e6, 0.0, rel) - 0.0032).abs() < 1e-15);
        assert!((turbulent_cf(7.0e6) - 0.0030720221).abs() < 1e-10);
        // At Re 1e6 the smooth 0.0043722887 is the larger.
        assert!((skin_friction(1.0e6, 0.0, rel) - 0.0043722887).abs() < 1e-10);
    }

    #[test]
    fn the_compressibility_corrections_are_blended_across_mach_point_nine_to_one_point_one() {
        // Smooth, at M 1: halfway between 1 − 0.1 = 0.9 and 1.15^−0.58 = 0.9221366: 0.9110683.
        assert!((turbulent_compressibility(1.0) - 0.9110682925).abs() < 1e-10);
        // Rough, at M 1: halfway between its values at 0.9 (0.919) and 1.1 (1/1.2178).
        assert!((roughness_compressibility(1.0) - 0.8700764493).abs() < 1e-10);
        // Continuous at both ends of the band.
        for f in [turbulent_compressibility, roughness_compressibility] {
            for m in [0.9, 1.1] {
                let (below, above) = (f(m - 1e-12), f(m + 1e-12));
                assert!((below - above).abs() < 1e-10, "{m}: {below} {above}");
            }
        }
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
    fn a_launch_lug_is_its_bores_pipe_friction_and_its_rings_stagnation_and_base_drag() {
        // A 5/16" lug 50 mm long with a 1/4" bore on a 54 mm rocket, at Mach 0.3 at sea level
        // (v/ν = 6.988826e6 /m), 60 µm finish, by hand: Re_d = 44728.48, Swamee–Jain
        // f = 0.25/log10(60e-6/(3.7 · 0.0064) + 5.74/Re_d^0.9)² = 0.0388610; bore
        // f (0.05/0.0064) π 0.0032², ring 0.7 (C_stag + C_base) π (0.00395² − 0.0032²), over
        // π 0.027²: 0.0094188954.
        let a_ref = std::f64::consts::PI * 0.027 * 0.027;
        let cd = launch_lug_cd(0.3, 6.988825584e6, 60e-6, 0.05, 0.0079, 0.0064, a_ref);
        assert!((cd - 0.0094188954).abs() < 1e-9, "{cd}");
        // Without a bore, the ring alone (here the whole face).
        let solid = launch_lug_cd(0.3, 6.988825584e6, 60e-6, 0.05, 0.0079, 0.0, a_ref);
        let want =
            0.7 * (stagnation_cd(0.3) + base_cd(0.3)) * std::f64::consts::PI * 0.00395f64.powi(2)
                / a_ref;
        assert!((solid - want).abs() < 1e-15, "{solid} vs {want}");
    }

    #[test]
    fn a_rail_button_inside_the_boundary_layer_meets_a_quarter_of_the_speed() {
        // A 10 mm × 8 mm button 1 m aft of the tip at Mach 0.3 at sea level: Re_x = 6.988826e6,
        // δ = 0.37/Re_x^0.2 = 0.0158242 m > h, so the air crossing it moves at
        // h/(2δ) = 0.2527779 of the rocket's speed; the cylinder's C_D there (Mach 0.0758) is
        // 1.2075833, and the button's 1.2075833 · 0.2527779² · C_stag(0.3) · 0.01 · 0.008 / A_ref
        // = 0.0023430209 on a 54 mm rocket (a lug of the button's area had counted 0.0303655).
        let a_ref = std::f64::consts::PI * 0.027 * 0.027;
        let cd = rail_button_cd(0.3, 6.988825584e6, 1.0, 0.01, 0.008, a_ref);
        assert!((cd - 0.0023430209).abs() < 1e-10, "{cd}");
        // A button standing out of a thin layer meets the speed less half the layer's share.
        let tall = rail_button_cd(0.3, 6.988825584e6, 1.0, 0.01, 0.05, a_ref);
        let delta = 0.37 / 6.988825584e6f64.powf(0.2);
        assert!((delta - 0.0158241679).abs() < 1e-10);
        let ratio = (0.05 - 0.5 * delta) / 0.05;
        // (Mach 0.2527: between the table's corners at 0.2 and 0.3.)
        let cyl = 1.22 + 0.03 * (ratio * 0.3 - 0.2) / 0.1;
        let want = cyl * ratio * ratio * stagnation_cd(0.3) * 0.01 * 0.05 / a_ref;
        assert!((tall - want).abs() < 1e-9 * want, "{tall} vs {want}");
        // The cylinder's table between its corners.
        assert!((cylinder_cd(0.85) - 1.85).abs() < 1e-12);
        assert_eq!(cylinder_cd(200.0), 1.33);
    }
}
