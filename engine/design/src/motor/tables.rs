//! The motor as the flight sees it: thrust, propellant and mass properties at any time,
//! from tables built once per flight.
//!
//! [`MotorTables::new`] scales the curve (dispersion), and stores per sample the time, the
//! thrust, the slope of the following segment and the cumulative impulse, so that the
//! impulse delivered `I(t) = I_i + F_i (t − t_i) + ½ s_i (t − t_i)²` is exact for the
//! piecewise-linear curve. [`MotorTables::eval`] finds the segment by binary search
//! (O(log n), no allocation, no state, so it can be shared between threads and called at any
//! time in any order, as adaptive and multi-stage integrators do).
//! [`MotorTables::eval_hinted`] is the same look-up started from the caller's last segment
//! (the caller keeps it): a flight whose stages stay in one segment skips the search.
//!
//! The mass model (simulators differ here; this is the one we use, see also the
//! [module docs](super)): propellant `m_p(t) = m_p0 (1 − I(t)/I_total)`, so
//! `ṁ = −m_p0 F(t)/I_total` and `m̈ = −m_p0 F′(t)/I_total` (piecewise constant), as RocketPy's
//! motors burn. The casing is a thin cylindrical shell carrying the dry mass; the propellant a
//! solid cylinder of the same length and diameter whose inertia is proportional to its mass;
//! both centered at the motor's mid-length `x = motor_aft_m − length/2` in the station frame,
//! unless [`MotorOptions`] places them (RocketPy's `SolidMotor` `center_of_dry_mass_position`
//! and `grains_center_of_mass_position`, measured forward of the nozzle) and gives the
//! casing's own inertia (its `dry_inertia`). The motor's center of mass then moves as the
//! propellant burns, which the flight's mass state follows as it follows the rocket's. Given
//! as BATES [`Grains`], the propellant has their mass and their inertia as they burn
//! ([`super::grains`]), which is not in proportion to the mass left.
//!
//! Dispersion: with impulse scale `k_I` and time scale `k_t` the thrust is
//! `F_s(t) = (k_I/k_t) F(t/k_t)`: the impulse scales by `k_I`, the burn time by `k_t`.
//!
//! A cluster ([`MotorTables::clustered`]) is `n` of these motors lit together, their axes
//! parallel to the rocket's at offsets `d_i` across it whose mean is on the axis: thrust,
//! impulse and masses are `n` times one motor's, and each motor adds its mass times
//! `J(d_i) = |d_i|² 1 − d_i d_iᵀ` to the inertia (parallel axes), so the propellant's inertia
//! stays proportional to its mass.

use nalgebra::{Matrix3, Vector3};

use super::{GrainInertia, Grains, Motor, MotorError, MotorField};
use crate::mass::{offsets_inertia, MassProps};

/// Overrides and dispersion applied when the tables are built. The default changes nothing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotorOptions {
    /// Propellant mass at ignition, kg, instead of the file's.
    pub propellant_mass_kg: Option<f64>,
    /// Casing (dry) mass, kg, instead of the file's total less propellant.
    pub dry_mass_kg: Option<f64>,
    /// Total impulse multiplier `k_I` (> 0).
    pub impulse_scale: f64,
    /// Burn time multiplier `k_t` (> 0).
    pub time_scale: f64,
    /// The casing's (dry mass's) center, m forward of the nozzle (the motor's aft end),
    /// instead of its mid-length: RocketPy's `center_of_dry_mass_position`.
    pub dry_center_from_nozzle_m: Option<f64>,
    /// The propellant's center, m forward of the nozzle, instead of the mid-length:
    /// RocketPy's `grains_center_of_mass_position`.
    pub propellant_center_from_nozzle_m: Option<f64>,
    /// The casing's inertia about its own center, `[axial, transverse]` kg·m², instead of a
    /// thin shell's: RocketPy's `dry_inertia` `(I_11, I_22, I_33)` is `[I_33, I_11]`.
    pub dry_inertia_kg_m2: Option<[f64; 2]>,
    /// The propellant as BATES grains (RocketPy's `SolidMotor`): their mass is the propellant's
    /// (so `propellant_mass_kg` is not given with them) and their shape its inertia as they
    /// burn, instead of a solid cylinder's in proportion to the mass left.
    pub grains: Option<Grains>,
    /// The propellant as a solid cylinder of this `[radius, height]`, m, instead of the
    /// motor's own size: RocketPy's `GenericMotor` `chamber_radius`, `chamber_height` (its
    /// `chamber_position` is [`MotorOptions::propellant_center_from_nozzle_m`]).
    pub chamber_m: Option<[f64; 2]>,
    /// The nozzle exit's radius, m (RocketPy's `nozzle_radius`), for the jet damping; default
    /// [`NOZZLE_RADIUS_FRACTION`] of the motor's radius.
    pub nozzle_radius_m: Option<f64>,
}

/// The nozzle exit's radius as a fraction of the motor's radius when not given (RocketPy's
/// Calisto: a 33 mm nozzle on a 75 mm motor, 0.88).
pub const NOZZLE_RADIUS_FRACTION: f64 = 0.88;

impl Default for MotorOptions {
    fn default() -> Self {
        MotorOptions {
            propellant_mass_kg: None,
            dry_mass_kg: None,
            impulse_scale: 1.0,
            time_scale: 1.0,
            dry_center_from_nozzle_m: None,
            propellant_center_from_nozzle_m: None,
            dry_inertia_kg_m2: None,
            grains: None,
            chamber_m: None,
            nozzle_radius_m: None,
        }
    }
}

impl MotorOptions {
    pub fn with_propellant_mass_kg(self, kg: f64) -> Self {
        MotorOptions {
            propellant_mass_kg: Some(kg),
            ..self
        }
    }
    pub fn with_dry_mass_kg(self, kg: f64) -> Self {
        MotorOptions {
            dry_mass_kg: Some(kg),
            ..self
        }
    }
    pub fn with_impulse_scale(self, k: f64) -> Self {
        MotorOptions {
            impulse_scale: k,
            ..self
        }
    }
    pub fn with_time_scale(self, k: f64) -> Self {
        MotorOptions {
            time_scale: k,
            ..self
        }
    }
}

/// The motor at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MotorState {
    /// Thrust along the motor's axis, N (0 before ignition at t = 0 and after burnout).
    pub thrust_n: f64,
    /// dF/dt, N/s (the current segment's slope; 0 outside the burn).
    pub thrust_rate_n_per_s: f64,
    /// Propellant left, kg.
    pub propellant_kg: f64,
    /// d(propellant)/dt, kg/s (≤ 0).
    pub propellant_rate_kg_s: f64,
    /// d²(propellant)/dt², kg/s² (piecewise constant).
    pub propellant_accel_kg_s2: f64,
}

/// How fast the motor's mass and inertia change: the propellant's, about its own center,
/// which does not move (the whole motor's center moves when the casing's is elsewhere; the
/// flight's mass state composes the two).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotorMassRates {
    /// dm/dt, kg/s.
    pub mass_rate_kg_s: f64,
    /// d²m/dt², kg/s².
    pub mass_accel_kg_s2: f64,
    /// dI/dt of the propellant's inertia about its center, station axes, kg·m²/s.
    pub inertia_rate_kg_m2_s: Matrix3<f64>,
    /// d²I/dt², kg·m²/s².
    pub inertia_accel_kg_m2_s2: Matrix3<f64>,
}

/// Flight tables of one motor (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct MotorTables {
    times_s: Vec<f64>,
    thrust_n: Vec<f64>,
    /// Slope of the segment starting at each sample, N/s (0 for the last sample).
    slope_n_per_s: Vec<f64>,
    /// Impulse delivered up to each sample, N·s.
    impulse_ns: Vec<f64>,
    total_impulse_ns: f64,
    burn_time_s: f64,
    propellant_mass_kg: f64,
    dry_mass_kg: f64,
    length_m: f64,
    diameter_m: f64,
    /// Casing inertia about its center.
    casing_inertia: Matrix3<f64>,
    /// Propellant inertia about its center per kilogram of propellant.
    propellant_inertia_per_kg: Matrix3<f64>,
    /// The casing's center, m forward of the motor's aft end.
    casing_center_from_aft_m: f64,
    /// The propellant's center, m forward of the motor's aft end.
    propellant_center_from_aft_m: f64,
    /// The propellant's grains, whose shape adds an inertia not in proportion to the mass
    /// (each motor's, for a cluster).
    grains: Option<Grains>,
    nozzle_radius_m: f64,
    /// Motors lit together (1, or a cluster's tubes).
    motors: usize,
}

impl MotorTables {
    /// Tables of `motor` as it is in its file.
    pub fn from_motor(motor: &Motor) -> Result<Self, MotorError> {
        Self::new(motor, &MotorOptions::default())
    }

    /// Tables of `motor` with `options` applied. Fails when an option or one of the motor's
    /// public mass or size fields is out of range (masses finite and ≥ 0, scales and sizes
    /// finite and > 0).
    pub fn new(motor: &Motor, options: &MotorOptions) -> Result<Self, MotorError> {
        let check = |field: MotorField, value: f64, positive: bool| {
            let ok = value.is_finite() && if positive { value > 0.0 } else { value >= 0.0 };
            if ok {
                Ok(value)
            } else {
                Err(MotorError::InvalidOption {
                    motor: motor.source.clone(),
                    field,
                    value,
                    rule: if positive {
                        "must be finite and greater than zero"
                    } else {
                        "must be finite and not negative"
                    },
                })
            }
        };
        let k_i = check(MotorField::ImpulseScale, options.impulse_scale, true)?;
        let k_t = check(MotorField::TimeScale, options.time_scale, true)?;
        let invalid =
            |field: MotorField, value: f64, rule: &'static str| MotorError::InvalidOption {
                motor: motor.source.clone(),
                field,
                value,
                rule,
            };
        if let Some(g) = &options.grains {
            if let Some((field, value, rule)) = g.check() {
                return Err(invalid(field, value, rule));
            }
            if let Some(m) = options.propellant_mass_kg {
                return Err(invalid(
                    MotorField::PropellantMass,
                    m,
                    "is the grains' (their count, size and density give it): give one or the other",
                ));
            }
        }
        let propellant_mass_kg = match (options.propellant_mass_kg, &options.grains) {
            (_, Some(g)) => g.mass_kg(),
            (Some(m), None) => check(MotorField::PropellantMass, m, false)?,
            (None, None) => check(
                MotorField::MotorFilePropellantMass,
                motor.propellant_mass_kg,
                false,
            )?,
        };
        let dry_mass_kg = match options.dry_mass_kg {
            Some(m) => check(MotorField::DryMass, m, false)?,
            None => check(MotorField::MotorFileDryMass, motor.dry_mass_kg(), false)?,
        };
        let length_m = check(MotorField::MotorFileLength, motor.length_m, true)?;
        let diameter_m = check(MotorField::MotorFileDiameter, motor.diameter_m, true)?;
        let within = |field: MotorField, value: Option<f64>| match value {
            None => Ok(0.5 * length_m),
            Some(x) if (0.0..=length_m).contains(&x) => Ok(x),
            Some(x) => Err(invalid(
                field,
                x,
                "must lie within the motor: from 0 (its nozzle) to its length forward",
            )),
        };
        if let Some([radius, height]) = options.chamber_m {
            if options.grains.is_some() {
                return Err(invalid(
                    MotorField::Chamber,
                    radius,
                    "is the grains' when grains are given: give one or the other",
                ));
            }
            if !(radius.is_finite() && radius > 0.0 && radius <= 0.5 * diameter_m) {
                return Err(invalid(
                    MotorField::ChamberRadius,
                    radius,
                    "must be positive and at most the motor's radius",
                ));
            }
            if !(height.is_finite() && height > 0.0 && height <= length_m) {
                return Err(invalid(
                    MotorField::ChamberHeight,
                    height,
                    "must be positive and at most the motor's length",
                ));
            }
        }
        if let Some(g) = &options.grains {
            if 2.0 * g.outer_radius_m > diameter_m {
                return Err(invalid(
                    MotorField::GrainsOuterRadius,
                    g.outer_radius_m,
                    "must fit in the motor: at most half its diameter",
                ));
            }
            if g.stack_length_m() > length_m {
                return Err(invalid(
                    MotorField::GrainsHeight,
                    g.height_m,
                    "the stack (count × height + the separations between) must fit in the motor's length",
                ));
            }
        }
        let nozzle_radius_m = match options.nozzle_radius_m {
            None => 0.5 * diameter_m * NOZZLE_RADIUS_FRACTION,
            Some(r) if r.is_finite() && r > 0.0 && r <= 0.5 * diameter_m => r,
            Some(r) => {
                return Err(invalid(
                    MotorField::NozzleRadius,
                    r,
                    "must be positive and at most the motor's radius",
                ))
            }
        };
        let casing_center_from_aft_m = within(
            MotorField::DryCenterFromNozzle,
            options.dry_center_from_nozzle_m,
        )?;
        let propellant_center_from_aft_m = within(
            MotorField::PropellantCenterFromNozzle,
            options.propellant_center_from_nozzle_m,
        )?;
        let dry_inertia = match options.dry_inertia_kg_m2 {
            None => None,
            Some([axial, transverse]) => {
                check(MotorField::DryInertiaAxial, axial, false)?;
                check(MotorField::DryInertiaTransverse, transverse, false)?;
                // A body round its axis has I_axial = ∫(y² + z²) dm ≤ 2 I_transverse.
                if axial > 2.0 * transverse {
                    return Err(invalid(
                        MotorField::DryInertiaAxial,
                        axial,
                        "must be at most twice the transverse inertia (no body round its axis has more)",
                    ));
                }
                Some(Matrix3::from_diagonal(&Vector3::new(
                    axial, transverse, transverse,
                )))
            }
        };

        let times_s: Vec<f64> = motor.times_s().iter().map(|t| t * k_t).collect();
        let thrust_n: Vec<f64> = motor.thrust_n().iter().map(|f| f * (k_i / k_t)).collect();
        let n = times_s.len();
        let mut slope_n_per_s = vec![0.0; n];
        let mut impulse_ns = vec![0.0; n];
        for i in 1..n {
            let dt = times_s[i] - times_s[i - 1];
            slope_n_per_s[i - 1] = (thrust_n[i] - thrust_n[i - 1]) / dt;
            impulse_ns[i] = impulse_ns[i - 1] + 0.5 * (thrust_n[i - 1] + thrust_n[i]) * dt;
        }
        let total_impulse_ns = impulse_ns.last().copied().unwrap_or(0.0);
        let burn_time_s = times_s.last().copied().unwrap_or(0.0);
        let collapsed = times_s.windows(2).any(|w| w[1] <= w[0] || w[1].is_nan())
            || slope_n_per_s.iter().any(|s| !s.is_finite())
            || !total_impulse_ns.is_finite()
            || total_impulse_ns <= 0.0
            || !(propellant_mass_kg / total_impulse_ns).is_finite();
        if collapsed {
            return Err(MotorError::InvalidOption {
                motor: motor.source.clone(),
                field: MotorField::Scales,
                value: k_i / k_t,
                rule: "the scaled curve must keep strictly increasing times, finite thrust and a finite positive impulse",
            });
        }

        let r2 = 0.25 * diameter_m * diameter_m;
        let l2 = length_m * length_m;
        // Thin shell: axial m r², transverse m (r²/2 + L²/12).
        let casing_inertia = dry_inertia.unwrap_or_else(|| {
            Matrix3::from_diagonal(&Vector3::new(
                r2,
                0.5 * r2 + l2 / 12.0,
                0.5 * r2 + l2 / 12.0,
            )) * dry_mass_kg
        });
        // Solid cylinder (the motor's size or the chamber's): axial m r²/2, transverse
        // m (3 r² + L²)/12; grains have their own.
        let (r2, l2) = match options.chamber_m {
            Some([radius, height]) => (radius * radius, height * height),
            None => (r2, l2),
        };
        let transverse = (3.0 * r2 + l2) / 12.0;
        let propellant_inertia_per_kg = if options.grains.is_some() {
            Matrix3::zeros()
        } else {
            Matrix3::from_diagonal(&Vector3::new(0.5 * r2, transverse, transverse))
        };
        Ok(MotorTables {
            times_s,
            thrust_n,
            slope_n_per_s,
            impulse_ns,
            total_impulse_ns,
            burn_time_s,
            propellant_mass_kg,
            dry_mass_kg,
            length_m,
            diameter_m,
            casing_inertia,
            propellant_inertia_per_kg,
            casing_center_from_aft_m,
            propellant_center_from_aft_m,
            grains: options.grains,
            nozzle_radius_m,
            motors: 1,
        })
    }

    /// A cluster of these motors (as built, options applied), one on each axis at
    /// `offsets_m` (`[y, z]` off the rocket's axis, m, station frame; their mean on the axis,
    /// which the design's validation ensures): `n` times the thrust, impulse and masses, and
    /// each motor's inertia carried to the rocket's axis. One offset `[0, 0]` leaves the
    /// tables as they are, bit for bit; no offsets at all is taken as one motor on the axis.
    pub fn clustered(mut self, offsets_m: &[[f64; 2]]) -> MotorTables {
        let n = offsets_m.len().max(1);
        let k = n as f64;
        let spread = offsets_inertia(offsets_m);
        for v in self
            .thrust_n
            .iter_mut()
            .chain(self.slope_n_per_s.iter_mut())
            .chain(self.impulse_ns.iter_mut())
        {
            *v *= k;
        }
        self.total_impulse_ns *= k;
        self.casing_inertia = self.casing_inertia * k + spread * self.dry_mass_kg;
        self.propellant_inertia_per_kg += spread / k;
        self.propellant_mass_kg *= k;
        self.dry_mass_kg *= k;
        self.motors = n;
        self
    }

    /// Motors lit together: 1, or the tubes of a cluster ([`MotorTables::clustered`]).
    pub fn motors(&self) -> usize {
        self.motors
    }

    /// The segment holding `t_s` (`t_i ≤ t < t_{i+1}`), for `0 ≤ t < burn time`.
    #[inline]
    fn segment(&self, t_s: f64) -> usize {
        self.times_s
            .partition_point(|&x| x <= t_s)
            .saturating_sub(1)
    }

    /// Impulse delivered from ignition (t = 0) to `t_s`, N·s: 0 before, the total after
    /// burnout, exact for the piecewise-linear curve in between.
    #[inline]
    pub fn impulse_ns(&self, t_s: f64) -> f64 {
        if t_s.is_nan() {
            return f64::NAN;
        }
        if t_s <= 0.0 {
            return 0.0;
        }
        if t_s >= self.burn_time_s {
            return self.total_impulse_ns;
        }
        let i = self.segment(t_s);
        let dt = t_s - self.times_s[i];
        self.impulse_ns[i] + dt * (self.thrust_n[i] + 0.5 * self.slope_n_per_s[i] * dt)
    }

    /// The segment holding `t_s` as [`MotorTables::segment`] finds it, tried first at
    /// `hint` (the times increase strictly, so a segment that holds `t_s` is the one).
    #[inline]
    fn segment_from(&self, t_s: f64, hint: usize) -> usize {
        let ts = &self.times_s;
        if hint + 1 < ts.len() && ts[hint] <= t_s && t_s < ts[hint + 1] {
            return hint;
        }
        self.segment(t_s)
    }

    /// Thrust and propellant at `t_s` (time since ignition). Before ignition the motor is
    /// full and silent; after burnout it is empty and silent. NaN in, NaN out.
    #[inline]
    pub fn eval(&self, t_s: f64) -> MotorState {
        self.eval_in(t_s, |m, t| m.segment(t))
    }

    /// [`MotorTables::eval`] with the curve's segment looked for first where the last look-up
    /// found it (`hint`, updated): the same state, without a search while the times stay in
    /// one segment (a flight's successive stages).
    #[inline]
    pub fn eval_hinted(&self, t_s: f64, hint: &mut usize) -> MotorState {
        self.eval_in(t_s, |m, t| {
            *hint = m.segment_from(t, *hint);
            *hint
        })
    }

    /// The state at `t_s`, the curve's segment there found by `segment`.
    #[inline(always)]
    fn eval_in(&self, t_s: f64, segment: impl FnOnce(&Self, f64) -> usize) -> MotorState {
        if t_s.is_nan() {
            return MotorState {
                thrust_n: f64::NAN,
                thrust_rate_n_per_s: f64::NAN,
                propellant_kg: f64::NAN,
                propellant_rate_kg_s: f64::NAN,
                propellant_accel_kg_s2: f64::NAN,
            };
        }
        if t_s < 0.0 {
            return MotorState {
                propellant_kg: self.propellant_mass_kg,
                ..MotorState::default()
            };
        }
        if t_s >= self.burn_time_s {
            return MotorState::default();
        }
        let i = segment(self, t_s);
        let dt = t_s - self.times_s[i];
        let slope = self.slope_n_per_s[i];
        let thrust = self.thrust_n[i] + slope * dt;
        let impulse = self.impulse_ns[i] + dt * (self.thrust_n[i] + 0.5 * slope * dt);
        let per_ns = self.propellant_mass_kg / self.total_impulse_ns;
        MotorState {
            thrust_n: thrust,
            thrust_rate_n_per_s: slope,
            propellant_kg: (self.propellant_mass_kg - per_ns * impulse).max(0.0),
            propellant_rate_kg_s: -per_ns * thrust,
            propellant_accel_kg_s2: -per_ns * slope,
        }
    }

    /// Mass properties of the motor (casing and propellant) at `t_s`, station frame, the
    /// motor's aft end `motor_aft_m` aft of the nose tip.
    #[inline]
    pub fn mass_props(&self, t_s: f64, motor_aft_m: f64) -> MassProps {
        self.mass_props_of(&self.eval(t_s), motor_aft_m)
    }

    /// Mass properties for a state already evaluated (saves the second look-up).
    #[inline]
    pub fn mass_props_of(&self, state: &MotorState, motor_aft_m: f64) -> MassProps {
        let propellant_inertia = self.propellant_inertia(state.propellant_kg);
        if self.casing_center_from_aft_m == self.propellant_center_from_aft_m {
            // One center: the sum needs no parallel axes.
            return MassProps {
                mass_kg: self.dry_mass_kg + state.propellant_kg,
                cg_m: Vector3::new(motor_aft_m - self.casing_center_from_aft_m, 0.0, 0.0),
                inertia_cg: self.casing_inertia + propellant_inertia,
            };
        }
        if state.propellant_kg == 0.0 {
            return self.casing_props(motor_aft_m);
        }
        let propellant = MassProps {
            mass_kg: state.propellant_kg,
            inertia_cg: propellant_inertia,
            ..self.propellant_props(motor_aft_m)
        };
        self.casing_props(motor_aft_m).combine(&propellant)
    }

    /// The propellant's inertia about its center with `propellant_kg` left, station axes.
    fn propellant_inertia(&self, propellant_kg: f64) -> Matrix3<f64> {
        let scaling = self.propellant_inertia_per_kg * propellant_kg;
        match self.grain_inertia(propellant_kg) {
            None => scaling,
            Some(g) => scaling + station_diagonal(g.inertia_kg_m2),
        }
    }

    /// The grains' own inertia (the cluster's motors' together) with `propellant_kg` left.
    pub fn grain_inertia(&self, propellant_kg: f64) -> Option<GrainInertia> {
        self.grains
            .map(|g| g.cluster_inertia(self.motors, propellant_kg))
    }

    /// Each motor's grains, if the propellant is given as grains.
    pub fn grains(&self) -> Option<&Grains> {
        self.grains.as_ref()
    }

    /// The nozzle exit's radius, m.
    pub fn nozzle_radius_m(&self) -> f64 {
        self.nozzle_radius_m
    }

    /// The casing (the dry mass) where it is, station frame.
    pub fn casing_props(&self, motor_aft_m: f64) -> MassProps {
        MassProps {
            mass_kg: self.dry_mass_kg,
            cg_m: Vector3::new(motor_aft_m - self.casing_center_from_aft_m, 0.0, 0.0),
            inertia_cg: self.casing_inertia,
        }
    }

    /// The whole propellant load where it is, station frame.
    pub fn propellant_props(&self, motor_aft_m: f64) -> MassProps {
        MassProps {
            inertia_cg: self.propellant_inertia(self.propellant_mass_kg),
            ..self.propellant_props_scaling(motor_aft_m)
        }
    }

    /// The part of the whole propellant load whose inertia scales with the propellant left:
    /// all of it, but for grains' own inertia ([`MotorTables::grain_inertia`]).
    pub fn propellant_props_scaling(&self, motor_aft_m: f64) -> MassProps {
        MassProps {
            mass_kg: self.propellant_mass_kg,
            cg_m: Vector3::new(motor_aft_m - self.propellant_center_from_aft_m, 0.0, 0.0),
            inertia_cg: self.propellant_inertia_per_kg * self.propellant_mass_kg,
        }
    }

    /// Exact rates of the motor's mass and inertia for a state: the propellant's inertia is
    /// proportional to its mass, so `dI/dt = ṁ/m · I_prop` (= `ṁ` times the inertia per kg).
    #[inline]
    pub fn mass_rates(&self, state: &MotorState) -> MotorMassRates {
        let (rate, accel) = (state.propellant_rate_kg_s, state.propellant_accel_kg_s2);
        let mut inertia_rate = self.propellant_inertia_per_kg * rate;
        let mut inertia_accel = self.propellant_inertia_per_kg * accel;
        if let Some(g) = self.grain_inertia(state.propellant_kg) {
            // I(m(t)): I′ ṁ and I″ ṁ² + I′ m̈.
            let d1 = station_diagonal(g.per_kg_m2);
            inertia_rate += d1 * rate;
            inertia_accel += station_diagonal(g.per_kg2_m2) * (rate * rate) + d1 * accel;
        }
        MotorMassRates {
            mass_rate_kg_s: rate,
            mass_accel_kg_s2: accel,
            inertia_rate_kg_m2_s: inertia_rate,
            inertia_accel_kg_m2_s2: inertia_accel,
        }
    }

    /// Total impulse after scaling, N·s.
    pub fn total_impulse_ns(&self) -> f64 {
        self.total_impulse_ns
    }
    /// Burnout time after scaling, s.
    #[inline]
    pub fn burn_time_s(&self) -> f64 {
        self.burn_time_s
    }
    /// Propellant mass at ignition, kg.
    pub fn propellant_mass_kg(&self) -> f64 {
        self.propellant_mass_kg
    }
    /// Casing mass, kg.
    pub fn dry_mass_kg(&self) -> f64 {
        self.dry_mass_kg
    }
    /// Motor mass at ignition, kg.
    pub fn ignition_mass_kg(&self) -> f64 {
        self.dry_mass_kg + self.propellant_mass_kg
    }
    pub fn length_m(&self) -> f64 {
        self.length_m
    }
    pub fn diameter_m(&self) -> f64 {
        self.diameter_m
    }
    /// Sample times after scaling, s (0 first, burnout last): the curve's kinks, where an
    /// integrator may want to stop.
    pub fn times_s(&self) -> &[f64] {
        &self.times_s
    }
}

/// `[axial, transverse]` as a station-frame diagonal tensor (x along the axis).
fn station_diagonal([axial, transverse]: [f64; 2]) -> Matrix3<f64> {
    Matrix3::from_diagonal(&Vector3::new(axial, transverse, transverse))
}
