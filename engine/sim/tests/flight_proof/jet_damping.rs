//! The nozzle's jet damping, RocketPy's about the center of dry mass and hpr's about the nose
//! tip, on the Calisto (`calisto.rs`'s reference and motor).

use crate::calisto::{reference, rocketpy_motor};
use crate::common::*;
use hpr_sim::flight::{Rail, Simulation};

/// RocketPy writes its equations about the center of dry mass and hpr about the nose tip;
/// the nozzle's gyration tensor must be about the same point as the inertia rate it meets.
/// As both give it, the mass-flow terms' moment about the center of mass for a transverse ω
/// is `(−I_cm′ + ṁ (R²/4 − 3/4 d² + (p − r)²)) ω`, `d` the nozzle's distance from the center
/// of dry mass (RocketPy's `S11 = R²/4 + d²/4` less `d²`), `p` and `r` the nozzle's and the
/// center of mass's axial positions. With RocketPy's tensor put into the equations about the
/// nose tip unchanged (as before), it was +4.94 N·m·s per rad/s at rail exit against
/// RocketPy's +0.44: an anti-damping that grew the Calisto's pitching by e every 2 s while it
/// burnt (in the west wind its apogee was 27 m further west, 361 m against 334 m now; RocketPy
/// with its lever arm corrected: 329 m).
#[test]
fn the_jet_damping_is_rocketpy_s_about_the_nose_tip_as_about_the_center_of_dry_mass() {
    let r = reference();
    let sim = Simulation::with_motor_options(
        design("calisto.json"),
        motor("Cesaroni_M1670"),
        rocketpy_motor(&r),
        vacuum(G0),
        Rail::default(),
    )
    .unwrap();
    let noz = sim.model().nozzle;
    let d = noz.r_noz.z.abs() - sim.mass_properties_at(10.0).cg_m.x;
    let quarter_r2 = 0.5 * noz.s_noz[(2, 2)];
    for t in [0.3633, 1.0, 2.0, 3.0] {
        let ms = mass_at(&sim, t);
        let (m, m_dot, rz, rz_dot) = (ms.mass_kg, ms.mass_rate, ms.r_cm.z, ms.r_cm_rate.z);
        let i_cm = ms.inertia_cm()[(0, 0)];
        let i_cm_rate = ms.inertia_o_rate[(0, 0)] - m_dot * rz * rz - 2.0 * m * rz * rz_dot;
        let p = noz.r_noz.z;
        let expected = -i_cm_rate + m_dot * (quarter_r2 - 0.75 * d * d + (p - rz) * (p - rz));
        let w = 1e-3;
        let y = state(
            [0.0, 0.0, 100.0],
            [0.0; 3],
            [1.0, 0.0, 0.0, 0.0],
            [w, 0.0, 0.0],
        );
        let mut dy = [0.0; hpr_sim::eom::N6];
        sim.model()
            .derivative_6dof_at(&ms, 0.0, 0.0, t, &y, &mut dy);
        let got = dy[10] / w * i_cm;
        eprintln!("t {t} s: mass-flow moment {got:.5} N m s per rad/s, expected {expected:.5}");
        assert!(
            (got - expected).abs() <= 1e-9 * expected.abs().max(1.0),
            "t {t}: {got} against {expected}"
        );
        assert!(dy[11].abs() < 1e-12 && dy[12].abs() < 1e-12);
    }
}
