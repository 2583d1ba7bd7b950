//! The motor as RocketPy's `SolidMotor` gives it (BATES grains, the casing's and the grains'
//! centers, the casing's inertia) through the flight: the mass state's rates are the time
//! derivatives of its values, and the batch flies it bit for bit as single flights.

use crate::calisto::{calisto_sim, reference, rocketpy_motor, site_gravity};
use crate::common::*;

#[test]
fn the_mass_state_of_a_grain_motor_changes_at_the_rates_it_states() {
    let r = reference();
    let sim = calisto_sim(design("calisto.json"), rocketpy_motor(&r), site_gravity(&r));
    let h = 1e-6;
    // Inside the M1670's thrust segments (knots at 0.5, 1, 1.5, ... s), where the rates are
    // smooth; central differences err by O(h²) and by rounding 1e-16 · 10 / h ≈ 1e-9.
    for t in [0.3, 0.7, 1.7, 2.7, 3.6] {
        let (lo, mid, hi) = (mass_at(&sim, t - h), mass_at(&sim, t), mass_at(&sim, t + h));
        let d_inertia = (hi.inertia_o - lo.inertia_o) / (2.0 * h);
        assert!(
            (d_inertia - mid.inertia_o_rate).norm() <= 1e-6 * mid.inertia_o_rate.norm(),
            "t {t}: {d_inertia} against {}",
            mid.inertia_o_rate
        );
        let d_cm = (hi.r_cm - lo.r_cm) / (2.0 * h);
        assert!(
            (d_cm - mid.r_cm_rate).norm() <= 1e-6 * mid.r_cm_rate.norm(),
            "t {t}: {d_cm} against {}",
            mid.r_cm_rate
        );
    }
    // The propellant burns at the grains' center, 2.136 m aft of the tip (the casing's stays
    // at 2.216 m): the center of mass moves at ṁ (c_p − r)/M, forward (+b3) while it burns.
    let c_p = sim.model().mass.propellant_cg_b;
    for t in [0.7, 2.7] {
        let ms = mass_at(&sim, t);
        let want = (c_p - ms.r_cm) * (ms.mass_rate / ms.mass_kg);
        assert!(
            (ms.r_cm_rate - want).norm() <= 1e-12 * want.norm(),
            "t {t}: {} against {want}",
            ms.r_cm_rate
        );
        assert!(ms.r_cm_rate.z > 0.0);
    }
}

#[test]
fn a_grain_motor_flies_in_the_batch_bit_for_bit_as_its_single_flights() {
    let r = reference();
    let sim = calisto_sim(design("calisto.json"), rocketpy_motor(&r), site_gravity(&r));
    let lanes = batch_flies_as_singles(sim);
    assert!(lanes.iter().all(|l| l.metrics.apogee_m.unwrap() > 2000.0));
}
