//! Zero-lift drag coefficient against Mach estimated from the geometry, for designs that give
//! no drag curves: OpenRocket's method (S. Niskanen, *Development of an Open Source model
//! rocket simulation software*, 2009, §3.4), referenced to the area of the reference diameter.
//!
//! `C_D(M) = C_D,friction + Σ (A_part/A_ref) C_D•,part`, summing (formulas in
//! [`super::drag_formulas`] and [`super::nose_drag`]):
//! - skin friction (eq. 3.85): `C_fc [(1 + 1/(2 f_B)) A_wet,body + (1 + 2t/c̄) A_wet,fins]/A_ref`,
//!   with `C_fc` the fully turbulent / roughness-limited coefficient with its compressibility
//!   correction, `f_B = L/d` the rocket's fineness, `t` the fin thickness, `c̄` the mean
//!   aerodynamic chord, and `A_wet,fins` both sides of every fin;
//! - nose and shoulder pressure drag on `π (r_aft² − r_fore²)`; boattail pressure drag on
//!   `π (r_fore² − r_aft²)`;
//! - fin pressure drag (leading and trailing edge by cross-section) on `N t s`;
//! - launch lugs (eqs. 3.95, 3.96) and rail buttons (treated, as the thesis suggests, as a lug
//!   of the button's frontal area `diameter × height` and length equal to its diameter);
//! - base drag (eq. 3.94) on every step down in radius between body components and on the
//!   aft end. Power on, the aft end's base area is reduced by the motor's cross-section
//!   (§3.4.5, "subtracting the area of the thrusting motors"), taken as the motor mount's inner
//!   diameter times the number of tubes of its cluster; the steps keep their base drag.
//!
//! **Air properties.** The flight uses these tables at any altitude; the Reynolds number of
//! each Mach row is the sea-level one of the International Standard Atmosphere:
//! `Re/L = M a₀/ν₀`, `a₀ = 340.294 m/s`, `ν₀ = μ₀/ρ₀ = 1.7894e-5/1.225 = 1.46073e-5 m²/s`,
//! on the rocket's length `L`. (The Mach-0 row, a rocket at rest, takes the Reynolds number of
//! the Mach-0.01 row so that the table does not jump to the `R < 10⁴` value.) Skin friction at
//! altitude is somewhat higher than this (lower Reynolds number); the effect on `C_D` is a few
//! per cent.
//!
//! Not modelled: fin–body interference drag, fin-tip vortices, the angle of attack (the flight
//! applies its own correction if any), and the nozzle's own base drag.

use super::drag_formulas::{
    base_cd, boattail_cd, fin_pressure_cd, launch_guide_area_m2, launch_guide_cd, skin_friction,
};
use super::fins::Fins;
use super::nose_drag::NosePressureDrag;
use super::profile::{nose_shape_of, Section};
use super::table::MachTable;
use crate::design::{ComponentKind, Design, FinCrossSection};
use std::f64::consts::PI;

/// Sea-level speed of sound of the ISA, m/s.
pub const SEA_LEVEL_SPEED_OF_SOUND_M_S: f64 = 340.294;
/// Sea-level kinematic viscosity of the ISA, m²/s (`1.7894e-5 Pa·s / 1.225 kg/m³`).
pub const SEA_LEVEL_KINEMATIC_VISCOSITY_M2_S: f64 = 1.7894e-5 / 1.225;

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
    pub roughness_m: f64,
    /// Body sections fore to aft.
    pub sections: Vec<Section>,
    pub fins: Vec<FinDrag>,
    /// Launch guides: (length, outer diameter, inner diameter), m.
    pub guides: Vec<(f64, f64, f64)>,
    /// Motor cross-section subtracted from the aft base area with the motor burning, m².
    pub motor_area_m2: f64,
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
}

/// Power-off and power-on `C_D(M)` tables.
#[derive(Debug, Clone)]
pub struct DragEstimate {
    pub power_off: MachTable,
    pub power_on: MachTable,
}

impl DragGeometry {
    /// Collects the geometry of `design` (body components sorted fore to aft).
    pub fn from_design(design: &Design, roughness_m: f64) -> Self {
        let d = design.reference_diameter_m;
        let mut bodies: Vec<(f64, Section)> = Vec::new();
        let mut fins = Vec::new();
        let mut guides = Vec::new();
        for c in &design.components {
            match &c.kind {
                ComponentKind::NoseCone(n) => bodies.push((
                    c.x_top_m,
                    Section::nose(n.shape, c.length_m, n.base_diameter_m / 2.0),
                )),
                ComponentKind::BodyTube(t) => bodies.push((
                    c.x_top_m,
                    Section::tube(c.length_m, t.outer_diameter_m / 2.0),
                )),
                ComponentKind::Transition(t) => bodies.push((
                    c.x_top_m,
                    Section {
                        shape: nose_shape_of(t.shape),
                        length_m: c.length_m,
                        fore_radius_m: t.fore_diameter_m / 2.0,
                        aft_radius_m: t.aft_diameter_m / 2.0,
                    },
                )),
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
                    })
                }
                ComponentKind::LaunchLug(l) => guides.push((
                    c.length_m,
                    l.outer_diameter_m,
                    l.outer_diameter_m - 2.0 * l.wall_thickness_m,
                )),
                ComponentKind::RailButton(b) => {
                    // A pin of frontal area D·h, as a solid lug of that area and length D.
                    let d_eq = (4.0 * b.outer_diameter_m * b.height_m / PI).sqrt();
                    guides.push((d_eq, d_eq, 0.0))
                }
                _ => {}
            }
        }
        bodies.sort_by(|a, b| a.0.total_cmp(&b.0));
        let motor_area_m2 = design.motor_mount.as_ref().map_or(0.0, |m| {
            let tubes = match &design.components.get(m.component).map(|c| &c.kind) {
                Some(ComponentKind::InnerTube(t)) => t.cluster_offsets_m.len().max(1),
                _ => 1,
            };
            tubes as f64 * PI * m.inner_diameter_m * m.inner_diameter_m / 4.0
        });
        DragGeometry {
            ref_area_m2: PI * d * d / 4.0,
            length_m: design.length_m,
            ref_diameter_m: d,
            roughness_m,
            sections: bodies.into_iter().map(|b| b.1).collect(),
            fins,
            guides,
            motor_area_m2,
        }
    }

    /// Builds the power-off and power-on tables.
    pub fn estimate(&self) -> DragEstimate {
        let a_ref = self.ref_area_m2;
        let fineness = self.length_m / self.ref_diameter_m;
        let body_wet: f64 = self.sections.iter().map(Section::wetted_area_m2).sum();
        let fin_wet: f64 = self
            .fins
            .iter()
            .map(|f| (1.0 + 2.0 * f.thickness_m / f.mac_m) * 2.0 * f.count as f64 * f.area_m2)
            .sum();
        let friction_area = ((1.0 + 1.0 / (2.0 * fineness)) * body_wet + fin_wet) / a_ref;
        let rel_roughness = self.roughness_m / self.length_m;

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
        // Steps down between consecutive sections, and the aft base.
        let steps: f64 = self
            .sections
            .windows(2)
            .map(|w| {
                let (a, b) = (w[0].aft_radius_m, w[1].fore_radius_m);
                if b < a {
                    PI * (a * a - b * b)
                } else {
                    0.0
                }
            })
            .sum::<f64>()
            / a_ref;
        let aft_r = self.sections.last().map_or(0.0, |s| s.aft_radius_m);
        let base_off = PI * aft_r * aft_r / a_ref;
        let base_on = (PI * aft_r * aft_r - self.motor_area_m2).max(0.0) / a_ref;

        let common = |mach: f64| {
            let re = reynolds_per_metre(mach.max(0.01)) * self.length_m;
            let friction = skin_friction(re, mach, rel_roughness) * friction_area;
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
            let guides: f64 = self
                .guides
                .iter()
                .map(|&(l, d, di)| {
                    launch_guide_cd(mach, l, d) * launch_guide_area_m2(l, d, di) / a_ref
                })
                .sum();
            friction + body + fins + guides + base_cd(mach) * steps
        };
        let power_off = MachTable::from_fn(|m| common(m) + base_cd(m) * base_off);
        let power_on = MachTable::from_fn(|m| common(m) + base_cd(m) * base_on);
        DragEstimate {
            power_off,
            power_on,
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
            fins: vec![],
            guides: vec![],
            motor_area_m2: PI * 0.02 * 0.02,
        }
    }

    #[test]
    fn a_finless_cone_and_tube_sums_friction_nose_and_base_drag_as_by_hand() {
        let est = cone_and_tube().estimate();
        let mach = 0.3;
        // Wetted area: π R sqrt(R² + L²) + 2π R 0.7 = 0.267685391 m²; f_B = 10 so the body
        // factor is 1.05: 0.267685391 · 1.05 / (π 0.05²) = 35.786900657.
        let re = 0.3 * 2.32960853e7; // on L = 1 m; zero roughness: smooth turbulent
        let friction = skin_friction(re, mach, 0.0) * 35.786900657;
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
        // Power on: the 40 mm motor's area (0.16 of the base) has no base drag.
        let want_on = want_off - base * 0.16;
        assert!((est.power_on.at(mach) - want_on).abs() < 1e-6);
        // The friction coefficient alone: 1/(1.5 ln(6.98883e6) − 5.6)² · 0.991 = 0.00304518
        let cf = friction / 35.786900657;
        assert!((cf - 0.00304518).abs() < 1e-8, "{cf}");
    }
}
