//! The turning Earth: with a site's latitude the launch frame turns with the Earth at
//! Ω = ω (0, cos φ, sin φ) and the flight feels the Coriolis acceleration −2 Ω × v. Checked
//! against the closed form of a vacuum flight (both the 6-DOF and the descent), and, in air,
//! against what the derivative must add by hand. RocketPy's own measure of it on Calisto is in
//! `calisto.rs`.

use crate::common::*;
use hpr_sim::eom::{self, N3, N6};
use hpr_sim::flight::model::MAX_SHIFTS;
use hpr_sim::flight::{Environment, Parachute, Rail, Simulation};
use hpr_sim::frames;
use hpr_sim::gravity::{earth_rate_n, EARTH_RATE_RAD_S};
use hpr_sim::wind::Wind;
use hpr_sim::{EventKind, Trigger};
use nalgebra::Vector3;

/// The example rocket after burnout in a vacuum under gravity `g` at `latitude_deg`, with a
/// canopy that opens at apogee (no drag in a vacuum: the descent's equations, the same motion).
fn coasting_at(latitude_deg: Option<f64>, g: f64, max_time_s: f64) -> Simulation {
    let env = Environment {
        latitude_deg,
        ..vacuum(g)
    };
    Simulation::new(
        design("example-minimal.json"),
        motor("Cesaroni_I175"),
        env,
        Rail::default(),
    )
    .and_then(|s| s.with_options(options(TIGHT, max_time_s)))
    .and_then(|s| s.with_parachutes(vec![Parachute::new("canopy", 1.0, Trigger::Apogee, 0.0)]))
    .expect("set up")
}

/// The closed form of `v′ = g − 2 Ω × v` (Ω, g constant) from `(p0, v0)`: with k = Ω/|Ω| and
/// R(φ) the turn by φ about k, `v(t) = R(−2ωt) v0 + ∫₀ᵗ R(−2ωu) g du` and `p` its integral.
/// For a vector x = x∥ + x⊥ (along and across k):
/// `∫₀ᵗ R(−2ωu) x du = x∥ t + x⊥ sin 2ωt / 2ω − (k × x) sin² ωt / ω` and
/// `∫₀ᵗ∫₀ˢ R(−2ωu) x du ds = x∥ t²/2 + x⊥ sin² ωt / 2ω² + (k × x)(sin 2ωt / 2ω − t) / 2ω`.
struct Turning {
    k: Vector3<f64>,
    w: f64,
    g: Vector3<f64>,
    p0: Vector3<f64>,
    v0: Vector3<f64>,
}

impl Turning {
    fn parts(&self, x: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let along = self.k * self.k.dot(x);
        (along, x - along, self.k.cross(x))
    }
    fn turn(&self, x: &Vector3<f64>, t: f64) -> Vector3<f64> {
        let (a, c, kx) = self.parts(x);
        let phi = 2.0 * self.w * t;
        a + c * phi.cos() - kx * phi.sin()
    }
    fn once(&self, x: &Vector3<f64>, t: f64) -> Vector3<f64> {
        let (a, c, kx) = self.parts(x);
        let w = self.w;
        let s = (w * t).sin();
        a * t + c * ((2.0 * w * t).sin() / (2.0 * w)) - kx * (s * s / w)
    }
    fn twice(&self, x: &Vector3<f64>, t: f64) -> Vector3<f64> {
        let (a, c, kx) = self.parts(x);
        let w = self.w;
        let s = (w * t).sin();
        a * (0.5 * t * t)
            + c * (s * s / (2.0 * w * w))
            + kx * (((2.0 * w * t).sin() / (2.0 * w) - t) / (2.0 * w))
    }
    fn velocity(&self, t: f64) -> Vector3<f64> {
        self.turn(&self.v0, t) + self.once(&self.g, t)
    }
    fn position(&self, t: f64) -> Vector3<f64> {
        self.p0 + self.once(&self.v0, t) + self.twice(&self.g, t)
    }
    /// The root of `f` near `t` by Newton's method with `df` its derivative.
    fn root(f: impl Fn(f64) -> f64, df: impl Fn(f64) -> f64, mut t: f64) -> f64 {
        for _ in 0..50 {
            t -= f(t) / df(t);
        }
        t
    }
}

#[test]
fn on_a_turning_earth_a_flight_in_a_vacuum_follows_the_closed_form_up_and_down() {
    // Southern hemisphere (Ω has a downward part), thrown up and sideways from 100 m while
    // tumbling; up in the 6-DOF equations, down in the descent's from apogee.
    let latitude = -33.9;
    let probe = coasting_at(Some(latitude), G0, 1e9);
    let t0 = probe.model().burnout_s + 1.0;
    let y0 = state(
        [10.0, 20.0, 100.0],
        [120.0, -70.0, 150.0],
        frames::rail_attitude(70.0, 120.0),
        [3.0, -2.0, 8.0],
    );
    let sim = coasting_at(Some(latitude), G0, t0 + 200.0);
    let f = sim.run_from(&mut (), t0, &y0).expect("flies");
    let ms = mass_at(&sim, t0);
    let r = frames::body_to_inertial(&[y0[6], y0[7], y0[8], y0[9]]);
    let [ox, oy, oz] = earth_rate_n(latitude);
    let omega = Vector3::new(ox, oy, oz);
    let exact = Turning {
        k: omega / omega.norm(),
        w: omega.norm(),
        g: Vector3::new(0.0, 0.0, -G0),
        p0: eom::center_of_mass_position(&y0, &ms, &r),
        v0: eom::center_of_mass_velocity(&y0, &ms, &r),
    };
    let (mut err_p, mut err_v, mut drift) = (0.0f64, 0.0f64, 0.0f64);
    for s in &f.samples {
        let dt = s.t_s - t0;
        err_p = err_p.max((v3(s.position_m) - exact.position(dt)).amax());
        err_v = err_v.max((v3(s.velocity_m_s) - exact.velocity(dt)).amax());
        let still = exact.p0 + exact.v0 * dt + exact.g * (0.5 * dt * dt);
        drift = drift.max((v3(s.position_m) - still).norm());
    }
    let t_apo = Turning::root(
        |t| exact.velocity(t).z,
        |t| exact.g.z - 2.0 * omega.cross(&exact.velocity(t)).z,
        exact.v0.z / G0,
    );
    let t_land = Turning::root(
        |t| exact.position(t).z,
        |t| exact.velocity(t).z,
        2.0 * exact.v0.z / G0,
    );
    let apo = f.event(EventKind::Apogee).expect("apogee");
    let land = f.event(EventKind::Landing).expect("landing");
    let descent = f
        .samples
        .iter()
        .filter(|s| s.t_s > apo.time_s + 1e-9)
        .count();
    eprintln!(
        "turning Earth at {latitude}°, {} samples ({descent} under the canopy): max error of the \
         center's position {err_p:.2e} m, velocity {err_v:.2e} m/s; apogee {:+.2e} s, landing \
         {:+.2e} s against the closed form; Coriolis moved the center by up to {drift:.3} m \
         from the still-Earth parabola",
        f.samples.len(),
        apo.time_s - t0 - t_apo,
        land.time_s - t0 - t_land
    );
    // No drag, no stiffness: the descent takes a few long steps.
    assert!(descent >= 3, "the descent's equations must fly part of it");
    assert!(drift > 5.0, "Coriolis must be felt: {drift} m");
    // Dormand–Prince at rtol 1e-12 on a flight whose solution is not a polynomial: measured
    // 2.1e-10 m, 3.2e-12 m/s, 1.7e-13 s and 4.1e-13 s.
    assert!(err_p <= 1e-9, "position error {err_p} m");
    assert!(err_v <= 1e-10, "velocity error {err_v} m/s");
    assert!((apo.time_s - t0 - t_apo).abs() <= 1e-11);
    assert!((land.time_s - t0 - t_land).abs() <= 1e-11);
}

#[test]
fn the_earth_s_turning_leaves_a_tumbling_body_s_rotation_alone() {
    // Coriolis acts on the whole mass at its center, like gravity: no moment about it. The
    // same tumbling flight with and without the Earth's turning rotates identically.
    let probe = coasting_at(None, 0.0, 1e9);
    let t0 = probe.model().burnout_s + 1.0;
    let y0 = state(
        [0.0, 0.0, 1000.0],
        [300.0, 50.0, 100.0],
        frames::rail_attitude(70.0, 120.0),
        [3.0, -2.0, 8.0],
    );
    let fly = |lat| {
        coasting_at(lat, 0.0, t0 + 3.0)
            .run_from(&mut (), t0, &y0)
            .expect("flies")
    };
    let (still, turning) = (fly(None), fly(Some(60.0)));
    let (a, b) = (
        still.samples.last().unwrap(),
        turning.samples.last().unwrap(),
    );
    let d_omega = (v3(a.omega_rad_s) - v3(b.omega_rad_s)).amax();
    let d_q = (0..4)
        .map(|i| (a.quaternion[i] - b.quaternion[i]).abs())
        .fold(0.0, f64::max);
    let d_p = (v3(a.position_m) - v3(b.position_m)).norm();
    eprintln!(
        "after 3 s tumbling: body rates differ by {d_omega:.2e} rad/s, quaternions by {d_q:.2e}; \
         the center moved {d_p:.4} m (−2Ω×v at 60°: {:.4} m/s² on 320 m/s)",
        2.0 * EARTH_RATE_RAD_S * 320.0
    );
    assert!(d_p > 0.1, "the center must feel it");
    // Both integrate the same rotation; their step sizes differ through the position states.
    assert!(d_omega <= 1e-9 && d_q <= 1e-10);
}

#[test]
fn in_air_the_derivative_adds_the_coriolis_acceleration_of_the_center_of_mass() {
    // The same state in wind at 45° N and with no latitude: the 6-DOF derivative's O
    // acceleration differs by −2 Ω × v_cm (v_cm the center's ground velocity), its angular
    // acceleration not at all; the descent's acceleration by −2 Ω × v.
    let sim = |lat| {
        let env = Environment {
            latitude_deg: lat,
            wind: Wind::constant(7.0, 250.0).unwrap(),
            ..Environment::default()
        };
        Simulation::new(
            design("example-minimal.json"),
            motor("Cesaroni_I175"),
            env,
            Rail::default(),
        )
        .expect("set up")
    };
    let (still, turning) = (sim(None), sim(Some(45.0)));
    let starts = [f64::INFINITY; MAX_SHIFTS];
    let y = state(
        [3.0, -4.0, 600.0],
        [40.0, -25.0, 180.0],
        frames::rail_attitude(75.0, 200.0),
        [0.4, -0.3, 2.0],
    );
    let [ox, oy, oz] = earth_rate_n(45.0);
    let omega = Vector3::new(ox, oy, oz);
    for t in [0.8, 4.0] {
        let (mut a, mut b) = ([0.0; N6], [0.0; N6]);
        still.model().derivative_6dof(&starts, t, &y, &mut a);
        turning.model().derivative_6dof(&starts, t, &y, &mut b);
        let ms = mass_at(&still, t);
        let r = frames::body_to_inertial(&[y[6], y[7], y[8], y[9]]);
        let v_cm = eom::center_of_mass_velocity(&y, &ms, &r);
        let want = -2.0 * omega.cross(&v_cm);
        let got = Vector3::new(b[3] - a[3], b[4] - a[4], b[5] - a[5]);
        let d_wdot = (10..13).map(|k| (b[k] - a[k]).abs()).fold(0.0, f64::max);
        eprintln!(
            "t = {t} s: Coriolis {:.6e} m/s² by hand, the derivative's {:.6e}, off by {:.1e}; \
             angular accelerations off by {d_wdot:.1e} rad/s²",
            want.norm(),
            got.norm(),
            (got - want).norm()
        );
        // The loads are O(100 m/s²): rounding of the sum is 1e-13.
        assert!((got - want).amax() <= 1e-12 * (1.0 + a[5].abs()));
        assert!(want.norm() > 0.02);
        assert!(d_wdot <= 1e-12, "ω̇ moved by {d_wdot}");
        assert_eq!(&a[..3], &b[..3]);
        assert_eq!(&a[6..10], &b[6..10]);
    }
    let yd = [30.0, -20.0, 400.0, 6.0, -9.0, -15.0];
    let (mut a, mut b) = ([0.0; N3], [0.0; N3]);
    let canopies = eom::Canopies {
        cds_m2: 1.2,
        added_air_m3: hpr_sim::CanopyShape::default().added_air_volume_m3(1.2),
    };
    still.model().descent_rates(&canopies, 30.0, &yd, &mut a);
    turning.model().descent_rates(&canopies, 30.0, &yd, &mut b);
    let want = -2.0 * omega.cross(&Vector3::new(yd[3], yd[4], yd[5]));
    for k in 0..3 {
        assert_eq!(a[k], b[k]);
        // Rounding of the sum with the drag and gravity, O(10 m/s²).
        let off = b[k + 3] - a[k + 3] - want[k];
        assert!(
            off.abs() <= 1e-14 * (1.0 + a[k + 3].abs()),
            "descent, axis {k}: {off:e}"
        );
    }
}

#[test]
fn a_latitude_beyond_the_poles_is_refused_with_its_field() {
    for bad in [90.5, -91.0, f64::NAN] {
        let env = Environment {
            latitude_deg: Some(bad),
            ..Environment::default()
        };
        let e = Simulation::new(
            design("example-minimal.json"),
            motor("Cesaroni_I175"),
            env,
            Rail::default(),
        )
        .err()
        .unwrap_or_else(|| panic!("latitude {bad} accepted"));
        assert!(e.to_string().contains("latitude_deg"), "{e}");
    }
}
