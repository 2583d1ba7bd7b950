//! A rocket that really flew: EPFL's Bella Lui (Kaltbrunn, 2020-02-22), flown from
//! `scenarios/bella_lui.toml` in its day's ERA5 weather, against its flight computer's log
//! (`validation/real-flights/bella-lui/`) and against RocketPy flying the same set-up
//! (`validation/rocketpy/bella_lui.py`, its record `bella_lui_reference.json`).
//!
//! The figures are RocketPy's acceptance test's (`tests/acceptance/test_bella_lui_rocket.py`
//! in RocketPy-Team/RocketPy), each within its bound there: apogee (1.5 %), apogee time
//! (2 %), maximum vertical speed (6 %), maximum acceleration (5 %, against the smoothed
//! derivative of the measured speed), speed at touchdown (30 %); and the whole climb: the RMS
//! and the worst difference of height from liftoff to apogee.
//!
//! Heights are rises above the start, as the log's barometric height is (zeroed on the pad)
//! and as RocketPy's are (its center of dry mass starts at the site's elevation): hpr-mc's
//! altitude is its center of mass's above the ground, 1.10 m at the start on the rail.
//!
//! The clocks: the log's first row is not ignition (the rocket already climbs at 5 m/s, 0.2 m
//! up). Times are compared two ways: on the log's clock taken as the flight's (as RocketPy's
//! test does), and with the clocks aligned where the rocket has risen the log's first height
//! (0.201 m), an event both see.

use hpr_mc::campaign::{Prepared, Scenario};
use hpr_sim::flight::Flight;
use serde_json::Value;
use std::path::Path;

fn repo(path: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// The flight computer's log: (time s, height above the pad m, vertical speed m/s).
fn log() -> Vec<[f64; 3]> {
    let text = std::fs::read_to_string(repo(
        "validation/real-flights/bella-lui/bella_lui_flight_data_filtered.csv",
    ))
    .unwrap();
    text.lines()
        .skip(1)
        .map(|l| {
            let c: Vec<f64> = l.split(',').map(|x| x.trim().parse().unwrap()).collect();
            [c[2], c[3], c[4]]
        })
        .collect()
}

fn reference() -> Value {
    let text =
        std::fs::read_to_string(repo("validation/rocketpy/bella_lui_reference.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn num(v: &Value, path: &str) -> f64 {
    v.pointer(path)
        .and_then(Value::as_f64)
        .unwrap_or_else(|| panic!("{path}"))
}

/// The nominal flight of `scenarios/bella_lui.toml`, with its samples.
fn nominal() -> Flight {
    let scenario = Scenario::load(&repo("scenarios/bella_lui.toml")).unwrap();
    let prepared = Prepared::new(scenario).unwrap();
    prepared.nominal_flight(0).unwrap().run(&mut ()).unwrap()
}

/// A flight's height above its start and vertical speed at `t`, cubic (Hermite) between
/// samples: exact to the fourth order in the step.
fn rise_at(f: &Flight, t: f64) -> (f64, f64) {
    let s = &f.samples;
    let z0 = s[0].altitude_m;
    let k = s.partition_point(|x| x.t_s <= t).clamp(1, s.len() - 1);
    let (a, b) = (&s[k - 1], &s[k]);
    let h = b.t_s - a.t_s;
    let u = ((t - a.t_s) / h).clamp(0.0, 1.0);
    let (za, zb, va, vb) = (
        a.altitude_m,
        b.altitude_m,
        a.velocity_m_s[2],
        b.velocity_m_s[2],
    );
    let (h00, h10, h01, h11) = (
        2.0 * u.powi(3) - 3.0 * u * u + 1.0,
        u.powi(3) - 2.0 * u * u + u,
        -2.0 * u.powi(3) + 3.0 * u * u,
        u.powi(3) - u * u,
    );
    let z = h00 * za + h10 * h * va + h01 * zb + h11 * h * vb;
    let v = va + (vb - va) * u;
    (z - z0, v)
}

/// The first time after `after` at which the flight's rise crosses `height` going the way
/// `up` says, found by bisection on [`rise_at`].
fn time_at_rise(f: &Flight, height: f64, after: f64, up: bool) -> f64 {
    let s = &f.samples;
    let z0 = s[0].altitude_m;
    let k = s
        .iter()
        .position(|x| x.t_s > after && ((x.altitude_m - z0 >= height) == up))
        .unwrap();
    let (mut lo, mut hi) = (s[k - 1].t_s.max(after), s[k].t_s);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if (rise_at(f, mid).0 >= height) == up {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

/// What RocketPy's acceptance test compares, of a simulated flight.
struct Figures {
    apogee_m: f64,
    apogee_time_s: f64,
    max_vertical_speed_m_s: f64,
    max_acceleration_m_s2: f64,
    touchdown_time_s: f64,
    touchdown_vertical_speed_m_s: f64,
}

fn figures(f: &Flight) -> Figures {
    let z0 = f.samples[0].altitude_m;
    let apogee_time_s = f.metrics.apogee_time_s.unwrap();
    let touchdown = time_at_rise(f, 0.0, apogee_time_s, false);
    Figures {
        apogee_m: f.metrics.apogee_m.unwrap() - z0,
        apogee_time_s,
        max_vertical_speed_m_s: f
            .samples
            .iter()
            .map(|s| s.velocity_m_s[2])
            .fold(f64::MIN, f64::max),
        // The acceleration's magnitude: the rocket climbs within a degree of vertical while
        // it burns, where the largest is (its vertical part is 1.5e-4 less).
        max_acceleration_m_s2: f.metrics.max_accel_m_s2,
        touchdown_time_s: touchdown,
        touchdown_vertical_speed_m_s: rise_at(f, touchdown).1,
    }
}

#[test]
fn bella_lui_flown_in_its_weather_meets_rocketpy_s_acceptance_bounds_against_its_flight_computer() {
    let f = nominal();
    let ours = figures(&f);
    let r = reference();
    let m = &r["measured"];
    let rp = &r["rocketpy"];
    let log = log();
    // The clocks aligned where the rocket has risen the log's first height (0.201 m).
    let offset_s = time_at_rise(&f, log[0][1], 0.0, true) - log[0][0];
    let rel = |sim: f64, measured: f64| (sim - measured) / measured;
    let rows = [
        (
            "apogee, m",
            ours.apogee_m,
            num(rp, "/apogee_agl_m"),
            num(m, "/apogee_agl_m"),
            0.015,
        ),
        (
            "apogee time, s (log's clock)",
            ours.apogee_time_s,
            num(rp, "/apogee_time_s"),
            num(m, "/apogee_time_s"),
            0.02,
        ),
        (
            "apogee time, s (clocks aligned)",
            ours.apogee_time_s - offset_s,
            f64::NAN,
            num(m, "/apogee_time_s"),
            0.02,
        ),
        (
            "max vertical speed, m/s",
            ours.max_vertical_speed_m_s,
            num(rp, "/max_vertical_speed_m_s"),
            num(m, "/max_vertical_speed_m_s"),
            0.06,
        ),
        (
            "max acceleration, m/s²",
            ours.max_acceleration_m_s2,
            num(rp, "/max_vertical_acceleration_m_s2"),
            num(m, "/max_acceleration_smoothed_m_s2"),
            0.05,
        ),
        (
            "touchdown vertical speed, m/s",
            -ours.touchdown_vertical_speed_m_s,
            -num(rp, "/impact_vertical_speed_m_s"),
            -num(m, "/touchdown_vertical_speed_m_s"),
            0.30,
        ),
        (
            "touchdown time, s (clocks aligned)",
            ours.touchdown_time_s - offset_s,
            f64::NAN,
            num(m, "/touchdown_time_s"),
            0.05,
        ),
    ];
    eprintln!("clock offset: the log's 0 s is the flight's {offset_s:.4} s");
    eprintln!(
        "{:36} {:>9} {:>9} {:>9} {:>8} {:>8} {:>6}",
        "figure", "measured", "RocketPy", "hpr-mc", "RocketPy", "hpr-mc", "bound"
    );
    for (name, sim, rocketpy, measured, bound) in rows {
        eprintln!(
            "{name:36} {measured:9.3} {rocketpy:9.3} {sim:9.3} {:+7.2}% {:+7.2}% {:5.1}%",
            100.0 * rel(rocketpy, measured),
            100.0 * rel(sim, measured),
            100.0 * bound
        );
        assert!(
            rel(sim, measured).abs() < bound,
            "{name}: hpr-mc {sim}, measured {measured}, bound {bound}"
        );
    }
    // The whole climb, liftoff to apogee: the log's heights against the flight's at the
    // same (aligned) times.
    let apogee_log_s = num(m, "/apogee_time_s");
    let climb: Vec<f64> = log
        .iter()
        .filter(|r| r[0] <= apogee_log_s)
        .map(|r| rise_at(&f, r[0] + offset_s).0 - r[1])
        .collect();
    let rms = (climb.iter().map(|d| d * d).sum::<f64>() / climb.len() as f64).sqrt();
    let worst = climb.iter().fold(0.0f64, |w, d| w.max(d.abs()));
    let unaligned: Vec<f64> = log
        .iter()
        .filter(|r| r[0] <= apogee_log_s)
        .map(|r| rise_at(&f, r[0]).0 - r[1])
        .collect();
    let rms_unaligned =
        (unaligned.iter().map(|d| d * d).sum::<f64>() / unaligned.len() as f64).sqrt();
    eprintln!(
        "climb ({} rows of the log, liftoff to apogee): height RMS {rms:.2} m, worst {worst:.2} m (clocks aligned); RMS {rms_unaligned:.2} m on the log's clock",
        climb.len()
    );
    // A flight within 1.5 % of the apogee (7 m) and 2 % in time climbs within that of the
    // log all the way: RMS below 4 m, nowhere more than 8 m.
    assert!(rms < 4.0 && worst < 8.0, "RMS {rms} m, worst {worst} m");
}

#[test]
fn bella_lui_flown_by_hpr_mc_and_by_rocketpy_corrected_agree_to_a_tenth_of_a_percent() {
    // RocketPy 1.13 with its lever arm's sign and its speed of sound corrected
    // (validation/rocketpy/corrections.py), the same set-up, the same ERA5 file: the two
    // differ only in how they interpolate the air's pressure between the file's levels
    // (RocketPy linearly, hpr-mc hydrostatically: 4e-4 of the density at most) and in
    // hpr-mc's reading of the drag at the airframe's point at the center of mass.
    let f = nominal();
    let ours = figures(&f);
    let rp = &reference()["corrected"];
    let close = [
        ("apogee", ours.apogee_m, num(rp, "/apogee_agl_m"), 1e-3),
        (
            "apogee time",
            ours.apogee_time_s,
            num(rp, "/apogee_time_s"),
            1e-3,
        ),
        (
            "max vertical speed",
            ours.max_vertical_speed_m_s,
            num(rp, "/max_vertical_speed_m_s"),
            1e-3,
        ),
        (
            "rail exit speed",
            f.metrics.rail_exit_speed_m_s.unwrap(),
            num(rp, "/rail_exit_speed_m_s"),
            1e-3,
        ),
        (
            "static margin at liftoff",
            f.metrics.static_margin_liftoff_cal.unwrap(),
            num(rp, "/static_margin_at_liftoff_cal"),
            1e-3,
        ),
    ];
    for (name, a, b, tol) in close {
        let d = (a - b) / b;
        eprintln!(
            "{name}: hpr-mc {a:.4}, RocketPy corrected {b:.4} ({:+.4} %)",
            100.0 * d
        );
        assert!(d.abs() < tol, "{name}: {a} against {b}");
    }
}

/// The share of `values` below `x` (the empirical distribution function); `values` are left
/// sorted.
fn rank(values: &mut [f64], x: f64) -> f64 {
    values.sort_by(f64::total_cmp);
    values.partition_point(|&v| v < x) as f64 / values.len() as f64
}

#[test]
fn bella_lui_s_monte_carlo_holds_the_measured_flight_inside_its_band() {
    // The scenario's 1,000 variants (the team's stated uncertainties of mass, center of
    // mass, impulse, burn time, drag, rail and drogue, and a launch time drawn within an
    // hour of 13:00 UTC in the ERA5 file). Two faithful simulators with the same inputs miss
    // a real flight alike: what a Monte Carlo can honestly claim is that the measurement
    // lies inside the band of its variants. The measured figures are put on the campaign's
    // terms: its apogee is the center of mass's above the ground (the rise plus the
    // nominal flight's 1.10 m at the start), its times the flight's clock (the log's plus
    // the aligned offset), its landing time the center of mass's reaching the ground (the
    // log's touchdown at a rise of 0 plus the 1.10 m fallen at the log's last speed).
    use arrow::array::{Array, Float64Array};
    use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
    let out = tempfile::tempdir().unwrap();
    let cfg = hpr_mc::campaign::RunConfig {
        out: Some(out.path().join("bella_lui")),
        quiet: true,
        ..Default::default()
    };
    let report = hpr_mc::campaign::run_campaign(&repo("scenarios/bella_lui.toml"), &cfg).unwrap();
    let reader = ParquetRecordBatchReaderBuilder::try_new(
        std::fs::File::open(&report.outputs.variants).unwrap(),
    )
    .unwrap()
    .build()
    .unwrap();
    let mut cols: std::collections::BTreeMap<&str, Vec<f64>> = Default::default();
    for batch in reader {
        let batch = batch.unwrap();
        for name in [
            "apogee_m",
            "apogee_time_s",
            "landing_time_s",
            "launch_time_h",
        ] {
            let c = batch
                .column_by_name(name)
                .unwrap()
                .as_any()
                .downcast_ref::<Float64Array>()
                .unwrap();
            cols.entry(name)
                .or_default()
                .extend((0..c.len()).map(|i| c.value(i)));
        }
    }
    assert_eq!(cols["apogee_m"].len(), 1000);
    assert!(
        cols["apogee_m"].iter().all(|x| x.is_finite()),
        "every variant landed"
    );
    // The launch times drawn cover the hour either side of 13:00.
    let (lo, hi) = cols["launch_time_h"]
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
    assert!(
        lo >= -1.0 && lo < -0.99 && hi <= 1.0 && hi > 0.99,
        "{lo} {hi}"
    );
    let f = nominal();
    let z0 = f.samples[0].altitude_m;
    let log = log();
    let offset_s = time_at_rise(&f, log[0][1], 0.0, true) - log[0][0];
    let m = &reference()["measured"];
    let measured = [
        ("apogee_m", num(m, "/apogee_agl_m") + z0),
        ("apogee_time_s", num(m, "/apogee_time_s") + offset_s),
        (
            "landing_time_s",
            num(m, "/touchdown_time_s") + offset_s - z0 / num(m, "/touchdown_vertical_speed_m_s"),
        ),
    ];
    for (name, x) in measured {
        let values = cols.get_mut(name).unwrap();
        let p = rank(values, x);
        let (p5, p50, p95) = (values[50], values[500], values[950]);
        eprintln!(
            "{name}: measured {x:.3} at the {:.1} % point of 1000 variants (5 / 50 / 95 %: {p5:.3} / {p50:.3} / {p95:.3})",
            100.0 * p
        );
        assert!((0.05..=0.95).contains(&p), "{name}: measured {x} at {p}");
    }
}

#[test]
fn bella_lui_with_its_drag_estimated_from_its_geometry_is_within_rocketpy_s_apogee_bound() {
    // The same flight with hpr-mc's own drag (OpenRocket's estimate from the geometry, the
    // skins at its default "regular paint" roughness) in place of the team's Cd table:
    // 1.0 % under the measured apogee, where the team's table gives 0.3 % over it.
    let dir = tempfile::tempdir().unwrap();
    let mut design: Value = serde_json::from_str(
        &std::fs::read_to_string(repo("validation/designs/bella-lui.json")).unwrap(),
    )
    .unwrap();
    design["drag"] = serde_json::json!({ "estimate": {} });
    let design_file = dir.path().join("bella-lui-estimated.json");
    std::fs::write(&design_file, design.to_string()).unwrap();
    let validation = repo("validation").display().to_string();
    let text = std::fs::read_to_string(repo("scenarios/bella_lui.toml"))
        .unwrap()
        .replace(
            "../validation/designs/bella-lui.json",
            &design_file.display().to_string(),
        )
        .replace("\"../validation", &format!("\"{validation}"));
    let scenario_file = dir.path().join("bella_lui_estimated.toml");
    std::fs::write(&scenario_file, &text).unwrap();
    // The design's motor path is relative to it: the scenario names the motor itself.
    let f = Prepared::new(Scenario::load(&scenario_file).unwrap())
        .unwrap()
        .nominal_flight(0)
        .unwrap()
        .run(&mut ())
        .unwrap();
    let apogee = f.metrics.apogee_m.unwrap() - f.samples[0].altitude_m;
    let measured = num(&reference()["measured"], "/apogee_agl_m");
    let off = (apogee - measured) / measured;
    eprintln!(
        "drag estimated from the geometry: apogee {apogee:.2} m, {:+.2} % against the measured {measured:.2} m",
        100.0 * off
    );
    assert!(off.abs() < 0.015, "{apogee} m");
    // The estimate is a different drag: the flight is not the table's.
    assert!((apogee - figures(&nominal()).apogee_m).abs() > 1.0);
}

/// A design's own motor file is found beside the design, wherever the command is run from:
/// `inspect` of the Bella Lui design, run from the system's temporary folder, says exactly
/// what it says when the same motor file is given by its full path.
#[test]
fn a_design_s_own_motor_file_is_found_beside_the_design_from_any_working_directory() {
    let design = repo("validation/designs/bella-lui.json");
    let motor = repo("validation/real-flights/bella-lui/AeroTech_K828FJ.eng");
    let run = |extra: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_hpr-mc"))
            .current_dir(std::env::temp_dir())
            .args(["inspect", design.to_str().unwrap(), "--json"])
            .args(extra)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let own = run(&[]);
    assert!(own.contains("K828"), "{own}");
    assert_eq!(own, run(&["--motor", motor.to_str().unwrap()]));
}
