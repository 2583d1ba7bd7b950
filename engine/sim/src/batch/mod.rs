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
mod prefix;
mod stream;

pub use group::{eval_four, LANES_IN_FLIGHT};
pub use prefix::{Prefix, PrefixStore, Share};

use crate::atmosphere::{AirModel, AirTable};
use crate::events::EventKind;
use crate::flight::changes::InputContext;
use crate::flight::driver::{fly_to_free, AfterFree, Progress};
use crate::flight::DesignTables;
use crate::flight::{Flight, Metrics, SetupError, SimError, Simulation, Warning};
use crate::inputs::{Input, Part};
use crate::weather::SiteWeather;
use group::{step_group, Flying, Lane, LaneEnd, Scratch};
use hpr_design::design::dimension::{DesignSource, Dimension};
use hpr_design::motor::Motor;
use hpr_design::Design;
use std::cell::{OnceCell, RefCell};
use std::collections::HashMap;
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
/// `r`-th of those variants. An input without a column keeps the base simulation's value in
/// every variant; a column has one value per variant, as a scenario writes it (the
/// [`Input`]'s key and unit), applied by [`Changes::set`](crate::flight::changes::Changes::set).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Columns {
    pub len: usize,
    /// The varied inputs, each with its values.
    pub inputs: Vec<(Input, Vec<f64>)>,
    /// The seed of the parachutes' sensor noise ([`Simulation::with_sensor_seed`]), empty or
    /// one per variant.
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
    /// Columns of `len` variants, none of them varied yet.
    pub fn new(len: usize) -> Columns {
        Columns {
            len,
            ..Columns::default()
        }
    }

    /// These columns with `input` given `values` (one per variant).
    pub fn with(mut self, input: Input, values: Vec<f64>) -> Columns {
        self.inputs.push((input, values));
        self
    }

    /// The values of `input`, if it has a column.
    pub fn get(&self, input: Input) -> Option<&[f64]> {
        self.inputs
            .iter()
            .find(|(i, _)| *i == input)
            .map(|(_, c)| c.as_slice())
    }

    /// The values of `input`, a column of its own made if it has none yet.
    pub fn column_mut(&mut self, input: Input) -> &mut Vec<f64> {
        let k = match self.inputs.iter().position(|(i, _)| *i == input) {
            Some(k) => k,
            None => {
                self.inputs.push((input, Vec::new()));
                self.inputs.len() - 1
            }
        };
        &mut self.inputs[k].1
    }

    /// The rows `rows` of these columns. A column too short for `rows` gives the values it
    /// has, which [`Batch::check`] then refuses (never a panic).
    pub fn slice(&self, rows: Range<usize>) -> Columns {
        fn part<T: Clone>(c: &[T], rows: &Range<usize>) -> Vec<T> {
            let end = rows.end.min(c.len());
            c[rows.start.min(end)..end].to_vec()
        }
        Columns {
            len: rows.len(),
            inputs: self
                .inputs
                .iter()
                .map(|(input, c)| (*input, part(c, &rows)))
                .collect(),
            sensor_seed: part(&self.sensor_seed, &rows),
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
    /// The motors the [`Input::Motor`] column numbers.
    motors: Arc<Vec<Motor>>,
    /// The design's dimensions the [`Input::Design`] columns give, and the designs built.
    designs: Option<Arc<BatchDesigns>>,
}

/// The designs of a batch whose lanes change the design's dimensions ([`Input::Design`]): the
/// design's JSON form, the dimensions by number, and the designs already built with their
/// tables, by their dimensions' values (each sweep point's, built once before the run). A row
/// of values not among them (a dimension dispersed) is built for its lane: the design
/// validated again and its tables built again.
#[derive(Debug)]
pub struct BatchDesigns {
    pub source: DesignSource,
    pub dimensions: Vec<Dimension>,
    built: HashMap<Vec<(usize, u64)>, (Design, Arc<DesignTables>)>,
}

impl BatchDesigns {
    pub fn new(source: DesignSource, dimensions: Vec<Dimension>) -> BatchDesigns {
        BatchDesigns {
            source,
            dimensions,
            built: HashMap::new(),
        }
    }

    fn key(values: &[(usize, f64)]) -> Vec<(usize, u64)> {
        let mut key: Vec<(usize, u64)> = values.iter().map(|&(k, v)| (k, v.to_bits())).collect();
        key.sort_unstable();
        key
    }

    /// The design with the dimensions `values` (by number) changed, and its tables: built
    /// before, or built now. The error names the rule the design breaks.
    pub fn design(&self, values: &[(usize, f64)]) -> Result<(Design, Arc<DesignTables>), SimError> {
        if let Some((d, t)) = self.built.get(&Self::key(values)) {
            return Ok((d.clone(), t.clone()));
        }
        let mut changes = Vec::with_capacity(values.len());
        for &(k, v) in values {
            let dim = self.dimensions.get(k).ok_or(SetupError::NoSuchDimension {
                index: k,
                count: self.dimensions.len(),
            })?;
            changes.push((dim, v));
        }
        let design = self
            .source
            .design_with(&changes)
            .map_err(SetupError::Design)?;
        let tables = DesignTables::new(&design)?;
        Ok((design, Arc::new(tables)))
    }

    /// Build the design of `values` now and keep it for the lanes that fly it (a sweep
    /// point's). The error names the rule the design breaks (nothing is kept).
    pub fn keep(&mut self, values: &[(usize, f64)]) -> Result<(), SimError> {
        let built = self.design(values)?;
        self.built.insert(Self::key(values), built);
        Ok(())
    }
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

/// Why a batch's columns can't be flown: their shapes do not fit each other or the batch
/// ([`Batch::check`]). Nothing is flown.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ColumnsError {
    /// The seeds are given, but not one per variant.
    #[error("column sensor_seed has {seeds} values for {variants} variants")]
    SeedCount { seeds: usize, variants: usize },
    /// An input's column is not one value per variant.
    #[error("column {} has {values} values for {variants} variants", .input.name())]
    Length {
        input: Input,
        values: usize,
        variants: usize,
    },
    /// An input has two columns.
    #[error("column {} is given twice", .input.name())]
    Twice { input: Input },
    /// An input of a parachute, shift or release the base flight does not have (it has
    /// `count` of that kind).
    #[error("column {} is of a part the flight does not have (it has {count})", .input.name())]
    NoSuchPart { input: Input, count: usize },
    /// A ballast's mass for a batch that names no part ([`Batch::new`]).
    #[error("column {} needs the part it gives the mass of", .input.name())]
    NeedsPart { input: Input },
}

/// Run `f`, turning a panic into its message.
fn guarded<R>(f: impl FnOnce() -> R) -> Result<R, String> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).map_err(|p| panic_message(&*p))
}

/// Sort `lanes` stably (in place, allocating nothing): free flights whose mass changes, the
/// other free flights, then descents.
fn sort_stably_by_phase(lanes: &mut [Lane<'_>]) {
    debug_assert!(
        lanes.len() <= LANES_IN_FLIGHT,
        "a chunk flies at most {LANES_IN_FLIGHT} lanes"
    );
    let mut keys = [0u8; LANES_IN_FLIGHT];
    for (k, l) in keys.iter_mut().zip(lanes.iter()) {
        *k = match &l.flying {
            Flying::Free(p) => u8::from(!p.mass_changing()),
            _ => 2,
        };
    }
    for i in 1..lanes.len() {
        let mut j = i;
        while j > 0 && keys[j - 1] > keys[j] {
            keys.swap(j - 1, j);
            lanes.swap(j - 1, j);
            j -= 1;
        }
    }
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
            motors: Arc::new(Vec::new()),
            designs: None,
        })
    }

    /// The batch whose variants may draw their launch time and ensemble member from
    /// `weather` (the base's air and wind must be the file's at its time and member).
    pub fn with_weather(mut self, weather: BatchWeather) -> Batch {
        self.weather = Some(weather);
        self
    }

    /// The batch whose [`Input::Motor`] column numbers `motors`.
    pub fn with_motors(mut self, motors: Vec<Motor>) -> Batch {
        self.motors = Arc::new(motors);
        self
    }

    /// The batch whose [`Input::Design`] columns give `designs`' dimensions.
    pub fn with_designs(mut self, designs: Arc<BatchDesigns>) -> Batch {
        self.designs = Some(designs);
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
            motors: self.motors.clone(),
            designs: self.designs.clone(),
        })
    }

    /// The base flight (samples off, unless [`Batch::keeping_samples`]).
    pub fn base(&self) -> &Simulation {
        &self.base
    }

    /// Check the shapes of `columns`: every column `columns.len` long (the seeds empty or
    /// that long), no input twice, every parachute's, shift's or release's input of one the
    /// base has, and a ballast's mass only for a batch that names its part.
    pub fn check(&self, columns: &Columns) -> Result<(), ColumnsError> {
        let n = columns.len;
        let seeds = columns.sensor_seed.len();
        if seeds != 0 && seeds != n {
            return Err(ColumnsError::SeedCount { seeds, variants: n });
        }
        for (k, (input, c)) in columns.inputs.iter().enumerate() {
            let input = *input;
            if c.len() != n {
                return Err(ColumnsError::Length {
                    input,
                    values: c.len(),
                    variants: n,
                });
            }
            if columns.inputs[..k].iter().any(|(i, _)| *i == input) {
                return Err(ColumnsError::Twice { input });
            }
            if let Some((part, index)) = input.part() {
                let count = match part {
                    Part::Parachute => self.base.parachutes().len(),
                    Part::Shift => self.base.shifts().len(),
                    Part::Release => self.base.releases().len(),
                };
                if index >= count {
                    return Err(ColumnsError::NoSuchPart { input, count });
                }
            }
            if input == Input::BallastKg && self.part.is_none() {
                return Err(ColumnsError::NeedsPart { input });
            }
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
        let find = |air: &AirModel| tables.find(air);
        let design = |values: &[(usize, f64)]| match &self.designs {
            Some(d) => d.design(values),
            None => Err(SimError::Setup(SetupError::NoDesigns)),
        };
        let context = InputContext {
            part: self.part.as_deref(),
            weather: self.weather.as_ref(),
            air_table: Some(&find),
            motors: &self.motors,
            design: Some(&design),
        };
        let changed = self.base.clone().with_changes(|ch| {
            for (input, c) in &columns.inputs {
                if let Some(&v) = c.get(row) {
                    ch.set(*input, v);
                }
            }
            ch.apply_inputs(&context)?;
            if let Some(&seed) = columns.sensor_seed.get(row) {
                ch.sensor_seed(seed);
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
    /// their results in row order. Errs (flying nothing) if the columns' shapes are wrong
    /// ([`ColumnsError`]).
    ///
    /// Up to [`LANES_IN_FLIGHT`] rows fly at once; each lane's pad, rail, events and step
    /// ends run as in a single flight, and the free-flight steps of four lanes are taken
    /// together: every stage of their Dormand–Prince steps is one evaluation of the kernel on
    /// four lanes ([`derivative_6dof_lanes`](crate::flight::model::derivative_6dof_lanes) on
    /// [`F64x4`](crate::lanes::F64x4)); each lane under canopy takes its own RODAS4 step. A
    /// lane that lands is replaced by the next row.
    pub fn fly_chunk(
        &self,
        columns: &Columns,
        first: usize,
    ) -> Result<Vec<LaneResult>, ColumnsError> {
        self.fly_chunk_sharing(columns, first, None)
    }

    /// [`Batch::fly_chunk`], rows that share the beginning of their flights with rows of
    /// other chunks flying it once (`share`: each row's [`Prefix`], or `None` for a row
    /// that shares nothing, and the [`PrefixStore`] the chunks leave and take beginnings
    /// in). The results are [`Batch::fly_chunk`]'s, bit for bit.
    pub fn fly_chunk_sharing(
        &self,
        columns: &Columns,
        first: usize,
        share: Option<(&[Option<Prefix>], &PrefixStore<'_>)>,
    ) -> Result<Vec<LaneResult>, ColumnsError> {
        self.check(columns)?;
        // Lanes keeping their samples share nothing: a store's beginnings may have kept none.
        let share = share.filter(|_| !self.base.options().keep_samples);
        let prefix_of =
            |row: usize| share.and_then(|(p, store)| Some((p.get(row).copied().flatten()?, store)));
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
                let prefix = prefix_of(row);
                let sim = match sim {
                    Ok(s) => s,
                    Err((status, e)) => {
                        results[row] = Some(self.empty(variant, *status, e.clone()));
                        // A refused borrower takes nothing: its owner's flight is kept for
                        // one flight fewer.
                        if let Some((
                            Prefix {
                                take: Some(take), ..
                            },
                            store,
                        )) = prefix
                        {
                            store.pass(&take);
                        }
                        continue;
                    }
                };
                let keeps = prefix.is_some_and(|(p, _)| p.keep.is_some());
                let lane = |flying| Lane {
                    row,
                    sim,
                    flying,
                    end: None,
                    retrying: false,
                    owns_prefix: keeps,
                };
                if let Some((
                    Prefix {
                        take: Some(take), ..
                    },
                    store,
                )) = prefix
                {
                    match guarded(|| store.take(&take, sim.model(), columns, row)) {
                        Ok(Some(paused)) => {
                            lanes.push(lane(Flying::Free(paused)));
                            continue;
                        }
                        Ok(None) => {}
                        Err(p) => {
                            results[row] = Some(self.panicked(variant, &p));
                            continue;
                        }
                    }
                }
                // Lanes observe nothing: a zero-sized observer, leaked without allocating.
                let observer: &mut () = Box::leak(Box::new(()));
                match guarded(|| fly_to_free(sim.model(), observer, None)) {
                    Ok(Ok(Progress::Free(paused))) => lanes.push(lane(Flying::Free(paused))),
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
            // Owners whose next step might tell their flight from their borrowers' leave
            // it for them now, between steps.
            if let Some((prefixes, store)) = share {
                for lane in lanes.iter_mut().filter(|l| l.owns_prefix && !l.retrying) {
                    let (
                        Flying::Free(p),
                        Some(Some(Prefix {
                            keep: Some(keep), ..
                        })),
                    ) = (&mut lane.flying, prefixes.get(lane.row))
                    else {
                        lane.owns_prefix = false;
                        continue;
                    };
                    if !p.next_step_before(keep.until_s) {
                        lane.owns_prefix = false;
                        // Leaving it is no part of this lane's flight: if it fails, the
                        // borrowers fly from the pad.
                        let _ = guarded(|| store.keep(keep, p, columns, lane.row));
                    }
                }
            }
            // Free flights whose mass changes first (their groups compute mass states four at
            // a time), then the other free flights, then descents: each group holds lanes of
            // one phase. (A lane's results do not depend on its group.) Stable, so that lanes
            // keep their groups from round to round where they can (measured 1-2 % quicker
            // than the unstable sort): an insertion sort in place on keys read once per lane
            // (a sort by key would read them at every comparison).
            sort_stably_by_phase(&mut lanes);
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
