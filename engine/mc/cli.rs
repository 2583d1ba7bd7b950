//! The `inspect` and `fly` commands, and the re-export of `run` (see [`crate::campaign`]).
//! Each command loads its inputs, calls the library, and prints through [`crate::report`].

use crate::campaign::scenario::GravityModel;
use crate::report;
use anyhow::{anyhow, bail, Context, Result};
use hpr_design::motor::{self, Grains, Motor, MotorOptions};
use hpr_design::{Design, MAX_SAMPLING_RATE_HZ};
use hpr_sim::flight::{Environment, Parachute, Rail, SimOptions, Simulation};
use hpr_sim::trigger::Trigger;
use hpr_sim::turbulence::MAX_TURBULENCE_INTENSITY;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

pub use crate::campaign::cli::{run, RunArgs, RunCommand};

/// Write `text` to standard output. A reader that went away (`hpr-mc fly … | head`) ends the
/// output quietly, as it does for other command-line tools, instead of a panic of `print!`.
pub fn emit(text: &str) -> Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(e).context("can't write to standard output")
        }
        _ => Ok(()),
    }
}

#[derive(clap::Args, Debug)]
pub struct InspectArgs {
    /// The design (JSON, or an OpenRocket .ork).
    pub design: PathBuf,
    /// Motor: a file path (.eng or .rse; FILE#NAME or FILE#K picks one motor of a file that
    /// holds several), a bundled file stem (Cesaroni_I175), a designation (411-I175-WH-14A)
    /// or a common name (I175). Defaults to the design's own motor.
    #[arg(long)]
    pub motor: Option<String>,
    #[command(flatten)]
    pub motor_masses: MotorMasses,
    /// Print JSON instead of tables.
    #[arg(long)]
    pub json: bool,
}

/// The motor's masses in place of its file's (RocketPy's `SolidMotor` gives its own: the
/// grains' mass and `dry_mass`), where they are and the casing's inertia, each motor's for a
/// cluster.
#[derive(clap::Args, Debug, Clone, Copy, Default)]
pub struct MotorMasses {
    /// Propellant mass of the motor at ignition, kg (default: its file's).
    #[arg(long, value_parser = not_negative, allow_negative_numbers = true)]
    pub propellant_mass_kg: Option<f64>,
    /// Casing (dry) mass of the motor, kg (default: its file's loaded less propellant mass).
    #[arg(long, value_parser = not_negative, allow_negative_numbers = true)]
    pub motor_dry_mass_kg: Option<f64>,
    /// The casing's center of mass, m forward of the nozzle (RocketPy's
    /// center_of_dry_mass_position; default: the motor's mid-length).
    #[arg(long, value_parser = not_negative, allow_negative_numbers = true)]
    pub motor_dry_center_from_nozzle_m: Option<f64>,
    /// The propellant's center of mass, m forward of the nozzle (RocketPy's
    /// grains_center_of_mass_position; default: the motor's mid-length).
    #[arg(long, value_parser = not_negative, allow_negative_numbers = true)]
    pub motor_propellant_center_from_nozzle_m: Option<f64>,
    /// The casing's inertia about its center, AXIAL,TRANSVERSE kg·m² (RocketPy's dry_inertia
    /// (I_11, I_22, I_33) is I_33,I_11; default: a thin shell's).
    #[arg(long, value_name = "AXIAL,TRANSVERSE", value_parser = inertia_pair)]
    pub motor_dry_inertia_kg_m2: Option<[f64; 2]>,
    /// The propellant as BATES grains, in RocketPy's SolidMotor order: grain_number,
    /// grain_density (kg/m³), grain_outer_radius, grain_initial_inner_radius,
    /// grain_initial_height, grain_separation (m). Their mass is the propellant's (not with
    /// --propellant-mass-kg) and their shape its inertia as they burn.
    #[arg(
        long,
        value_name = "COUNT,DENSITY,OUTER_R,INNER_R,HEIGHT,SEPARATION",
        value_parser = grains,
        conflicts_with_all = ["propellant_mass_kg", "motor_chamber_m"],
    )]
    pub motor_grains: Option<Grains>,
    /// The propellant as a solid cylinder RADIUS,HEIGHT m (RocketPy's GenericMotor
    /// chamber_radius, chamber_height; its chamber_position is
    /// --motor-propellant-center-from-nozzle-m). Default: the motor's own size.
    #[arg(long, value_name = "RADIUS,HEIGHT", value_parser = chamber)]
    pub motor_chamber_m: Option<[f64; 2]>,
    /// The nozzle exit's radius, m (RocketPy's nozzle_radius), for the jet damping (default:
    /// 0.88 of the motor's radius).
    #[arg(long, value_parser = positive)]
    pub motor_nozzle_radius_m: Option<f64>,
    /// Cut the thrust curve at this time, s: the samples before it, the thrust there, then
    /// burnout (RocketPy's burn_time).
    #[arg(long, value_parser = positive)]
    pub motor_burn_time_s: Option<f64>,
    /// The casing's outer diameter, m, in place of its file's (a motor flown in another
    /// casing; grains and nozzle must fit it, and the mount must hold it).
    #[arg(long, value_parser = positive)]
    pub motor_diameter_m: Option<f64>,
}

/// Comma-separated numbers, as many as `names`, each finite (the rules beyond that are the
/// motor tables', which name the field).
fn numbers<const N: usize>(text: &str, names: &str) -> std::result::Result<[f64; N], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != N {
        return Err(format!("give {N} numbers, {names}"));
    }
    let mut out = [0.0; N];
    for (o, p) in out.iter_mut().zip(&parts) {
        *o = match p.parse::<f64>() {
            Ok(v) if v.is_finite() => v,
            Ok(_) => return Err(format!("{p}: must be finite ({names})")),
            Err(_) => return Err(format!("{p}: not a number ({names})")),
        };
    }
    Ok(out)
}

/// `--motor-grains`: six numbers, the first a whole count.
fn grains(text: &str) -> std::result::Result<Grains, String> {
    const NAMES: &str = "COUNT,DENSITY,OUTER_R,INNER_R,HEIGHT,SEPARATION";
    let [count, density, outer, inner, height, separation] = numbers::<6>(text, NAMES)?;
    if !(count >= 1.0 && count.fract() == 0.0 && count <= f64::from(u32::MAX)) {
        return Err(format!(
            "COUNT = {count}: must be a whole number, 1 or more"
        ));
    }
    Ok(Grains {
        count: count as u32,
        outer_radius_m: outer,
        inner_radius_m: inner,
        height_m: height,
        separation_m: separation,
        density_kg_m3: density,
    })
}

/// `--motor-chamber-m`: two numbers.
fn chamber(text: &str) -> std::result::Result<[f64; 2], String> {
    numbers::<2>(text, "RADIUS,HEIGHT")
}

/// Two numbers, `a,b`, each finite and not negative.
fn inertia_pair(text: &str) -> std::result::Result<[f64; 2], String> {
    let pair = numbers::<2>(text, "AXIAL,TRANSVERSE")?;
    match pair.iter().find(|v| **v < 0.0) {
        Some(v) => Err(format!("{v}: must be 0 or more (AXIAL,TRANSVERSE)")),
        None => Ok(pair),
    }
}

impl MotorMasses {
    /// `motor` cut at `--motor-burn-time-s` and in the casing of `--motor-diameter-m`.
    pub fn edit(&self, motor: Motor) -> Result<Motor> {
        let mut m = motor;
        if let Some(t) = self.motor_burn_time_s {
            m = m
                .cut_at(t)
                .map_err(|e| anyhow!("--motor-burn-time-s: {e}"))?;
            if let Some(note) = m.notes.last() {
                eprintln!("note: motor {}: {note}", m.source);
            }
        }
        if let Some(d) = self.motor_diameter_m {
            m = m
                .with_diameter(d)
                .map_err(|e| anyhow!("--motor-diameter-m: {e}"))?;
        }
        Ok(m)
    }

    pub fn options(&self) -> MotorOptions {
        MotorOptions {
            propellant_mass_kg: self.propellant_mass_kg,
            dry_mass_kg: self.motor_dry_mass_kg,
            dry_center_from_nozzle_m: self.motor_dry_center_from_nozzle_m,
            propellant_center_from_nozzle_m: self.motor_propellant_center_from_nozzle_m,
            dry_inertia_kg_m2: self.motor_dry_inertia_kg_m2,
            grains: self.motor_grains,
            chamber_m: self.motor_chamber_m,
            nozzle_radius_m: self.motor_nozzle_radius_m,
            ..MotorOptions::default()
        }
    }
}

/// `fly`'s exit codes, as `fly --help` shows them, and where its flags are grouped.
pub const FLY_EXIT_CODES: &str = "Exit codes: 0 the flight landed; 1 it did not (it never left the rail, or was still flying at its time limit: 600 s, a scenario's integrator.max_time_s), said on standard error; 2 bad input or an error that stopped the flight.

The flags grouped by purpose, and the trajectory file's columns: docs/command-line.md.";

#[derive(clap::Args, Debug, Clone)]
#[command(after_help = FLY_EXIT_CODES)]
pub struct FlyArgs {
    /// The design (JSON, or an OpenRocket .ork).
    #[arg(required_unless_present = "scenario")]
    pub design: Option<PathBuf>,
    /// Fly a scenario's nominal flight instead (every input at its center, its shifts,
    /// parachutes, site and integrator): the flight its variants scatter around.
    #[arg(long, value_name = "SCENARIO", conflicts_with_all = [
        "design", "motor", "rail_length_m", "inclination_deg", "heading_deg", "elevation_m",
        "latitude_deg", "gravity", "wind_m_s", "wind_from_deg", "wind_turbulence_intensity",
        "drogue_cds_m2", "main_cds_m2",
        "main_height_m", "lag_s", "sampling_rate_hz", "temperature_k", "pressure_pa",
        "sounding", "propellant_mass_kg", "motor_dry_mass_kg", "motor_dry_center_from_nozzle_m",
        "motor_propellant_center_from_nozzle_m", "motor_dry_inertia_kg_m2", "motor_grains",
        "motor_chamber_m", "motor_nozzle_radius_m", "motor_burn_time_s", "motor_diameter_m",
        "weather", "longitude_deg", "launch_time", "weather_member",
    ])]
    pub scenario: Option<PathBuf>,
    /// With --scenario: the sweep point whose nominal flight to fly (see the run's summary;
    /// default 0).
    #[arg(long)]
    pub point: Option<usize>,
    /// With --scenario: fly variant ID of the scenario's run as the run flew it (its sampled
    /// inputs and its noise seed): its metrics are its row of variants.parquet, bit for bit.
    #[arg(long, value_name = "ID", requires = "scenario", conflicts_with_all = ["point", "seed"])]
    pub variant: Option<u64>,
    /// With --variant: the run's variants per sweep point, where `hpr-mc run --variants`
    /// replaced the scenario's.
    #[arg(long, value_name = "N", requires = "variant")]
    pub variants: Option<u64>,
    /// With --variant: the run's seed, where `hpr-mc run --seed` replaced the scenario's.
    #[arg(long, value_name = "S", requires = "variant")]
    pub run_seed: Option<u64>,
    /// Draw the flight to FILE.html (a page) or FILE.svg: height, speed, acceleration,
    /// margins, angle of attack, thrust and mass against time, side profile, ground track.
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// Motor: a file path (.eng or .rse; FILE#NAME or FILE#K picks one motor of a file that
    /// holds several), a bundled file stem (Cesaroni_I175), a designation (411-I175-WH-14A)
    /// or a common name (I175). Defaults to the design's own motor.
    #[arg(long)]
    pub motor: Option<String>,
    #[command(flatten)]
    pub motor_masses: MotorMasses,
    /// Print JSON instead of tables.
    #[arg(long)]
    pub json: bool,
    /// Write the samples to FILE.csv or FILE.parquet: one row per step, its phase, time,
    /// position (x east, y north of the rail's foot), velocity, speed, Mach, dynamic
    /// pressure, angle of attack, acceleration, thrust, mass, center of mass, margins and
    /// attitude quaternion (the columns: docs/command-line.md).
    #[arg(long, value_name = "FILE")]
    pub trajectory: Option<PathBuf>,
    /// Rail length, m.
    #[arg(long, default_value_t = 2.0, value_parser = positive)]
    pub rail_length_m: f64,
    /// Rail inclination above the horizon, degrees.
    #[arg(long, default_value_t = 90.0)]
    pub inclination_deg: f64,
    /// Rail heading, degrees clockwise from north.
    #[arg(long, default_value_t = 0.0)]
    pub heading_deg: f64,
    /// Launch site elevation above sea level, m (default 0, or with --sounding the
    /// sounding's ground).
    #[arg(long)]
    pub elevation_m: Option<f64>,
    /// The site's latitude, degrees north: the flight feels the Earth's rotation (Coriolis).
    /// Without it the launch frame is inertial.
    #[arg(long, allow_negative_numbers = true)]
    pub latitude_deg: Option<f64>,
    /// The site's longitude, degrees east (a weather file's grid is read there).
    #[arg(long, allow_negative_numbers = true)]
    pub longitude_deg: Option<f64>,
    /// Gravity: standard (9.80665 m/s²), inverse_square, somigliana (the WGS 84
    /// ellipsoid's at --latitude-deg, RocketPy's default), or a constant value in m/s² (such
    /// as 9.81, RocketPy's gravity=9.81).
    #[arg(long, value_parser = GravityModel::parse, default_value = "standard")]
    pub gravity: GravityModel,
    /// The air's temperature at the site, K: with --pressure-pa, the atmosphere runs from the
    /// site's measured air to the standard 216.65 K at 11 km (OpenRocket's custom launch
    /// conditions); either alone takes the standard's other. Default: the standard atmosphere.
    #[arg(long, value_parser = positive)]
    pub temperature_k: Option<f64>,
    /// The air's pressure at the site, Pa (see --temperature-k).
    #[arg(long, value_parser = positive)]
    pub pressure_pa: Option<f64>,
    /// A radiosonde sounding (the University of Wyoming's text listing, as RocketPy's
    /// wyoming_sounding reads it): the air and the wind over the site, in place of
    /// --temperature-k, --pressure-pa, --wind-m-s and --wind-from-deg.
    #[arg(long, value_name = "FILE", conflicts_with_all = [
        "temperature_k", "pressure_pa", "wind_m_s", "wind_from_deg",
    ])]
    pub sounding: Option<PathBuf>,
    /// A weather-model file on pressure levels (ECMWF's ERA5 as NetCDF-3 or NetCDF-4, a GFS
    /// forecast, an ensemble): the air and the wind over the site (--latitude-deg,
    /// --longitude-deg, --elevation-m, all needed) at --launch-time, in place of
    /// --temperature-k, --pressure-pa, --wind-m-s, --wind-from-deg and --sounding.
    #[arg(long, value_name = "FILE", requires_all = ["launch_time", "latitude_deg", "longitude_deg", "elevation_m"], conflicts_with_all = [
        "temperature_k", "pressure_pa", "wind_m_s", "wind_from_deg", "sounding",
    ])]
    pub weather: Option<PathBuf>,
    /// With --weather: the launch time, with its zone (2020-02-22T13:00Z, or
    /// 2020-02-22T14:00+01:00).
    #[arg(long, value_name = "TIME", requires = "weather")]
    pub launch_time: Option<String>,
    /// With --weather: the ensemble member, by the file's number (default: its first).
    #[arg(long, value_name = "N", requires = "weather")]
    pub weather_member: Option<f64>,
    /// Constant wind speed, m/s.
    #[arg(long, default_value_t = 0.0, value_parser = not_negative)]
    pub wind_m_s: f64,
    /// Direction the wind blows from, degrees clockwise from north.
    #[arg(long, default_value_t = 0.0)]
    pub wind_from_deg: f64,
    /// The wind's turbulence as OpenRocket gives it: its speed's standard deviation over its
    /// mean, 0 to 1 (OpenRocket's default is 0.1); the gusts are pink noise drawn from --seed.
    #[arg(long, default_value_t = 0.0, value_parser = turbulence_intensity)]
    pub wind_turbulence_intensity: f64,
    /// The flight's noise seed: the wind's gusts and a noisy barometer's readings (with
    /// --scenario, its nominal flight's; a campaign writes each variant's as sensor_seed,
    /// which --variant flies) [default: 0].
    #[arg(long)]
    pub seed: Option<u64>,
    /// Drogue CdS, m², opened at apogee (default: the design's smaller parachute). Any of
    /// the four parachute flags flies a drogue and a main by them, in place of the
    /// design's own deployments (its parachutes' `deploy`).
    #[arg(long, value_parser = positive)]
    pub drogue_cds_m2: Option<f64>,
    /// Main CdS, m², opened on the way down at --main-height-m (default: the design's larger parachute).
    #[arg(long, value_parser = positive)]
    pub main_cds_m2: Option<f64>,
    /// Height of the main's opening above ground, m [default: 300].
    #[arg(long, value_parser = not_negative)]
    pub main_height_m: Option<f64>,
    /// Time from a trigger to an open canopy, s [default: 1].
    #[arg(long, value_parser = not_negative)]
    pub lag_s: Option<f64>,
    /// The sampling rate of the flight computer that fires both parachutes, Hz: a trigger
    /// fires at its first sample at or after the moment its condition is met (default:
    /// watched continuously).
    #[arg(long, value_parser = sampling_rate)]
    pub sampling_rate_hz: Option<f64>,
    /// Fly an OpenRocket design (.ork) as its own saved simulation launched it (the one its
    /// import's note names: rod, wind, site, air) and print what OpenRocket found beside
    /// this flight. The launch flags cannot be given with it.
    #[arg(long, conflicts_with_all = [
        "scenario", "rail_length_m", "inclination_deg", "heading_deg", "elevation_m",
        "latitude_deg", "gravity", "temperature_k", "pressure_pa", "sounding", "wind_m_s",
        "wind_from_deg", "wind_turbulence_intensity", "weather",
    ])]
    pub openrocket_conditions: bool,
}

/// A flag's number that must be positive and finite (clap names the flag in its error).
fn positive(text: &str) -> std::result::Result<f64, String> {
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        Ok(_) => Err("must be positive and finite".to_owned()),
        Err(_) => Err("not a number".to_owned()),
    }
}

/// A flight computer's sampling rate, Hz: positive, at most [`MAX_SAMPLING_RATE_HZ`].
fn sampling_rate(text: &str) -> std::result::Result<f64, String> {
    match positive(text)? {
        v if v <= MAX_SAMPLING_RATE_HZ => Ok(v),
        _ => Err(format!("must be at most {MAX_SAMPLING_RATE_HZ} Hz")),
    }
}

/// A turbulence intensity: 0 to [`MAX_TURBULENCE_INTENSITY`].
fn turbulence_intensity(text: &str) -> std::result::Result<f64, String> {
    match not_negative(text)? {
        v if v <= MAX_TURBULENCE_INTENSITY => Ok(v),
        _ => Err(format!(
            "must be at most {MAX_TURBULENCE_INTENSITY}, the wind speed's standard deviation over its mean (OpenRocket's 10 % is 0.1)"
        )),
    }
}

/// A flag's number that must be finite and not negative.
fn not_negative(text: &str) -> std::result::Result<f64, String> {
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        Ok(_) => Err("must be 0 or more and finite".to_owned()),
        Err(_) => Err("not a number".to_owned()),
    }
}

/// The design and its motor (the `--motor` choice, else the design's own).
pub fn load(design: &PathBuf, motor: &Option<String>) -> Result<(Design, Motor)> {
    let d = Design::load(design).map_err(|e| anyhow!("{e}"))?;
    ork_notes(design);
    for warning in &d.warnings {
        eprintln!("warning: {warning}");
    }
    let name = match motor {
        Some(m) => m.clone(),
        None => beside(
            design,
            &d.default_motor.clone().ok_or_else(|| {
                anyhow!(
                    "{}: the design names no motor (field \"motor\"); give --motor",
                    design.display()
                )
            })?,
        ),
    };
    let m = motor::find(&name).map_err(|e| anyhow!("{e}"))?;
    report::motor_notes(&m);
    Ok((d, m))
}

/// A design's own motor as `motor::find` takes it: a relative file path (with or without a
/// `#NAME` or `#K` after it) is the design file's neighbour, as a scenario's motor is the
/// scenario's; a designation or a path that is no file beside the design is kept as written.
fn beside(design: &Path, motor: &str) -> String {
    let (file, choice) = match motor.split_once('#') {
        Some((file, choice)) => (file, Some(choice)),
        None => (motor, None),
    };
    let dir = design.parent().unwrap_or(Path::new(""));
    let path = dir.join(file);
    if file.is_empty() || Path::new(file).is_absolute() || !path.is_file() {
        return motor.to_owned();
    }
    match choice {
        Some(choice) => format!("{}#{choice}", path.display()),
        None => path.display().to_string(),
    }
}

/// A rail long enough for any design (for commands that do not fly).
fn roomy_rail(design: &Design) -> Rail {
    Rail {
        length_m: design.length_m + 5.0,
        ..Rail::default()
    }
}

pub fn inspect(a: &InspectArgs) -> Result<ExitCode> {
    let (design, motor) = load(&a.design, &a.motor)?;
    let motor = a.motor_masses.edit(motor)?;
    let sim = Simulation::with_motor_options(
        design.clone(),
        motor.clone(),
        a.motor_masses.options(),
        Environment::default(),
        roomy_rail(&design),
    )
    .map_err(|e| anyhow!("{e}"))?;
    let r = report::Inspection::of(&sim);
    if a.json {
        emit(&format!(
            "{}\n",
            serde_json::to_string_pretty(&r.to_json())?
        ))?;
    } else {
        emit(&r.to_text())?;
    }
    Ok(ExitCode::SUCCESS)
}

#[derive(clap::Args, Debug)]
pub struct ReportArgs {
    /// A run's output directory (its variants.parquet and the other files).
    pub results_dir: PathBuf,
}

/// `hpr-mc report RESULTS_DIR`: the report and the landing maps drawn again from the files.
pub fn report(a: &ReportArgs) -> Result<ExitCode> {
    let w = crate::campaign::report::write_dir(&a.results_dir)?;
    let mut text = format!(
        "wrote {} ({:.0} kB) in {:.2} s\n",
        w.report.display(),
        w.bytes as f64 / 1000.0,
        w.seconds
    );
    if let (Some(k), Some(g)) = (&w.kml, &w.geojson) {
        text.push_str(&format!("wrote {} and {}\n", k.display(), g.display()));
    }
    emit(&text)?;
    Ok(ExitCode::SUCCESS)
}

#[derive(clap::Args, Debug)]
pub struct ImportArgs {
    /// The OpenRocket design (.ork: a ZIP, gzipped or plain XML).
    pub ork: PathBuf,
    /// Write the design (JSON) here instead of to standard output.
    #[arg(long, short)]
    pub output: Option<PathBuf>,
}

/// What the import of an OpenRocket design left out, on standard error (nothing for a JSON
/// design): a flight of a `.ork` says what it does not fly.
fn ork_notes(design: &std::path::Path) {
    if let Some(Ok(import)) = ork_import(design) {
        for note in &import.notes {
            eprintln!("note: {note}");
        }
    }
}

/// The import of `design` if it is an OpenRocket file; `None` for a JSON design or a file
/// that cannot be read (`Design::load` says why).
fn ork_import(
    design: &std::path::Path,
) -> Option<std::result::Result<hpr_design::ork::OrkImport, hpr_design::DesignError>> {
    let bytes = hpr_design::limits::read_limited(
        design,
        hpr_design::limits::MAX_DESIGN_FILE_BYTES,
        "a design file",
    )
    .ok()?;
    hpr_design::ork::is_ork_file(design, &bytes)
        .then(|| hpr_design::ork::import(&bytes, &design.display().to_string()))
}

/// `hpr-mc import`: an OpenRocket design as hpr's design JSON, checked as a hand-written
/// design is before anything is written; what the import left out goes to standard error.
/// (`inspect`, `fly` and scenarios read a `.ork` directly; this shows and keeps the JSON.)
pub fn import(a: &ImportArgs) -> Result<ExitCode> {
    let file = a.ork.display().to_string();
    let bytes = hpr_design::limits::read_limited(
        &a.ork,
        hpr_design::limits::MAX_DESIGN_FILE_BYTES,
        "a design file",
    )
    .with_context(|| format!("{file}: can't read it"))?;
    let import = hpr_design::ork::import(&bytes, &file).map_err(|e| anyhow!("{e}"))?;
    let text = hpr_design::ork::to_pretty_json(&import.json);
    // Checked before it is written: a design the import cannot make valid writes nothing.
    Design::from_json_str(&text, Some(&a.ork)).map_err(|e| anyhow!("{e}"))?;
    for note in &import.notes {
        eprintln!("note: {note}");
    }
    match &a.output {
        Some(out) => std::fs::write(out, text)
            .with_context(|| format!("{}: can't write it", out.display()))?,
        None => emit(&text)?,
    }
    Ok(ExitCode::SUCCESS)
}

/// The main's height above ground and the lag `fly` takes when no flag gives them.
pub const MAIN_HEIGHT_M: f64 = 300.0;
pub const LAG_S: f64 = 1.0;

/// The parachutes of a `fly`. With none of the four flags given, a design whose parachutes
/// say how they deploy (`deploy`) flies those parachutes so (one that does not say is not
/// flown, as OpenRocket's "never"). Otherwise a drogue at apogee and a main at the main
/// height: the flags' CdS, else the design's parachute components (the smaller canopy the
/// drogue, the larger the main).
pub fn parachutes_for(
    design: &Design,
    drogue: Option<f64>,
    main: Option<f64>,
    main_height_m: Option<f64>,
    lag_s: Option<f64>,
) -> Vec<Parachute> {
    let flagged = drogue.is_some() || main.is_some() || main_height_m.is_some() || lag_s.is_some();
    let deployed: Vec<Parachute> = design
        .components
        .iter()
        .filter_map(|c| match &c.kind {
            hpr_design::ComponentKind::Parachute(p) => p
                .deploy
                .map(|d| Parachute::new(&c.id, p.cds_m2(), Trigger::from(d.trigger), d.lag_s)),
            _ => None,
        })
        .collect();
    if !flagged && !deployed.is_empty() {
        return deployed;
    }
    let (main_height_m, lag_s) = (
        main_height_m.unwrap_or(MAIN_HEIGHT_M),
        lag_s.unwrap_or(LAG_S),
    );
    let mut from_design: Vec<f64> = design
        .components
        .iter()
        .filter_map(|c| match &c.kind {
            hpr_design::ComponentKind::Parachute(p) => Some(p.cds_m2()),
            _ => None,
        })
        .collect();
    from_design.sort_by(f64::total_cmp);
    let drogue = drogue.or(from_design.first().copied());
    let main = main.or(if from_design.len() > 1 {
        from_design.get(1).copied()
    } else {
        None
    });
    let mut out = Vec::new();
    if let Some(c) = drogue {
        out.push(Parachute::new("drogue", c, Trigger::Apogee, lag_s));
    }
    if let Some(c) = main {
        out.push(Parachute::new(
            "main",
            c,
            Trigger::HeightDescending {
                height_m: main_height_m,
            },
            lag_s,
        ));
    }
    out
}

pub fn fly(a: &FlyArgs) -> Result<ExitCode> {
    if a.point.is_some() && a.scenario.is_none() {
        return Err(anyhow!(
            "--point picks a sweep point of a scenario: it needs --scenario FILE"
        ));
    }
    // With a scenario, which flight of it this is: its file and sweep point.
    let mut openrocket = None;
    let (sim, origin) = match (&a.scenario, &a.design) {
        (Some(scenario), _) if a.variant.is_some() => {
            let id = a.variant.unwrap_or_default();
            let cfg = crate::campaign::RunConfig {
                seed: a.run_seed,
                variants_per_point: a.variants,
                ..Default::default()
            };
            let prepared = crate::campaign::run::prepare(scenario, &cfg)?;
            let sim = prepared
                .variant_flight(id)
                .map_err(|e| anyhow!("{}: {e}", scenario.display()))?;
            let v = prepared.plan.variant(id);
            let label = format!(
                "variant {id} of {} (replicate {}{}; seed {}, {} variants per point)",
                scenario.display(),
                v.replicate,
                if prepared.plan.points() > 1 {
                    prepared.point_label(v.point)
                } else {
                    String::new()
                },
                prepared.scenario.seed,
                prepared.scenario.variants_per_point
            );
            (sim, Some((v.point, label)))
        }
        (Some(scenario), _) => {
            let prepared = crate::campaign::run::prepare(scenario, &Default::default())?;
            let point = a.point.unwrap_or(0);
            let sim = prepared
                .nominal_flight(point)
                .map_err(|e| anyhow!("{}: {e}", scenario.display()))?;
            let label = format!(
                "the nominal flight of {}{}",
                scenario.display(),
                prepared.point_label(point)
            );
            (sim, Some((point, label)))
        }
        (None, Some(design)) if a.openrocket_conditions => {
            let (args, sim) = as_openrocket_flew(design, a)?;
            openrocket = Some(sim);
            (flight_of_arguments(design, &args)?, None)
        }
        (None, Some(design)) => (flight_of_arguments(design, a)?, None),
        (None, None) => return Err(anyhow!("give a design or --scenario")),
    };
    if let Some(path) = &a.trajectory {
        report::trajectory_format(path)?;
    }
    if let Some(path) = &a.plot {
        crate::flight_plot::plot_format(path)?;
    }
    // A variant flies its own noise seed, as its row says.
    let sim = match (a.variant, a.seed) {
        (Some(_), _) => sim,
        (None, seed) => sim.with_sensor_seed(seed.unwrap_or(0)),
    };
    let flight = sim.run(&mut ()).map_err(|e| anyhow!("{e}"))?;
    if let Some(path) = &a.trajectory {
        report::write_trajectory(path, &flight)
            .with_context(|| format!("writing {}", path.display()))?;
    }
    if let Some(path) = &a.plot {
        let title = origin.as_ref().map_or_else(
            || format!("{} on {}", sim.design().name, sim.motor().designation),
            |(_, label)| label.clone(),
        );
        crate::flight_plot::write(
            path,
            &title,
            &report::flight_text(&sim, &flight),
            &sim,
            &flight,
        )
        .with_context(|| format!("writing {}", path.display()))?;
    }
    if a.json {
        let mut json = report::flight_json(&sim, &flight);
        if let (Some(id), Some(o)) = (a.variant, json.as_object_mut()) {
            o.insert("variant".into(), id.into());
        }
        if let (Some((point, label)), Some(o)) = (&origin, json.as_object_mut()) {
            o.insert("scenario_point".into(), (*point).into());
            o.insert("flown".into(), label.clone().into());
        }
        if let (Some(or), Some(o)) = (&openrocket, json.as_object_mut()) {
            o.insert("openrocket".into(), report::openrocket_json(or));
        }
        emit(&format!("{}\n", serde_json::to_string_pretty(&json)?))?;
    } else {
        let head = origin.map_or(String::new(), |(_, label)| format!("{label}\n"));
        let beside = openrocket.map_or(String::new(), |or| {
            report::openrocket_text(&or, &flight.metrics)
        });
        emit(&format!(
            "{head}{}{beside}",
            report::flight_text(&sim, &flight)
        ))?;
    }
    // A flight that did not land is not a success: said, with exit code 1 (as a run whose
    // variants did not all land).
    if let Some(end) = flight.event(hpr_sim::EventKind::TimeLimit) {
        let why = if flight.metrics.rail_exit_time_s.is_none() {
            "never left the rail: it was still on it"
        } else {
            "did not land: it was still flying"
        };
        eprintln!(
            "hpr-mc: the flight {why} at its time limit, {} s (its events above say how far it got)",
            end.time_s
        );
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

/// `fly`'s options with the launch conditions of the OpenRocket simulation the `.ork`
/// `design` saved (the one its import reports), and that simulation.
fn as_openrocket_flew(
    design: &PathBuf,
    a: &FlyArgs,
) -> Result<(FlyArgs, hpr_design::ork::OrkSimulation)> {
    let file = design.display().to_string();
    std::fs::metadata(design).with_context(|| format!("{file}: can't read it"))?;
    let import = ork_import(design)
        .ok_or_else(|| {
            anyhow!(
                "{file}: --openrocket-conditions needs an OpenRocket design (.ork), which saves its simulations"
            )
        })?
        .map_err(|e| anyhow!("{e}"))?;
    let sim = import
        .simulation
        .ok_or_else(|| anyhow!("{file}: --openrocket-conditions: the file holds no simulation"))?;
    let mut args = a.clone();
    if let Some(l) = sim.rail_length_m {
        args.rail_length_m = l;
    }
    args.inclination_deg = sim.inclination_deg;
    args.heading_deg = sim.heading_deg.unwrap_or(0.0);
    args.wind_m_s = sim.wind_m_s.unwrap_or(0.0);
    args.wind_from_deg = sim.wind_from_deg;
    args.wind_turbulence_intensity = sim.wind_turbulence_intensity.unwrap_or(0.0);
    args.elevation_m = sim.elevation_m;
    if let Some(lat) = sim.latitude_deg {
        args.latitude_deg = Some(lat);
        args.gravity = GravityModel::Somigliana;
    }
    args.temperature_k = sim.temperature_k;
    args.pressure_pa = sim.pressure_pa;
    Ok((args, sim))
}

/// The flight `fly`'s options describe for `design`.
fn flight_of_arguments(design: &PathBuf, a: &FlyArgs) -> Result<Simulation> {
    let (design, motor) = load(design, &a.motor)?;
    let motor = a.motor_masses.edit(motor)?;
    let (elevation_m, wind, air) = match (&a.sounding, &a.weather) {
        (None, Some(file)) => {
            let what = |e: &dyn std::fmt::Display| anyhow!("--weather {}: {e}", file.display());
            // clap requires these four with --weather.
            let (Some(lat), Some(lon), Some(elevation_m), Some(time)) = (
                a.latitude_deg,
                a.longitude_deg,
                a.elevation_m,
                &a.launch_time,
            ) else {
                bail!("--weather needs --latitude-deg, --longitude-deg, --elevation-m and --launch-time");
            };
            let time_s =
                hpr_sim::weather::parse_utc(time).map_err(|e| anyhow!("--launch-time: {e}"))?;
            let w = hpr_sim::weather::SiteWeather::read(file, lat, lon).map_err(|e| what(&e))?;
            let member = w
                .member_index(a.weather_member.unwrap_or(w.members()[0]))
                .map_err(|e| anyhow!("--weather-member: {e}"))?;
            let site = w
                .over_site(time_s, member, elevation_m)
                .map_err(|e| what(&e))?;
            let top = w.top_m(time_s, member).map_err(|e| what(&e))?;
            eprintln!(
                "note: --weather {}: the air and wind of {} over {lat}° N, {lon}° E at {elevation_m} m, its top level {top:.0} m above sea level (above it: the standard lapse, the top's wind)",
                file.display(),
                hpr_sim::weather::format_utc(time_s)
            );
            (
                elevation_m,
                site.wind().map_err(|e| what(&e))?,
                site.air_model(),
            )
        }
        (None, None) => {
            let elevation_m = a.elevation_m.unwrap_or(0.0);
            let wind = hpr_sim::wind::Wind::constant(a.wind_m_s, a.wind_from_deg)
                .map_err(|e| anyhow!("--wind: {e}"))?;
            let air = hpr_sim::AirModel::site(elevation_m, a.temperature_k, a.pressure_pa)
                .map_err(|e| anyhow!("--temperature-k/--pressure-pa: {e}"))?;
            (elevation_m, wind, air)
        }
        (Some(file), _) => {
            let what = |e: &dyn std::fmt::Display| anyhow!("--sounding {}: {e}", file.display());
            let text = hpr_design::limits::read_text_limited(
                file,
                hpr_design::limits::MAX_SOUNDING_FILE_BYTES,
                "a sounding",
            )
            .map_err(|e| what(&e))?;
            let site = hpr_sim::sounding::Sounding::parse(&text)
                .and_then(|s| s.over_site(a.elevation_m))
                .map_err(|e| what(&e))?;
            let wind = hpr_sim::wind::Wind::table(&site.wind).map_err(|e| what(&e))?;
            let air = hpr_sim::AirModel::Profile(std::sync::Arc::new(site.air));
            air.check().map_err(|e| what(&e))?;
            (site.elevation_m, wind, air)
        }
    };
    let gravity = a
        .gravity
        .at_site(a.latitude_deg, elevation_m, "--latitude-deg")
        .map_err(|e| anyhow!("--gravity: {e}"))?;
    let wind = wind
        .with_turbulence(a.wind_turbulence_intensity)
        .map_err(|e| anyhow!("--wind-turbulence-intensity: {e}"))?;
    let env = Environment {
        elevation_m,
        wind,
        gravity,
        latitude_deg: a.latitude_deg,
        air,
        ..Environment::default()
    };
    let rail = Rail {
        length_m: a.rail_length_m,
        inclination_deg: a.inclination_deg,
        heading_deg: a.heading_deg,
    };
    let chutes = parachutes_for(
        &design,
        a.drogue_cds_m2,
        a.main_cds_m2,
        a.main_height_m,
        a.lag_s,
    )
    .into_iter()
    .map(|p| Parachute {
        sampling_rate_hz: a.sampling_rate_hz,
        ..p
    })
    .collect();
    Simulation::with_motor_options(design, motor, a.motor_masses.options(), env, rail)
        .and_then(|s| s.with_parachutes(chutes))
        .and_then(|s| s.with_options(SimOptions::default()))
        .map_err(|e| anyhow!("{e}"))
}
