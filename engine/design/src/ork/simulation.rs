//! What an OpenRocket file says of its own flights: the launch conditions of the simulation
//! that flies the default configuration, written as `hpr-mc fly`'s flags, and what
//! OpenRocket found, so that a team can fly the design as OpenRocket did and compare. Said
//! in a note; nothing of it enters the design (a design is the rocket, not its day).
//!
//! The element names and units are those of OpenRocket's loader
//! (`SimulationConditionsHandler`, `WindHandler`, `AtmosphereHandler`): the rod's length in
//! metres, its angle from the vertical and its direction in degrees, the average wind's
//! speed in m/s and its direction in radians, the direction it blows from, clockwise from
//! north (OpenRocket's default, π/2, is "an East wind"); the launch altitude in metres above
//! sea level, the extended ISA's base temperature (K) and pressure (Pa). The rod's direction
//! is clockwise from north from OpenRocket 22 on (the wind's when "launch into the wind" is
//! set); before, with no wind direction saved, it was the rod's relative to the wind, 0
//! towards it (OpenRocket 15.03's launch tab: "0° = towards the wind, 180° = downwind").

use super::{parse_number, El};

/// The note for the simulations under `root` (`<openrocket>`, whose `<rocket>` is `rocket`):
/// of those that fly the default configuration `config` (else of all), the first up to date
/// whose flight went on past its apogee, else the first that did (an aborted flight ends at
/// its highest point, a few seconds in), else the first; if there is one.
pub(super) fn note(root: &El<'_, '_>, rocket: &El<'_, '_>, config: Option<&str>) -> Option<String> {
    let sims: Vec<El<'_, '_>> = root
        .child("simulations")?
        .children()
        .filter(|s| s.tag() == "simulation")
        .collect();
    let flies_default = |s: &El<'_, '_>| {
        s.child("conditions")
            .and_then(|c| c.text("configid"))
            .is_some_and(|id| Some(id.trim()) == config)
    };
    let own: Vec<&El<'_, '_>> = sims.iter().filter(|s| flies_default(s)).collect();
    let pool = if own.is_empty() {
        sims.iter().collect()
    } else {
        own
    };
    let past_apogee = |s: &El<'_, '_>| {
        s.child("flightdata").is_some_and(|d| {
            let got = |a: &str| d.attribute(a).and_then(parse_number);
            d.attribute("groundhitvelocity").is_some()
                || matches!((got("flighttime"), got("timetoapogee")), (Some(f), Some(a)) if f > a)
        })
    };
    let current = |s: &El<'_, '_>| s.attribute("status") != Some("outdated");
    let sim = *pool
        .iter()
        .find(|s| current(s) && past_apogee(s))
        .or_else(|| pool.iter().find(|s| past_apogee(s)))
        .or(pool.first())?;
    let c = sim.child("conditions")?;
    let sim_config = c.text("configid").map(str::trim);
    let motor = super::components::find_motor(rocket, sim_config.or(config))
        .and_then(|m| {
            let d = m.text("designation")?.trim();
            let maker = m.text("manufacturer").unwrap_or("").trim();
            Some(format!("{maker} {d}").trim().to_owned())
        })
        .map_or(String::new(), |m| format!(" on the {m}"));
    let num = |el: &El<'_, '_>, tag: &str| el.text(tag).and_then(parse_number);
    let mut flags = Vec::new();
    let mut unsaid = Vec::new();
    if let Some(l) = num(&c, "launchrodlength") {
        flags.push(format!("--rail-length-m {}", round(l)));
    }
    let angle = num(&c, "launchrodangle").unwrap_or(0.0);
    flags.push(format!("--inclination-deg {}", round(90.0 - angle)));
    // The average wind: OpenRocket 24's <wind model="average">, or the older elements.
    let (speed, direction, turbulence) = match c.child("wind") {
        Some(w) if w.attribute("model") == Some("average") => {
            let speed = num(&w, "speed");
            let sd = num(&w, "standarddeviation").unwrap_or(0.0);
            (
                speed,
                num(&w, "direction"),
                speed.map(|v| if v > 0.0 { sd / v } else { 0.0 }),
            )
        }
        Some(w) => {
            unsaid.push(format!(
                "its wind model \"{}\" (a wind table goes in a scenario)",
                w.attribute("model").unwrap_or("?")
            ));
            (None, None, None)
        }
        None => (
            num(&c, "windaverage"),
            num(&c, "winddirection"),
            num(&c, "windturbulence"),
        ),
    };
    let from = direction
        .unwrap_or(std::f64::consts::FRAC_PI_2)
        .to_degrees()
        .rem_euclid(360.0);
    // The rod's direction: from OpenRocket 22 on, clockwise from north, or the wind's own
    // when launched into the wind; before (no wind direction saved), relative to the wind,
    // 0 towards it (the rod leaning into the wind), 180° downwind.
    let absolute = c.child("winddirection").is_some()
        || c.child("wind").is_some()
        || c.child("launchintowind").is_some();
    let rod = num(&c, "launchroddirection");
    let heading = if !absolute {
        Some(from + rod.unwrap_or(0.0))
    } else if c.text("launchintowind").map(str::trim) == Some("true") {
        Some(from)
    } else {
        rod
    };
    // A vertical rod has no heading.
    if let Some(h) = heading.filter(|h| angle != 0.0 && h.rem_euclid(360.0) != 0.0) {
        flags.push(format!("--heading-deg {}", round(h.rem_euclid(360.0))));
    }
    if let Some(v) = speed {
        flags.push(format!("--wind-m-s {}", round(v)));
        flags.push(format!("--wind-from-deg {}", round(from)));
    }
    if let Some(t) = turbulence.filter(|t| *t > 0.0) {
        unsaid.push(format!("its wind's turbulence, {} %", round(100.0 * t)));
    }
    if let Some(h) = num(&c, "launchaltitude") {
        flags.push(format!("--elevation-m {}", round(h)));
    }
    if let Some(a) = c.child("atmosphere") {
        if a.attribute("model") == Some("extendedisa") {
            if let Some(t) = num(&a, "basetemperature") {
                flags.push(format!("--temperature-k {}", round(t)));
            }
            if let Some(p) = num(&a, "basepressure") {
                flags.push(format!("--pressure-pa {}", round(p)));
            }
        }
    }
    let name = sim.text("name").unwrap_or("a simulation").trim();
    let mut text = format!(
        "OpenRocket's simulation \"{name}\" flew it{motor} with {}",
        flags.join(" ")
    );
    if !unsaid.is_empty() {
        text += &format!("; not in these flags: {}", unsaid.join(", "));
    }
    if let Some(data) = sim.child("flightdata") {
        let got = |a: &str| data.attribute(a).and_then(parse_number);
        let mut found = Vec::new();
        if let Some(h) = got("maxaltitude") {
            let at = got("timetoapogee").map_or(String::new(), |t| format!(" at {} s", round(t)));
            found.push(format!("apogee {} m{at}", round(h)));
        }
        if let Some(v) = got("maxvelocity") {
            found.push(format!("max speed {} m/s", round(v)));
        }
        if let Some(v) = got("launchrodvelocity") {
            found.push(format!("off the rod at {} m/s", round(v)));
        }
        if let Some(v) = got("groundhitvelocity") {
            let after =
                got("flighttime").map_or(String::new(), |t| format!(" after {} s", round(t)));
            found.push(format!("landing at {} m/s{after}", round(v)));
        }
        if !found.is_empty() {
            let status = sim.attribute("status").unwrap_or("");
            let stale = if status == "outdated" {
                " (OpenRocket marks them outdated)"
            } else {
                ""
            };
            text += &format!("; it found {}{stale}", found.join(", "));
        }
    }
    text.push('.');
    Some(text)
}

/// A number as a person writes it: at most four decimals, no trailing zeros.
pub(super) fn round(v: f64) -> String {
    let s = format!("{:.4}", (v * 1e4).round() / 1e4);
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_owned()
    } else {
        s.to_owned()
    }
}
