//! Solid rocket motors: reading thrust curves, the bundled library, and the time tables the
//! flight reads at every integration step.
//!
//! - [`eng`] and [`rse`] parse RASP `.eng` and RockSim `.rse` files into [`Motor`]s, checking
//!   the rules of [`curve`] (implicit (0 s, 0 N) start, strictly increasing times, no negative
//!   thrust; the slips OpenRocket mends mended, with a note) and reporting a broken rule as a
//!   [`MotorError`] naming the file,
//!   line, field and rule. No input makes them panic (a property test feeds them random bytes
//!   and mutated real files).
//! - [`library`] embeds the files of `engine/design/motors/` in the binary and finds a motor
//!   by path, file stem, designation or common name ([`find`], [`bundled`]).
//! - [`tables`] turns a [`Motor`] (with optional overrides and dispersion scales) into
//!   [`MotorTables`], whose [`MotorTables::eval`] and [`MotorTables::mass_props`] allocate
//!   nothing and find their sample by binary search.
//!
//! # The motor's mass model
//!
//! Simulators differ here; this is the one we use. The propellant burns in proportion to the
//! impulse delivered, as RocketPy's `SolidMotor` and OpenRocket assume:
//! `m_p(t) = m_p0 (1 − I(t)/I_total)`, with `I(t)` the exact integral of the piecewise-linear
//! thrust curve. The casing (the dry mass, `total − propellant` unless overridden) is a thin
//! cylindrical shell of the motor's length and diameter; the propellant is a solid cylinder
//! of the same length and diameter whose uniform density falls with its mass, so its inertia
//! is proportional to its mass. Both are centered at the motor's mid-length, so the motor's
//! center of mass does not move as it burns; only its mass and inertia change. The `.rse`
//! per-sample mass and CG columns are not used.

pub mod curve;
pub mod eng;
pub mod error;
pub mod grains;
pub mod library;
pub mod rse;
pub mod tables;

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_fuzz;
#[cfg(test)]
mod tests_grains;
#[cfg(test)]
mod tests_tables;

use std::path::Path;

pub use curve::impulse_class;
pub use eng::parse_eng;
pub use error::{MotorError, MotorField, Rule};
pub use grains::{GrainInertia, Grains};
pub use library::{bundled, find, BundledFile, BUNDLED_FILES, BUNDLED_README};
pub use rse::parse_rse;
pub use tables::{MotorMassRates, MotorOptions, MotorState, MotorTables};

use curve::Curve;
use error::parse_error;

/// The file format a motor was read from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MotorFormat {
    /// RASP `.eng`.
    Eng,
    /// RockSim `.rse` (XML).
    Rse,
}

impl MotorFormat {
    /// The format of a file name by its extension (case-insensitive).
    pub fn of_file(file_name: &str) -> Option<MotorFormat> {
        let ext = Path::new(file_name).extension()?.to_str()?;
        if ext.eq_ignore_ascii_case("eng") {
            Some(MotorFormat::Eng)
        } else if ext.eq_ignore_ascii_case("rse") {
            Some(MotorFormat::Rse)
        } else {
            None
        }
    }
}

/// A solid motor as its file describes it. SI units.
///
/// The metadata fields are public; the thrust curve is private so that it always obeys the
/// rules the parsers check (times start at 0 and strictly increase, thrust is non-negative,
/// the impulse is positive and within the class letters; no thrust after the last sample).
#[derive(Debug, Clone, PartialEq)]
pub struct Motor {
    /// Designation as the file writes it (`.eng` header name, `.rse` `code`), e.g.
    /// `411-I175-WH-14A`.
    pub designation: String,
    /// Impulse letter and average-thrust number, from the designation (`I175`); see
    /// [`curve`] for the rule.
    pub common_name: String,
    /// Manufacturer as the file writes it (`AT`, `CTI`, `Aerotech`, ...); see
    /// [`Motor::manufacturer_name`].
    pub manufacturer: String,
    pub diameter_m: f64,
    pub length_m: f64,
    /// Available ejection delays, s; empty for a plugged motor. `0` is a charge with no delay.
    pub delays_s: Vec<f64>,
    /// Propellant mass at ignition, kg (`.rse`: `propWt`).
    pub propellant_mass_kg: f64,
    /// Loaded motor mass at ignition, kg (`.rse`: `initWt`).
    pub total_mass_kg: f64,
    /// The file's stem (`Cesaroni_I175`).
    pub source: String,
    pub format: MotorFormat,
    /// What the reader mended in the file's samples, as OpenRocket's loader does (a
    /// repeated sample, a doubled sample at 0 s or at burnout), each naming its line; empty
    /// for a clean file.
    pub notes: Vec<String>,
    times_s: Vec<f64>,
    thrust_n: Vec<f64>,
    total_impulse_ns: f64,
}

impl Motor {
    /// Builds a motor from a checked curve (used by the parsers).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn assemble(
        designation: String,
        manufacturer: String,
        diameter_m: f64,
        length_m: f64,
        delays_s: Vec<f64>,
        propellant_mass_kg: f64,
        total_mass_kg: f64,
        curve: Curve,
        file: &str,
        format: MotorFormat,
    ) -> Motor {
        let source = Path::new(file)
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or(file)
            .to_string();
        let burn_time_s = curve.times_s.last().copied().unwrap_or(0.0);
        let average_n = curve.total_impulse_ns / burn_time_s;
        let class = impulse_class(curve.total_impulse_ns).unwrap_or('?');
        Motor {
            common_name: curve::common_name(&designation, class, average_n),
            designation,
            manufacturer,
            diameter_m,
            length_m,
            delays_s,
            propellant_mass_kg,
            total_mass_kg,
            source,
            format,
            notes: curve.notes,
            times_s: curve.times_s,
            thrust_n: curve.thrust_n,
            total_impulse_ns: curve.total_impulse_ns,
        }
    }

    /// The one motor in `bytes`, a file called `file_name` whose extension (`.eng`, `.rse`)
    /// chooses the parser.
    pub fn parse(bytes: &[u8], file_name: &str) -> Result<Motor, MotorError> {
        Motor::only_one(Motor::parse_all(bytes, file_name)?, file_name)
    }

    /// The one motor of a file's `motors`.
    fn only_one(mut motors: Vec<Motor>, file_name: &str) -> Result<Motor, MotorError> {
        if motors.len() != 1 {
            return Err(MotorError::SeveralMotors {
                file: file_name.to_string(),
                designations: motors.iter().map(|m| m.designation.clone()).collect(),
            });
        }
        Ok(motors.remove(0))
    }

    /// Every motor in `bytes`, a file called `file_name` (as [`Motor::parse`]).
    pub fn parse_all(bytes: &[u8], file_name: &str) -> Result<Vec<Motor>, MotorError> {
        let format = MotorFormat::of_file(file_name).ok_or_else(|| MotorError::UnknownFormat {
            file: file_name.to_string(),
        })?;
        let text = std::str::from_utf8(bytes).map_err(|e| {
            let line = 1 + bytes[..e.valid_up_to()]
                .iter()
                .filter(|&&b| b == b'\n')
                .count();
            parse_error(file_name, line, "text", Rule::NotUtf8)
        })?;
        match format {
            MotorFormat::Eng => parse_eng(text, file_name),
            MotorFormat::Rse => parse_rse(text, file_name),
        }
    }

    /// The one motor in the `.eng` or `.rse` file at `path`.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Motor, MotorError> {
        let file = path.as_ref().display().to_string();
        Motor::only_one(Motor::all_from_file(path)?, &file)
    }

    /// Every motor in the `.eng` or `.rse` file at `path`.
    pub fn all_from_file(path: impl AsRef<Path>) -> Result<Vec<Motor>, MotorError> {
        let path = path.as_ref();
        let file = path.display().to_string();
        let bytes =
            crate::limits::read_limited(path, crate::limits::MAX_MOTOR_FILE_BYTES, "a motor file")
                .map_err(|source| MotorError::Io {
                    file: file.clone(),
                    source,
                })?;
        Motor::parse_all(&bytes, &file)
    }

    /// The motor with its thrust curve cut at `burn_time_s` (RocketPy's `burn_time`): the
    /// samples before it, then one at it with the curve's thrust there (linear between the
    /// samples around it), after which the motor burns out. The impulse is the cut curve's;
    /// the propellant (the file's, or the one a flight gives) burns over it. A cut at the
    /// curve's own burnout is the motor unchanged; a cut must be after 0 and no later than
    /// burnout.
    pub fn cut_at(&self, burn_time_s: f64) -> Result<Motor, MotorError> {
        let end = self.burn_time_s();
        if !(burn_time_s.is_finite() && burn_time_s > 0.0 && burn_time_s <= end) {
            return Err(MotorError::InvalidOption {
                motor: self.designation.clone(),
                field: MotorField::BurnTime,
                value: burn_time_s,
                rule:
                    "must be after 0 and no later than the thrust curve's burnout (its last sample)",
            });
        }
        if burn_time_s == end {
            return Ok(self.clone());
        }
        let (t, f) = (&self.times_s, &self.thrust_n);
        let k = t.partition_point(|&x| x < burn_time_s); // t[k - 1] < cut <= t[k]
        let thrust_at_cut = if t[k] == burn_time_s {
            f[k]
        } else {
            let w = (burn_time_s - t[k - 1]) / (t[k] - t[k - 1]);
            f[k - 1] + w * (f[k] - f[k - 1])
        };
        let mut times_s = t[..k].to_vec();
        let mut thrust_n = f[..k].to_vec();
        times_s.push(burn_time_s);
        thrust_n.push(thrust_at_cut);
        let total_impulse_ns = times_s
            .windows(2)
            .zip(thrust_n.windows(2))
            .map(|(t, f)| 0.5 * (f[0] + f[1]) * (t[1] - t[0]))
            .sum::<f64>();
        if total_impulse_ns <= 0.0 {
            return Err(MotorError::InvalidOption {
                motor: self.designation.clone(),
                field: MotorField::BurnTime,
                value: burn_time_s,
                rule: "cuts the curve before it delivers any impulse",
            });
        }
        let class = impulse_class(total_impulse_ns).unwrap_or('?');
        let mut notes = self.notes.clone();
        notes.push(format!(
            "thrust curve cut at {burn_time_s} s (its burnout was {end} s): {thrust_at_cut:.2} N there, then none; impulse {total_impulse_ns:.1} N·s of {:.1}",
            self.total_impulse_ns
        ));
        Ok(Motor {
            common_name: curve::common_name(
                &self.designation,
                class,
                total_impulse_ns / burn_time_s,
            ),
            notes,
            times_s,
            thrust_n,
            total_impulse_ns,
            ..self.clone()
        })
    }

    /// The motor in a casing of outer diameter `diameter_m` instead of its file's (a motor
    /// flown in another casing, or a set-up whose published grains are wider than the file's
    /// casing, as RocketPy's Bella Lui's): the mount must hold it, and its grains and nozzle
    /// must fit it.
    pub fn with_diameter(&self, diameter_m: f64) -> Result<Motor, MotorError> {
        if !(diameter_m.is_finite() && diameter_m > 0.0 && diameter_m <= 2.0) {
            return Err(MotorError::InvalidOption {
                motor: self.designation.clone(),
                field: MotorField::Diameter,
                value: diameter_m,
                rule: "must be positive and at most 2 m",
            });
        }
        Ok(Motor {
            diameter_m,
            ..self.clone()
        })
    }

    /// Sample times, s: start at 0, strictly increasing, the implicit (0, 0) point included.
    pub fn times_s(&self) -> &[f64] {
        &self.times_s
    }

    /// Thrust at each of [`Motor::times_s`], N; none after the last (which is 0 in a clean
    /// file).
    pub fn thrust_n(&self) -> &[f64] {
        &self.thrust_n
    }

    /// ∫F dt of the curve by trapezoids (exact for the piecewise-linear curve), N·s.
    pub fn total_impulse_ns(&self) -> f64 {
        self.total_impulse_ns
    }

    /// Time of the last sample, s: burnout.
    pub fn burn_time_s(&self) -> f64 {
        self.times_s.last().copied().unwrap_or(0.0)
    }

    /// Total impulse over burn time, N.
    pub fn average_thrust_n(&self) -> f64 {
        self.total_impulse_ns / self.burn_time_s()
    }

    /// Largest sample thrust, N.
    pub fn peak_thrust_n(&self) -> f64 {
        self.thrust_n.iter().copied().fold(0.0, f64::max)
    }

    /// NAR/TRA class letter of the integrated impulse (see [`impulse_class`]).
    pub fn impulse_class(&self) -> char {
        impulse_class(self.total_impulse_ns).unwrap_or('?')
    }

    /// Loaded mass less propellant, kg.
    pub fn dry_mass_kg(&self) -> f64 {
        self.total_mass_kg - self.propellant_mass_kg
    }

    /// The manufacturer's full name for the common abbreviations (`AT`, `Aerotech` ->
    /// `AeroTech`; `CTI` -> `Cesaroni Technology`; `Loki` -> `Loki Research`), else as
    /// written.
    pub fn manufacturer_name(&self) -> &str {
        match self.manufacturer.to_ascii_lowercase().as_str() {
            "at" | "aerotech" | "aerotech/rcs" => "AeroTech",
            "cti" | "cesaroni" | "cesaroni technology" => "Cesaroni Technology",
            "loki" | "loki research" => "Loki Research",
            _ => &self.manufacturer,
        }
    }
}
