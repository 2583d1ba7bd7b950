//! Closed-form (and, for arbitrary profiles, numerically integrated) mass properties of the
//! shapes components are made of.
//!
//! Conventions: uniform density; a body of revolution has its axis along station `x` with
//! its fore end (or apex) at `x = 0`; the box is centered on the origin; the fin plate is in
//! its own frame (see [`fin_plate`]). Place a result with [`MassProps::translated`] and
//! [`MassProps::rotated`]. Each function takes the mass; the `*_volume` functions give the
//! volume for a density.
//!
//! Sources: the standard tables of moments of inertia (e.g. Meriam & Kraige, appendix B) for
//! the cylinders, cone, cube and plate; the others are derived in their docs.

use super::MassProps;
use crate::design::model::{polygon_signed_area_m2, FinPlanform, FinSet};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::PI;

fn diag(axial: f64, transverse: f64) -> Matrix3<f64> {
    Matrix3::from_diagonal(&Vector3::new(axial, transverse, transverse))
}

/// Hollow cylinder (thick tube) of outer radius `ro`, inner radius `ri` (0 for solid, `ro`
/// for a thin shell) and length `l`: `I_ax = m (ro² + ri²)/2`,
/// `I_tr = m (3 (ro² + ri²) + l²)/12`, center at `l/2`.
pub fn hollow_cylinder(mass_kg: f64, ro: f64, ri: f64, l: f64) -> MassProps {
    let q = ro * ro + ri * ri;
    MassProps {
        mass_kg,
        cg_m: Vector3::new(l / 2.0, 0.0, 0.0),
        inertia_cg: diag(mass_kg * q / 2.0, mass_kg * (3.0 * q + l * l) / 12.0),
    }
}

/// Volume of a hollow cylinder, m³.
pub fn hollow_cylinder_volume(ro: f64, ri: f64, l: f64) -> f64 {
    PI * (ro * ro - ri * ri) * l
}

/// Solid cylinder: `I_ax = m r²/2`, `I_tr = m (3 r² + l²)/12`.
pub fn solid_cylinder(mass_kg: f64, r: f64, l: f64) -> MassProps {
    hollow_cylinder(mass_kg, r, 0.0, l)
}

/// Thin cylindrical shell: `I_ax = m R²`, `I_tr = m (R²/2 + l²/12)`.
pub fn thin_cylindrical_shell(mass_kg: f64, r: f64, l: f64) -> MassProps {
    hollow_cylinder(mass_kg, r, r, l)
}

/// Thin conical shell, apex at 0, base radius `r` at `l` (lateral surface only). Its mass per
/// unit length grows as `x`, so the center is at `2l/3`; each ring of radius `ρ = r x/l`
/// adds `ρ² dm` about the axis and `(ρ²/2 + x²) dm` across it, which gives `I_ax = m r²/2`
/// and, about the center, `I_tr = m (r²/4 + l²/18)`.
pub fn thin_conical_shell(mass_kg: f64, r: f64, l: f64) -> MassProps {
    MassProps {
        mass_kg,
        cg_m: Vector3::new(2.0 * l / 3.0, 0.0, 0.0),
        inertia_cg: diag(
            mass_kg * r * r / 2.0,
            mass_kg * (r * r / 4.0 + l * l / 18.0),
        ),
    }
}

/// Solid cone, apex at 0, base radius `r` at `l`: center at `3l/4`, `I_ax = 3 m r²/10`,
/// `I_tr = m (3 r²/20 + 3 l²/80)` about the center.
pub fn solid_cone(mass_kg: f64, r: f64, l: f64) -> MassProps {
    MassProps {
        mass_kg,
        cg_m: Vector3::new(0.75 * l, 0.0, 0.0),
        inertia_cg: diag(
            0.3 * mass_kg * r * r,
            mass_kg * (3.0 * r * r / 20.0 + 3.0 * l * l / 80.0),
        ),
    }
}

/// Solid box with edges `[lx, ly, lz]` along the station axes, centered on the origin:
/// `I_xx = m (ly² + lz²)/12` and so on.
pub fn solid_box(mass_kg: f64, edges: [f64; 3]) -> MassProps {
    let [a, b, c] = edges.map(|e| e * e);
    MassProps {
        mass_kg,
        cg_m: Vector3::zeros(),
        inertia_cg: Matrix3::from_diagonal(&Vector3::new(b + c, a + c, a + b)) * (mass_kg / 12.0),
    }
}

/// Panels of the composite Gauss–Legendre rule in [`revolution`].
pub const REVOLUTION_PANELS: usize = 1024;

/// Four-point Gauss–Legendre nodes and weights on [−1, 1] (exact for degree 7).
fn gauss4() -> ([f64; 4], [f64; 4]) {
    let a = (3.0 / 7.0 - 2.0 / 7.0 * (6.0f64 / 5.0).sqrt()).sqrt();
    let b = (3.0 / 7.0 + 2.0 / 7.0 * (6.0f64 / 5.0).sqrt()).sqrt();
    let wa = (18.0 + 30.0f64.sqrt()) / 36.0;
    let wb = (18.0 - 30.0f64.sqrt()) / 36.0;
    ([-b, -a, a, b], [wb, wa, wa, wb])
}

/// A shell's wall thickness and how it is measured, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Wall {
    /// Across the axis: the inner radius is `r − t`.
    AcrossAxis(f64),
    /// Along the surface's normal (OpenRocket's).
    AlongNormal(f64),
}

impl Wall {
    /// A wall `t` thick, along the normal or across the axis.
    pub fn of(t: f64, along_normal: bool) -> Wall {
        if along_normal {
            Wall::AlongNormal(t)
        } else {
            Wall::AcrossAxis(t)
        }
    }
}

/// A body of revolution of unit density (its mass is its volume, m³), profile `r(x)` for
/// `0 <= x <= length_m`: solid (`wall_m = None`) or a shell between `r(x)` and
/// `max(r(x) − t, 0)` (wall measured across the axis).
///
/// [`Wall::AlongNormal`] measures the wall along the surface's normal, as OpenRocket does:
/// the inner radius is then `max(r − t √(1 + r′²), 0)` (`t / cos θ` across the axis, θ the
/// surface's slope; OpenRocket takes the slope of each of its slices, here the profile's
/// own, by a central difference).
///
/// Each slice `dx` is an annulus, `dm = π (ro² − ri²) dx`, adding `(ro² + ri²)/2 dm` about
/// the axis and `((ro² + ri²)/4 + x²) dm` across it. The integral is over
/// `x = L (1 − cos φ)/2`, `φ ∈ [0, π]`, which clusters points at both ends where profiles
/// have infinite slope (`r ~ sqrt(x)` at an elliptical tip, `x^¼` for von Kármán), with
/// [`REVOLUTION_PANELS`] panels of four-point Gauss–Legendre: polynomial profiles come out
/// exact to rounding.
pub fn revolution(profile: impl Fn(f64) -> f64, length_m: f64, wall_m: Option<Wall>) -> MassProps {
    let (nodes, weights) = gauss4();
    let half = length_m / 2.0;
    let h = PI / REVOLUTION_PANELS as f64;
    // Moments about x = L/2 keep the transverse sum free of cancellation.
    let (mut m, mut mx, mut ixx, mut iyy) = (0.0, 0.0, 0.0, 0.0);
    for p in 0..REVOLUTION_PANELS {
        let mid = (p as f64 + 0.5) * h;
        for (node, weight) in nodes.iter().zip(weights) {
            let phi = mid + node * h / 2.0;
            let x = half * (1.0 - phi.cos());
            let dxdphi = half * phi.sin();
            let ro = profile(x).max(0.0);
            let ri = match wall_m {
                None => 0.0,
                Some(Wall::AcrossAxis(t)) => (ro - t).max(0.0),
                Some(Wall::AlongNormal(t)) => {
                    let d = 1e-6 * length_m;
                    let (a, b) = ((x - d).max(0.0), (x + d).min(length_m));
                    let slope = (profile(b) - profile(a)) / (b - a);
                    (ro - t * (1.0 + slope * slope).sqrt()).max(0.0)
                }
            };
            let dm = PI * (ro * ro - ri * ri) * dxdphi * weight * h / 2.0;
            let q = ro * ro + ri * ri;
            let u = x - half;
            m += dm;
            mx += u * dm;
            ixx += q / 2.0 * dm;
            iyy += (q / 4.0 + u * u) * dm;
        }
    }
    if m <= 0.0 {
        return MassProps::ZERO;
    }
    let u_cg = mx / m;
    MassProps {
        mass_kg: m,
        cg_m: Vector3::new(half + u_cg, 0.0, 0.0),
        inertia_cg: diag(ixx, iyy - m * u_cg * u_cg),
    }
}

/// One flat fin of mass `mass_kg`, in its own frame: `x` along the root chord from its
/// leading edge (aft), `y` from the root toward the tip (span), `z` through the thickness.
/// The root is on `y = 0` from `x = 0` to `root`. A trapezoid's tip chord is on `y = span`
/// from `x = sweep`; its second moments come from integrating across the span with
/// three-point Gauss–Legendre (exact: the integrands are cubics). A half ellipse has
/// semi-axes `a = root/2` and `b = span` about `(a, 0)`; its moments are closed forms
/// (`∫ dA = π a b/2`, `∫ y dA = 2 a b²/3`, `∫ (x − a)² dA = π a³ b/8`, `∫ y² dA = π a b³/8`,
/// `∫ (x − a) y dA = 0`). A free-form outline's are Green's theorem's sums over its edges.
/// The thickness adds `t²/12` through it.
pub fn fin_plate(
    mass_kg: f64,
    root: f64,
    span: f64,
    planform: &FinPlanform,
    thickness: f64,
) -> MassProps {
    // ∫ over the plate of 1, x, y, x², y², x y (per unit thickness).
    let (mut a, mut ax, mut ay, mut axx, mut ayy, mut axy) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    match planform {
        &FinPlanform::Trapezoidal {
            tip_chord_m: tip,
            sweep_m: sweep,
        } => {
            let g = (0.6f64).sqrt();
            let nodes = [-g, 0.0, g];
            let weights = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
            for (n, w) in nodes.iter().zip(weights) {
                let y = span * (1.0 + n) / 2.0;
                let w = w * span / 2.0;
                let xl = sweep * y / span;
                let c = root + (tip - root) * y / span;
                let xr = xl + c;
                a += w * c;
                ax += w * (xr * xr - xl * xl) / 2.0;
                ay += w * y * c;
                axx += w * (xr.powi(3) - xl.powi(3)) / 3.0;
                ayy += w * y * y * c;
                axy += w * y * (xr * xr - xl * xl) / 2.0;
            }
        }
        FinPlanform::Elliptical => {
            let (h, b) = (root / 2.0, span);
            a = PI * h * b / 2.0;
            ax = h * a;
            ay = 2.0 * h * b * b / 3.0;
            axx = PI * h.powi(3) * b / 8.0 + h * h * a;
            ayy = PI * h * b.powi(3) / 8.0;
            axy = h * ay;
        }
        FinPlanform::FreeForm { points_m } => {
            // Green's theorem over the closed outline (exact for straight edges), oriented
            // counter-clockwise so that the integrals come out positive.
            let n = points_m.len();
            let sign = polygon_signed_area_m2(points_m).signum();
            for i in 0..n {
                let ([x0, y0], [x1, y1]) = (points_m[i], points_m[(i + 1) % n]);
                let cross = sign * (x0 * y1 - x1 * y0);
                a += cross / 2.0;
                ax += cross * (x0 + x1) / 6.0;
                ay += cross * (y0 + y1) / 6.0;
                axx += cross * (x0 * x0 + x0 * x1 + x1 * x1) / 12.0;
                ayy += cross * (y0 * y0 + y0 * y1 + y1 * y1) / 12.0;
                axy += cross * (x0 * y1 + 2.0 * x0 * y0 + 2.0 * x1 * y1 + x1 * y0) / 24.0;
            }
        }
    }
    if a <= 0.0 {
        return MassProps::ZERO;
    }
    let (xc, yc) = (ax / a, ay / a);
    let sxx = axx / a - xc * xc;
    let syy = ayy / a - yc * yc;
    let sxy = axy / a - xc * yc;
    let szz = thickness * thickness / 12.0;
    // Inertia per unit mass = tr(C) E − C, C the covariance of the points.
    let cov = Matrix3::new(sxx, sxy, 0.0, sxy, syy, 0.0, 0.0, 0.0, szz);
    let inertia = (Matrix3::identity() * cov.trace() - cov) * mass_kg;
    MassProps {
        mass_kg,
        cg_m: Vector3::new(xc, yc, 0.0),
        inertia_cg: inertia,
    }
}

/// Area of one fin's planform, m².
pub fn fin_area(fins: &FinSet) -> f64 {
    fins.planform.area_m2(fins.root_chord_m, fins.span_m)
}

/// A fin set of total mass `mass_kg` (shared equally), roots at `body_radius_m` from the
/// axis, the root leading edges at `x = 0`, on the station axis. Fin `i` is at
/// `rotation_deg + 360° i / N` from `+y` toward `+z`; the cant turns each fin about its
/// radial line through the root's mid-chord. The set's tensor is the sum of each plate's own,
/// turned into station axes, plus the parallel-axis term: for `N >= 2` evenly spaced the
/// center is on the axis, for `N >= 3` the transverse inertia is isotropic.
pub fn fin_set(mass_kg: f64, fins: &FinSet) -> MassProps {
    let n = fins.count.max(1);
    let plate = fin_plate(
        mass_kg / n as f64,
        fins.root_chord_m,
        fins.span_m,
        &fins.planform,
        fins.thickness_m,
    );
    // Cant: turn about the plate's y axis through (root/2, 0, 0).
    let (sd, cd) = fins.cant_deg.to_radians().sin_cos();
    let cant = Matrix3::new(cd, 0.0, -sd, 0.0, 1.0, 0.0, sd, 0.0, cd);
    let pivot = Vector3::new(fins.root_chord_m / 2.0, 0.0, 0.0);
    let canted = plate
        .translated(&-pivot)
        .rotated(&cant)
        .translated(&(pivot + Vector3::new(0.0, fins.body_radius_m, 0.0)));
    let mut total = MassProps::ZERO;
    for i in 0..n {
        let phi = (fins.rotation_deg + 360.0 * i as f64 / n as f64).to_radians();
        let (s, c) = phi.sin_cos();
        // Columns: plate x -> station x, plate y -> radial (0, cos, sin), plate z -> (0, −sin, cos).
        let q = Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c);
        total = total.combine(&canted.rotated(&q));
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    #[test]
    fn a_thin_cylindrical_shell_has_m_r_squared_about_its_axis() {
        let s = thin_cylindrical_shell(2.0, 0.05, 0.6);
        assert_eq!(s.axial_inertia(), 2.0 * 0.05 * 0.05);
        assert_eq!(
            s.transverse_inertia(),
            2.0 * (0.05 * 0.05 / 2.0 + 0.36 / 12.0)
        );
        assert_eq!(s.cg_m, Vector3::new(0.3, 0.0, 0.0));
    }

    #[test]
    fn a_hollow_cylinder_equals_the_outer_solid_less_the_inner_one() {
        // Independent of the formula: subtract the solid core (negative mass) from the solid.
        let (ro, ri, l, rho) = (0.05, 0.04, 0.5, 1000.0);
        let outer = solid_cylinder(rho * PI * ro * ro * l, ro, l);
        let core = solid_cylinder(-rho * PI * ri * ri * l, ri, l);
        let diff = outer.combine(&core);
        let tube = hollow_cylinder(rho * hollow_cylinder_volume(ro, ri, l), ro, ri, l);
        assert!(rel(diff.mass_kg, tube.mass_kg) < 1e-14);
        assert!(rel(diff.axial_inertia(), tube.axial_inertia()) < 1e-13);
        assert!(rel(diff.transverse_inertia(), tube.transverse_inertia()) < 1e-13);
    }

    #[test]
    fn a_solid_cylinder_matches_its_revolution_integral() {
        let (r, l) = (0.03, 0.2);
        let num = revolution(|_| r, l, None);
        let exact = solid_cylinder(PI * r * r * l, r, l);
        assert!(rel(num.mass_kg, exact.mass_kg) < 1e-13);
        assert!((num.cg_m.x - 0.1).abs() < 1e-15);
        assert!(rel(num.axial_inertia(), exact.axial_inertia()) < 1e-13);
        assert!(rel(num.transverse_inertia(), exact.transverse_inertia()) < 1e-13);
    }

    #[test]
    fn a_filled_cone_has_its_center_at_three_quarters_and_three_tenths_m_r_squared() {
        let (r, l) = (0.04, 0.3);
        let num = revolution(|x| r * x / l, l, None);
        let exact = solid_cone(PI * r * r * l / 3.0, r, l);
        assert!(rel(num.mass_kg, exact.mass_kg) < 1e-13);
        assert!(rel(num.cg_m.x, 0.225) < 1e-13, "{}", num.cg_m.x);
        assert!(rel(num.axial_inertia(), 0.3 * num.mass_kg * r * r) < 1e-13);
        assert!(rel(num.transverse_inertia(), exact.transverse_inertia()) < 1e-12);
    }

    /// The shell between the cone r(x) = R x/L and max(r − t, 0), `t` across the axis: the
    /// solid cone (R, L) less a cone of base R − t and length L (R − t)/R whose apex is at
    /// t L / R.
    fn cone_less_cone(r: f64, l: f64, t: f64) -> MassProps {
        let (ri, li) = (r - t, l * (r - t) / r);
        let outer = solid_cone(PI * r * r * l / 3.0, r, l);
        let inner = solid_cone(-PI * ri * ri * li / 3.0, ri, li).translated(&Vector3::new(
            t * l / r,
            0.0,
            0.0,
        ));
        outer.combine(&inner)
    }

    /// `num` is `exact` to `tol` in mass, center and both inertias.
    fn same_body(num: &MassProps, exact: &MassProps, tol: f64) {
        assert!(
            rel(num.mass_kg, exact.mass_kg) < tol,
            "{}",
            rel(num.mass_kg, exact.mass_kg)
        );
        assert!(rel(num.cg_m.x, exact.cg_m.x) < tol);
        assert!(rel(num.axial_inertia(), exact.axial_inertia()) < tol);
        assert!(rel(num.transverse_inertia(), exact.transverse_inertia()) < tol);
    }

    #[test]
    fn a_conical_shell_is_a_cone_less_the_cone_inside_its_wall() {
        let (r, l, t) = (0.04, 0.3, 0.002);
        let num = revolution(|x| r * x / l, l, Some(Wall::AcrossAxis(t)));
        // The clamp at r = t leaves a kink in the integrand; measured 3e-14 at worst.
        same_body(&num, &cone_less_cone(r, l, t), 1e-12);
    }

    #[test]
    fn a_conical_wall_measured_along_its_normal_is_thicker_across_the_axis_by_the_slope() {
        // Measured along the normal, a cone's wall t is t' = t √(1 + (R/L)²) across the axis
        // everywhere (the slope is constant): the shell is the cone less the cone inside a
        // wall of t', as OpenRocket's frustum slices give it exactly for a cone.
        let (r, l, t) = (0.04, 0.12, 0.002);
        let num = revolution(|x| r * x / l, l, Some(Wall::AlongNormal(t)));
        let tp = t * (1.0 + (r / l).powi(2)).sqrt();
        // The slope by a central difference is exact on a line; the clamp's kink as above.
        same_body(&num, &cone_less_cone(r, l, tp), 1e-12);
        // Heavier than the same t across the axis, by about 1/cos θ for a thin wall.
        let across = revolution(|x| r * x / l, l, Some(Wall::AcrossAxis(t)));
        let ratio = num.mass_kg / across.mass_kg;
        assert!(
            (ratio - (1.0 + (r / l).powi(2)).sqrt()).abs() < 0.02,
            "{ratio}"
        );
    }

    #[test]
    fn a_thin_conical_shell_has_its_center_at_two_thirds_and_half_m_r_squared() {
        // The closed form against the integral of a very thin wall (t = 1e-6 R): they differ
        // by the wall's own thickness, t/R = 1e-6 (measured 2.5e-7 on the center, 1.0e-6 on
        // the inertias).
        let (r, l) = (0.04, 0.3);
        let t = 1e-6 * r;
        let num = revolution(|x| r * x / l, l, Some(Wall::AcrossAxis(t)));
        let thin = thin_conical_shell(num.mass_kg, r, l);
        assert!(rel(num.cg_m.x, 0.2) < 5e-7);
        assert!(rel(num.axial_inertia(), thin.axial_inertia()) < 2e-6);
        assert!(rel(num.transverse_inertia(), thin.transverse_inertia()) < 2e-6);
        assert_eq!(thin.axial_inertia(), num.mass_kg * r * r / 2.0);
    }

    #[test]
    fn a_filled_elliptical_nose_is_half_a_spheroid() {
        // Half spheroid, semi-axes R, R, L: V = 2π R² L/3, center 3L/8 from the base,
        // I_ax = 2 m R²/5, I_tr = m (R²/5 + L²/5) − m (3L/8)² about the center.
        let (r, l) = (0.03, 0.12);
        let num = revolution(
            |x| r * (1.0 - (1.0 - x / l).powi(2)).max(0.0).sqrt(),
            l,
            None,
        );
        let m = 2.0 * PI * r * r * l / 3.0;
        assert!(rel(num.mass_kg, m) < 1e-13, "{}", rel(num.mass_kg, m));
        assert!(rel(num.cg_m.x, l - 3.0 * l / 8.0) < 1e-13);
        assert!(rel(num.axial_inertia(), 0.4 * m * r * r) < 1e-13);
        let it = m * (r * r + l * l) / 5.0 - m * (3.0 * l / 8.0).powi(2);
        assert!(rel(num.transverse_inertia(), it) < 1e-13);
    }

    #[test]
    fn a_rectangular_fin_is_a_thin_rectangular_plate() {
        // c × s × t plate: about its chord line m (s² + t²)/12, across the span
        // m (c² + t²)/12, through the thickness m (c² + s²)/12.
        let (m, c, s, t) = (0.1, 0.12, 0.07, 0.003);
        let p = fin_plate(m, c, s, &trapezoid(c, 0.0), t);
        assert!((p.cg_m - Vector3::new(0.06, 0.035, 0.0)).amax() < 1e-16);
        let i = p.inertia_cg;
        assert!(rel(i[(0, 0)], m * (s * s + t * t) / 12.0) < 1e-13);
        assert!(rel(i[(1, 1)], m * (c * c + t * t) / 12.0) < 1e-13);
        assert!(rel(i[(2, 2)], m * (c * c + s * s) / 12.0) < 1e-13);
        assert!(i[(0, 1)].abs() < 1e-18);
    }

    /// A uniform triangle's covariance is `(1/12) Σ (vᵢ − g)(vᵢ − g)ᵀ` over its vertices.
    fn triangle(mass: f64, v: [[f64; 2]; 3], t: f64) -> MassProps {
        let g = [
            (v[0][0] + v[1][0] + v[2][0]) / 3.0,
            (v[0][1] + v[1][1] + v[2][1]) / 3.0,
        ];
        let (mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0);
        for p in v {
            let (dx, dy) = (p[0] - g[0], p[1] - g[1]);
            sxx += dx * dx / 12.0;
            syy += dy * dy / 12.0;
            sxy += dx * dy / 12.0;
        }
        let cov = Matrix3::new(sxx, sxy, 0.0, sxy, syy, 0.0, 0.0, 0.0, t * t / 12.0);
        MassProps {
            mass_kg: mass,
            cg_m: Vector3::new(g[0], g[1], 0.0),
            inertia_cg: (Matrix3::identity() * cov.trace() - cov) * mass,
        }
    }

    #[test]
    fn a_swept_trapezoidal_fin_is_the_sum_of_its_two_triangles() {
        let (root, tip, span, sweep, t) = (0.15, 0.05, 0.08, 0.09, 0.004);
        let area = (root + tip) / 2.0 * span;
        let sigma = 2.0; // kg/m² (any)
        let plate = fin_plate(sigma * area, root, span, &trapezoid(tip, sweep), t);
        // Split along the diagonal from the root's trailing edge to the tip's leading edge.
        let a1 = root * span / 2.0;
        let a2 = tip * span / 2.0;
        let t1 = triangle(sigma * a1, [[0.0, 0.0], [root, 0.0], [sweep, span]], t);
        let t2 = triangle(
            sigma * a2,
            [[root, 0.0], [sweep + tip, span], [sweep, span]],
            t,
        );
        let sum = t1.combine(&t2);
        assert!(rel(plate.mass_kg, sum.mass_kg) < 1e-14);
        assert!((plate.cg_m - sum.cg_m).amax() < 1e-15);
        let d = plate.inertia_cg - sum.inertia_cg;
        assert!(d.amax() < 1e-12 * sum.inertia_cg.amax(), "{d}");
    }

    fn trapezoid(tip_chord_m: f64, sweep_m: f64) -> FinPlanform {
        FinPlanform::Trapezoidal {
            tip_chord_m,
            sweep_m,
        }
    }

    #[test]
    fn an_elliptical_fin_matches_its_moments_integrated_across_the_span() {
        // Independent of the closed forms: with y = s sin θ the chord is C_r cos θ between
        // x = (C_r/2)(1 ∓ cos θ), dy = s cos θ dθ, and every integrand is smooth in θ
        // (Simpson, 2000 panels).
        let (m, root, span, t) = (0.04, 0.15, 0.09, 0.003);
        let (h, n) = (root / 2.0, 2000);
        let dt = 0.5 * PI / n as f64;
        let mut sums = [0.0f64; 6];
        for i in 0..=n {
            let th = i as f64 * dt;
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            } * dt
                / 3.0;
            let (y, dy) = (span * th.sin(), span * th.cos());
            let (xl, xr) = (h * (1.0 - th.cos()), h * (1.0 + th.cos()));
            let terms = [
                xr - xl,
                (xr * xr - xl * xl) / 2.0,
                y * (xr - xl),
                (xr.powi(3) - xl.powi(3)) / 3.0,
                y * y * (xr - xl),
                y * (xr * xr - xl * xl) / 2.0,
            ];
            for k in 0..6 {
                sums[k] += w * dy * terms[k];
            }
        }
        let [a, ax, ay, axx, ayy, axy] = sums;
        assert!(rel(a, PI * root * span / 4.0) < 1e-12, "area {a}");
        let (xc, yc) = (ax / a, ay / a);
        let (sxx, syy, sxy) = (axx / a - xc * xc, ayy / a - yc * yc, axy / a - xc * yc);
        let p = fin_plate(m, root, span, &FinPlanform::Elliptical, t);
        assert!((p.cg_m - Vector3::new(xc, yc, 0.0)).amax() < 1e-14);
        // The center: mid-chord, 4 s/(3π) out.
        assert!((p.cg_m.y - 4.0 * span / (3.0 * PI)).abs() < 1e-15);
        let i = p.inertia_cg;
        assert!(rel(i[(0, 0)], m * (syy + t * t / 12.0)) < 1e-11);
        assert!(rel(i[(1, 1)], m * (sxx + t * t / 12.0)) < 1e-11);
        assert!(rel(i[(2, 2)], m * (sxx + syy)) < 1e-11);
        assert!((i[(0, 1)] + m * sxy).abs() < 1e-11 * i[(2, 2)]);
    }

    #[test]
    fn a_free_form_outline_weighs_as_the_planform_it_traces() {
        // Green's theorem on the corners against the trapezoid's own integration, and a
        // clockwise outline (the same corners reversed, root last) the same.
        let (m, t) = (0.05, 0.004);
        let trapezoid = fin_plate(m, 0.15, 0.08, &trapezoid(0.05, 0.09), t);
        let corners = vec![[0.0, 0.0], [0.09, 0.08], [0.14, 0.08], [0.15, 0.0]];
        let outline = fin_plate(
            m,
            0.15,
            0.08,
            &FinPlanform::FreeForm { points_m: corners },
            t,
        );
        assert!((outline.cg_m - trapezoid.cg_m).amax() < 1e-15);
        let d = outline.inertia_cg - trapezoid.inertia_cg;
        assert!(d.amax() < 1e-13 * trapezoid.inertia_cg.amax(), "{d}");
        let mirrored = fin_plate(
            m,
            0.15,
            0.08,
            &FinPlanform::FreeForm {
                points_m: vec![[0.0, 0.0], [0.15, 0.0], [0.14, 0.08], [0.09, 0.08]],
            },
            t,
        );
        assert!((mirrored.cg_m - trapezoid.cg_m).amax() < 1e-15);
        assert!(
            (mirrored.inertia_cg - trapezoid.inertia_cg).amax()
                < 1e-13 * trapezoid.inertia_cg.amax()
        );
    }

    fn four_fins(rotation_deg: f64, count: u32) -> FinSet {
        FinSet {
            count,
            root_chord_m: 0.12,
            span_m: 0.07,
            planform: trapezoid(0.12, 0.0),
            thickness_m: 0.003,
            cant_deg: 0.0,
            body_radius_m: 0.04,
            rotation_deg,
            cross_section: crate::design::model::FinCrossSection::Square,
            lift_slope_2d_per_rad: 2.0 * std::f64::consts::PI,
        }
    }

    #[test]
    fn four_rectangular_fins_match_the_hand_calculation() {
        // Each fin m = 0.05 (c 0.12, s 0.07, t 0.003) with its center R + s/2 = 0.075 off the axis.
        // Roll: N m [(s² + t²)/12 + 0.075²]. Pitch (about y through the center): the two fins
        // along y give m (c² + t²)/12 each, the two along z m (c² + s²)/12 + m 0.075² each.
        let (m, c, s, t, d) = (0.05, 0.12, 0.07, 0.003, 0.075);
        let set = fin_set(4.0 * m, &four_fins(0.0, 4));
        assert!((set.cg_m - Vector3::new(0.06, 0.0, 0.0)).amax() < 1e-16);
        let roll = 4.0 * m * ((s * s + t * t) / 12.0 + d * d);
        let pitch = 2.0 * m * (c * c + t * t) / 12.0 + 2.0 * m * ((c * c + s * s) / 12.0 + d * d);
        assert!(rel(set.axial_inertia(), roll) < 1e-13);
        assert!(rel(set.transverse_inertia(), pitch) < 1e-13);
        assert!(rel(set.inertia_cg[(2, 2)], pitch) < 1e-13);
    }

    #[test]
    fn three_or_more_evenly_spaced_fins_have_an_isotropic_transverse_inertia() {
        for count in [3u32, 5, 7] {
            let mut fins = four_fins(17.0, count);
            fins.planform = trapezoid(0.05, 0.06);
            fins.cant_deg = 2.0;
            let set = fin_set(0.3, &fins);
            let i = set.inertia_cg;
            let scale = i[(1, 1)];
            assert!(
                (i[(1, 1)] - i[(2, 2)]).abs() < 1e-14 * scale,
                "N={count} {i}"
            );
            assert!(i[(1, 2)].abs() < 1e-14 * scale, "N={count} {i}");
            assert!(set.cg_m.y.abs() < 1e-15 && set.cg_m.z.abs() < 1e-15);
        }
    }

    #[test]
    fn a_box_has_a_twelfth_of_m_times_the_other_two_edges_squared() {
        let b = solid_box(12.0, [1.0, 2.0, 3.0]);
        assert_eq!(
            b.inertia_cg,
            Matrix3::from_diagonal(&Vector3::new(13.0, 10.0, 5.0))
        );
    }
}
