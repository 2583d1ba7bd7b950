//! Released mass's checks, each holding the bound `docs/released-mass.md` gives and printing
//! what it measured: the mass properties after a release against the two-body formula, both
//! momenta kept across and after a release in free space, the static margin's jump against
//! the hand calculation, a part falling on the vacuum's parabola and reaching its canopy's
//! terminal speed, and the triggers.

use crate::atmosphere::{AirModel, AirProfile, AirRow, R_AIR_J_KG_K};
use crate::eom::{self, N6};
use crate::events::EventKind;
use crate::flight::{Environment, Integrator, Parachute, Phase, Rail, SimOptions, Simulation};
use crate::frames;
use crate::gravity::Gravity;
use crate::{PartChute, PartTrigger, Release, Trigger};
use hpr_design::mass::{self, point_inertia};
use hpr_design::{motor, Design};
use nalgebra::Vector3;

use crate::reference::testing::{component_mut, design, reference_json, simulation};
use crate::reference::{self, ballast_shift};

/// The worked example: the reference design on its I175 drops its 200 g ballast at 5 s (the
/// burn ends at 2.5 s), in still standard air.
fn dropped_at_5_s() -> Simulation {
    reference::simulation()
        .with_releases(vec![Release::new(Trigger::Time { time_s: 5.0 }, "ballast")])
        .unwrap()
}

fn tight(max_time_s: f64) -> SimOptions {
    SimOptions {
        integrator: Integrator::Adaptive {
            rtol: 1e-13,
            atol_position_m: 1e-13,
            atol_velocity_m_s: 1e-13,
            atol_quaternion: 1e-15,
            atol_rate_rad_s: 1e-13,
        },
        max_time_s,
        keep_samples: true,
    }
}

/// The ballast as the design holds it, and the rocket's mass properties at `t` with every
/// part on board.
fn ballast(sim: &Simulation) -> mass::MassProps {
    let d = sim.design();
    mass::subtree(d, d.component_index("ballast").unwrap())
}

#[test]
fn mass_properties_after_a_release_match_the_two_body_formula() {
    let sim = dropped_at_5_s();
    let flight = sim.run(&mut ()).unwrap();
    assert_eq!(flight.releases[0].time_s, Some(5.0));
    assert!(sim.model().burnout_s < 4.0);
    // The whole (motor out) and the ballast; what remains is the whole less the ballast.
    let whole = sim.mass_properties(&flight, 4.0);
    let b = ballast(&sim);
    let (m, big_m) = (b.mass_kg, whole.mass_kg);
    let rest_m = big_m - m;
    let rest_cg = (whole.cg_m * big_m - b.cg_m * m) / rest_m;
    // Two bodies about their common center: I = I_rest + I_ballast + μ J(d), μ = m M_r / M.
    let mu = m * rest_m / big_m;
    let rest_inertia = whole.inertia_cg - b.inertia_cg - point_inertia(&(b.cg_m - rest_cg)) * mu;
    let just_before = sim.mass_properties(&flight, 5.0 - 1e-9);
    assert_eq!(just_before, whole, "nothing changes until the release");
    let mut worst: f64 = 0.0;
    for t in [5.0, 5.5, 40.0] {
        let p = sim.mass_properties(&flight, t);
        let e_m = (p.mass_kg - rest_m).abs();
        let e_cg = (p.cg_m - rest_cg).amax();
        let e_i = (p.inertia_cg - rest_inertia).amax();
        eprintln!("t = {t} s: mass error {e_m:.1e} kg, center of mass error {e_cg:.1e} m, inertia error {e_i:.1e} kg·m²");
        worst = worst.max(e_m).max(e_cg).max(e_i);
    }
    assert!(worst <= 1e-15, "worst error {worst:e} (bound 1e-15)");
    // The hand figures (the moving-mass page's arithmetic on its rounded figures: the
    // whole 0.8188 kg at 0.6681 m, the ballast 0.2 kg at 0.375 m): what remains weighs
    // 0.6188 kg with its center at 0.7628 m, 0.0947 m aft of the whole's, and its
    // transverse inertia about it is the whole's less the ballast's own less
    // μ (0.7628 − 0.375)² = 0.1511 × 0.3878² = 0.0227 kg·m².
    let hand_rest: f64 = (0.8188 * 0.6681 - 0.2 * 0.375) / 0.6188;
    let hand_mu: f64 = 0.2 * 0.6188 / 0.8188;
    let hand_drop = hand_mu * (hand_rest - 0.375).powi(2);
    assert_eq!(
        format!(
            "{:.4} {hand_rest:.4} {:.4} {hand_drop:.4}",
            0.8188 - 0.2,
            hand_rest - 0.6681
        ),
        "0.6188 0.7628 0.0947 0.0227"
    );
    let after = sim.mass_properties(&flight, 5.5);
    let drop = whole.transverse_inertia() - b.inertia_cg[(1, 1)] - after.transverse_inertia();
    eprintln!(
        "unrounded: {:.6} kg at {:.6} m ({:+.6} m), transverse inertia {:.6} → {:.6} kg·m² (the ballast's own {:.2e}, the rest {drop:.6})",
        after.mass_kg,
        after.cg_m.x,
        after.cg_m.x - whole.cg_m.x,
        whole.transverse_inertia(),
        after.transverse_inertia(),
        b.inertia_cg[(1, 1)]
    );
    for (exact, hand) in [
        (after.mass_kg, 0.6188),
        (after.cg_m.x, hand_rest),
        (after.cg_m.x - whole.cg_m.x, hand_rest - 0.6681),
        (drop, hand_drop),
    ] {
        assert!(
            (exact - hand).abs() < 2e-4,
            "{exact} against the hand's {hand}"
        );
    }
}

#[test]
fn a_release_jumps_the_static_margin_by_the_hand_calculation() {
    let sim = dropped_at_5_s();
    let flight = sim.run(&mut ()).unwrap();
    let d = sim.model().ref_diameter_m;
    let whole = sim.mass_properties(&flight, 4.0);
    let b = ballast(&sim);
    // The center of mass moves m (x_cg − x_b) / (M − m) aft; the center of pressure at Mach 0
    // stays: the margin falls by that over the diameter.
    let cg_jump = b.mass_kg * (whole.cg_m.x - b.cg_m.x) / (whole.mass_kg - b.mass_kg);
    let hand = -cg_jump / d;
    let r = &flight.releases[0];
    let (before, after) = (r.margin_before_cal.unwrap(), r.margin_after_cal.unwrap());
    let e_jump = ((after - before) - hand).abs();
    let e_before = (before - sim.static_margin_for(whole.cg_m.x)).abs();
    // Every coast sample: the margin before up to the release's instant, after it past.
    let mut worst: f64 = 0.0;
    let mut n = 0;
    for s in flight
        .samples
        .iter()
        .filter(|s| s.t_s > sim.model().burnout_s && s.phase == Phase::Free)
    {
        let expected = if s.t_s <= 5.0 { before } else { after };
        worst = worst.max((s.static_margin_cal - expected).abs());
        n += 1;
    }
    eprintln!("static margin {before:.6} → {after:.6} cal: jump off the hand's {hand:.6} by {e_jump:.1e}; before off the whole's by {e_before:.1e}; {n} coast samples within {worst:.1e} cal");
    assert!(e_jump <= 1e-12, "{e_jump:e} (bound 1e-12)");
    assert!(
        e_before <= 1e-12 && worst <= 1e-12,
        "{e_before:e} {worst:e}"
    );
    assert!(n > 20);
    // 4.297 → 2.615 calibres: 0.0947 m over 0.0563 m.
    assert_eq!(
        format!("{before:.3} {after:.3} {:.3} {cg_jump:.4}", after - before),
        "4.297 2.615 -1.683 0.0947"
    );
}

fn free_space() -> Environment {
    Environment {
        gravity: Gravity::constant(0.0).unwrap(),
        vacuum: true,
        ..Environment::default()
    }
}

/// A state in free flight: O at 1 km, moving, tilted, turning about all three axes.
fn tumbling_state() -> [f64; N6] {
    let q = nalgebra::UnitQuaternion::from_euler_angles(0.3, -0.2, 0.5);
    let q = q.quaternion();
    [
        0.0, 0.0, 1000.0, 10.0, -5.0, 50.0, q.w, q.i, q.j, q.k, 0.7, -0.4, 2.0,
    ]
}

/// Total linear momentum and angular momentum about the launch frame's origin of a body
/// whose center is at `pos` moving at `vel`, of mass `m`, with the angular momentum about its
/// own center `h_own` (all inertial).
fn momenta_of(
    m: f64,
    pos: &Vector3<f64>,
    vel: &Vector3<f64>,
    h_own: &Vector3<f64>,
) -> (Vector3<f64>, Vector3<f64>) {
    (vel * m, h_own + pos.cross(&(vel * m)))
}

#[test]
fn a_part_released_off_the_axis_keeps_both_momenta_in_free_space() {
    // The ballast 1 cm off the axis, dropped at 5 s while the rocket turns about all three
    // axes in free space (no gravity, no air): nothing acts on either body, so the rocket's
    // and the part's momenta add up to the whole's before, at every instant after.
    let mut v = reference_json();
    let bj = component_mut(&mut v, "ballast");
    bj["radial_offset_m"] = serde_json::json!(0.01);
    bj["radius_m"] = serde_json::json!(0.015);
    let sim = simulation(design(&v), free_space(), tight(6.5))
        .with_releases(vec![Release::new(Trigger::Time { time_s: 5.0 }, "ballast")])
        .unwrap();
    let flight = sim.run_from(&mut (), 4.5, &tumbling_state()).unwrap();
    let t_r = flight.releases[0].time_s.unwrap();
    assert_eq!(t_r, 5.0);
    let model = sim.model();
    let pre = {
        let mut s = flight.starts();
        s[0] = f64::INFINITY;
        s
    };
    let post = flight.starts();
    // The rocket's momenta at a sample (before the release: the whole's).
    let rocket = |s: &crate::flight::Sample| {
        let ms = model
            .instant(if s.t_s <= t_r { &pre } else { &post }, s.t_s)
            .mass;
        let mut y = [0.0; N6];
        y[6..10].copy_from_slice(&s.quaternion);
        y[10..13].copy_from_slice(&s.omega_rad_s);
        let r = frames::body_to_inertial(&s.quaternion);
        let h = eom::angular_momentum_about_cm(&y, &ms, &r);
        momenta_of(
            ms.mass_kg,
            &Vector3::from(s.position_m),
            &Vector3::from(s.velocity_m_s),
            &h,
        )
    };
    let (p0, h0) = rocket(&flight.samples[0]);
    // The part: its center and velocity where it left, and its own spin's angular momentum,
    // R I_own ω at the release, which no torque changes afterwards.
    let part = flight.releases[0].part.as_ref().unwrap();
    let at_release = flight.samples.iter().find(|s| s.t_s == t_r).unwrap();
    let released = &model.mass.released[0];
    let r_release = frames::body_to_inertial(&at_release.quaternion);
    let spin = r_release * (released.inertia_cg_b * Vector3::from(at_release.omega_rad_s));
    let part_momenta = |pos: [f64; 3], vel: [f64; 3]| {
        momenta_of(
            part.mass_kg,
            &Vector3::from(pos),
            &Vector3::from(vel),
            &spin,
        )
    };
    let (pp, hp) = part_momenta(part.start_position_m, part.start_velocity_m_s);
    // Across the release: the rocket that remains, at the release's state, plus the part.
    let (y_o, ms_pre, ms_post) = {
        let s = at_release;
        let r = frames::body_to_inertial(&s.quaternion);
        let ms_pre = model.instant(&pre, t_r).mass;
        let w = Vector3::from(s.omega_rad_s);
        let o = Vector3::from(s.position_m) - r * ms_pre.r_cm;
        let v_o = Vector3::from(s.velocity_m_s) - r * (w.cross(&ms_pre.r_cm) + ms_pre.r_cm_rate);
        let mut y = [0.0; N6];
        y[0..3].copy_from_slice(o.as_slice());
        y[3..6].copy_from_slice(v_o.as_slice());
        y[6..10].copy_from_slice(&s.quaternion);
        y[10..13].copy_from_slice(&s.omega_rad_s);
        (y, ms_pre, model.instant(&post, t_r).mass)
    };
    let whole_vs_two = {
        let r = frames::body_to_inertial(&at_release.quaternion);
        let of = |ms: &eom::MassState| {
            momenta_of(
                ms.mass_kg,
                &eom::center_of_mass_position(&y_o, ms, &r),
                &eom::center_of_mass_velocity(&y_o, ms, &r),
                &eom::angular_momentum_about_cm(&y_o, ms, &r),
            )
        };
        let (pw, hw) = of(&ms_pre);
        let (pr, hr) = of(&ms_post);
        (
            (pr + pp - pw).norm() / pw.norm(),
            (hr + hp - hw).norm() / hw.norm(),
        )
    };
    // After: every sample of the rocket plus the part (whose own samples keep theirs).
    let (mut ep, mut eh, mut after) = (0.0f64, 0.0f64, 0);
    for s in &flight.samples {
        let (p, h) = rocket(s);
        let (p, h) = if s.t_s > t_r {
            after += 1;
            (p + pp, h + hp)
        } else {
            (p, h)
        };
        ep = ep.max((p - p0).norm() / p0.norm());
        eh = eh.max((h - h0).norm() / h0.norm());
    }
    let mut part_drift: f64 = 0.0;
    for s in &part.samples {
        let (p, h) = part_momenta(s.position_m, s.velocity_m_s);
        part_drift = part_drift.max((p - pp).norm() / p0.norm());
        part_drift = part_drift.max((h - hp).norm() / h0.norm());
    }
    eprintln!(
        "across the release: linear momentum kept to {:.1e}, angular to {:.1e} of itself; over {} samples ({after} after): linear {ep:.1e}, angular {eh:.1e}; the part's own {} samples {part_drift:.1e}; the part carries {:.1}% of the angular momentum ({:.2}% in its own spin)",
        whole_vs_two.0,
        whole_vs_two.1,
        flight.samples.len(),
        part.samples.len(),
        100.0 * hp.norm() / h0.norm(),
        100.0 * spin.norm() / h0.norm(),
    );
    assert!(
        whole_vs_two.0 <= 1e-15 && whole_vs_two.1 <= 1e-15,
        "{whole_vs_two:?}"
    );
    assert!(ep <= 1e-12, "linear momentum {ep:e} (bound 1e-12)");
    assert!(eh <= 1e-12, "angular momentum {eh:e} (bound 1e-12)");
    assert!(part_drift <= 1e-12, "{part_drift:e}");
    assert!(after > 20 && part.samples.len() > 2);
    // The test means something: the part takes a fair share of the angular momentum away.
    assert!(hp.norm() > 1e-2 * h0.norm(), "{}", hp.norm() / h0.norm());
}

#[test]
fn a_part_released_at_apogee_in_a_vacuum_falls_on_the_closed_form_parabola() {
    // A rail 80° up toward the north-east: in a vacuum the rocket coasts along a parabola
    // with its attitude fixed, and at apogee still moves sideways.
    let env = Environment {
        vacuum: true,
        ..Environment::default()
    };
    let g = env.gravity.at(0.0);
    let rail = Rail {
        length_m: 2.0,
        inclination_deg: 80.0,
        heading_deg: 45.0,
    };
    let sim = Simulation::new(
        design(&reference_json()),
        motor::find("Cesaroni_I175").unwrap(),
        env,
        rail,
    )
    .unwrap()
    .with_options(SimOptions {
        max_time_s: 200.0,
        ..SimOptions::default()
    })
    .unwrap()
    .with_releases(vec![Release::new(Trigger::Apogee, "ballast")])
    .unwrap();
    let flight = sim.run(&mut ()).unwrap();
    let apogee = flight.event(EventKind::Apogee).unwrap();
    assert_eq!(flight.releases[0].time_s, Some(apogee.time_s));
    let part = flight.releases[0].part.as_ref().unwrap();
    let (t0, p0, v0) = (
        apogee.time_s,
        Vector3::from(part.start_position_m),
        Vector3::from(part.start_velocity_m_s),
    );
    let on_parabola = |t: f64| {
        let tau = t - t0;
        p0 + v0 * tau - Vector3::new(0.0, 0.0, 0.5 * g * tau * tau)
    };
    let worst = part
        .samples
        .iter()
        .map(|s| (Vector3::from(s.position_m) - on_parabola(s.t_s)).norm())
        .fold(0.0, f64::max);
    let tau_land = (v0.z + (v0.z * v0.z + 2.0 * g * p0.z).sqrt()) / g;
    let landing = part.landing_position_m.unwrap();
    let hand = on_parabola(t0 + tau_land);
    let e_time = (part.landing_time_s.unwrap() - (t0 + tau_land)).abs();
    let e_point = (landing[0] - hand.x).hypot(landing[1] - hand.y);
    let e_speed = (part.landing_speed_m_s.unwrap()
        - (v0 + Vector3::new(0.0, 0.0, -g * tau_land)).norm())
    .abs();
    eprintln!(
        "released at {:.1} m moving {:.2} m/s sideways; {} samples within {worst:.1e} m of the parabola; landing {e_time:.1e} s, {e_point:.1e} m, {e_speed:.1e} m/s off",
        p0.z,
        v0.xy().norm(),
        part.samples.len()
    );
    assert!(v0.xy().norm() > 10.0, "the part moves sideways");
    assert!(part.samples.len() >= 3);
    assert!(worst <= 1e-9, "{worst:e} m (bound 1e-9)");
    assert!(e_point <= 1e-9 && e_time <= 1e-9 && e_speed <= 1e-9);
}

/// Still air of one density at every height: the temperature falling at g₀/R (34.16 K/km,
/// the autoconvective lapse rate) keeps p/T, and so the density, the same as the pressure
/// falls, so that a terminal speed is one speed all the way down.
fn constant_density_air() -> (AirModel, f64) {
    let (t0, p0) = (288.15, 101_325.0);
    let top_m = 4000.0;
    let geopotential = crate::atmosphere::geopotential_altitude_m(top_m);
    let t_top = t0 - crate::atmosphere::G0_M_S2 / R_AIR_J_KG_K * geopotential;
    let air = AirModel::Profile(std::sync::Arc::new(AirProfile {
        elevation_m: 0.0,
        pressure_pa: p0,
        rows: vec![
            AirRow {
                height_m: 0.0,
                temperature_k: t0,
                pressure_pa: None,
            },
            AirRow {
                height_m: top_m,
                temperature_k: t_top,
                pressure_pa: None,
            },
        ],
    }));
    (air, p0 / (R_AIR_J_KG_K * t0))
}

#[test]
fn a_part_under_its_own_parachute_reaches_its_terminal_speed_at_the_ground() {
    let (air, rho) = constant_density_air();
    let env = Environment {
        air,
        ..Environment::default()
    };
    let g = env.gravity.at(0.0);
    let cds = 0.3;
    // On the steady descent the error control holds the speed within about its velocity
    // tolerance of the terminal speed (1e-4 m/s by default, 4e-5 of it here): tolerances of
    // 1e-10 hold it within the bound.
    let options = SimOptions {
        integrator: Integrator::Adaptive {
            rtol: 1e-10,
            atol_position_m: 1e-10,
            atol_velocity_m_s: 1e-10,
            atol_quaternion: 1e-12,
            atol_rate_rad_s: 1e-10,
        },
        max_time_s: 2000.0,
        keep_samples: false,
    };
    let sim = simulation(design(&reference_json()), env, options)
        .with_releases(vec![Release::new(Trigger::Apogee, "ballast")
            .with_parachute(PartChute::new(cds, PartTrigger::Release, 2.0))])
        .unwrap();
    let flight = sim.run(&mut ()).unwrap();
    let density_spread = [0.0, 500.0, 1000.0, 1500.0]
        .map(|h| (sim.model().air.at_msl(h).density_kg_m3 - rho).abs() / rho)
        .into_iter()
        .fold(0.0, f64::max);
    let r = &flight.releases[0];
    let part = r.part.as_ref().unwrap();
    assert_eq!(part.chute_open_s, Some(r.time_s.unwrap() + 2.0));
    let terminal = (2.0 * part.mass_kg * g / (rho * cds)).sqrt();
    let landed = part.landing_speed_m_s.unwrap();
    let e = (landed - terminal).abs() / terminal;
    eprintln!(
        "the air's density within {density_spread:.1e} of {rho:.6} kg/m³ up to 1.5 km; released at {:.1} m, canopy open at {:.2} s, landed at {:.2} s at {landed:.9} m/s; terminal {terminal:.9} m/s; off by {e:.1e} of itself",
        part.start_position_m[2],
        part.chute_open_s.unwrap(),
        part.landing_time_s.unwrap()
    );
    assert!(density_spread <= 1e-12, "{density_spread:e}");
    assert!(e <= 1e-6, "{e:e} (bound 1e-6)");
}

#[test]
fn a_release_fires_at_its_trigger() {
    // Apogee, a height on the way down, burnout and burnout plus a delay, each dropping a
    // part of its own (the rocket under no canopy, so that every one fires in free flight).
    let mut v = reference_json();
    let children = component_mut(&mut v, "body")["children"]
        .as_array_mut()
        .unwrap();
    for (id, x) in [("weight_a", 0.42), ("weight_b", 0.46)] {
        children.push(serde_json::json!({
            "id": id, "type": "mass_component", "mass_kg": 0.03, "length_m": 0.02, "radius_m": 0.01,
            "position": { "from": "nose_tip", "offset_m": x }
        }));
    }
    let sim = simulation(design(&v), Environment::default(), SimOptions::default())
        .with_releases(vec![
            Release::new(Trigger::Apogee, "ballast"),
            Release::new(Trigger::HeightDescending { height_m: 200.0 }, "avionics"),
            Release::new(Trigger::Burnout, "weight_a"),
            Release::new(Trigger::BurnoutPlusDelay { delay_s: Some(2.0) }, "weight_b"),
        ])
        .unwrap();
    let flight = sim.run(&mut ()).unwrap();
    let apogee = flight.event(EventKind::Apogee).unwrap();
    let burnout = sim.model().burnout_s;
    let at = |j: usize| flight.event(EventKind::Release(j)).unwrap();
    eprintln!(
        "apogee at {:.6} s; releases at {:?}; heights {:.9} m",
        apogee.time_s,
        flight
            .releases
            .iter()
            .map(|r| r.time_s.unwrap())
            .collect::<Vec<_>>(),
        at(1).altitude_m
    );
    assert_eq!(at(0).time_s, apogee.time_s);
    assert!((at(1).altitude_m - 200.0).abs() <= 1e-6);
    assert_eq!(at(2).time_s, burnout);
    assert_eq!(at(3).time_s, burnout + 2.0);
    // Each part landed, and the rocket weighs what is left.
    let end = flight.metrics.landing_time_s.unwrap();
    let parts: f64 = flight
        .releases
        .iter()
        .map(|r| r.part.as_ref().unwrap().mass_kg)
        .sum();
    let whole = sim.mass_properties(&flight, burnout - 1e-9).mass_kg
        - sim.model().motor.eval(burnout - 1e-9).propellant_kg;
    assert!((sim.mass_properties(&flight, end).mass_kg - (whole - parts)).abs() < 1e-12);
    for r in &flight.releases {
        let p = r.part.as_ref().unwrap();
        assert!(p.landing_time_s.unwrap() > r.time_s.unwrap());
        assert!(p.landing_speed_m_s.unwrap() > 0.0);
    }
}

#[test]
fn a_part_moved_then_released_leaves_from_where_its_move_left_it() {
    // The ballast slides 0.3 m aft over 1 s from 5 s, and leaves at 7 s: what remains is the
    // whole less the ballast where it ended, and the part leaves from there.
    let sim = reference::simulation()
        .with_shifts(vec![ballast_shift(5.0)])
        .unwrap()
        .with_releases(vec![Release::new(Trigger::Time { time_s: 7.0 }, "ballast")])
        .unwrap();
    let flight = sim.run(&mut ()).unwrap();
    let moved = sim.mass_properties(&flight, 6.5);
    let after = sim.mass_properties(&flight, 7.5);
    let b = ballast(&sim);
    let c = b.cg_m + Vector3::new(0.3, 0.0, 0.0);
    let rest_m = moved.mass_kg - b.mass_kg;
    let rest_cg = (moved.cg_m * moved.mass_kg - c * b.mass_kg) / rest_m;
    let mu = b.mass_kg * rest_m / moved.mass_kg;
    let rest_inertia = moved.inertia_cg - b.inertia_cg - point_inertia(&(c - rest_cg)) * mu;
    let e = (after.cg_m - rest_cg)
        .amax()
        .max((after.inertia_cg - rest_inertia).amax())
        .max((after.mass_kg - rest_m).abs());
    // The part's start: its moved center in the launch frame, at the release's sample.
    let s = flight.samples.iter().find(|s| s.t_s == 7.0).unwrap();
    let r = frames::body_to_inertial(&s.quaternion);
    let mut moved_only = flight.starts();
    moved_only[1] = f64::INFINITY;
    let ms = sim.model().instant(&moved_only, 7.0).mass;
    let o = Vector3::from(s.position_m) - r * ms.r_cm;
    let start = o + r * frames::station_to_body(&c);
    let part = flight.releases[0].part.as_ref().unwrap();
    let e_start = (Vector3::from(part.start_position_m) - start).norm();
    eprintln!("what remains off the two-body formula by {e:.1e}; the part's start off its moved center by {e_start:.1e} m");
    assert!(e <= 1e-15, "{e:e}");
    assert!(e_start <= 1e-12, "{e_start:e}");
}

#[test]
fn a_part_released_under_the_rocket_s_canopy_leaves_from_its_center_and_lightens_it() {
    // Under the drogue from apogee, the ballast drops at 300 m: the rocket descends lighter,
    // and the part leaves from the rocket's center with its velocity (the descent knows no
    // attitude: the rocket is a point there).
    let base = || {
        reference::simulation()
            .with_parachutes(vec![Parachute::new("drogue", 0.1, Trigger::Apogee, 1.0)])
            .unwrap()
    };
    let kept = base().run(&mut ()).unwrap();
    let sim = base()
        .with_releases(vec![Release::new(
            Trigger::HeightDescending { height_m: 300.0 },
            "ballast",
        )
        .with_cda(0.002)])
        .unwrap();
    let flight = sim.run(&mut ()).unwrap();
    let ev = flight.event(EventKind::Release(0)).unwrap();
    let s = flight.samples.iter().find(|s| s.t_s == ev.time_s).unwrap();
    assert_eq!(s.phase, Phase::Descent);
    let part = flight.releases[0].part.as_ref().unwrap();
    assert_eq!(part.start_position_m, s.position_m);
    assert_eq!(part.start_velocity_m_s, s.velocity_m_s);
    assert!((ev.altitude_m - 300.0).abs() < 1e-6);
    let later = flight.samples.iter().find(|s| s.t_s > ev.time_s).unwrap();
    assert!((later.mass_kg - (s.mass_kg - 0.2)).abs() < 1e-12);
    // Lighter under the same canopy: slower, so later to the ground; the ballast, falling
    // free, first.
    let (t_kept, t_light) = (
        kept.metrics.landing_time_s.unwrap(),
        flight.metrics.landing_time_s.unwrap(),
    );
    let t_part = part.landing_time_s.unwrap();
    eprintln!("rocket lands at {t_kept:.2} s with its ballast, {t_light:.2} s without; the ballast at {t_part:.2} s, {:.1} m/s", part.landing_speed_m_s.unwrap());
    assert!(t_light > t_kept && t_part < t_kept);
}

#[test]
fn a_part_s_canopy_opens_at_its_own_apogee_or_height() {
    // Released at 5 s while climbing, one part's canopy opens at its own apogee and another's
    // at 150 m on its way down, each a second after its trigger.
    let mut v = reference_json();
    component_mut(&mut v, "body")["children"]
        .as_array_mut()
        .unwrap()
        .push(serde_json::json!({
            "id": "payload", "type": "mass_component", "mass_kg": 0.05, "length_m": 0.04, "radius_m": 0.02,
            "position": { "from": "nose_tip", "offset_m": 0.45 }
        }));
    let sim =
        simulation(design(&v), Environment::default(), SimOptions::default())
            .with_releases(vec![
                Release::new(Trigger::Time { time_s: 5.0 }, "ballast")
                    .with_parachute(PartChute::new(0.2, PartTrigger::Apogee, 1.0)),
                Release::new(Trigger::Time { time_s: 5.0 }, "payload").with_parachute(
                    PartChute::new(0.1, PartTrigger::HeightDescending { height_m: 150.0 }, 1.0),
                ),
            ])
            .unwrap();
    let flight = sim.run(&mut ()).unwrap();
    let a = flight.releases[0].part.as_ref().unwrap();
    let b = flight.releases[1].part.as_ref().unwrap();
    // The part's apogee: its own samples' highest; the canopy opens a second after it.
    let top = a
        .samples
        .iter()
        .max_by(|x, y| x.position_m[2].total_cmp(&y.position_m[2]))
        .unwrap();
    assert!(top.velocity_m_s[2].abs() < 1e-9, "{:?}", top.velocity_m_s);
    assert_eq!(top.position_m[2], a.apogee_m);
    assert_eq!(a.chute_open_s, Some(top.t_s + 1.0));
    let at_150 = b
        .samples
        .iter()
        .find(|s| (s.position_m[2] - 150.0).abs() < 1e-6)
        .expect("a sample at 150 m");
    assert_eq!(b.chute_open_s, Some(at_150.t_s + 1.0));
    eprintln!(
        "ballast: apogee {:.2} m at {:.3} s, canopy {:.3} s, lands {:.2} m/s; payload: 150 m at {:.3} s, canopy {:.3} s, lands {:.2} m/s",
        a.apogee_m,
        top.t_s,
        a.chute_open_s.unwrap(),
        a.landing_speed_m_s.unwrap(),
        at_150.t_s,
        b.chute_open_s.unwrap(),
        b.landing_speed_m_s.unwrap()
    );
}

#[test]
fn a_part_s_drag_area_comes_from_the_release_the_design_or_its_size() {
    // The ballast: 50 mm long, 40 mm across, tumbling with 0.56 × 0.05 × 0.04 m².
    let sim = |v: &serde_json::Value, release: Release| {
        simulation(design(v), Environment::default(), SimOptions::default())
            .with_releases(vec![release])
            .unwrap()
            .release_plan()
            .cda_m2[0]
    };
    let plain = reference_json();
    let estimate = sim(&plain, Release::new(Trigger::Apogee, "ballast"));
    assert_eq!(estimate, super::TUMBLE_CD * 0.05 * 0.04);
    let mut given = reference_json();
    component_mut(&mut given, "ballast")["released_cda_m2"] = serde_json::json!(0.003);
    assert_eq!(sim(&given, Release::new(Trigger::Apogee, "ballast")), 0.003);
    assert_eq!(
        sim(
            &given,
            Release::new(Trigger::Apogee, "ballast").with_cda(0.004)
        ),
        0.004,
        "the release's own comes first"
    );
    // The design's field is an internal part's, positive and finite.
    let mut bad = reference_json();
    component_mut(&mut bad, "ballast")["released_cda_m2"] = serde_json::json!(-1.0);
    let e = Design::from_json_str(&bad.to_string(), None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("released_cda_m2") && e.contains("ballast"),
        "{e}"
    );
    let mut on_body = reference_json();
    component_mut(&mut on_body, "body")["released_cda_m2"] = serde_json::json!(0.01);
    let e = Design::from_json_str(&on_body.to_string(), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("released_cda_m2"), "{e}");
    eprintln!("estimate {estimate:.5} m²; refused on a body tube: {e}");
}

#[test]
fn a_fixed_step_flight_flies_its_released_part_to_the_same_ground() {
    // RK4 at 10 ms against the adaptive default: the part's own descent is stepped by the
    // flight's integrator too, and lands where the adaptive one does.
    let fly = |integrator: Integrator| {
        let sim = simulation(
            design(&reference_json()),
            Environment {
                wind: crate::wind::Wind::constant(5.0, 270.0).unwrap(),
                ..Environment::default()
            },
            SimOptions {
                integrator,
                ..SimOptions::default()
            },
        )
        .with_releases(vec![Release::new(Trigger::Apogee, "ballast")
            .with_parachute(PartChute::new(0.3, PartTrigger::Release, 1.0))])
        .unwrap();
        let f = sim.run(&mut ()).unwrap();
        let p = f.releases[0].part.clone().unwrap();
        (
            p.landing_time_s.unwrap(),
            p.landing_position_m.unwrap(),
            p.samples.len(),
        )
    };
    let (t_a, [xa, ya], _) = fly(Integrator::DEFAULT);
    let (t_f, [xf, yf], steps) = fly(Integrator::Rk4 { step_s: 0.01 });
    let moved = (xa - xf).hypot(ya - yf);
    eprintln!("adaptive lands at {t_a:.3} s, ({xa:.2}, {ya:.2}) m; RK4 at 10 ms ({steps} samples) {:.1e} s later, {moved:.1e} m away", t_f - t_a);
    assert!(steps > 10_000, "RK4 steps the part's descent: {steps}");
    assert!(
        (t_a - t_f).abs() < 1e-3 && moved < 1e-2,
        "{t_a} {t_f} {moved}"
    );
}
