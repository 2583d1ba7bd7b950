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
//! sea level, the launch latitude in degrees (OpenRocket turns its launch frame with the Earth
//! unless its geodetic method is `flat`, and takes the WGS 84 gravity there: `fly`'s
//! `--latitude-deg` with `--gravity somigliana`), the extended ISA's base temperature (K) and
//! pressure (Pa). The rod's direction
//! is clockwise from north from OpenRocket 22 on (the wind's when "launch into the wind" is
//! set); before, with no wind direction saved, it was the rod's relative to the wind, 0
//! towards it (OpenRocket 15.03's launch tab: "0° = towards the wind, 180° = downwind").

use super::{parse_number, El};

/// OpenRocket's own simulation of the design, as `fly` can repeat it: its launch conditions
/// in `fly`'s terms, what they leave out, and what OpenRocket found.
#[derive(Debug, Clone, PartialEq)]
pub struct OrkSimulation {
    pub name: String,
    /// "Maker designation" of the motor it flew, if the file names one.
    pub motor: Option<String>,
    pub rail_length_m: Option<f64>,
    pub inclination_deg: f64,
    /// `None` for a vertical rod or a heading of north.
    pub heading_deg: Option<f64>,
    /// The average wind's speed, if the simulation has an average wind.
    pub wind_m_s: Option<f64>,
    /// Where the wind blows from, clockwise from north.
    pub wind_from_deg: f64,
    /// The wind's turbulence intensity (its speed's standard deviation over its mean), where
    /// the wind has some and `fly` can fly it (at most 1).
    pub wind_turbulence_intensity: Option<f64>,
    pub elevation_m: Option<f64>,
    /// The site's latitude, where OpenRocket turned the launch frame with the Earth
    /// (Coriolis; its geodetic method not `flat`) and took the WGS 84 gravity there.
    pub latitude_deg: Option<f64>,
    /// The extended ISA's base temperature and pressure.
    pub temperature_k: Option<f64>,
    pub pressure_pa: Option<f64>,
    /// What `fly` cannot repeat (turbulence, a wind table), one phrase each.
    pub unsaid: Vec<String>,
    /// OpenRocket marks its results outdated.
    pub outdated: bool,
    pub found: OrkResults,
}

/// What OpenRocket's simulation found (`<flightdata>`), each where the file gives it.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct OrkResults {
    pub apogee_m: Option<f64>,
    pub time_to_apogee_s: Option<f64>,
    pub max_speed_m_s: Option<f64>,
    pub rod_speed_m_s: Option<f64>,
    pub landing_speed_m_s: Option<f64>,
    pub flight_time_s: Option<f64>,
}

/// The simulation under `root` (`<openrocket>`, whose `<rocket>` is `rocket`) the import
/// reports: of those that fly the default configuration `config` (else of all), the first
/// up to date whose flight went on past its apogee, else the first that did (an aborted
/// flight ends at its highest point, a few seconds in), else the first; if there is one.
pub(super) fn simulation(
    root: &El<'_, '_>,
    rocket: &El<'_, '_>,
    config: Option<&str>,
) -> Option<OrkSimulation> {
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
    let motor = super::components::find_motor(rocket, sim_config.or(config)).and_then(|m| {
        let d = m.text("designation")?.trim();
        let maker = m.text("manufacturer").unwrap_or("").trim();
        Some(format!("{maker} {d}").trim().to_owned())
    });
    let num = |el: &El<'_, '_>, tag: &str| el.text(tag).and_then(parse_number);
    let mut unsaid = Vec::new();
    let angle = num(&c, "launchrodangle").unwrap_or(0.0);
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
    let turbulence = turbulence.filter(|t| *t > 0.0 && speed.is_some_and(|v| v > 0.0));
    if let Some(t) = turbulence.filter(|t| *t > 1.0) {
        unsaid.push(format!(
            "its wind's turbulence, {} % (fly's is at most 100 %)",
            round(100.0 * t)
        ));
    }
    let latitude = num(&c, "launchlatitude");
    let flat = c.text("geodeticmethod").map(str::trim) == Some("flat");
    if let (true, Some(lat)) = (flat, latitude) {
        unsaid.push(format!(
            "its gravity at latitude {}° without the Earth's rotation",
            round(lat)
        ));
    }
    let (mut temperature_k, mut pressure_pa) = (None, None);
    if let Some(a) = c.child("atmosphere") {
        if a.attribute("model") == Some("extendedisa") {
            temperature_k = num(&a, "basetemperature");
            pressure_pa = num(&a, "basepressure");
        }
    }
    let found = sim
        .child("flightdata")
        .map_or_else(OrkResults::default, |d| {
            let got = |a: &str| d.attribute(a).and_then(parse_number);
            OrkResults {
                apogee_m: got("maxaltitude"),
                time_to_apogee_s: got("timetoapogee"),
                max_speed_m_s: got("maxvelocity"),
                rod_speed_m_s: got("launchrodvelocity"),
                landing_speed_m_s: got("groundhitvelocity"),
                flight_time_s: got("flighttime"),
            }
        });
    Some(OrkSimulation {
        name: sim.text("name").unwrap_or("a simulation").trim().to_owned(),
        motor,
        rail_length_m: num(&c, "launchrodlength"),
        inclination_deg: 90.0 - angle,
        // A vertical rod has no heading.
        heading_deg: heading
            .map(|h| h.rem_euclid(360.0))
            .filter(|h| angle != 0.0 && *h != 0.0),
        wind_m_s: speed,
        wind_from_deg: from,
        wind_turbulence_intensity: turbulence.filter(|t| *t <= 1.0),
        elevation_m: num(&c, "launchaltitude"),
        latitude_deg: latitude.filter(|_| !flat),
        temperature_k,
        pressure_pa,
        unsaid,
        outdated: sim.attribute("status") == Some("outdated"),
        found,
    })
}

impl OrkSimulation {
    /// Its launch conditions as `hpr-mc fly`'s flags.
    pub fn flags(&self) -> Vec<String> {
        let mut flags = Vec::new();
        if let Some(l) = self.rail_length_m {
            flags.push(format!("--rail-length-m {}", round(l)));
        }
        flags.push(format!("--inclination-deg {}", round(self.inclination_deg)));
        if let Some(h) = self.heading_deg {
            flags.push(format!("--heading-deg {}", round(h)));
        }
        if let Some(v) = self.wind_m_s {
            flags.push(format!("--wind-m-s {}", round(v)));
            flags.push(format!("--wind-from-deg {}", round(self.wind_from_deg)));
        }
        if let Some(t) = self.wind_turbulence_intensity {
            flags.push(format!("--wind-turbulence-intensity {}", round(t)));
        }
        if let Some(h) = self.elevation_m {
            flags.push(format!("--elevation-m {}", round(h)));
        }
        if let Some(lat) = self.latitude_deg {
            flags.push(format!(
                "--latitude-deg {} --gravity somigliana",
                round(lat)
            ));
        }
        if let Some(t) = self.temperature_k {
            flags.push(format!("--temperature-k {}", round(t)));
        }
        if let Some(p) = self.pressure_pa {
            flags.push(format!("--pressure-pa {}", round(p)));
        }
        flags
    }

    /// What OpenRocket found, as a phrase list (`apogee 1234.5 m at 12.25 s`, ...).
    pub fn found_phrases(&self) -> Vec<String> {
        let f = &self.found;
        let mut found = Vec::new();
        if let Some(h) = f.apogee_m {
            let at = f
                .time_to_apogee_s
                .map_or(String::new(), |t| format!(" at {} s", round(t)));
            found.push(format!("apogee {} m{at}", round(h)));
        }
        if let Some(v) = f.max_speed_m_s {
            found.push(format!("max speed {} m/s", round(v)));
        }
        if let Some(v) = f.rod_speed_m_s {
            found.push(format!("off the rod at {} m/s", round(v)));
        }
        if let Some(v) = f.landing_speed_m_s {
            let after = f
                .flight_time_s
                .map_or(String::new(), |t| format!(" after {} s", round(t)));
            found.push(format!("landing at {} m/s{after}", round(v)));
        }
        found
    }

    /// The import's note: the simulation as `fly`'s flags, what they leave out, what it found.
    pub(super) fn note(&self) -> String {
        let motor = self
            .motor
            .as_ref()
            .map_or(String::new(), |m| format!(" on the {m}"));
        let mut text = format!(
            "OpenRocket's simulation \"{}\" flew it{motor} with {}",
            self.name,
            self.flags().join(" ")
        );
        if !self.unsaid.is_empty() {
            text += &format!("; not in these flags: {}", self.unsaid.join(", "));
        }
        let found = self.found_phrases();
        if !found.is_empty() {
            let stale = if self.outdated {
                " (OpenRocket marks them outdated)"
            } else {
                ""
            };
            text += &format!("; it found {}{stale}", found.join(", "));
        }
        text.push('.');
        text
    }
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
