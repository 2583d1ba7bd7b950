//! Shared set-up of the proof's flights: designs and motors from the repository, a vacuum,
//! tight tolerances, and the state and mass of a sample.

use hpr_design::motor::Motor;
use hpr_design::Design;
use hpr_sim::eom::{MassState, N6};
use hpr_sim::flight::model::MAX_SHIFTS;
use hpr_sim::flight::{
    CanopyShape, Environment, Integrator, Parachute, Sample, SimOptions, Simulation,
};
use hpr_sim::gravity::Gravity;
use hpr_sim::Trigger;
use nalgebra::{Matrix3, Vector3};
use std::path::{Path, PathBuf};

/// Standard gravity, m/s².
pub const G0: f64 = 9.80665;

/// A file of the repository.
pub fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(path)
}

/// A design of `validation/designs/`.
pub fn design(file: &str) -> Design {
    Design::load(repo(&format!("validation/designs/{file}")))
        .unwrap_or_else(|e| panic!("{file}: {e}"))
}

/// A motor of the bundled library.
pub fn motor(name: &str) -> Motor {
    hpr_design::motor::find(name).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// `design` on `motor` in the standard atmosphere with no wind, off the default vertical
/// 2 m rail.
pub fn still_air(design: Design, motor: Motor) -> Simulation {
    Simulation::new(
        design,
        motor,
        Environment::default(),
        hpr_sim::flight::Rail::default(),
    )
    .expect("set up")
}

/// No air, constant gravity `g`.
pub fn vacuum(g: f64) -> Environment {
    Environment {
        vacuum: true,
        gravity: Gravity::constant(g).expect("g >= 0"),
        ..Environment::default()
    }
}

/// Dormand–Prince at relative tolerance 1e-12 (absolute 1e-10 m, 1e-10 m/s, 1e-13, 1e-12 rad/s).
pub const TIGHT: Integrator = Integrator::Adaptive {
    rtol: 1e-12,
    atol_position_m: 1e-10,
    atol_velocity_m_s: 1e-10,
    atol_quaternion: 1e-13,
    atol_rate_rad_s: 1e-12,
};

/// Options with `integrator`, stopping at `max_time_s`, keeping every sample.
pub fn options(integrator: Integrator, max_time_s: f64) -> SimOptions {
    SimOptions {
        integrator,
        max_time_s,
        keep_samples: true,
    }
}

/// The mass state at `t` with no shift.
pub fn mass_at(sim: &Simulation, t: f64) -> MassState {
    sim.model().instant(&[f64::INFINITY; MAX_SHIFTS], t).mass
}

/// A 6-DOF state from O's position and velocity, a quaternion and body rates.
pub fn state(o: [f64; 3], v: [f64; 3], q: [f64; 4], w: [f64; 3]) -> [f64; N6] {
    [
        o[0], o[1], o[2], v[0], v[1], v[2], q[0], q[1], q[2], q[3], w[0], w[1], w[2],
    ]
}

/// The attitude and rates of a sample as a 6-DOF state (O's position and velocity zero:
/// what the angular momentum about the center of mass needs).
pub fn attitude_state(s: &Sample) -> [f64; N6] {
    state([0.0; 3], [0.0; 3], s.quaternion, s.omega_rad_s)
}

/// Body → inertial rotation of a sample.
pub fn rotation(s: &Sample) -> Matrix3<f64> {
    hpr_sim::frames::body_to_inertial(&s.quaternion)
}

pub fn v3(a: [f64; 3]) -> Vector3<f64> {
    Vector3::new(a[0], a[1], a[2])
}

/// A RocketPy drogue and main (`drogue_cds`, `main_cds` m², RocketPy's default canopies) as
/// hpr-mc flies them. RocketPy's canopies replace one another, hpr-mc's add up, so hpr-mc's
/// main is RocketPy's less the drogue: in CdS, and in the air it carries along (a hemisphere
/// of radius `R` with `R³ = R_main³ − R_drogue³`, each `R = √(CdS / (1.4 π))`). Once the
/// main is out, both fly the same drag and the same added mass.
pub fn rocketpy_chutes(
    drogue: (f64, Trigger, f64),
    main: (f64, Trigger, f64),
    sampling_rate_hz: f64,
) -> Vec<Parachute> {
    let ((drogue_cds, drogue_trigger, drogue_lag_s), (main_cds, main_trigger, main_lag_s)) =
        (drogue, main);
    let r3 = |cds: f64| (cds / (hpr_sim::eom::CANOPY_CD * std::f64::consts::PI)).powf(1.5);
    vec![
        Parachute::new("drogue", drogue_cds, drogue_trigger, drogue_lag_s)
            .with_sampling_rate(sampling_rate_hz),
        Parachute::new("main", main_cds - drogue_cds, main_trigger, main_lag_s)
            .with_canopy(CanopyShape {
                radius_m: Some((r3(main_cds) - r3(drogue_cds)).cbrt()),
                ..CanopyShape::default()
            })
            .with_sampling_rate(sampling_rate_hz),
    ]
}

/// The reference design (the synthetic 54 mm rocket) on its I175 off the default rail in a
/// constant wind of `speed_m_s` from `from_deg`, flown to the ground under `chutes`.
pub fn reference_flight_in_wind(
    speed_m_s: f64,
    from_deg: f64,
    chutes: Vec<Parachute>,
) -> hpr_sim::flight::Flight {
    let env = Environment {
        wind: hpr_sim::wind::Wind::constant(speed_m_s, from_deg).unwrap(),
        ..Environment::default()
    };
    hpr_sim::flight::Simulation::new(
        design("synthetic-54mm-three-fin.json"),
        motor("Cesaroni_I175"),
        env,
        hpr_sim::flight::Rail::default(),
    )
    .and_then(|s| s.with_parachutes(chutes))
    .expect("set up")
    .run(&mut ())
    .expect("flies")
}

/// Eight variants of `sim` (impulse, burn time, drag and rail inclination spread evenly
/// between their bounds) flown through the batch in chunks of 3 on 2 threads; every lane
/// must land with the metrics of its single flight, bit for bit. Returns the lanes.
pub fn batch_flies_as_singles(sim: Simulation) -> Vec<hpr_sim::batch::LaneResult> {
    use hpr_sim::batch::{Batch, Columns, Status};
    let n = 8;
    let spread = |lo: f64, hi: f64, m: usize| -> Vec<f64> {
        (0..n)
            .map(|i| lo + (hi - lo) * ((i * m) % n) as f64 / (n - 1) as f64)
            .collect()
    };
    use hpr_sim::inputs::Input;
    let (impulse, burn) = (sim.motor().total_impulse_ns(), sim.motor().burn_time_s());
    let times = |c: f64, v: Vec<f64>| v.into_iter().map(|x| c * x).collect();
    let columns = Columns::new(n)
        .with(Input::MotorImpulseNs, times(impulse, spread(0.9, 1.1, 1)))
        .with(Input::MotorBurnTimeS, times(burn, spread(0.97, 1.03, 3)))
        .with(Input::DragScale, spread(0.9, 1.1, 5))
        .with(Input::RailInclinationDeg, spread(84.0, 89.0, 7));
    let batch = Batch::new(sim, None).expect("batch");
    let mut lanes = Vec::new();
    batch
        .run(n, 3, 2, |rows| columns.slice(rows), |l| lanes.push(l))
        .expect("runs");
    assert_eq!(lanes.len(), n);
    for (i, lane) in lanes.iter().enumerate() {
        let single = batch.variant(&columns, i).unwrap().run(&mut ()).unwrap();
        assert_eq!(lane.status, Status::Landed, "variant {i}");
        assert_eq!(lane.metrics, single.metrics, "variant {i}: bit for bit");
    }
    lanes
}
