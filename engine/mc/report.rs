//! What the commands print: text tables for people and JSON for scripts, from the same
//! figures; the notes a motor's reader left; and the trajectory files (CSV or Parquet) of
//! `fly`. The command line and the campaign's run both print through it, and it calls
//! neither.

use crate::campaign::parquet::field;
use anyhow::{bail, Result};
use hpr_design::mass;
use hpr_sim::flight::{Flight, Simulation};
use hpr_sim::EventKind;
use serde_json::{json, Value};
use std::fmt::Write as _;
use std::path::Path;
use std::sync::Arc;

/// What the motor's reader mended in its file (nothing for a clean file), on standard error.
pub fn motor_notes(m: &hpr_design::motor::Motor) {
    for note in &m.notes {
        eprintln!("note: motor {}: {note}", m.source);
    }
}

/// The figures `inspect` reports.
pub struct Inspection {
    pub design: String,
    pub motor: Value,
    pub liftoff: Value,
    pub burnout: Value,
    pub cp_m: f64,
    pub ref_diameter_m: f64,
    pub components: Vec<Value>,
    /// Each nose, transition and fin set's normal-force slope at Mach 0 (1/rad, on the
    /// reference area) and center of pressure (m aft of the nose tip), as OpenRocket's
    /// component analysis lists them.
    pub surfaces: Vec<Value>,
    /// Each parachute component: its CdS and, if it says, how it deploys (what `fly` flies).
    pub parachutes: Vec<Value>,
    /// What the design's validation let pass (`geometry_checks: "openrocket"`).
    pub warnings: Vec<String>,
    /// The design's air brakes (null without).
    pub air_brakes: Value,
}

fn mass_json(sim: &Simulation, t: f64) -> Value {
    let p = sim.mass_properties_at(t);
    json!({
        "time_s": t,
        "mass_kg": p.mass_kg,
        "cg_m": p.cg_m.x,
        "inertia_axial_kg_m2": p.axial_inertia(),
        "inertia_transverse_kg_m2": p.transverse_inertia(),
        "static_margin_cal": sim.static_margin_for(p.cg_m.x),
    })
}

impl Inspection {
    pub fn of(sim: &Simulation) -> Inspection {
        let d = sim.design();
        let m = sim.motor();
        let tables = &sim.model().motor;
        let motors = tables.motors();
        let burnout = sim.model().burnout_s;
        // Where the casing and the propellant are (the simulation has a motor mount).
        let aft_m = d.motor_mount.map_or(f64::NAN, |mount| mount.motor_aft_m);
        let grains = tables.grains().map_or(Value::Null, |g| {
            json!({
                "count": g.count, "outer_radius_m": g.outer_radius_m, "inner_radius_m": g.inner_radius_m,
                "height_m": g.height_m, "separation_m": g.separation_m, "density_kg_m3": g.density_kg_m3,
            })
        });
        let components = mass::mass_table(d)
            .iter()
            .map(|r| {
                let c = &d.components[r.idx];
                json!({
                    "id": r.id, "type": r.kind, "depth": r.depth,
                    "x_top_m": c.x_top_m, "length_m": c.length_m,
                    "mass_kg": r.own.mass_kg, "cg_m": r.own.cg_m.x,
                    "subtree_mass_kg": r.subtree.mass_kg, "subtree_cg_m": r.subtree.cg_m.x,
                })
            })
            .collect();
        Inspection {
            design: d.name.clone(),
            motor: json!({
                "motors": motors,
                "designation": m.designation, "common_name": m.common_name, "manufacturer": m.manufacturer_name(),
                "file": m.source, "class": m.impulse_class().to_string(),
                "total_impulse_ns": m.total_impulse_ns(), "burn_time_s": m.burn_time_s(), "average_thrust_n": m.average_thrust_n(),
                "peak_thrust_n": m.peak_thrust_n(), "propellant_mass_kg": sim.model().motor.propellant_mass_kg() / motors as f64,
                "loaded_mass_kg": sim.model().motor.ignition_mass_kg() / motors as f64, "diameter_m": m.diameter_m, "length_m": m.length_m,
                "casing_cg_m": tables.casing_props(aft_m).cg_m.x, "propellant_cg_m": tables.propellant_props(aft_m).cg_m.x,
                "nozzle_radius_m": tables.nozzle_radius_m(), "grains": grains,
            }),
            liftoff: mass_json(sim, 0.0),
            burnout: mass_json(sim, burnout),
            cp_m: sim.model().cp_mach0_m,
            ref_diameter_m: sim.model().ref_diameter_m,
            components,
            // The simulation was built from this design, whose aerodynamics therefore build.
            surfaces: hpr_design::aero::AeroModel::from_design(d)
                .map(|a| {
                    a.surfaces
                        .iter()
                        .map(|l| {
                            json!({
                                "id": l.id, "kind": match l.kind {
                                    hpr_design::aero::SurfaceKind::NoseCone => "nose_cone",
                                    hpr_design::aero::SurfaceKind::Transition => "transition",
                                    hpr_design::aero::SurfaceKind::FinSet => "fin_set",
                                },
                                "cn_alpha_mach0_per_rad": l.cn_alpha(0.0), "x_cp_m": l.x_cp_m,
                            })
                        })
                        .collect()
                })
                .unwrap_or_default(),
            parachutes: d
                .components
                .iter()
                .filter_map(|c| match &c.kind {
                    hpr_design::ComponentKind::Parachute(p) => Some(json!({
                        "id": c.id,
                        "cds_m2": p.cds_m2(),
                        "deploy": p.deploy.map_or(Value::Null, |d| json!({
                            "trigger": hpr_sim::Trigger::from(d.trigger).to_string(),
                            "lag_s": d.lag_s,
                        })),
                    })),
                    _ => None,
                })
                .collect(),
            warnings: d.warnings.clone(),
            air_brakes: d.air_brakes.map_or(Value::Null, |b| {
                json!({
                    "cd": b.cd, "reference_area_m2": b.reference_area_m2,
                    "target_apogee_m": b.target_apogee_m, "sampling_rate_hz": b.sampling_rate_hz,
                })
            }),
        }
    }

    pub fn to_json(&self) -> Value {
        json!({
            "design": self.design, "motor": self.motor, "liftoff": self.liftoff, "after_burnout": self.burnout,
            "center_of_pressure_m": self.cp_m, "reference_diameter_m": self.ref_diameter_m, "components": self.components,
            "lifting_surfaces": self.surfaces, "parachutes": self.parachutes,
            "warnings": self.warnings, "air_brakes": self.air_brakes,
        })
    }

    pub fn to_text(&self) -> String {
        let mut s = String::new();
        let m = &self.motor;
        let _ = writeln!(s, "design  {}", self.design);
        let motors = m["motors"].as_u64().unwrap_or(1);
        let _ = writeln!(
            s,
            "motor   {}{} {} ({}): class {}, {:.1} N·s over {:.3} s, average {:.1} N, peak {:.1} N, propellant {:.4} kg of {:.4} kg{}",
            if motors > 1 { format!("a cluster of {motors} × ") } else { String::new() },
            m["manufacturer"].as_str().unwrap_or(""),
            m["designation"].as_str().unwrap_or(""),
            m["file"].as_str().unwrap_or(""),
            m["class"].as_str().unwrap_or(""),
            m["total_impulse_ns"].as_f64().unwrap_or(f64::NAN),
            m["burn_time_s"].as_f64().unwrap_or(f64::NAN),
            m["average_thrust_n"].as_f64().unwrap_or(f64::NAN),
            m["peak_thrust_n"].as_f64().unwrap_or(f64::NAN),
            m["propellant_mass_kg"].as_f64().unwrap_or(f64::NAN),
            m["loaded_mass_kg"].as_f64().unwrap_or(f64::NAN),
            if motors > 1 { ", each" } else { "" },
        );
        let grains = match m["grains"]["count"].as_u64() {
            Some(n) => format!(" ({n} BATES grains)"),
            None => String::new(),
        };
        let _ = writeln!(
            s,
            "        casing at {:.4} m, propellant at {:.4} m{grains} aft of the nose tip; nozzle radius {:.4} m",
            m["casing_cg_m"].as_f64().unwrap_or(f64::NAN),
            m["propellant_cg_m"].as_f64().unwrap_or(f64::NAN),
            m["nozzle_radius_m"].as_f64().unwrap_or(f64::NAN),
        );
        let _ = writeln!(
            s,
            "reference diameter {:.4} m; center of pressure (Mach 0) {:.4} m aft of the nose tip",
            self.ref_diameter_m, self.cp_m
        );
        for l in &self.surfaces {
            let _ = writeln!(
                s,
                "  {:<26} CNα {:>8.4} /rad at Mach 0, center of pressure {:.4} m",
                l["id"].as_str().unwrap_or(""),
                l["cn_alpha_mach0_per_rad"].as_f64().unwrap_or(f64::NAN),
                l["x_cp_m"].as_f64().unwrap_or(f64::NAN),
            );
        }
        let _ = writeln!(
            s,
            "\n{:<15} {:>9} {:>10} {:>9} {:>12} {:>16} {:>14}",
            "", "time (s)", "mass (kg)", "CG (m)", "I axial", "I transverse", "margin (cal)"
        );
        for (name, v) in [("liftoff", &self.liftoff), ("after burnout", &self.burnout)] {
            let f = |k: &str| v[k].as_f64().unwrap_or(f64::NAN);
            let _ = writeln!(
                s,
                "{:<15} {:>9.3} {:>10.4} {:>9.4} {:>12.6} {:>16.5} {:>14.3}",
                name,
                f("time_s"),
                f("mass_kg"),
                f("cg_m"),
                f("inertia_axial_kg_m2"),
                f("inertia_transverse_kg_m2"),
                f("static_margin_cal")
            );
        }
        let _ = writeln!(
            s,
            "(CG in m aft of the nose tip; inertias in kg·m² about the center of mass)\n"
        );
        let _ = writeln!(
            s,
            "{:<28} {:<15} {:>9} {:>9} {:>10} {:>9} {:>11}",
            "component", "type", "top (m)", "length", "mass (kg)", "CG (m)", "with parts"
        );
        for c in &self.components {
            let depth = c["depth"].as_u64().unwrap_or(0) as usize;
            let name = format!("{}{}", "  ".repeat(depth), c["id"].as_str().unwrap_or(""));
            let f = |k: &str| c[k].as_f64().unwrap_or(f64::NAN);
            let _ = writeln!(
                s,
                "{:<28} {:<15} {:>9.4} {:>9.4} {:>10.4} {:>9.4} {:>11.4}",
                name,
                c["type"].as_str().unwrap_or(""),
                f("x_top_m"),
                f("length_m"),
                f("mass_kg"),
                f("cg_m"),
                f("subtree_mass_kg")
            );
        }
        if !self.parachutes.is_empty() {
            let _ = writeln!(s, "\nparachutes");
            for p in &self.parachutes {
                let when = match &p["deploy"] {
                    Value::Null => "says no deployment: fly opens the smaller at apogee, the \
                                    larger at --main-height-m"
                        .to_owned(),
                    d => format!(
                        "deploys at {}, open {} s after",
                        d["trigger"].as_str().unwrap_or(""),
                        d["lag_s"].as_f64().unwrap_or(f64::NAN)
                    ),
                };
                let _ = writeln!(
                    s,
                    "  {:<26} CdS {:>7.4} m²  {when}",
                    p["id"].as_str().unwrap_or(""),
                    p["cds_m2"].as_f64().unwrap_or(f64::NAN),
                );
            }
        }
        let b = &self.air_brakes;
        if !b.is_null() {
            let f = |k: &str| b[k].as_f64().unwrap_or(f64::NAN);
            let _ = writeln!(
                s,
                "\nair brakes: Cd {} on {} m² fully open, aiming at {} m, sampled at {} Hz from burnout",
                f("cd"),
                f("reference_area_m2"),
                f("target_apogee_m"),
                f("sampling_rate_hz")
            );
        }
        s
    }
}

fn opt(v: Option<f64>) -> Value {
    v.map_or(Value::Null, |x| json!(x))
}

pub fn flight_json(sim: &Simulation, f: &Flight) -> Value {
    let m = &f.metrics;
    json!({
        "design": sim.design().name,
        "motor": sim.motor().designation,
        "motors": sim.model().motor.motors(),
        "metrics": {
            "apogee_m": opt(m.apogee_m), "apogee_time_s": opt(m.apogee_time_s),
            "max_speed_m_s": m.max_speed_m_s, "max_mach": m.max_mach, "max_accel_m_s2": m.max_accel_m_s2,
            "max_dynamic_pressure_pa": m.max_dynamic_pressure_pa,
            "liftoff_time_s": opt(m.liftoff_time_s), "rail_exit_time_s": opt(m.rail_exit_time_s), "rail_exit_speed_m_s": opt(m.rail_exit_speed_m_s),
            "burnout_time_s": opt(m.burnout_time_s),
            "static_margin_liftoff_cal": opt(m.static_margin_liftoff_cal), "static_margin_rail_exit_cal": opt(m.static_margin_rail_exit_cal),
            "static_margin_burnout_cal": opt(m.static_margin_burnout_cal), "static_margin_min_cal": opt(m.static_margin_min_cal),
            "flight_margin_min_cal": opt(m.flight_margin_min_cal),
            "max_alpha_deg": opt(m.max_alpha_deg),
            "landing_time_s": opt(m.landing_time_s),
            "landing_x_m": opt(m.landing_position_m.map(|p| p[0])), "landing_y_m": opt(m.landing_position_m.map(|p| p[1])),
            "landing_speed_m_s": opt(m.landing_speed_m_s),
            "air_brakes_open_time_s": opt(m.air_brakes_open_time_s), "air_brakes_max_opening": opt(m.air_brakes_max_opening),
        },
        "warnings": f.warnings().iter().map(|w| w.to_string()).collect::<Vec<_>>(),
        "releases": f.releases.iter().zip(sim.releases()).map(|(r, spec)| {
            let part = r.part.as_ref();
            json!({
                "component": spec.component,
                "time_s": opt(r.time_s),
                "margin_before_cal": opt(r.margin_before_cal), "margin_after_cal": opt(r.margin_after_cal),
                "part_mass_kg": opt(part.map(|p| p.mass_kg)),
                "part_apogee_m": opt(part.map(|p| p.apogee_m)),
                "part_chute_open_time_s": opt(part.and_then(|p| p.chute_open_s)),
                "part_landing_time_s": opt(part.and_then(|p| p.landing_time_s)),
                "part_landing_x_m": opt(part.and_then(|p| p.landing_position_m).map(|p| p[0])),
                "part_landing_y_m": opt(part.and_then(|p| p.landing_position_m).map(|p| p[1])),
                "part_landing_speed_m_s": opt(part.and_then(|p| p.landing_speed_m_s)),
            })
        }).collect::<Vec<_>>(),
        "events": f.events.iter().map(|e| json!({"event": e.kind.name(), "time_s": e.time_s, "altitude_m": e.altitude_m, "speed_m_s": e.speed_m_s})).collect::<Vec<_>>(),
        "derivative_evaluations": f.derivative_evaluations,
        "steps": f.steps,
    })
}

/// What an OpenRocket simulation found beside this flight's metrics, for `fly
/// --openrocket-conditions`: each quantity the file saved, both values and the difference.
pub fn openrocket_text(
    or: &hpr_design::ork::OrkSimulation,
    m: &hpr_sim::flight::Metrics,
) -> String {
    let mut out = format!("\nOpenRocket's simulation \"{}\"", or.name);
    if let Some(motor) = &or.motor {
        let _ = write!(out, " on the {motor}");
    }
    let _ = writeln!(out, " ({}):", or.flags().join(" "));
    let _ = writeln!(
        out,
        "  {:<18}{:>14}{:>14}{:>12}",
        "", "OpenRocket", "hpr-mc", "difference"
    );
    let f = &or.found;
    // OpenRocket's flight time is its landing's only if it landed (a simulation may stop
    // at apogee).
    let landed = f.landing_speed_m_s.and(f.flight_time_s);
    // Quantity, OpenRocket's, this flight's, unit, whether the difference is relative.
    type Row<'a> = (&'a str, Option<f64>, Option<f64>, &'a str, bool);
    let rows: [Row; 6] = [
        ("apogee", f.apogee_m, m.apogee_m, "m", true),
        (
            "time to apogee",
            f.time_to_apogee_s,
            m.apogee_time_s,
            "s",
            false,
        ),
        (
            "max speed",
            f.max_speed_m_s,
            Some(m.max_speed_m_s),
            "m/s",
            true,
        ),
        (
            "off the rod",
            f.rod_speed_m_s,
            m.rail_exit_speed_m_s,
            "m/s",
            true,
        ),
        (
            "landing speed",
            f.landing_speed_m_s,
            m.landing_speed_m_s,
            "m/s",
            true,
        ),
        ("flight time", landed, m.landing_time_s, "s", false),
    ];
    for (what, theirs, ours, unit, relative) in rows {
        let Some(theirs) = theirs else { continue };
        let ours_text = ours.map_or("-".to_owned(), |v| format!("{v:.2} {unit}"));
        let diff = match ours {
            Some(v) if relative && theirs != 0.0 => format!("{:+.2} %", 100.0 * (v / theirs - 1.0)),
            Some(v) => format!("{:+.2} {unit}", v - theirs),
            None => String::new(),
        };
        let _ = writeln!(
            out,
            "  {what:<18}{:>14}{ours_text:>14}{diff:>12}",
            format!("{theirs:.2} {unit}")
        );
    }
    if or.outdated {
        out.push_str("  (OpenRocket marks its results outdated)\n");
    }
    if !or.unsaid.is_empty() {
        let _ = writeln!(out, "  not repeated here: {}", or.unsaid.join(", "));
    }
    out
}

/// An OpenRocket simulation for `fly --openrocket-conditions --json`: its name, motor, the
/// flags it was flown with, what they leave out, and what it found (null where not saved).
pub fn openrocket_json(or: &hpr_design::ork::OrkSimulation) -> Value {
    let f = &or.found;
    json!({
        "simulation": or.name,
        "motor": or.motor,
        "flags": or.flags(),
        "not_repeated": or.unsaid,
        "outdated": or.outdated,
        "apogee_m": f.apogee_m,
        "apogee_time_s": f.time_to_apogee_s,
        "max_speed_m_s": f.max_speed_m_s,
        "rail_exit_speed_m_s": f.rod_speed_m_s,
        "landing_speed_m_s": f.landing_speed_m_s,
        "landing_time_s": f.landing_speed_m_s.and(f.flight_time_s),
    })
}

pub fn flight_text(sim: &Simulation, f: &Flight) -> String {
    let m = &f.metrics;
    let mut s = String::new();
    let o = |v: Option<f64>, unit: &str, digits: usize| {
        v.map_or("—".to_string(), |x| format!("{x:.digits$} {unit}"))
    };
    let motors = match sim.model().motor.motors() {
        1 => String::new(),
        n => format!("a cluster of {n} × "),
    };
    let _ = writeln!(
        s,
        "{} on {motors}{}",
        sim.design().name,
        sim.motor().designation
    );
    let _ = writeln!(
        s,
        "apogee              {} at {}",
        o(m.apogee_m, "m", 1),
        o(m.apogee_time_s, "s", 3)
    );
    let _ = writeln!(
        s,
        "max speed           {:.2} m/s (Mach {:.3})",
        m.max_speed_m_s, m.max_mach
    );
    let _ = writeln!(s, "max acceleration    {:.1} m/s²", m.max_accel_m_s2);
    let _ = writeln!(
        s,
        "max dynamic press.  {:.1} kPa",
        m.max_dynamic_pressure_pa / 1000.0
    );
    let _ = writeln!(
        s,
        "rail exit           {} at {}",
        o(m.rail_exit_speed_m_s, "m/s", 2),
        o(m.rail_exit_time_s, "s", 4)
    );
    let _ = writeln!(
        s,
        "static margin       {} at liftoff, {} at rail exit, {} at burnout, {} at least",
        o(m.static_margin_liftoff_cal, "cal", 3),
        o(m.static_margin_rail_exit_cal, "cal", 3),
        o(m.static_margin_burnout_cal, "cal", 3),
        o(m.static_margin_min_cal, "cal", 3)
    );
    let _ = writeln!(
        s,
        "flight margin       {} at least",
        o(m.flight_margin_min_cal, "cal", 3)
    );
    let _ = writeln!(
        s,
        "angle of attack     {} at most while climbing",
        m.max_alpha_deg
            .map_or("—".to_string(), |a| format!("{a:.1}°"))
    );
    let _ = writeln!(
        s,
        "landing             {} at {}, {} east and {} north of the rail",
        o(m.landing_speed_m_s, "m/s", 2),
        o(m.landing_time_s, "s", 2),
        o(m.landing_position_m.map(|p| p[0]), "m", 1),
        o(m.landing_position_m.map(|p| p[1]), "m", 1)
    );
    if let Some(b) = sim.design().air_brakes {
        let _ = writeln!(
            s,
            "air brakes          aiming at {:.1} m: {}, widest opening {}",
            b.target_apogee_m,
            m.air_brakes_open_time_s
                .map_or("never opened".to_string(), |t| format!(
                    "opened at {t:.3} s"
                )),
            m.air_brakes_max_opening
                .map_or("—".to_string(), |u| format!("{:.1} %", 100.0 * u))
        );
    }
    for (r, spec) in f.releases.iter().zip(sim.releases()) {
        let Some((t, part)) = r.time_s.zip(r.part.as_ref()) else {
            let _ = writeln!(s, "release             {}: never released", spec.component);
            continue;
        };
        let _ = writeln!(
            s,
            "release             {} ({:.3} kg) at {t:.3} s, static margin {} → {}; it topped out at {:.1} m{} and landed {}",
            spec.component,
            part.mass_kg,
            o(r.margin_before_cal, "cal", 3),
            o(r.margin_after_cal, "cal", 3),
            part.apogee_m,
            part.chute_open_s
                .map_or(String::new(), |c| format!(", its canopy open at {c:.2} s")),
            match (part.landing_time_s, part.landing_position_m, part.landing_speed_m_s) {
                (Some(lt), Some([x, y]), Some(v)) => format!(
                    "at {v:.2} m/s at {lt:.2} s, {x:.1} m east and {y:.1} m north of the rail"
                ),
                _ => "— the time limit came first".to_string(),
            }
        );
    }
    for w in f.warnings() {
        let _ = writeln!(s, "warning             {w}");
    }
    let _ = writeln!(s, "\nevents");
    for e in &f.events {
        // The parachute's name, or the part a shift moves or a release drops, beside its
        // index.
        let name = match e.kind {
            EventKind::ParachuteTrigger(i) | EventKind::ParachuteDeploy(i) => {
                sim.parachutes().get(i).map(|p| p.name.as_str())
            }
            EventKind::Shift(k) => sim.shifts().get(k).map(|m| m.component.as_str()),
            EventKind::Release(j) => sim.releases().get(j).map(|r| r.component.as_str()),
            _ => None,
        };
        let label = match name {
            Some(n) => format!("{} ({n})", e.kind.name()),
            None => e.kind.name(),
        };
        let _ = writeln!(
            s,
            "  {:<30} {:>10.4} s {:>10.1} m {:>9.2} m/s",
            label, e.time_s, e.altitude_m, e.speed_m_s
        );
    }
    let _ = writeln!(
        s,
        "({} steps, {} derivative evaluations)",
        f.steps, f.derivative_evaluations
    );
    s
}

/// Column names (with units) and values of a sample, shared by the CSV and Parquet writers.
const COLUMNS: [&str; 21] = [
    "time_s",
    "x_m",
    "y_m",
    "altitude_m",
    "vx_m_s",
    "vy_m_s",
    "vz_m_s",
    "speed_m_s",
    "mach",
    "dynamic_pressure_pa",
    "alpha_deg",
    "accel_m_s2",
    "thrust_n",
    "mass_kg",
    "cg_m",
    "static_margin_cal",
    "flight_margin_cal",
    "q0",
    "q1",
    "q2",
    "q3",
];

/// The unit of each of [`COLUMNS`], as the campaign's files give it in the field metadata.
const UNITS: [&str; 21] = [
    "s", "m", "m", "m", "m/s", "m/s", "m/s", "m/s", "1", "Pa", "deg", "m/s²", "N", "kg", "m",
    "cal", "cal", "1", "1", "1", "1",
];

fn row(s: &hpr_sim::flight::Sample) -> [f64; 21] {
    [
        s.t_s,
        s.position_m[0],
        s.position_m[1],
        s.altitude_m,
        s.velocity_m_s[0],
        s.velocity_m_s[1],
        s.velocity_m_s[2],
        s.speed_m_s,
        s.mach,
        s.dynamic_pressure_pa,
        s.alpha_deg,
        s.accel_m_s2,
        s.thrust_n,
        s.mass_kg,
        s.cg_m,
        s.static_margin_cal,
        s.flight_margin_cal,
        s.quaternion[0],
        s.quaternion[1],
        s.quaternion[2],
        s.quaternion[3],
    ]
}

/// The format of a trajectory file by its extension (`csv` or `parquet`), checked before a
/// flight is flown for it.
pub fn trajectory_format(path: &Path) -> Result<String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "csv" | "parquet" => Ok(ext),
        _ => bail!(
            "{}: a trajectory is written as .csv or .parquet (by the file's extension)",
            path.display()
        ),
    }
}

/// Write the samples as CSV or Parquet (by the file's extension), through a temporary file
/// renamed at the end so that no half-written file is left.
pub fn write_trajectory(path: &Path, f: &Flight) -> Result<()> {
    let ext = trajectory_format(path)?;
    let tmp = path.with_extension(format!("{ext}.partial"));
    if ext == "csv" {
        let mut out = String::with_capacity(f.samples.len() * 200);
        out.push_str("phase,");
        out.push_str(&COLUMNS.join(","));
        out.push('\n');
        for s in &f.samples {
            out.push_str(s.phase.name());
            for v in row(s) {
                let _ = write!(out, ",{v}");
            }
            out.push('\n');
        }
        std::fs::write(&tmp, out)?;
    } else {
        use arrow::array::{ArrayRef, Float64Array, StringArray};
        use arrow::datatypes::{DataType, Schema};
        use arrow::record_batch::RecordBatch;
        let mut fields = vec![field("phase", DataType::Utf8, false, None)];
        fields.extend(
            COLUMNS
                .iter()
                .zip(UNITS)
                .map(|(c, unit)| field(c, DataType::Float64, true, Some(unit))),
        );
        let schema = Arc::new(Schema::new(fields));
        let mut cols: Vec<ArrayRef> = vec![Arc::new(StringArray::from_iter_values(
            f.samples.iter().map(|s| s.phase.name()),
        ))];
        for j in 0..COLUMNS.len() {
            cols.push(Arc::new(Float64Array::from_iter_values(
                f.samples.iter().map(|s| row(s)[j]),
            )));
        }
        let batch = RecordBatch::try_new(schema.clone(), cols)?;
        let file = std::fs::File::create(&tmp)?;
        let props = parquet::file::properties::WriterProperties::builder()
            .set_compression(parquet::basic::Compression::ZSTD(Default::default()))
            .build();
        let mut w = parquet::arrow::ArrowWriter::try_new(file, schema, Some(props))?;
        w.write(&batch)?;
        w.close()?;
    }
    std::fs::rename(&tmp, path)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{COLUMNS, UNITS};

    #[test]
    fn every_trajectory_column_s_unit_is_the_one_its_name_ends_in() {
        for (column, unit) in COLUMNS.iter().zip(UNITS) {
            let expected = [
                ("_m_s2", "m/s²"),
                ("_m_s", "m/s"),
                ("_deg", "deg"),
                ("_cal", "cal"),
                ("_kg", "kg"),
                ("_pa", "Pa"),
                ("_n", "N"),
                ("_s", "s"),
                ("_m", "m"),
            ]
            .iter()
            .find(|(suffix, _)| column.ends_with(suffix))
            .map_or("1", |(_, u)| u);
            assert_eq!(unit, expected, "{column}");
        }
    }
}
