//! The batch engine: thousands of variants of one flight, their inputs held as columns
//! (structure of arrays), flown in fixed-size chunks across threads with rayon, their results
//! streamed out in variant order.
//!
//! **One physics.** A lane is the base [`Simulation`] with one variant's inputs applied:
//! everything that depends on the design alone (shape integrals, aerodynamic tables, the air
//! table) is shared by `Arc` and never rebuilt; the lane's own light model (motor tables, mass
//! split, rail, wind, parachutes, shifts) is built from the columns, and the flight is the
//! same driver over the same kernels as a single flight. So a lane's metrics are *the*
//! single-flight simulator's for the same inputs ([`Batch::variant`] gives that simulation).
//!
//! **Determinism.** A lane depends only on its row of the columns, never on its chunk, its
//! thread or the order lanes are scheduled in; results are handed to the sink in variant
//! order. **Memory** is a window of chunks in flight at once, whatever the number of
//! variants. **Failures** are rows: a refused input or a flight that fails is recorded with
//! its reason and the run goes on.
//!
//! What it does not do yet: lanes are advanced one whole flight at a time; the stages of
//! different lanes are not evaluated together in SIMD registers.

use crate::events::EventKind;
use crate::flight::{Metrics, Simulation};
use crate::trigger::Trigger;
use crate::wind::Wind;
use rayon::prelude::*;

/// Inputs of each variant, one column per input. An empty column means every variant has the
/// base simulation's value; a full column has one value per variant. Nested columns are per
/// parachute or per shift (in the base simulation's order), each empty or full.
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
    pub wind_speed_m_s: Vec<f64>,
    /// Direction the wind blows from, degrees clockwise from north.
    pub wind_from_deg: Vec<f64>,
    pub rail_length_m: Vec<f64>,
    pub rail_inclination_deg: Vec<f64>,
    pub rail_heading_deg: Vec<f64>,
    pub chute_cds_m2: Vec<Vec<f64>>,
    pub chute_lag_s: Vec<Vec<f64>>,
    /// The number in a parachute's trigger (its time, height or delay).
    pub chute_trigger: Vec<Vec<f64>>,
    pub shift_travel_m: Vec<Vec<f64>>,
    pub shift_duration_s: Vec<Vec<f64>>,
    /// The number in a shift's trigger (its time, height or delay).
    pub shift_trigger: Vec<Vec<f64>>,
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
    /// The flight's metrics (default where the flight did not happen).
    pub metrics: Metrics,
    /// Per shift: its start time, and the static margin just before and just after its move.
    pub shifts: Vec<ShiftOutcome>,
    pub derivative_evaluations: u64,
}

/// What one shift did in a lane.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShiftOutcome {
    pub start_s: Option<f64>,
    pub margin_before_cal: Option<f64>,
    pub margin_after_cal: Option<f64>,
}

/// A batch: the base flight, its columns, and the part the `part_mass_kg` column names.
#[derive(Debug, Clone)]
pub struct Batch {
    base: Simulation,
    part: Option<String>,
    columns: Columns,
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

impl Batch {
    /// A batch of `columns.len` variants of `base`. `part` names the component whose mass the
    /// `part_mass_kg` column gives. Checks the columns' shapes.
    pub fn new(base: Simulation, part: Option<&str>, columns: Columns) -> Result<Batch, String> {
        let n = columns.len;
        let flat: [(&str, &Vec<f64>); 12] = [
            ("structure_delta_mass_kg", &columns.structure_delta_mass_kg),
            ("structure_delta_cg_m", &columns.structure_delta_cg_m),
            ("part_mass_kg", &columns.part_mass_kg),
            ("impulse_scale", &columns.impulse_scale),
            ("time_scale", &columns.time_scale),
            ("drag_scale", &columns.drag_scale),
            ("elevation_m", &columns.elevation_m),
            ("wind_speed_m_s", &columns.wind_speed_m_s),
            ("wind_from_deg", &columns.wind_from_deg),
            ("rail_length_m", &columns.rail_length_m),
            ("rail_inclination_deg", &columns.rail_inclination_deg),
            ("rail_heading_deg", &columns.rail_heading_deg),
        ];
        for (name, c) in flat {
            if !c.is_empty() && c.len() != n {
                return Err(format!(
                    "column {name} has {} values for {n} variants",
                    c.len()
                ));
            }
        }
        let nested = [
            (
                "chute_cds_m2",
                &columns.chute_cds_m2,
                base.parachutes().len(),
            ),
            ("chute_lag_s", &columns.chute_lag_s, base.parachutes().len()),
            (
                "chute_trigger",
                &columns.chute_trigger,
                base.parachutes().len(),
            ),
            (
                "shift_travel_m",
                &columns.shift_travel_m,
                base.shifts().len(),
            ),
            (
                "shift_duration_s",
                &columns.shift_duration_s,
                base.shifts().len(),
            ),
            ("shift_trigger", &columns.shift_trigger, base.shifts().len()),
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
        if !columns.part_mass_kg.is_empty() && part.is_none() {
            return Err("column part_mass_kg needs the part it gives the mass of".into());
        }
        // Lanes keep no samples: only metrics, events and shift start times.
        let options = crate::flight::SimOptions {
            keep_samples: false,
            ..*base.options()
        };
        let base = base.with_options(options).map_err(|e| e.to_string())?;
        Ok(Batch {
            base,
            part: part.map(str::to_string),
            columns,
        })
    }

    pub fn len(&self) -> usize {
        self.columns.len
    }

    pub fn is_empty(&self) -> bool {
        self.columns.len == 0
    }

    /// The single-flight simulation of variant `i`: the base with row `i` applied. The lane
    /// flies exactly this.
    pub fn variant(&self, i: usize) -> Result<Simulation, String> {
        let c = &self.columns;
        let get = |col: &Vec<f64>| col.get(i).copied();
        let nested =
            |cols: &Vec<Vec<f64>>, k: usize| cols.get(k).and_then(|col| col.get(i).copied());
        let e = |e: crate::flight::SimError| e.to_string();
        let mut sim = self.base.clone();
        if get(&c.elevation_m).is_some()
            || get(&c.wind_speed_m_s).is_some()
            || get(&c.wind_from_deg).is_some()
            || get(&c.rail_length_m).is_some()
            || get(&c.rail_inclination_deg).is_some()
            || get(&c.rail_heading_deg).is_some()
        {
            let mut env = sim.environment().clone();
            if let Some(v) = get(&c.elevation_m) {
                env.elevation_m = v;
            }
            if get(&c.wind_speed_m_s).is_some() || get(&c.wind_from_deg).is_some() {
                let (speed, from) = env
                    .wind
                    .constant_parts()
                    .ok_or("the base wind is a table, which the wind columns can't vary")?;
                env.wind = Wind::constant(
                    get(&c.wind_speed_m_s).unwrap_or(speed),
                    get(&c.wind_from_deg).unwrap_or(from),
                )
                .map_err(|e| format!("wind: {e}"))?;
            }
            let mut rail = *sim.rail();
            rail.length_m = get(&c.rail_length_m).unwrap_or(rail.length_m);
            rail.inclination_deg = get(&c.rail_inclination_deg).unwrap_or(rail.inclination_deg);
            rail.heading_deg = get(&c.rail_heading_deg).unwrap_or(rail.heading_deg);
            sim = sim.with_site(env, rail).map_err(e)?;
        }
        if get(&c.impulse_scale).is_some() || get(&c.time_scale).is_some() {
            let mut o = *sim.motor_options();
            o = o
                .with_impulse_scale(get(&c.impulse_scale).unwrap_or(o.impulse_scale))
                .with_time_scale(get(&c.time_scale).unwrap_or(o.time_scale));
            sim = sim.with_motor_scales(o).map_err(e)?;
        }
        if let Some(v) = get(&c.drag_scale) {
            sim = sim.with_drag_scale(v).map_err(e)?;
        }
        if let Some(m) = get(&c.part_mass_kg) {
            sim = sim
                .with_part_mass(self.part.as_deref().unwrap_or_default(), m)
                .map_err(e)?;
        }
        if get(&c.structure_delta_mass_kg).is_some() || get(&c.structure_delta_cg_m).is_some() {
            sim = sim
                .with_mass_adjustment(
                    get(&c.structure_delta_mass_kg).unwrap_or(0.0),
                    get(&c.structure_delta_cg_m).unwrap_or(0.0),
                )
                .map_err(e)?;
        }
        let mut chutes = sim.parachutes().to_vec();
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
                p.trigger = with_number(p.trigger, v).map_err(|r| format!("parachute {k}: {r}"))?;
                changed = true;
            }
        }
        if changed {
            sim = sim.with_parachutes(chutes).map_err(e)?;
        }
        let mut shifts = sim.shifts().to_vec();
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
                s.trigger = with_number(s.trigger, v).map_err(|r| format!("shift {k}: {r}"))?;
                changed = true;
            }
        }
        if changed {
            sim = sim.with_shifts(shifts).map_err(e)?;
        }
        Ok(sim)
    }

    /// Fly lane `i` (no samples kept).
    pub fn fly(&self, i: usize) -> LaneResult {
        let n_shifts = self.base.shifts().len();
        let empty = |status, error: String| LaneResult {
            variant: i,
            status,
            error: Some(error),
            metrics: Metrics::default(),
            shifts: vec![ShiftOutcome::default(); n_shifts],
            derivative_evaluations: 0,
        };
        let sim = match self.variant(i) {
            Ok(s) => s,
            Err(e) => return empty(Status::Refused, e),
        };
        let flight = match sim.run(&mut ()) {
            Ok(f) => f,
            Err(e) => return empty(Status::Failed, e.to_string()),
        };
        let model = sim.model();
        let end = flight.events.last().map_or(0.0, |e| e.time_s);
        let margin = |t: f64| {
            (t <= end).then(|| sim.static_margin_for(sim.mass_properties(&flight, t).cg_m.x))
        };
        let shifts = (0..n_shifts)
            .map(|k| {
                let start = flight.shift_starts_s.get(k).copied().flatten();
                ShiftOutcome {
                    start_s: start,
                    margin_before_cal: start.and_then(margin),
                    margin_after_cal: start.and_then(|t| margin(t + model.shifts[k].duration_s)),
                }
            })
            .collect();
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
            variant: i,
            status,
            error,
            metrics: flight.metrics,
            shifts,
            derivative_evaluations: flight.derivative_evaluations,
        }
    }

    /// Fly every variant on the current rayon pool, `chunk` variants per task, keeping at most
    /// `window` chunks in flight, and hand each result to `sink` in variant order.
    pub fn run(&self, chunk: usize, window: usize, mut sink: impl FnMut(LaneResult)) {
        let chunk = chunk.max(1);
        let window = window.max(1);
        let n = self.len();
        let mut start = 0;
        while start < n {
            let end = (start + chunk * window).min(n);
            let chunks: Vec<Vec<LaneResult>> = (start..end)
                .step_by(chunk)
                .collect::<Vec<_>>()
                .into_par_iter()
                .map(|c0| (c0..(c0 + chunk).min(end)).map(|i| self.fly(i)).collect())
                .collect();
            for r in chunks.into_iter().flatten() {
                sink(r);
            }
            start = end;
        }
    }
}

#[cfg(test)]
#[path = "batch_tests.rs"]
mod tests;
