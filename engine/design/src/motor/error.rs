//! Errors of the motor layer: reading a thrust-curve file, looking a motor up by name, and
//! building the flight tables. Each parse error names the file, the line, the field and the
//! rule broken, so a user can fix the file without reading the parser.

use std::fmt;

/// Everything that can go wrong with a motor.
#[derive(Debug, thiserror::Error)]
pub enum MotorError {
    /// The file could not be read at all.
    #[error("{file}: cannot read the motor file: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
    },
    /// A value in the file breaks a rule of the format.
    #[error("{file}, line {line}, {field}: {rule}")]
    Parse {
        /// File name (or path) as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The header field, attribute or column at fault.
        field: String,
        rule: Rule,
    },
    /// An `.rse` file is not well-formed XML.
    #[error("{file}, line {line}: not well-formed XML: {message}")]
    Xml {
        file: String,
        line: usize,
        message: String,
    },
    /// The extension is neither `.eng` nor `.rse`.
    #[error("{file}: unknown motor file type (expected a RASP `.eng` or RockSim `.rse` file)")]
    UnknownFormat { file: String },
    /// A single motor was asked for but the file describes several.
    #[error("{file}: holds {} motors ({}); name one as `{file}#DESIGNATION`, or `{file}#K` by its place in the file (from 1)", designations.len(), designations.join(", "))]
    SeveralMotors {
        file: String,
        designations: Vec<String>,
    },
    /// A name that reads as a path (a directory in it, or a `.eng`/`.rse` ending) names no
    /// file and no bundled motor's file.
    #[error("no such motor file: `{file}` (a bundled motor is named by its file stem, e.g. `Cesaroni_I175`, or its designation)")]
    NoSuchFile { file: String },
    /// No file and no bundled motor matches the name.
    #[error("no motor file or bundled motor matches `{name}` (bundled motors: {})", available.join(", "))]
    NotFound {
        name: String,
        available: Vec<String>,
    },
    /// `FILE#NAME` names no motor of the file.
    #[error("{file}: no motor named `{name}` (it holds {}); name one as `{file}#DESIGNATION`, or `{file}#K` by its place in the file (from 1)", designations.join(", "))]
    NotInFile {
        file: String,
        name: String,
        designations: Vec<String>,
    },
    /// `FILE#NAME` names several motors of the file (test runs of one motor).
    #[error("{file}: {count} motors are named `{name}`; name one by its place in the file, `{file}#K` (from 1)")]
    AmbiguousInFile {
        file: String,
        name: String,
        count: usize,
    },
    /// The name matches more than one distinct motor.
    #[error("motor name `{name}` is ambiguous between {}; name one by its file stem or full designation", join_and(candidates))]
    Ambiguous {
        name: String,
        /// One line per candidate: manufacturer, designation and file stem.
        candidates: Vec<String>,
    },
    /// A [`MotorOptions`](super::MotorOptions) value is out of range.
    #[error("motor {motor}, option {field} = {value}: {rule}")]
    InvalidOption {
        motor: String,
        field: MotorField,
        value: f64,
        rule: &'static str,
    },
}

/// The value a [`MotorError::InvalidOption`] names: an option of
/// [`MotorOptions`](super::MotorOptions), of [`Motor::cut_at`](super::Motor::cut_at) or
/// [`Motor::with_diameter`](super::Motor::with_diameter), or one of the motor's own numbers
/// (`MotorFile*`: its file's, not an option's). Displayed as the message's field text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MotorField {
    ImpulseScale,
    TimeScale,
    /// The two scales together: the scaled curve collapsed.
    Scales,
    PropellantMass,
    DryMass,
    MotorFilePropellantMass,
    /// The file's total mass less its propellant.
    MotorFileDryMass,
    MotorFileLength,
    MotorFileDiameter,
    /// The chamber as a whole (given with grains).
    Chamber,
    ChamberRadius,
    ChamberHeight,
    GrainsCount,
    GrainsOuterRadius,
    GrainsInnerRadius,
    GrainsHeight,
    GrainsSeparation,
    GrainsDensity,
    NozzleRadius,
    DryCenterFromNozzle,
    PropellantCenterFromNozzle,
    DryInertiaAxial,
    DryInertiaTransverse,
    /// [`Motor::cut_at`](super::Motor::cut_at)'s time.
    BurnTime,
    /// [`Motor::with_diameter`](super::Motor::with_diameter)'s diameter.
    Diameter,
}

impl MotorField {
    /// The field as error messages name it.
    pub fn as_str(self) -> &'static str {
        match self {
            MotorField::ImpulseScale => "impulse_scale",
            MotorField::TimeScale => "time_scale",
            MotorField::Scales => "impulse_scale / time_scale",
            MotorField::PropellantMass => "propellant_mass_kg",
            MotorField::DryMass => "dry_mass_kg",
            MotorField::MotorFilePropellantMass => "motor propellant_mass_kg",
            MotorField::MotorFileDryMass => "motor dry mass (total - propellant)",
            MotorField::MotorFileLength => "motor length_m",
            MotorField::MotorFileDiameter => "motor diameter_m",
            MotorField::Chamber => "chamber_m",
            MotorField::ChamberRadius => "chamber_m (radius)",
            MotorField::ChamberHeight => "chamber_m (height)",
            MotorField::GrainsCount => "grains.count",
            MotorField::GrainsOuterRadius => "grains.outer_radius_m",
            MotorField::GrainsInnerRadius => "grains.inner_radius_m",
            MotorField::GrainsHeight => "grains.height_m",
            MotorField::GrainsSeparation => "grains.separation_m",
            MotorField::GrainsDensity => "grains.density_kg_m3",
            MotorField::NozzleRadius => "nozzle_radius_m",
            MotorField::DryCenterFromNozzle => "dry_center_from_nozzle_m",
            MotorField::PropellantCenterFromNozzle => "propellant_center_from_nozzle_m",
            MotorField::DryInertiaAxial => "dry_inertia_kg_m2 (axial)",
            MotorField::DryInertiaTransverse => "dry_inertia_kg_m2 (transverse)",
            MotorField::BurnTime => "burn_time_s",
            MotorField::Diameter => "diameter_m",
        }
    }
}

impl fmt::Display for MotorField {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The rule a value in a motor file breaks.
#[derive(Debug, Clone, PartialEq)]
pub enum Rule {
    /// The file is not UTF-8 text.
    NotUtf8,
    /// A line has the wrong number of whitespace-separated fields.
    FieldCount { expected: usize, found: usize },
    /// The text is not a number.
    NotANumber { text: String },
    /// The number is infinite or NaN.
    NotFinite { text: String },
    /// The value must be greater than zero.
    NotPositive { value: f64 },
    /// The value must not be negative.
    Negative { value: f64 },
    /// Times must strictly increase.
    NonIncreasingTime { previous_s: f64, time_s: f64 },
    /// A size given in millimetres that is no longer a positive, finite number of metres
    /// (`1e-323` mm underflows to 0 m).
    NotPositiveInMetres { value_mm: f64, value_m: f64 },
    /// The propellant mass exceeds the loaded motor mass.
    PropellantExceedsTotal { propellant_kg: f64, total_kg: f64 },
    /// The file has no header line (only comments or nothing).
    NoHeader,
    /// A motor has a header but no thrust samples.
    NoSamples,
    /// The curve delivers no impulse.
    ZeroImpulse,
    /// The curve's impulse is beyond every class letter (more than class Z).
    ImpulseBeyondClasses { impulse_ns: f64 },
    /// A required XML attribute is missing.
    MissingAttribute,
    /// A required XML element is missing.
    MissingElement,
    /// A text field is empty.
    Empty,
}

impl fmt::Display for Rule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Rule::NotUtf8 => write!(f, "the file is not UTF-8 text"),
            Rule::FieldCount { expected, found } => {
                write!(f, "expected {expected} whitespace-separated fields, found {found}")
            }
            Rule::NotANumber { text } => write!(f, "`{text}` is not a number"),
            Rule::NotFinite { text } => write!(f, "`{text}` is not a finite number"),
            Rule::NotPositive { value } => write!(f, "{value} must be greater than zero"),
            Rule::Negative { value } => write!(f, "{value} must not be negative"),
            Rule::NotPositiveInMetres { value_mm, value_m } => write!(
                f,
                "{value_mm:e} mm is {value_m} m: a size must be a positive, finite number of metres"
            ),
            Rule::NonIncreasingTime { previous_s, time_s } => write!(
                f,
                "time {time_s} s does not exceed the previous time {previous_s} s (times must strictly increase)"
            ),
            Rule::PropellantExceedsTotal { propellant_kg, total_kg } => write!(
                f,
                "propellant mass {propellant_kg} kg exceeds the total motor mass {total_kg} kg"
            ),
            Rule::NoHeader => write!(f, "no motor header line (the file holds only comments or nothing)"),
            Rule::NoSamples => write!(f, "the motor has no thrust samples"),
            Rule::ZeroImpulse => write!(f, "the thrust curve delivers no impulse"),
            Rule::ImpulseBeyondClasses { impulse_ns } => {
                write!(f, "total impulse {impulse_ns} N·s is beyond class Z")
            }
            Rule::MissingAttribute => write!(f, "required attribute is missing"),
            Rule::MissingElement => write!(f, "required element is missing"),
            Rule::Empty => write!(f, "must not be empty"),
        }
    }
}

/// "a", "a and b", "a, b and c".
fn join_and(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {}", init.join(", "), last),
    }
}

/// A parse error at `line` of `file`.
pub(crate) fn parse_error(file: &str, line: usize, field: &str, rule: Rule) -> MotorError {
    MotorError::Parse {
        file: file.to_string(),
        line,
        field: field.to_string(),
        rule,
    }
}

/// A finite number from `text`, or an error naming the field.
pub(crate) fn parse_number(
    text: &str,
    file: &str,
    line: usize,
    field: &str,
) -> Result<f64, MotorError> {
    let value: f64 = text.parse().map_err(|_| {
        parse_error(
            file,
            line,
            field,
            Rule::NotANumber {
                text: text.to_string(),
            },
        )
    })?;
    if !value.is_finite() {
        return Err(parse_error(
            file,
            line,
            field,
            Rule::NotFinite {
                text: text.to_string(),
            },
        ));
    }
    Ok(value)
}

/// A finite number that is greater than zero.
pub(crate) fn parse_positive(
    text: &str,
    file: &str,
    line: usize,
    field: &str,
) -> Result<f64, MotorError> {
    let value = parse_number(text, file, line, field)?;
    if value <= 0.0 {
        return Err(parse_error(file, line, field, Rule::NotPositive { value }));
    }
    Ok(value)
}

/// A size given in millimetres, in metres: greater than zero as written and once converted
/// (a size so small that it underflows to 0 m is the file's fault, named with its line and
/// field, not a motor whose tables then refuse a zero length).
pub(crate) fn parse_mm_as_m(
    text: &str,
    file: &str,
    line: usize,
    field: &str,
) -> Result<f64, MotorError> {
    let value_mm = parse_positive(text, file, line, field)?;
    let value_m = value_mm / 1000.0;
    if !(value_m.is_finite() && value_m > 0.0) {
        return Err(parse_error(
            file,
            line,
            field,
            Rule::NotPositiveInMetres { value_mm, value_m },
        ));
    }
    Ok(value_m)
}

/// A finite number that is not negative.
pub(crate) fn parse_non_negative(
    text: &str,
    file: &str,
    line: usize,
    field: &str,
) -> Result<f64, MotorError> {
    let value = parse_number(text, file, line, field)?;
    if value < 0.0 {
        return Err(parse_error(file, line, field, Rule::Negative { value }));
    }
    Ok(value)
}
