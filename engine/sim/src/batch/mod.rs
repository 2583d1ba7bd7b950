//! The batch engine: thousands of variants of one flight, their inputs given as columns
//! (structure of arrays) one chunk at a time, flown in fixed-size chunks across threads with
//! rayon, their results streamed out in variant order.
//!
//! **One physics.** A lane is the base [`Simulation`] with one variant's inputs applied:
//! everything that depends on the design alone (shape integrals, aerodynamic tables, the air
//! table) is shared by `Arc` and never rebuilt; the lane's own light model (motor tables, mass
//! split, rail, wind, parachutes, shifts, releases) is built once from its row of the columns
//! (all of the row's changes, one rebuild: [`Simulation::with_changes`]). The lane then flies
//! through the single flight's own driver: pad, rail, events, triggers, shifts, releases,
//! canopies and descent are the very same code, and so are the kernels. A released part's
//! flight to the ground is the lane's last descent (after the rocket's own), stepped in the
//! descent groups beside the other lanes' descents with its own mass and drag.
//!
//! **Lanes side by side.** Up to [`LANES_IN_FLIGHT`] rows of a chunk fly at once, and a lane
//! that lands is replaced by the next row. Their free flights are stepped four lanes at a
//! time: each lane keeps its own time, step size, stop times and error control (its own
//! Dormand–Prince stepper, which judges and commits its attempts), the four lanes' attempts
//! are held as structure of arrays, and every stage is one stage combination and *one*
//! evaluation of the generic 6-DOF kernel on [`F64x4`](crate::lanes::F64x4) lanes (AVX2
//! registers where the processor has them, [`eval_four`]). Each group step is one attempt
//! per lane: a lane whose attempt is rejected tries again, smaller, at the next group step,
//! beside the other lanes' new steps. A slot without a lane repeats another lane's input
//! and is ignored. Each round the chunk orders its lanes before grouping them: free flights
//! whose mass is changing (motor burning, a part moving) first, whose mass states a group then
//! computes on four lanes too ([`crate::massprops::mass_state_lanes`]), then the other free
//! flights, then descents (each of which takes its own RODAS4 step, the single flight's); a free-flight group whose slots hold the same lanes as at its last
//! step takes up what it packed then (model, mass states, thrusts). The four attempts' stage
//! times and their step-size controllers' logarithm and factors are computed side by side too,
//! by the stepper's own functions written over lanes ([`crate::integrate::dopri54::stage_time`],
//! [`crate::integrate::dopri54::growth`], [`crate::lanes::ln`]), and handed to each lane's
//! stepper to judge. The kernels and the step
//! arithmetic do lane by lane exactly the IEEE operations the single flight does, so a lane's
//! metrics are bit for bit the single-flight simulator's ([`Batch::variant`] gives that
//! simulation; the tests compare them).
//!
//! **Determinism.** A lane depends only on its row of the columns, never on its chunk, its
//! neighbours, its thread or the order lanes are scheduled in; results are handed to the sink
//! in variant order. **Memory** does not grow with the number of variants: [`Batch::run`] asks
//! a closure for the columns of one chunk at a time, inside the task that flies it, and starts
//! no chunk more than a window of chunks beyond the first whose results are not yet handed on
//! (`stream`: one worker per thread, chunks taken in order, results reordered, no barrier).
//! **Failures** are rows: a refused input, a flight that fails or a lane that panics is
//! recorded with its reason and the run goes on.
//!
//! What it does not do yet: each lane's step ends (event functions and their location,
//! metrics, triggers), each lane's verdict on its attempt (from the factors computed on four
//! lanes) and the pad and rail run one lane at a time (see `ARCHITECTURE.md`).

mod group;
mod memo;
mod stream;

pub use group::{eval_four, LANES_IN_FLIGHT};

use crate::atmosphere::{AirModel, AirTable};
use crate::events::EventKind;
use crate::flight::driver::{fly_to_free, AfterFree, Progress};
use crate::flight::{Flight, Metrics, SimError, Simulation, Warning};
use crate::trigger::Trigger;
use crate::weather::SiteWeather;
use crate::wind::Wind;
use group::{step_group, Flying, Lane, LaneEnd, Scratch};
use std::cell::{OnceCell, RefCell};
use std::ops::Range;
use std::sync::Arc;

/// The air tables a chunk's variants have built, by their air, so that variants of the same
/// site air (a temperature swept over a few values) share one (a table takes about 90 µs to
/// build, a tenth of a flight). Holds the last [`AirTables::KEPT`] tables.
#[derive(Default)]
struct AirTables(RefCell<Vec<Arc<AirTable>>>);

impl AirTables {
    const KEPT: usize = 8;

    fn find(&self, air: &AirModel) -> Option<Arc<AirTable>> {
        self.0.borrow().iter().find(|t| t.model() == air).cloned()
    }

    fn keep(&self, table: &Arc<AirTable>) {
        let mut kept = self.0.borrow_mut();
        if !kept.iter().any(|t| Arc::ptr_eq(t, table)) {
            if kept.len() == Self::KEPT {
                kept.remove(0);
            }
            kept.push(table.clone());
        }
    }
}

/// Inputs of some variants (a chunk of them, or all), one column per input: row `r` is the
/// `r`-th of those variants. An empty column means every variant has the base simulation's
/// value; a full column has one value per variant. Nested columns are per parachute or per
/// shift (in the base simulation's order), each empty or full.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Columns {
    pub len: usize,
    /// Change of the structure's mass, kg, and of its center of mass, m aft.
    pub structure_delta_mass_kg: Vec<f64>,
    pub structure_delta_cg_m: Vec<f64>,
    /// Mass of the batch's named part (e.g. the ballast), kg.
    pub part_mass_kg: Vec<f64>,
    /// Motor impulse and time scales.
    pub impulse_scale: Vec<f64>,
    pub time_scale: Vec<f64>,
    pub drag_scale: Vec<f64>,
    pub elevation_m: Vec<f64>,
    /// The site's air temperature, K, and pressure, Pa, at the site the base's air names
    /// ([`crate::atmosphere::AirModel::with_site_values`]).
    pub temperature_k: Vec<f64>,
    pub pressure_pa: Vec<f64>,
    /// The launch time, seconds since 1970 UTC, and the ensemble member (by the file's
    /// number) of the batch's weather file ([`Batch::with_weather`]): the variant's air and
    /// wind are that file's at them, before the columns above and below change them.
    pub launch_time_s: Vec<f64>,
    pub weather_member: Vec<f64>,
    pub wind_speed_m_s: Vec<f64>,
    /// Direction the wind blows from, degrees clockwise from north (with the speed: a
    /// constant wind's as given).
    pub wind_from_deg: Vec<f64>,
    /// Scale of the wind's speeds and clockwise turn of its directions, degrees, applied to
    /// the wind as given (a table, or the constant wind above): [`Wind::transformed`].
    pub wind_scale: Vec<f64>,
    pub wind_rotation_deg: Vec<f64>,
    /// The wind's turbulence intensity ([`Wind::with_turbulence`]), in place of the base
    /// wind's.
    pub wind_turbulence_intensity: Vec<f64>,
    pub rail_length_m: Vec<f64>,
    pub rail_inclination_deg: Vec<f64>,
    pub rail_heading_deg: Vec<f64>,
    /// The air brakes' target apogee, m ([`Simulation::with_air_brakes_target`]).
    pub air_brakes_target_m: Vec<f64>,
    pub chute_cds_m2: Vec<Vec<f64>>,
    pub chute_lag_s: Vec<Vec<f64>>,
    /// The number in a parachute's trigger (its time, height or delay).
    pub chute_trigger: Vec<Vec<f64>>,
    pub shift_travel_m: Vec<Vec<f64>>,
    pub shift_duration_s: Vec<Vec<f64>>,
    /// The number in a shift's trigger (its time, height or delay).
    pub shift_trigger: Vec<Vec<f64>>,
    /// The number in a release's trigger (its time, height or delay).
    pub release_trigger: Vec<Vec<f64>>,
    /// A released part's drag area falling free, m².
    pub release_cda_m2: Vec<Vec<f64>>,
    /// A released part's own parachute: its CdS, m², and its lag, s.
    pub release_chute_cds_m2: Vec<Vec<f64>>,
    pub release_chute_lag_s: Vec<Vec<f64>>,
    /// The seed of the parachutes' sensor noise ([`Simulation::with_sensor_seed`]).
    pub sensor_seed: Vec<u64>,
}

/// How a lane ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// Flew to the ground.
    Landed,
    /// Stopped at the time limit before landing.
    TimeLimit,
    /// Its inputs were refused (a shift out of its holder at these values, a bad number...).
    Refused,
    /// The flight failed (went non-finite, a shift on the rail, ...).
    Failed,
}

impl Status {
    pub fn name(&self) -> &'static str {
        match self {
            Status::Landed => "landed",
            Status::TimeLimit => "time_limit",
            Status::Refused => "refused",
            Status::Failed => "failed",
        }
    }
}

/// One lane's result.
#[derive(Debug, Clone, PartialEq)]
pub struct LaneResult {
    pub variant: usize,
    pub status: Status,
    pub error: Option<String>,
    /// Whether the flight happened (it may still have failed to land): its metrics, end and
    /// shifts are its own. False for a refused lane, a flight stopped by an error or a panic.
    pub flown: bool,
    /// The flight's metrics (default where the flight did not happen).
    pub metrics: Metrics,
    /// Time of the flight's last event (its landing, its time limit...), s; 0 where the
    /// flight did not happen.
    pub end_s: f64,
    /// Per shift: its start time, and the static margin just before and just after its move.
    pub shifts: Vec<ShiftOutcome>,
    /// Per parachute: its opening time and speed.
    pub parachutes: Vec<ParachuteOutcome>,
    /// Per release: when its part left, the static margin just before and after, and where,
    /// when and how fast the part landed.
    pub releases: Vec<ReleaseOutcome>,
    /// What the flight's figures hide (empty where the flight did not happen).
    pub warnings: Vec<Warning>,
    pub derivative_evaluations: u64,
    /// The flight's samples, one per step, for a batch that keeps them
    /// ([`Batch::keeping_samples`]); empty otherwise.
    pub samples: Vec<crate::flight::Sample>,
}

/// When one parachute opened in a lane (`None` if it never did).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ParachuteOutcome {
    pub deploy_time_s: Option<f64>,
    /// Speed of the center of mass as the canopy opened, m/s.
    pub deploy_speed_m_s: Option<f64>,
}

/// What one release did in a lane (`None` where it did not happen).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ReleaseOutcome {
    pub time_s: Option<f64>,
    pub margin_before_cal: Option<f64>,
    pub margin_after_cal: Option<f64>,
    /// The part's landing: time, s, point east and north of the rail's foot, m, speed, m/s.
    pub landing_time_s: Option<f64>,
    pub landing_position_m: Option<[f64; 2]>,
    pub landing_speed_m_s: Option<f64>,
    /// When the part's own parachute opened, s.
    pub chute_open_s: Option<f64>,
}

impl ReleaseOutcome {
    /// What release `record` of a flight did.
    pub fn of(record: &crate::flight::ReleaseRecord) -> ReleaseOutcome {
        let part = record.part.as_ref();
        ReleaseOutcome {
            time_s: record.time_s,
            margin_before_cal: record.margin_before_cal,
            margin_after_cal: record.margin_after_cal,
            landing_time_s: part.and_then(|p| p.landing_time_s),
            landing_position_m: part.and_then(|p| p.landing_position_m),
            landing_speed_m_s: part.and_then(|p| p.landing_speed_m_s),
            chute_open_s: part.and_then(|p| p.chute_open_s),
        }
    }
}

/// What one shift did in a lane.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShiftOutcome {
    pub start_s: Option<f64>,
    pub margin_before_cal: Option<f64>,
    pub margin_after_cal: Option<f64>,
}

impl Columns {
    /// The rows `rows` of these columns (empty columns stay empty). A column too short for
    /// `rows` gives the values it has, which [`Batch::check`] then refuses (never a panic).
    pub fn slice(&self, rows: Range<usize>) -> Columns {
        let flat = |c: &Vec<f64>| {
            let end = rows.end.min(c.len());
            c[rows.start.min(end)..end].to_vec()
        };
        let nested = |c: &Vec<Vec<f64>>| c.iter().map(flat).collect();
        Columns {
            len: rows.len(),
            structure_delta_mass_kg: flat(&self.structure_delta_mass_kg),
            structure_delta_cg_m: flat(&self.structure_delta_cg_m),
            part_mass_kg: flat(&self.part_mass_kg),
            impulse_scale: flat(&self.impulse_scale),
            time_scale: flat(&self.time_scale),
            drag_scale: flat(&self.drag_scale),
            elevation_m: flat(&self.elevation_m),
            temperature_k: flat(&self.temperature_k),
            pressure_pa: flat(&self.pressure_pa),
            launch_time_s: flat(&self.launch_time_s),
            weather_member: flat(&self.weather_member),
            wind_speed_m_s: flat(&self.wind_speed_m_s),
            wind_from_deg: flat(&self.wind_from_deg),
            wind_scale: flat(&self.wind_scale),
            wind_rotation_deg: flat(&self.wind_rotation_deg),
            wind_turbulence_intensity: flat(&self.wind_turbulence_intensity),
            rail_length_m: flat(&self.rail_length_m),
            rail_inclination_deg: flat(&self.rail_inclination_deg),
            rail_heading_deg: flat(&self.rail_heading_deg),
            air_brakes_target_m: flat(&self.air_brakes_target_m),
            chute_cds_m2: nested(&self.chute_cds_m2),
            chute_lag_s: nested(&self.chute_lag_s),
            chute_trigger: nested(&self.chute_trigger),
            shift_travel_m: nested(&self.shift_travel_m),
            shift_duration_s: nested(&self.shift_duration_s),
            shift_trigger: nested(&self.shift_trigger),
            release_trigger: nested(&self.release_trigger),
            release_cda_m2: nested(&self.release_cda_m2),
            release_chute_cds_m2: nested(&self.release_chute_cds_m2),
            release_chute_lag_s: nested(&self.release_chute_lag_s),
            sensor_seed: {
                let end = rows.end.min(self.sensor_seed.len());
                self.sensor_seed[rows.start.min(end)..end].to_vec()
            },
        }
    }
}

/// A batch: the base flight and the part the `part_mass_kg` column names. The variants'
/// inputs come as [`Columns`], a chunk at a time.
#[derive(Debug, Clone)]
pub struct Batch {
    base: Simulation,
    part: Option<String>,
    weather: Option<BatchWeather>,
}

/// The weather file a batch's variants draw their launch time and ensemble member from
/// (the `launch_time_s` and `weather_member` columns), and the base's: its air and wind are
/// the file's over a site `elevation_m` above sea level at `time_s`, member `member` (by the
/// file's number).
#[derive(Debug, Clone)]
pub struct BatchWeather {
    pub site: Arc<SiteWeather>,
    pub time_s: f64,
    pub member: f64,
    pub elevation_m: f64,
}

fn with_number(t: Trigger, v: f64) -> Result<Trigger, String> {
    Ok(match t {
        Trigger::Time { .. } => Trigger::Time { time_s: v },
        Trigger::HeightDescending { .. } => Trigger::HeightDescending { height_m: v },
        Trigger::BurnoutPlusDelay { .. } => Trigger::BurnoutPlusDelay { delay_s: Some(v) },
        Trigger::Apogee | Trigger::Burnout => {
            return Err(format!("trigger {t} has no number to vary"))
        }
    })
}

/// Run `f`, turning a panic into its message.
fn guarded<R>(f: impl FnOnce() -> R) -> Result<R, String> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).map_err(|p| panic_message(&*p))
}

/// The message of a panic's payload.
fn panic_message(panic: &(dyn std::any::Any + Send)) -> String {
    panic
        .downcast_ref::<String>()
        .cloned()
        .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_default()
}

impl Batch {
    /// A batch of variants of `base`. `part` names the component whose mass the
    /// `part_mass_kg` column gives. Lanes keep no samples.
    pub fn new(base: Simulation, part: Option<&str>) -> Result<Batch, String> {
        let options = crate::flight::SimOptions {
            keep_samples: false,
            ..*base.options()
        };
        let base = base.with_options(options).map_err(|e| e.to_string())?;
        Ok(Batch {
            base,
            part: part.map(str::to_string),
            weather: None,
        })
    }

    /// The batch whose variants may draw their launch time and ensemble member from
    /// `weather` (the base's air and wind must be the file's at its time and member).
    pub fn with_weather(mut self, weather: BatchWeather) -> Batch {
        self.weather = Some(weather);
        self
    }

    /// This batch with its lanes keeping their samples (each lane's [`LaneResult::samples`]),
    /// for the few variants whose time series are wanted. Recording a sample changes no
    /// number of the flight.
    pub fn keeping_samples(&self) -> Result<Batch, String> {
        let options = crate::flight::SimOptions {
            keep_samples: true,
            ..*self.base.options()
        };
        Ok(Batch {
            base: self
                .base
                .clone()
                .with_options(options)
                .map_err(|e| e.to_string())?,
            part: self.part.clone(),
            weather: self.weather.clone(),
        })
    }

    /// The base flight (samples off, unless [`Batch::keeping_samples`]).
    pub fn base(&self) -> &Simulation {
        &self.base
    }

    /// Check the shapes of `columns`: every flat column empty or `columns.len` long, every
    /// nested one empty or one column per parachute (shift) of the base, each empty or full.
    pub fn check(&self, columns: &Columns) -> Result<(), String> {
        let n = columns.len;
        let flat: [(&str, &Vec<f64>); 20] = [
            ("structure_delta_mass_kg", &columns.structure_delta_mass_kg),
            ("structure_delta_cg_m", &columns.structure_delta_cg_m),
            ("part_mass_kg", &columns.part_mass_kg),
            ("impulse_scale", &columns.impulse_scale),
            ("time_scale", &columns.time_scale),
            ("drag_scale", &columns.drag_scale),
            ("elevation_m", &columns.elevation_m),
            ("temperature_k", &columns.temperature_k),
            ("pressure_pa", &columns.pressure_pa),
            ("launch_time_s", &columns.launch_time_s),
            ("weather_member", &columns.weather_member),
            ("wind_speed_m_s", &columns.wind_speed_m_s),
            ("wind_from_deg", &columns.wind_from_deg),
            ("wind_scale", &columns.wind_scale),
            ("wind_rotation_deg", &columns.wind_rotation_deg),
            (
                "wind_turbulence_intensity",
                &columns.wind_turbulence_intensity,
            ),
            ("rail_length_m", &columns.rail_length_m),
            ("air_brakes_target_m", &columns.air_brakes_target_m),
            ("rail_inclination_deg", &columns.rail_inclination_deg),
            ("rail_heading_deg", &columns.rail_heading_deg),
        ];
        let seeds = ("sensor_seed", columns.sensor_seed.len());
        for (name, len) in flat.iter().map(|(name, c)| (*name, c.len())).chain([seeds]) {
            if len != 0 && len != n {
                return Err(format!("column {name} has {len} values for {n} variants"));
            }
        }
        let (chutes, shifts) = (self.base.parachutes().len(), self.base.shifts().len());
        let releases = self.base.releases().len();
        let nested = [
            ("chute_cds_m2", &columns.chute_cds_m2, chutes),
            ("chute_lag_s", &columns.chute_lag_s, chutes),
            ("chute_trigger", &columns.chute_trigger, chutes),
            ("shift_travel_m", &columns.shift_travel_m, shifts),
            ("shift_duration_s", &columns.shift_duration_s, shifts),
            ("shift_trigger", &columns.shift_trigger, shifts),
            ("release_trigger", &columns.release_trigger, releases),
            ("release_cda_m2", &columns.release_cda_m2, releases),
            (
                "release_chute_cds_m2",
                &columns.release_chute_cds_m2,
                releases,
            ),
            (
                "release_chute_lag_s",
                &columns.release_chute_lag_s,
                releases,
            ),
        ];
        for (name, c, count) in nested {
            if !c.is_empty() && c.len() != count {
                return Err(format!(
                    "column {name} has {} entries for {count} of them",
                    c.len()
                ));
            }
            for (k, col) in c.iter().enumerate() {
                if !col.is_empty() && col.len() != n {
                    return Err(format!(
                        "column {name}[{k}] has {} values for {n} variants",
                        col.len()
                    ));
                }
            }
        }
        if !columns.part_mass_kg.is_empty() && self.part.is_none() {
            return Err("column part_mass_kg needs the part it gives the mass of".into());
        }
        Ok(())
    }

    /// The single-flight simulation of row `row` of `columns` (checked by [`Batch::check`]):
    /// the base with the row applied, all of it with one rebuild. The lane flies exactly
    /// this. A site's elevation moves an inverse-square gravity's site with it.
    pub fn variant(&self, columns: &Columns, row: usize) -> Result<Simulation, String> {
        self.variant_in(columns, row, &AirTables::default())
    }

    /// [`Batch::variant`], its air table taken from `tables` when one there is the table of
    /// its air (a site's temperature or pressure swept over a few values), and kept there
    /// when new.
    fn variant_in(
        &self,
        columns: &Columns,
        row: usize,
        tables: &AirTables,
    ) -> Result<Simulation, String> {
        let c = columns;
        let get = |col: &Vec<f64>| col.get(row).copied();
        let nested =
            |cols: &Vec<Vec<f64>>, k: usize| cols.get(k).and_then(|col| col.get(row).copied());
        let base = &self.base;
        let setup = SimError::Setup;
        let changed = base.clone().with_changes(|ch| {
            let (temperature, pressure) = (get(&c.temperature_k), get(&c.pressure_pa));
            let (time, member) = (get(&c.launch_time_s), get(&c.weather_member));
            let drawn = time.is_some() || member.is_some();
            if get(&c.elevation_m).is_some()
                || temperature.is_some()
                || pressure.is_some()
                || drawn
                || get(&c.wind_speed_m_s).is_some()
                || get(&c.wind_from_deg).is_some()
                || get(&c.wind_scale).is_some()
                || get(&c.wind_rotation_deg).is_some()
                || get(&c.wind_turbulence_intensity).is_some()
                || get(&c.rail_length_m).is_some()
                || get(&c.rail_inclination_deg).is_some()
                || get(&c.rail_heading_deg).is_some()
            {
                let mut env = base.environment().clone();
                // The base wind's transformation and turbulence, before a drawn weather
                // replaces the wind as given.
                let (scale, rotation) = env.wind.transformation();
                let base_turbulence = env.wind.turbulence_intensity();
                if drawn {
                    let w = self.weather.as_ref().ok_or_else(|| {
                        setup("the launch time and weather member columns need the batch's weather file".into())
                    })?;
                    let index = w
                        .site
                        .member_index(member.unwrap_or(w.member))
                        .map_err(|e| setup(format!("weather: {e}")))?;
                    let site = w
                        .site
                        .over_site(time.unwrap_or(w.time_s), index, w.elevation_m)
                        .map_err(|e| setup(format!("weather: {e}")))?;
                    env.air = site.air_model();
                    env.wind = site.wind().map_err(|e| setup(format!("weather: {e}")))?;
                }
                if temperature.is_some() || pressure.is_some() {
                    env.air = env
                        .air
                        .with_site_values(env.elevation_m, temperature, pressure)
                        .map_err(|e| setup(format!("environment: {e}")))?;
                }
                if drawn || temperature.is_some() || pressure.is_some() {
                    if let Some(table) = tables.find(&env.air) {
                        ch.air_table_candidate(table);
                    }
                }
                if let Some(v) = get(&c.elevation_m) {
                    env.elevation_m = v;
                    env.gravity = env
                        .gravity
                        .at_launch_elevation(v)
                        .map_err(|e| setup(format!("environment: {e}")))?;
                }
                let turbulence = get(&c.wind_turbulence_intensity).unwrap_or(base_turbulence);
                if get(&c.wind_speed_m_s).is_some() || get(&c.wind_from_deg).is_some() {
                    let (speed, from) = env.wind.constant_parts().ok_or_else(|| {
                        setup("the base wind is a table, whose speed and direction the wind columns can't set (scale and turn it with wind_scale and wind_rotation_deg)".into())
                    })?;
                    env.wind = Wind::constant(
                        get(&c.wind_speed_m_s).unwrap_or(speed),
                        get(&c.wind_from_deg).unwrap_or(from),
                    )
                    .map_err(|e| setup(format!("wind: {e}")))?;
                }
                env.wind = env
                    .wind
                    .transformed(
                        get(&c.wind_scale).unwrap_or(scale),
                        get(&c.wind_rotation_deg).unwrap_or(rotation),
                    )
                    .and_then(|w| w.with_turbulence(turbulence))
                    .map_err(|e| setup(format!("{e}")))?;
                let mut rail = *base.rail();
                rail.length_m = get(&c.rail_length_m).unwrap_or(rail.length_m);
                rail.inclination_deg = get(&c.rail_inclination_deg).unwrap_or(rail.inclination_deg);
                rail.heading_deg = get(&c.rail_heading_deg).unwrap_or(rail.heading_deg);
                ch.site(env, rail)?;
            }
            if get(&c.impulse_scale).is_some() || get(&c.time_scale).is_some() {
                let o = *base.motor_options();
                ch.motor_scales(
                    o.with_impulse_scale(get(&c.impulse_scale).unwrap_or(o.impulse_scale))
                        .with_time_scale(get(&c.time_scale).unwrap_or(o.time_scale)),
                )?;
            }
            if let Some(v) = get(&c.drag_scale) {
                ch.drag_scale(v)?;
            }
            if let Some(v) = get(&c.air_brakes_target_m) {
                ch.air_brakes_target(v)?;
            }
            if let Some(&seed) = c.sensor_seed.get(row) {
                ch.sensor_seed(seed);
            }
            if let Some(m) = get(&c.part_mass_kg) {
                ch.part_mass(self.part.as_deref().unwrap_or_default(), m)?;
            }
            if get(&c.structure_delta_mass_kg).is_some() || get(&c.structure_delta_cg_m).is_some() {
                ch.mass_adjustment(
                    get(&c.structure_delta_mass_kg).unwrap_or(0.0),
                    get(&c.structure_delta_cg_m).unwrap_or(0.0),
                )?;
            }
            let mut chutes = base.parachutes().to_vec();
            let mut changed = false;
            for (k, p) in chutes.iter_mut().enumerate() {
                if let Some(v) = nested(&c.chute_cds_m2, k) {
                    p.cds_m2 = v;
                    changed = true;
                }
                if let Some(v) = nested(&c.chute_lag_s, k) {
                    p.lag_s = v;
                    changed = true;
                }
                if let Some(v) = nested(&c.chute_trigger, k) {
                    p.trigger = with_number(p.trigger, v)
                        .map_err(|r| setup(format!("parachute {k}: {r}")))?;
                    changed = true;
                }
            }
            if changed {
                ch.parachutes(chutes)?;
            }
            let mut shifts = base.shifts().to_vec();
            let mut changed = false;
            for (k, s) in shifts.iter_mut().enumerate() {
                if let Some(v) = nested(&c.shift_travel_m, k) {
                    s.travel_m = v;
                    changed = true;
                }
                if let Some(v) = nested(&c.shift_duration_s, k) {
                    s.duration_s = v;
                    changed = true;
                }
                if let Some(v) = nested(&c.shift_trigger, k) {
                    s.trigger =
                        with_number(s.trigger, v).map_err(|r| setup(format!("shift {k}: {r}")))?;
                    changed = true;
                }
            }
            if changed {
                ch.shifts(shifts)?;
            }
            let mut releases = base.releases().to_vec();
            let mut changed = false;
            for (k, r) in releases.iter_mut().enumerate() {
                if let Some(v) = nested(&c.release_trigger, k) {
                    r.trigger = with_number(r.trigger, v)
                        .map_err(|e| setup(format!("release {k}: {e}")))?;
                    changed = true;
                }
                if let Some(v) = nested(&c.release_cda_m2, k) {
                    r.cda_m2 = Some(v);
                    changed = true;
                }
                let cds = nested(&c.release_chute_cds_m2, k);
                let lag = nested(&c.release_chute_lag_s, k);
                if cds.is_some() || lag.is_some() {
                    let chute = r.parachute.as_mut().ok_or_else(|| {
                        setup(format!("release {k}: its part has no parachute to vary"))
                    })?;
                    chute.cds_m2 = cds.unwrap_or(chute.cds_m2);
                    chute.lag_s = lag.unwrap_or(chute.lag_s);
                    changed = true;
                }
            }
            if changed {
                ch.releases(releases)?;
            }
            Ok(())
        });
        let sim = changed.map_err(|e| e.to_string())?;
        tables.keep(&sim.model().air);
        Ok(sim)
    }

    fn empty(&self, variant: usize, status: Status, error: String) -> LaneResult {
        LaneResult {
            variant,
            status,
            error: Some(error),
            flown: false,
            metrics: Metrics::default(),
            end_s: 0.0,
            shifts: vec![ShiftOutcome::default(); self.base.shifts().len()],
            parachutes: vec![ParachuteOutcome::default(); self.base.parachutes().len()],
            releases: vec![ReleaseOutcome::default(); self.base.releases().len()],
            warnings: Vec::new(),
            derivative_evaluations: 0,
            samples: Vec::new(),
        }
    }

    /// A lane's result from its simulation and its flight: what a lane of `sim` gives
    /// for `flight` (public so that a variant flown again alone, with its samples, is judged
    /// by the same code as its lane).
    pub fn lane_result(
        &self,
        sim: &Simulation,
        flight: Result<Flight, SimError>,
        variant: usize,
    ) -> LaneResult {
        let mut flight = match flight {
            Ok(f) => f,
            Err(e) => return self.empty(variant, Status::Failed, e.to_string()),
        };
        let samples = std::mem::take(&mut flight.samples);
        let model = sim.model();
        let end = flight.events.last().map_or(0.0, |e| e.time_s);
        let margin = |t: f64| {
            (t <= end).then(|| sim.static_margin_for(sim.mass_properties(&flight, t).cg_m.x))
        };
        let shifts = (0..self.base.shifts().len())
            .map(|k| {
                let start = flight.shift_starts_s.get(k).copied().flatten();
                ShiftOutcome {
                    start_s: start,
                    margin_before_cal: start.and_then(margin),
                    margin_after_cal: start.and_then(|t| margin(t + model.shifts[k].duration_s)),
                }
            })
            .collect();
        let parachutes = (0..self.base.parachutes().len())
            .map(|i| {
                let d = flight.deploy(i);
                ParachuteOutcome {
                    deploy_time_s: d.map(|d| d.0),
                    deploy_speed_m_s: d.map(|d| d.1),
                }
            })
            .collect();
        let releases = flight.releases.iter().map(ReleaseOutcome::of).collect();
        let (status, error) = if flight.metrics.landing_time_s.is_some() {
            (Status::Landed, None)
        } else if flight.event(EventKind::TimeLimit).is_some() {
            (
                Status::TimeLimit,
                Some(format!(
                    "reached the time limit of {} s before landing",
                    model.options.max_time_s
                )),
            )
        } else {
            (
                Status::Failed,
                Some("the flight ended without landing".into()),
            )
        };
        LaneResult {
            variant,
            status,
            error,
            flown: true,
            metrics: flight.metrics,
            end_s: end,
            shifts,
            parachutes,
            releases,
            warnings: flight.warnings(),
            derivative_evaluations: flight.derivative_evaluations,
            samples,
        }
    }

    /// Fly every row of `columns` on this thread, row `r` as variant `first + r`, and return
    /// their results in row order. Errs (flying nothing) if the columns' shapes are wrong.
    ///
    /// Up to [`LANES_IN_FLIGHT`] rows fly at once; each lane's pad, rail, events and step
    /// ends run as in a single flight, and the free-flight steps of four lanes are taken
    /// together: every stage of their Dormand–Prince steps is one evaluation of the kernel on
    /// four lanes ([`derivative_6dof_lanes`](crate::flight::model::derivative_6dof_lanes) on
    /// [`F64x4`](crate::lanes::F64x4)); each lane under canopy takes its own RODAS4 step. A
    /// lane that lands is replaced by the next row.
    pub fn fly_chunk(&self, columns: &Columns, first: usize) -> Result<Vec<LaneResult>, String> {
        self.check(columns)?;
        let n = columns.len;
        // Each row's simulation, built when its lane starts; lanes borrow their model from it.
        let sims: Vec<OnceCell<Result<Simulation, (Status, String)>>> =
            (0..n).map(|_| OnceCell::new()).collect();
        let mut results: Vec<Option<LaneResult>> = (0..n).map(|_| None).collect();
        let mut lanes: Vec<Lane<'_>> = Vec::with_capacity(LANES_IN_FLIGHT);
        let mut scratch = Scratch::new();
        let air_tables = AirTables::default();
        let mut next_row = 0;
        loop {
            while lanes.len() < LANES_IN_FLIGHT && next_row < n {
                let row = next_row;
                next_row += 1;
                let variant = first + row;
                let sim = sims[row].get_or_init(|| {
                    match guarded(|| self.variant_in(columns, row, &air_tables)) {
                        Ok(Ok(sim)) => Ok(sim),
                        Ok(Err(refusal)) => Err((Status::Refused, refusal)),
                        Err(p) => Err((Status::Failed, format!("the simulator panicked: {p}"))),
                    }
                });
                let sim = match sim {
                    Ok(s) => s,
                    Err((status, e)) => {
                        results[row] = Some(self.empty(variant, *status, e.clone()));
                        continue;
                    }
                };
                // Lanes observe nothing: a zero-sized observer, leaked without allocating.
                let observer: &mut () = Box::leak(Box::new(()));
                match guarded(|| fly_to_free(sim.model(), observer, None)) {
                    Ok(Ok(Progress::Free(paused))) => lanes.push(Lane {
                        row,
                        sim,
                        flying: Flying::Free(paused),
                        end: None,
                        retrying: false,
                    }),
                    Ok(Ok(Progress::Done(flight))) => {
                        results[row] = Some(self.lane_result(sim, Ok(flight), variant))
                    }
                    Ok(Err(e)) => results[row] = Some(self.lane_result(sim, Err(e), variant)),
                    Err(p) => results[row] = Some(self.panicked(variant, &p)),
                }
            }
            if lanes.is_empty() {
                break;
            }
            // Free flights whose mass changes first (their groups compute mass states four at
            // a time), then the other free flights, then descents: each group holds lanes of
            // one phase. (A lane's results do not depend on its group.) Stable, so that lanes
            // keep their groups from round to round where they can (measured 1-2 % quicker
            // than the unstable sort); on at most 20 elements, as here, it is an insertion
            // sort in place and allocates nothing.
            lanes.sort_by_key(|l| match &l.flying {
                Flying::Free(p) => u8::from(!p.mass_changing()),
                _ => 2,
            });
            let n_free = lanes
                .iter()
                .take_while(|l| matches!(l.flying, Flying::Free(_)))
                .count();
            let (free, descents) = lanes.split_at_mut(n_free);
            for (index, group) in free.chunks_mut(4).enumerate() {
                step_group(group, &mut scratch, index);
            }
            for (index, group) in descents.chunks_mut(4).enumerate() {
                step_group(group, &mut scratch, index);
            }
            // Lanes whose phase ended: on to their descent, or to their result.
            let mut k = 0;
            while k < lanes.len() {
                let Some(end) = lanes[k].end.take() else {
                    k += 1;
                    continue;
                };
                let (sim, variant) = (lanes[k].sim, first + lanes[k].row);
                let flying = std::mem::replace(&mut lanes[k].flying, Flying::Gone);
                let result = match (end, flying) {
                    (LaneEnd::Free(end), Flying::Free(p)) => {
                        match guarded(move || p.after_free(end)) {
                            Ok(Ok(AfterFree::Descending(d))) => {
                                lanes[k].flying = Flying::Descent(d);
                                k += 1;
                                continue;
                            }
                            Ok(Ok(AfterFree::Done(flight))) => {
                                self.lane_result(sim, Ok(flight), variant)
                            }
                            Ok(Err(e)) => self.lane_result(sim, Err(e), variant),
                            Err(p) => self.panicked(variant, &p),
                        }
                    }
                    (LaneEnd::Landed, Flying::Descent(d)) => match guarded(move || d.finish()) {
                        Ok(flight) => self.lane_result(sim, Ok(flight), variant),
                        Err(p) => self.panicked(variant, &p),
                    },
                    (LaneEnd::Error(e), _) => self.lane_result(sim, Err(e), variant),
                    (LaneEnd::Panic(p), _) => self.panicked(variant, &p),
                    _ => self.panicked(variant, "lost its flight"),
                };
                let lane = lanes.swap_remove(k);
                results[lane.row] = Some(result);
            }
        }
        Ok(results
            .into_iter()
            .enumerate()
            .map(|(row, r)| r.unwrap_or_else(|| self.panicked(first + row, "was never flown")))
            .collect())
    }

    fn panicked(&self, variant: usize, message: &str) -> LaneResult {
        self.empty(
            variant,
            Status::Failed,
            format!("the simulator panicked: {message}"),
        )
    }
}

#[cfg(test)]
mod tests;
