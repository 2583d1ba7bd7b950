//! `hpr-mc fly … --plot FILE.html|FILE.svg`: one flight drawn from its samples. Height,
//! speed and acceleration against time with the flight's events marked; the static and the
//! flight margin against time; the angle of attack; the side profile and the ground track;
//! the thrust and the mass. An `.html` file is a self-contained page (the charts inline, the
//! figures above them, nothing fetched); an `.svg` file is the charts stacked in one image.

use crate::chart::{esc, extent, Chart, Key, PALETTE};
use anyhow::{bail, Context, Result};
use hpr_sim::flight::{Flight, Phase, Sample, Simulation};
use hpr_sim::EventKind;
use std::fmt::Write as _;
use std::path::Path;

const W: f64 = 560.0;
const H: f64 = 320.0;

/// Whether a plot can be written at `path` (by its extension), checked before a flight is
/// flown for it.
pub fn plot_format(path: &Path) -> Result<&'static str> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("html") | Some("htm") => Ok("html"),
        Some("svg") => Ok("svg"),
        _ => bail!(
            "{}: a plot is written as .html or .svg (by the file's extension)",
            path.display()
        ),
    }
}

/// The events a time chart marks, with their labels: rail exit, burnout, apogee, each shift's
/// start, each canopy's opening, the landing.
fn events(sim: &Simulation, f: &Flight) -> Vec<(f64, String)> {
    f.events
        .iter()
        .filter_map(|e| {
            let label = match e.kind {
                EventKind::RailExit => "rail exit".to_string(),
                EventKind::Burnout => "burnout".to_string(),
                EventKind::Apogee => "apogee".to_string(),
                EventKind::Landing => "landing".to_string(),
                EventKind::Shift(k) => format!(
                    "{} moves",
                    sim.shifts()
                        .get(k)
                        .map_or("shift", |m| m.component.as_str())
                ),
                EventKind::ParachuteDeploy(i) => format!(
                    "{} opens",
                    sim.parachutes()
                        .get(i)
                        .map_or("canopy", |p| p.name.as_str())
                ),
                _ => return None,
            };
            Some((e.time_s, label))
        })
        .collect()
}

/// A chart of quantities against time over [t0, t1], the events in the window marked.
fn time_chart(
    id: &str,
    title: &str,
    y_label: &str,
    samples: &[&Sample],
    lines: &[(&str, &str, fn(&Sample) -> f64)],
    window: (f64, f64),
    marks: &[(f64, String)],
) -> Option<String> {
    let pts: Vec<&&Sample> = samples
        .iter()
        .filter(|s| s.t_s >= window.0 && s.t_s <= window.1)
        .collect();
    let ys: Vec<f64> = pts
        .iter()
        .flat_map(|s| lines.iter().map(move |l| (l.2)(s)))
        .collect();
    let (y0, y1) = extent(&ys, 0.06)?;
    let mut ch = Chart::new(id, W, H, window, (y0, y1))
        .title(title)
        .labels("time after ignition (s)", y_label);
    for (k, (t, label)) in marks
        .iter()
        .filter(|m| m.0 >= window.0 && m.0 <= window.1)
        .enumerate()
    {
        ch.vline_row(*t, "#888888", true, label, k % 4);
    }
    for (k, (label, color, f)) in lines.iter().enumerate() {
        let line: Vec<(f64, f64)> = pts.iter().map(|s| (s.t_s, f(s))).collect();
        ch.line(&line, color, 2.0, false);
        if lines.len() > 1 {
            ch.key(label, color, Key::Line);
        }
        let _ = k;
    }
    Some(ch.svg())
}

/// Every chart of one flight, with a caption each.
pub fn charts(sim: &Simulation, f: &Flight) -> Vec<(String, String)> {
    let samples: Vec<&Sample> = f.samples.iter().collect();
    if samples.is_empty() {
        return vec![];
    }
    let marks = events(sim, f);
    let end = samples[samples.len() - 1].t_s;
    let apogee = f.metrics.apogee_time_s.unwrap_or(end);
    let ascent = (0.0, (apogee * 1.05).min(end));
    let burn = f.metrics.burnout_time_s.unwrap_or(apogee);
    let free: Vec<&Sample> = samples
        .iter()
        .copied()
        .filter(|s| s.phase != Phase::Descent)
        .collect();
    let mut out = vec![];
    let mut push = |svg: Option<String>, caption: &str| {
        if let Some(svg) = svg {
            out.push((svg, caption.to_string()));
        }
    };
    let late: Vec<(f64, String)> = marks
        .iter()
        .filter(|m| m.0 >= 0.5 * apogee)
        .cloned()
        .collect();
    push(
        time_chart(
            "height",
            "Height",
            "height above the ground (m)",
            &samples,
            &[("height", PALETTE[0], |s| s.altitude_m)],
            (0.0, end),
            &late,
        ),
        "The centre of mass's height above the ground over the whole flight.",
    );
    push(
        time_chart(
            "speed",
            "Speed",
            "speed (m/s)",
            &samples,
            &[("speed", PALETTE[0], |s| s.speed_m_s)],
            ascent,
            &marks,
        ),
        "The centre of mass's speed, from ignition to just past apogee.",
    );
    push(
        time_chart(
            "accel",
            "Acceleration",
            "acceleration (m/s²)",
            &samples,
            &[("acceleration", PALETTE[1], |s| s.accel_m_s2)],
            ascent,
            &marks,
        ),
        "The magnitude of the centre of mass's inertial acceleration.",
    );
    push(
        time_chart(
            "margin",
            "Stability margin",
            "margin (calibres)",
            &free,
            &[
                ("static (CP at Mach 0)", PALETTE[0], |s| s.static_margin_cal),
                ("flight (CP at the flight's Mach)", PALETTE[1], |s| {
                    s.flight_margin_cal
                }),
            ],
            (0.0, apogee.min(end)),
            &marks,
        ),
        "The static and the flight margin from ignition to apogee: a shift moves them.",
    );
    push(
        time_chart(
            "alpha",
            "Angle of attack",
            "angle of attack (degrees)",
            &free,
            &[("angle of attack", PALETTE[2], |s| s.alpha_deg)],
            ascent,
            &marks,
        ),
        "The angle between the airframe and its flow while it flies free (none on the rail or under canopy).",
    );
    push(
        time_chart(
            "thrust",
            "Thrust",
            "thrust (N)",
            &samples,
            &[("thrust", PALETTE[1], |s| s.thrust_n)],
            (0.0, (burn * 1.2).max(0.5).min(end)),
            &marks,
        ),
        "The motor's thrust through the burn.",
    );
    push(
        time_chart(
            "mass",
            "Mass",
            "mass (kg)",
            &samples,
            &[("mass", PALETTE[3], |s| s.mass_kg)],
            ascent,
            &marks,
        ),
        "The rocket's mass as the propellant burns.",
    );
    // Side profile: height against the horizontal distance along the line from the rail's
    // foot toward the apogee (east if the apogee is straight above it), signed.
    let top = samples
        .iter()
        .max_by(|p, q| p.altitude_m.total_cmp(&q.altitude_m))
        .map_or([0.0, 0.0], |s| [s.position_m[0], s.position_m[1]]);
    let reach = top[0].hypot(top[1]);
    let along = if reach > 1.0 {
        [top[0] / reach, top[1] / reach]
    } else {
        [1.0, 0.0]
    };
    let d: Vec<(f64, f64)> = samples
        .iter()
        .map(|s| {
            (
                s.position_m[0] * along[0] + s.position_m[1] * along[1],
                s.altitude_m,
            )
        })
        .collect();
    let (x0, x1) = extent(d.iter().map(|p| &p.0).chain([&0.0]), 0.05).unwrap_or((0.0, 1.0));
    let (y0, y1) = extent(d.iter().map(|p| &p.1), 0.05).unwrap_or((0.0, 1.0));
    let mut side = Chart::new("side", W, H, (x0.min(0.0), x1), (y0.min(0.0), y1))
        .title("Side profile")
        .labels(
            &format!(
                "distance toward the apogee, {:.0}° from north (m)",
                along[0].atan2(along[1]).to_degrees().rem_euclid(360.0)
            ),
            "height (m)",
        );
    side.line(&d, PALETTE[0], 2.0, false);
    push(
        Some(side.svg()),
        "Height against the horizontal distance from the rail's foot along the line toward the apogee (negative: the other way).",
    );
    // Ground track on a map.
    let xs: Vec<f64> = samples
        .iter()
        .map(|s| s.position_m[0])
        .chain([0.0])
        .collect();
    let ys: Vec<f64> = samples
        .iter()
        .map(|s| s.position_m[1])
        .chain([0.0])
        .collect();
    let (ex0, ex1) = extent(&xs, 0.08).unwrap_or((-1.0, 1.0));
    let (ey0, ey1) = extent(&ys, 0.08).unwrap_or((-1.0, 1.0));
    let mut track = Chart::map("track", W, 420.0, (ex0, ex1), (ey0, ey1))
        .title("Ground track")
        .labels("east of the rail (m)", "north of the rail (m)");
    let path: Vec<(f64, f64)> = samples
        .iter()
        .map(|s| (s.position_m[0], s.position_m[1]))
        .collect();
    track.line(&path, PALETTE[0], 2.0, false);
    track.dots(&[(0.0, 0.0)], 4.0, "#000000", 1.0);
    track.text((0.0, 0.0), 6.0, -6.0, "launch", "start", "#000000");
    if let Some(a) = f.event(EventKind::Apogee) {
        if let Some(s) = samples.iter().min_by(|p, q| {
            (p.t_s - a.time_s)
                .abs()
                .total_cmp(&(q.t_s - a.time_s).abs())
        }) {
            track.dots(&[(s.position_m[0], s.position_m[1])], 4.0, PALETTE[1], 1.0);
            track.text(
                (s.position_m[0], s.position_m[1]),
                6.0,
                -6.0,
                "apogee",
                "start",
                PALETTE[1],
            );
        }
    }
    if let Some(l) = f.metrics.landing_position_m {
        track.dots(&[(l[0], l[1])], 4.0, PALETTE[2], 1.0);
        track.text((l[0], l[1]), 6.0, -6.0, "landing", "start", PALETTE[2]);
    }
    push(
        Some(track.svg()),
        "The centre of mass's path over the ground (east and north at one scale).",
    );
    out
}

/// Write the plot of a flight (`.html` or `.svg`), atomically.
pub fn write(path: &Path, title: &str, summary: &str, sim: &Simulation, f: &Flight) -> Result<()> {
    let kind = plot_format(path)?;
    let charts = charts(sim, f);
    let text = if kind == "svg" {
        let mut y = 30.0;
        let mut body = String::new();
        for (svg, _) in &charts {
            let h: f64 = svg
                .split("height=\"")
                .nth(1)
                .and_then(|r| r.split('"').next())
                .and_then(|v| v.parse().ok())
                .unwrap_or(H);
            let _ = writeln!(body, "<g transform=\"translate(0 {y})\">{svg}</g>");
            y += h + 10.0;
        }
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{W}\" height=\"{y}\" viewBox=\"0 0 {W} {y}\" font-family=\"Helvetica, Arial, sans-serif\"><rect width=\"{W}\" height=\"{y}\" fill=\"#ffffff\"/><text x=\"10\" y=\"20\" font-size=\"15\" font-weight=\"bold\">{}</text>\n{body}</svg>\n",
            esc(title)
        )
    } else {
        let mut figs = String::new();
        for (svg, caption) in &charts {
            let _ = writeln!(
                figs,
                "<figure>{svg}<figcaption>{}</figcaption></figure>",
                esc(caption)
            );
        }
        format!(
            "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{t}</title><style>body{{font-family:Helvetica,Arial,sans-serif;color:#222;margin:0;background:#f4f4f2}}main{{max-width:1180px;margin:0 auto;padding:16px 20px;background:#fff}}h1{{font-size:21px}}pre{{font-size:12.5px;background:#f6f6f6;padding:8px;overflow-x:auto}}.grid{{display:flex;flex-wrap:wrap;gap:10px}}figure{{margin:0;border:1px solid #e4e4e4;padding:4px}}figure svg{{max-width:100%;height:auto;display:block}}figcaption{{font-size:12.5px;color:#444;max-width:560px;padding:2px 4px}}</style></head><body><main><h1>{t}</h1><pre>{s}</pre><div class=\"grid\">\n{figs}</div></main></body></html>\n",
            t = esc(title),
            s = esc(summary)
        )
    };
    let tmp = path.with_extension(format!("{kind}.partial"));
    std::fs::write(&tmp, text).with_context(|| format!("can't write {}", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("can't write {}", path.display()))?;
    Ok(())
}
