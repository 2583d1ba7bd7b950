//! Zero-lift drag coefficient against Mach estimated from the geometry, for designs that give
//! no drag curves: OpenRocket's method (S. Niskanen, *Development of an Open Source model
//! rocket simulation software*, 2009, §3.4) as OpenRocket's code computes it
//! (`BarrowmanCalculator`, `SymmetricComponentCalc`, `FinSetCalc`, `TubeCalc`,
//! `RailButtonCalc`), where that differs from the thesis, referenced to the area of the
//! reference diameter.
//!
//! `C_D(M) = C_D,friction + Σ (A_part/A_ref) C_D•,part`, summing (formulas in
//! [`super::drag_formulas`] and [`super::nose_drag`]):
//! - skin friction: `C_f [(1 + 1/(2 f_B)) A_wet,body + (1 + 2t/c̄) A_wet,fins]/A_ref`, with
//!   `C_f` the larger of the smooth turbulent and the roughness-limited coefficients, each with
//!   its compressibility correction (blended over Mach 0.9–1.1), `f_B` the body's length over
//!   its largest *radius* (OpenRocket's code; the thesis writes the diameter), `t` the fin
//!   thickness, `c̄` the mean aerodynamic chord, and `A_wet,fins` both sides of every fin;
//! - nose and shoulder pressure drag on `π (r_aft² − r_fore²)` (a tangent ogive has none
//!   below Mach 1: it meets the body at no angle); boattail pressure drag on
//!   `π (r_fore² − r_aft²)`;
//! - stagnation drag on every step up in radius between body components (and a blunt fore
//!   end), base drag (eq. 3.94) on every step down and on the aft end;
//! - fin pressure drag (leading and trailing edge by cross-section) on `N t s`;
//! - launch lugs: the bore's pipe friction (Swamee–Jain) and `0.7 (C_stag + C_base)` on the
//!   wall's ring; rail buttons: a cylinder standing in the boundary layer, meeting the air at
//!   its mean speed over its height (its drag a few per cent of the thesis' lug of the same
//!   frontal area).
//!
//! **Power on.** OpenRocket flies the same coefficient with the motor burning (its base drag
//! is not reduced for the exhaust), and so does the estimate: `power_on` is `power_off`. A
//! team with a power-on curve (RASAero's, a wind tunnel's) gives the curves instead.
//!
//! **Air properties.** The skin friction (and a launch lug's bore and a rail button's
//! boundary layer) depend on the Reynolds number, which OpenRocket takes from the flight's
//! airspeed and the air where it flies. The estimate is tabulated against Mach and the
//! Reynolds number's scale `k`, the flight's Reynolds number over that of the International
//! Standard Atmosphere at sea level at the same Mach (`Re/L = k M a₀/ν₀`, `a₀ = 340.294 m/s`,
//! `ν₀ = μ₀/ρ₀ = 1.7894e-5/1.225 = 1.46073e-5 m²/s`, on the rocket's length `L`): eleven
//! Mach tables at `ln k` = −4.5, −4, ..., 0.5 ([`ReynoldsTables`]), which the flight reads at
//! the `k` of the air around it (`(a/a₀)(ν₀/ν)`, Sutherland's viscosity). `power_off` is
//! the table at `k = 1`, sea level's. (The Mach-0 row, a rocket at rest, takes the Reynolds
//! number of the Mach-0.01 row so that the table does not jump to the `R < 10⁴` value.) With
//! the default 60 µm finish the friction of a high-power rocket is roughness-limited above
//! about 12 m/s, where the Reynolds number does not enter; a polished skin's friction rises
//! a few per cent with altitude.
//!
//! Not modelled: OpenRocket's "perfect finish" (partly laminar) friction, fin–body
//! interference drag, fin-tip vortices, the angle of attack (OpenRocket multiplies the axial
//! coefficient by up to 1.3 at 17°; the flight, as RocketPy's, reads the table as it is),
//! and the nozzle's own base drag.

use super::drag_formulas::{
    base_cd, boattail_cd, fin_pressure_cd, launch_lug_cd, rail_button_cd, skin_friction,
    stagnation_cd,
};
use super::fins::Fins;
use super::nose_drag::NosePressureDrag;
use super::profile::Section;
use super::table::{MachTable, ReynoldsTables};
use crate::design::{ComponentKind, Design, FinCrossSection};
use std::f64::consts::PI;

/// Sea-level speed of sound of the ISA, m/s.
pub const SEA_LEVEL_SPEED_OF_SOUND_M_S: f64 = 340.294;
/// Sea-level kinematic viscosity of the ISA, m²/s (`1.7894e-5 Pa·s / 1.225 kg/m³`).
pub const SEA_LEVEL_KINEMATIC_VISCOSITY_M2_S: f64 = 1.7894e-5 / 1.225;

/// The table of [`ReynoldsTables`] at `k = 1` (`ln k = 0`): sea-level standard air.
const SEA_LEVEL_TABLE: usize = 9;

/// Reynolds number per metre at `mach` in sea-level standard air.
pub fn reynolds_per_metre(mach: f64) -> f64 {
    mach * SEA_LEVEL_SPEED_OF_SOUND_M_S / SEA_LEVEL_KINEMATIC_VISCOSITY_M2_S
}

/// The estimate's inputs, taken from a design.
#[derive(Debug, Clone)]
pub struct DragGeometry {
    pub ref_area_m2: f64,
    pub length_m: f64,
    pub ref_diameter_m: f64,
    /// The default surface roughness (of the skins that give none, and of launch lugs), m.
    pub roughness_m: f64,
    /// Body sections fore to aft.
    pub sections: Vec<Section>,
    /// Each section's own surface roughness, m, in the order of `sections`; `None` (or no
    /// entry) is `roughness_m`.
    pub section_roughness_m: Vec<Option<f64>>,
    pub fins: Vec<FinDrag>,
    /// Launch guides.
    pub guides: Vec<Guide>,
}

/// What drag needs of a launch guide.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Guide {
    /// A launch lug: length, outer and inner (bore) diameter, m.
    Lug {
        length_m: f64,
        outer_diameter_m: f64,
        inner_diameter_m: f64,
    },
    /// A rail button: its center's station aft of the tip, its diameter and height, m.
    Button {
        station_m: f64,
        outer_diameter_m: f64,
        height_m: f64,
    },
}

/// What drag needs of a fin set.
#[derive(Debug, Clone, Copy)]
pub struct FinDrag {
    pub count: u32,
    pub area_m2: f64,
    pub span_m: f64,
    pub thickness_m: f64,
    pub mac_m: f64,
    pub leading_edge_sweep_rad: f64,
    pub cross_section: FinCrossSection,
    /// The fins' own surface roughness, m; `None` is the estimate's.
    pub roughness_m: Option<f64>,
}

/// Power-off and power-on `C_D(M)` tables in sea-level standard air, and `C_D` against Mach
/// and the Reynolds number's scale (the flight's Reynolds number over sea level's at the same
/// Mach), for the flight to read where it flies.
#[derive(Debug, Clone)]
pub struct DragEstimate {
    pub power_off: MachTable,
    pub power_on: MachTable,
    /// `C_D(M, k)`, power off and on alike; its table at `k = 1` is `power_off`.
    pub reynolds: ReynoldsTables,
}

impl DragGeometry {
    /// Collects the geometry of `design` (body components sorted fore to aft).
    pub fn from_design(design: &Design, roughness_m: f64) -> Self {
        let d = design.reference_diameter_m;
        let mut bodies: Vec<(f64, Section, Option<f64>)> = Vec::new();
        let mut fins = Vec::new();
        let mut guides = Vec::new();
        for c in &design.components {
            match &c.kind {
                ComponentKind::NoseCone(n) => bodies.push((
                    c.x_top_m,
                    Section::nose(n.shape, c.length_m, n.base_diameter_m / 2.0),
                    c.roughness_m,
                )),
                ComponentKind::BodyTube(t) => bodies.push((
                    c.x_top_m,
                    Section::tube(c.length_m, t.outer_diameter_m / 2.0),
                    c.roughness_m,
                )),
                ComponentKind::Transition(t) => {
                    bodies.push((c.x_top_m, Section::transition(c.length_m, t), c.roughness_m))
                }
                ComponentKind::FinSet(f) => {
                    let g = Fins::of(f).geometry();
                    fins.push(FinDrag {
                        count: f.count,
                        area_m2: g.area_m2,
                        span_m: f.span_m,
                        thickness_m: f.thickness_m,
                        mac_m: g.mac_length_m,
                        leading_edge_sweep_rad: g.leading_edge_sweep_rad,
                        cross_section: f.cross_section,
                        roughness_m: c.roughness_m,
                    })
                }
                ComponentKind::LaunchLug(l) => guides.push(Guide::Lug {
                    length_m: c.length_m,
                    outer_diameter_m: l.outer_diameter_m,
                    inner_diameter_m: l.outer_diameter_m - 2.0 * l.wall_thickness_m,
                }),
                // Its length along the axis is its diameter.
                ComponentKind::RailButton(b) => guides.push(Guide::Button {
                    station_m: c.x_top_m + b.outer_diameter_m / 2.0,
                    outer_diameter_m: b.outer_diameter_m,
                    height_m: b.height_m,
                }),
                _ => {}
            }
        }
        bodies.sort_by(|a, b| a.0.total_cmp(&b.0));
        DragGeometry {
            ref_area_m2: PI * d * d / 4.0,
            length_m: design.length_m,
            ref_diameter_m: d,
            roughness_m,
            section_roughness_m: bodies.iter().map(|b| b.2).collect(),
            sections: bodies.into_iter().map(|b| b.1).collect(),
            fins,
            guides,
        }
    }

    /// Builds the power-off and power-on tables (the same: OpenRocket keeps the base drag
    /// with the motor burning).
    pub fn estimate(&self) -> DragEstimate {
        let a_ref = self.ref_area_m2;
        // OpenRocket's body fineness: the body's length (plus 0.1 mm) over its largest
        // *radius* (the thesis writes L/d; the code, which its users fly, L/r).
        let max_r = self
            .sections
            .iter()
            .map(|s| s.fore_radius_m.max(s.aft_radius_m))
            .fold(0.0, f64::max);
        let fineness = (self.length_m + 1e-4) / max_r;
        // Skin friction part by part, as OpenRocket's `calculateFrictionDrag`: each skin's
        // coefficient is the larger of the smooth one and its own finish's roughness-limited
        // one. The skins are grouped by roughness (a design of one finish is one group, summed
        // as one), each group's wetted area referred to `A_ref`.
        let mut groups: Vec<(f64, f64, f64)> = Vec::new(); // (roughness, body wet, fin wet)
        let mut add = |roughness_m: Option<f64>, body: f64, fin: f64| {
            let r = roughness_m.unwrap_or(self.roughness_m);
            match groups.iter_mut().find(|g| g.0 == r) {
                Some(g) => {
                    g.1 += body;
                    g.2 += fin;
                }
                None => groups.push((r, body, fin)),
            }
        };
        for (i, s) in self.sections.iter().enumerate() {
            let r = self.section_roughness_m.get(i).copied().flatten();
            add(r, s.wetted_area_m2(), 0.0);
        }
        for f in &self.fins {
            let wet = (1.0 + 2.0 * f.thickness_m / f.mac_m) * 2.0 * f.count as f64 * f.area_m2;
            add(f.roughness_m, 0.0, wet);
        }
        let friction_parts: Vec<(f64, f64)> = groups
            .iter()
            .map(|&(r, body_wet, fin_wet)| {
                let area = ((1.0 + 1.0 / (2.0 * fineness)) * body_wet + fin_wet) / a_ref;
                (r / self.length_m, area)
            })
            .collect();

        // Pressure drag of every radius change, per A_ref, as closures over Mach.
        enum Pressure {
            Nose(NosePressureDrag, f64),
            Boattail(f64, f64),
        }
        let mut pressure = Vec::new();
        for s in &self.sections {
            let (r1, r2) = (s.fore_radius_m, s.aft_radius_m);
            if r2 > r1 {
                let f = s.length_m / (2.0 * (r2 - r1));
                let area = PI * (r2 * r2 - r1 * r1) / a_ref;
                pressure.push(Pressure::Nose(
                    NosePressureDrag::new(s.shape, f, s.sin_joint_angle()),
                    area,
                ));
            } else if r2 < r1 {
                let gamma = s.length_m / (2.0 * (r1 - r2));
                pressure.push(Pressure::Boattail(gamma, PI * (r1 * r1 - r2 * r2) / a_ref));
            }
        }
        // Steps between consecutive sections (and the blunt fore face of the first, and the
        // aft base): up, a face meeting the flow (stagnation drag); down, a base.
        let mut steps_up = 0.0;
        let mut steps_down = 0.0;
        let mut before = 0.0;
        for s in &self.sections {
            let (a, b) = (before, s.fore_radius_m);
            if b > a {
                steps_up += PI * (b * b - a * a) / a_ref;
            } else if b < a {
                steps_down += PI * (a * a - b * b) / a_ref;
            }
            before = s.aft_radius_m;
        }
        steps_down += PI * before * before / a_ref;

        // `k` scales the Reynolds number from sea level's at this Mach (1 there).
        let common = |mach: f64, k: f64| {
            let re = reynolds_per_metre(mach.max(0.01)) * k * self.length_m;
            let friction: f64 = friction_parts
                .iter()
                .map(|&(rel_roughness, area)| skin_friction(re, mach, rel_roughness) * area)
                .sum();
            let body: f64 = pressure
                .iter()
                .map(|p| match p {
                    Pressure::Nose(n, area) => n.at(mach) * area,
                    Pressure::Boattail(g, area) => boattail_cd(mach, *g) * area,
                })
                .sum();
            let fins: f64 = self
                .fins
                .iter()
                .map(|f| {
                    fin_pressure_cd(mach, f.cross_section, f.leading_edge_sweep_rad)
                        * f.count as f64
                        * f.thickness_m
                        * f.span_m
                        / a_ref
                })
                .sum();
            let per_m = reynolds_per_metre(mach.max(0.01)) * k;
            let guides: f64 = self
                .guides
                .iter()
                .map(|g| match *g {
                    Guide::Lug {
                        length_m,
                        outer_diameter_m,
                        inner_diameter_m,
                    } => launch_lug_cd(
                        mach,
                        per_m,
                        self.roughness_m,
                        length_m,
                        outer_diameter_m,
                        inner_diameter_m,
                        a_ref,
                    ),
                    Guide::Button {
                        station_m,
                        outer_diameter_m,
                        height_m,
                    } => rail_button_cd(mach, per_m, station_m, outer_diameter_m, height_m, a_ref),
                })
                .sum();
            friction
                + body
                + fins
                + guides
                + stagnation_cd(mach) * steps_up
                + base_cd(mach) * steps_down
        };
        let reynolds = ReynoldsTables::from_fn(common);
        let power_off = reynolds.table(SEA_LEVEL_TABLE).clone();
        DragEstimate {
            power_on: power_off.clone(),
            power_off,
            reynolds,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aero::drag_formulas::skin_friction;
    use crate::design::NoseShape;

    #[test]
    fn the_sea_level_reynolds_number_per_metre_at_mach_one_is_two_point_three_million() {
        // 340.294 / (1.7894e-5/1.225) = 2.32960853e7 per metre.
        assert!((reynolds_per_metre(1.0) - 2.32960853e7).abs() < 1.0);
        assert!((reynolds_per_metre(0.3) - 0.3 * 2.32960853e7).abs() < 1.0);
    }

    /// A 0.3 m cone on a 0.7 m tube, 100 mm diameter, no fins: every term by hand.
    fn cone_and_tube() -> DragGeometry {
        DragGeometry {
            ref_area_m2: PI * 0.05 * 0.05,
            length_m: 1.0,
            ref_diameter_m: 0.1,
            roughness_m: 0.0,
            sections: vec![
                Section::nose(NoseShape::Conical, 0.3, 0.05),
                Section::tube(0.7, 0.05),
            ],
            section_roughness_m: vec![],
            fins: vec![],
            guides: vec![],
        }
    }

    #[test]
    fn a_finless_cone_and_tube_sums_friction_nose_and_base_drag_as_by_hand() {
        let est = cone_and_tube().estimate();
        let mach = 0.3;
        // Wetted area: π R sqrt(R² + L²) + 2π R 0.7 = 0.267685391 m²; OpenRocket's body
        // fineness is (1 m + 0.1 mm)/R = 20.002, so the body factor is 1 + 1/40.004 =
        // 1.0249975: 0.267685391 · 1.0249975 / (π 0.05²) = 34.934746395.
        let re = 0.3 * 2.32960853e7; // on L = 1 m; zero roughness: smooth turbulent
        let friction = skin_friction(re, mach, 0.0) * 34.934746395;
        // Nose pressure drag (cone, fineness 3, sin φ = 0.05/sqrt(0.0925)) on its full base.
        let sin_eps = 0.05 / 0.0925f64.sqrt();
        let nose = NosePressureDrag::new(NoseShape::Conical, 3.0, sin_eps).at(mach);
        let base = 0.12 + 0.13 * 0.09;
        let want_off = friction + nose + base;
        assert!(
            (est.power_off.at(mach) - want_off).abs() < 1e-6,
            "{} vs {want_off}",
            est.power_off.at(mach)
        );
        // Power on: the same (OpenRocket keeps the base drag with the motor burning).
        assert_eq!(est.power_on.at(mach), est.power_off.at(mach));
        // The friction coefficient alone: 1/(1.5 ln(6.98883e6) − 5.6)² · 0.991 = 0.00304518
        let cf = friction / 34.934746395;
        assert!((cf - 0.00304518).abs() < 1e-8, "{cf}");
    }

    #[test]
    fn a_step_up_in_radius_meets_the_flow_with_stagnation_drag_and_a_step_down_has_base_drag() {
        // The cone and tube with a 0.2 m tube of 120 mm after it: a 10 mm step up (a face of
        // π (0.06² − 0.05²) meeting the flow) and the wider aft base.
        let mut g = cone_and_tube();
        g.sections.push(Section::tube(0.2, 0.06));
        g.ref_area_m2 = PI * 0.06 * 0.06;
        g.ref_diameter_m = 0.12;
        g.length_m = 1.2;
        let with_step = g.estimate().power_off.at(0.3);
        // The same airframe's friction and nose, by the parts: remove the face and the base.
        let a_ref = g.ref_area_m2;
        let face = stagnation_cd(0.3) * PI * (0.06f64.powi(2) - 0.05f64.powi(2)) / a_ref;
        let aft_base = base_cd(0.3) * PI * 0.06 * 0.06 / a_ref;
        let mut smooth = g.clone();
        smooth.sections[2] = Section::tube(0.2, 0.05);
        let plain = smooth.estimate().power_off.at(0.3);
        let plain_base = base_cd(0.3) * PI * 0.05 * 0.05 / a_ref;
        // Friction differs by the wider tube's extra wetted area only.
        let body_factor = 1.0 + 1.0 / (2.0 * (1.2 + 1e-4) / 0.06);
        let body_factor_plain = 1.0 + 1.0 / (2.0 * (1.2 + 1e-4) / 0.05);
        let cf = skin_friction(reynolds_per_metre(0.3) * 1.2, 0.3, 0.0);
        let wet_cone_tube = PI * 0.05 * (0.05f64 * 0.05 + 0.09).sqrt() + 2.0 * PI * 0.05 * 0.7;
        let friction = cf * (wet_cone_tube + 2.0 * PI * 0.06 * 0.2) * body_factor / a_ref;
        let friction_plain =
            cf * (wet_cone_tube + 2.0 * PI * 0.05 * 0.2) * body_factor_plain / a_ref;
        let want = plain - plain_base - friction_plain + friction + face + aft_base;
        assert!((with_step - want).abs() < 1e-12, "{with_step} vs {want}");
    }

    #[test]
    fn each_skin_s_friction_is_taken_at_its_own_roughness_as_openrocket_takes_each_part_s_finish() {
        // The cone and tube with the tube rough (500 µm: roughness-limited, 0.032 (5e-4)^0.2
        // = 0.0070 against the smooth 0.0030) and the cone smooth, and a fin set of its own
        // 20 µm: the drag differs from the all-smooth rocket's by the tube's and the fins'
        // friction taken at their roughness instead of smooth, nothing else.
        let fins = FinDrag {
            count: 3,
            area_m2: 0.01,
            span_m: 0.1,
            thickness_m: 0.003,
            mac_m: 0.1,
            leading_edge_sweep_rad: 0.5,
            cross_section: FinCrossSection::Square,
            roughness_m: None,
        };
        let mut smooth = cone_and_tube();
        smooth.fins.push(fins);
        let mut mixed = smooth.clone();
        mixed.section_roughness_m = vec![None, Some(500e-6)];
        mixed.fins[0].roughness_m = Some(20e-6);
        let a_ref = PI * 0.05 * 0.05;
        let body_factor = 1.0 + 1.0 / (2.0 * (1.0 + 1e-4) / 0.05);
        let wet_tube = 2.0 * PI * 0.05 * 0.7;
        let wet_fins = (1.0 + 2.0 * 0.003 / 0.1) * 2.0 * 3.0 * 0.01;
        for mach in [0.3, 0.8, 1.0, 2.0] {
            let re = reynolds_per_metre(mach) * 1.0;
            let cf0 = skin_friction(re, mach, 0.0);
            let want = (skin_friction(re, mach, 500e-6) - cf0) * wet_tube * body_factor / a_ref
                + (skin_friction(re, mach, 20e-6) - cf0) * wet_fins / a_ref;
            let got = mixed.estimate().power_off.at(mach) - smooth.estimate().power_off.at(mach);
            assert!(
                (got - want).abs() < 1e-12 && want > 0.05,
                "Mach {mach}: {got} vs {want}"
            );
        }
        // Giving every skin the estimate's own roughness changes no bit.
        let mut same = smooth.clone();
        same.section_roughness_m = vec![Some(0.0), Some(0.0)];
        same.fins[0].roughness_m = Some(0.0);
        for mach in [0.0, 0.3, 1.05, 3.0] {
            assert_eq!(
                same.estimate().power_off.at(mach).to_bits(),
                smooth.estimate().power_off.at(mach).to_bits()
            );
        }
    }

    #[test]
    fn the_skin_friction_follows_the_reynolds_number_of_the_air_the_rocket_flies_in() {
        // The finless cone and tube (smooth skin, so the friction is the smooth-turbulent
        // one at every Reynolds number): its table at ln k = −1 (a Reynolds number e times
        // smaller than sea level's at the same Mach, air about 9 km up) differs from sea
        // level's by the friction coefficients' difference on the body's 34.934746395 A_ref
        // of fineness-corrected wetted area, and nothing else; the table at k = 1 is the
        // sea-level curve, bit for bit.
        let est = cone_and_tube().estimate();
        let (j_sea, j_thin) = (9, 7);
        assert_eq!(ReynoldsTables::ln_scale_of(j_sea), 0.0);
        assert_eq!(ReynoldsTables::ln_scale_of(j_thin), -1.0);
        for mach in [0.0, 0.3, 0.95, 2.0] {
            let sea = est.reynolds.table(j_sea).at(mach);
            assert_eq!(sea.to_bits(), est.power_off.at(mach).to_bits());
            let re = reynolds_per_metre(f64::max(mach, 0.01)) * 1.0;
            let want = (skin_friction(re * (-1.0f64).exp(), mach, 0.0)
                - skin_friction(re, mach, 0.0))
                * 34.934746395;
            let got = est.reynolds.at(mach, -1.0) - sea;
            assert!(
                (got - want).abs() < 1e-9 * want && want > 0.0,
                "Mach {mach}: {got} vs {want}"
            );
        }
        // Between two tables, linear in ln k: halfway between ln k = −1 and −0.5.
        let mid = est.reynolds.at(0.3, -0.75);
        let ends = (est.reynolds.at(0.3, -1.0) + est.reynolds.at(0.3, -0.5)) / 2.0;
        assert!((mid - ends).abs() < 1e-15, "{mid} vs {ends}");
        // Beyond the ends, the end tables.
        assert_eq!(est.reynolds.at(0.3, -9.0), est.reynolds.table(0).at(0.3));
        assert_eq!(est.reynolds.at(0.3, 3.0), est.reynolds.table(10).at(0.3));
        assert_eq!(
            est.reynolds.at(0.3, f64::NEG_INFINITY),
            est.reynolds.table(0).at(0.3)
        );
    }
}
