//! Errors of the design layer. Each names the file, the component (or line) and the field,
//! and says which rule was broken.
//!
//! A [`DesignError`] displays as one line a user can act on, e.g.
//! `design.json: component "fins": field "span_m": must be positive and finite (got -0.1)`.
//! Tests and callers that need to know *which* rule fired match on [`Rule`] (see
//! [`DesignError::rule`]) rather than on the text.

use std::fmt;

/// Where in the design a problem is.
#[derive(Debug, Clone, PartialEq)]
pub enum Location {
    /// The design as a whole (top-level fields).
    Design,
    /// The `drag` object.
    Drag,
    /// A stage, by id.
    Stage(String),
    /// A component, by id.
    Component(String),
    /// A place without a usable id, as a JSON path (`stages[0].components[2]`).
    Path(String),
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Design => write!(f, "design"),
            Location::Drag => write!(f, "drag"),
            Location::Stage(id) => write!(f, "stage \"{id}\""),
            Location::Component(id) => write!(f, "component \"{id}\""),
            Location::Path(p) => write!(f, "{p}"),
        }
    }
}

/// The rule a design broke. Its `Display` is the human explanation, with the offending values.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Rule {
    /// A length, diameter, mass or density that must be `> 0` and finite.
    NotPositive {
        got: f64,
    },
    /// A value that must be `>= 0` and finite.
    Negative {
        got: f64,
    },
    /// A length or diameter larger than [`crate::MAX_PART_SIZE_M`]: likely millimetres.
    TooLarge {
        got: f64,
        max: f64,
    },
    /// A value that must be finite.
    NotFinite {
        got: f64,
    },
    /// A value outside its allowed closed range.
    OutOfRange {
        got: f64,
        min: f64,
        max: f64,
    },
    /// A wall thicker than the radius it belongs to.
    WallThickerThanRadius {
        wall_m: f64,
        radius_m: f64,
    },
    /// Not exactly one of the ways to give a mass (`options` lists them).
    MassSpecNotExactlyOne {
        options: &'static str,
        given: usize,
    },
    /// A field that needs another one beside it.
    NeedsField {
        other: &'static str,
    },
    /// A field that must be given in this case.
    Required {
        when: &'static str,
    },
    /// A power-on drag curve without a power-off one.
    PowerOnWithoutPowerOff,
    /// A shape parameter given to a shape that takes none.
    ShapeTakesNoParameter {
        shape: &'static str,
    },
    /// A fin dimension given to a planform that has no such dimension.
    NotForPlanform {
        planform: &'static str,
    },
    /// A free-form fin's outline that is not one: `point` (0-based) breaks `why`.
    FinOutline {
        point: usize,
        why: &'static str,
    },
    /// An empty id.
    EmptyId,
    /// An id used twice (stages and components share one namespace).
    DuplicateId {
        first: String,
    },
    /// A nose cone, body tube or transition placed inside another component.
    BodyInsideComponent {
        kind: &'static str,
    },
    /// A part that is not a body component at a stage's top level.
    NotABody {
        kind: &'static str,
    },
    /// Fins, lugs and rail buttons sit on a body component, not inside an inner tube.
    ExternalPartOffBody {
        kind: &'static str,
    },
    /// A part entirely outside its parent's axial extent (shoulders included).
    OutsideParent {
        top_m: f64,
        bottom_m: f64,
        parent_top_m: f64,
        parent_bottom_m: f64,
    },
    /// A part wider than its parent's inner diameter (diameters measured about the parent's
    /// axis: twice the part's largest distance from it).
    WiderThanParent {
        width_m: f64,
        inner_diameter_m: f64,
    },
    /// A file the field names (a drag or lift table) that cannot be read (boxed text: the
    /// rule stays as small as the others).
    FileUnreadable {
        file: Box<str>,
        why: Box<str>,
    },
    /// A part whose dimensions give a mass, center or inertia that is not a number.
    MassNotFinite {
        mass_kg: f64,
    },
    /// More components than a design may hold.
    TooManyComponents {
        max: usize,
    },
    /// A part reaching further outside the rocket (fore of its tip, aft of its tail) than
    /// the rocket is long.
    OutsideRocket {
        top_m: f64,
        bottom_m: f64,
        length_m: f64,
    },
    /// A part that reaches ahead of the nose tip, where no rocket is.
    AheadOfNoseTip {
        top_m: f64,
    },
    /// Fins with a tip chord but no root chord.
    FinRootChord {
        root_m: f64,
        tip_m: f64,
    },
    /// A second inner tube marked as the motor mount.
    TwoMotorMounts {
        first: String,
    },
    /// A motor mount (a cluster's centre, for a cluster) off the rocket's axis.
    MotorMountOffAxis {
        offset_m: f64,
        /// Tubes in the mount (1: a single tube).
        motors: usize,
    },
    /// A Mach column that is not strictly increasing.
    MachNotIncreasing {
        row: usize,
        previous: f64,
        got: f64,
    },
    /// A drag table with no rows.
    EmptyTable,
    /// Not exactly one of the drag models.
    DragModelNotExactlyOne {
        given: usize,
    },
    /// Both an inline power-on table and a CSV.
    PowerOnTwice,
    Airfoil {
        why: &'static str,
    },
    AtMostOneOf {
        fields: &'static str,
    },
    DeployTrigger {
        got: String,
    },
    /// A stage without a body component, or a design without stages.
    NoBodyComponent,
    /// Too many fins, or none.
    FinCount {
        got: u32,
        max: u32,
    },
    /// An inner tube cluster with no tube.
    EmptyCluster,
    /// A resolved position or size that overflowed.
    PositionNotFinite {
        got: f64,
    },
    /// `motor_fits` on a design with no motor mount.
    NoMotorMount,
    /// A motor wider than the mount's inner diameter.
    MotorTooWide {
        motor_diameter_m: f64,
        mount_inner_diameter_m: f64,
    },
    /// A motor longer than the mount tube plus its overhang.
    MotorTooLong {
        motor_length_m: f64,
        room_m: f64,
    },
}

impl fmt::Display for Rule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Rule::NotPositive { got } => write!(f, "must be positive and finite (got {got})"),
            Rule::Negative { got } => write!(f, "must be zero or positive and finite (got {got})"),
            Rule::NotFinite { got } => write!(f, "must be finite (got {got})"),
            Rule::TooLarge { got, max } => write!(
                f,
                "must be at most {max} m, more than any part of a high-power rocket \
                 (got {got} m; a length in millimetres? the design's lengths are in metres)"
            ),
            Rule::OutOfRange { got, min, max } => {
                write!(f, "must be between {min} and {max} (got {got})")
            }
            Rule::WallThickerThanRadius { wall_m, radius_m } => write!(
                f,
                "the wall ({wall_m} m) must not be thicker than the radius ({radius_m} m)"
            ),
            Rule::MassSpecNotExactlyOne { options, given } => {
                write!(f, "give exactly one of {options} (got {given})")
            }
            Rule::NeedsField { other } => write!(f, "needs \"{other}\" as well"),
            Rule::Required { when } => write!(f, "is required {when}"),
            Rule::PowerOnWithoutPowerOff => write!(
                f,
                "a power-on curve goes with a power-off curve (\"power_off\" or \"power_off_csv\"), \
                 not with \"estimate\""
            ),
            Rule::ShapeTakesNoParameter { shape } => {
                write!(f, "shape \"{shape}\" takes no shape_parameter")
            }
            Rule::NotForPlanform { planform } => {
                write!(f, "does not apply to a fin of planform \"{planform}\"")
            }
            Rule::FinOutline { point, why } => write!(f, "point {point}: {why}"),
            Rule::FileUnreadable { file, why } => {
                write!(f, "names {file}, which cannot be read: {why}")
            }
            Rule::MassNotFinite { mass_kg } => write!(
                f,
                "its dimensions give a mass ({mass_kg} kg), center of mass or inertia that is \
                 not a finite number: a part must be large enough to weigh and small enough \
                 to hold"
            ),
            Rule::TooManyComponents { max } => write!(
                f,
                "the design holds more than {max} components (body components and parts), \
                 the most hpr-mc reads of one design"
            ),
            Rule::OutsideRocket {
                top_m,
                bottom_m,
                length_m,
            } => write!(
                f,
                "the part ({top_m} m to {bottom_m} m aft of the nose tip) reaches further \
                 outside the rocket (0 to {length_m} m) than the rocket is long: no rocket holds \
                 it so (is a position or a length too large?)"
            ),
            Rule::AheadOfNoseTip { top_m } => write!(
                f,
                "the part starts {} m ahead of the nose tip: every part lies aft of the tip \
                 (positions are metres aft of it; is the position or a chord too large?)",
                -top_m
            ),
            Rule::EmptyId => write!(f, "must not be empty"),
            Rule::DuplicateId { first } => write!(f, "is already the id of {first}"),
            Rule::BodyInsideComponent { kind } => write!(
                f,
                "a {kind} is a body component: it goes in a stage's \"components\", not inside \
                 another component"
            ),
            Rule::NotABody { kind } => write!(
                f,
                "a {kind} is not a body component: put it in the \"children\" of a nose cone, \
                 body tube or transition"
            ),
            Rule::ExternalPartOffBody { kind } => write!(
                f,
                "a {kind} goes on the outside of a nose cone, body tube or transition, not \
                 inside an inner tube"
            ),
            Rule::OutsideParent { top_m, bottom_m, parent_top_m, parent_bottom_m } => write!(
                f,
                "the part ({top_m} m to {bottom_m} m aft of the nose tip) lies entirely outside \
                 its parent ({parent_top_m} m to {parent_bottom_m} m)"
            ),
            Rule::WiderThanParent { width_m, inner_diameter_m } => write!(
                f,
                "the part ({width_m} m across, offsets included) is wider than its parent's \
                 inner diameter ({inner_diameter_m} m)"
            ),
            Rule::FinRootChord { root_m, tip_m } => write!(
                f,
                "the root chord must be positive when the tip chord is {tip_m} m (got {root_m})"
            ),
            Rule::TwoMotorMounts { first } => {
                write!(f, "a design has one motor mount and component \"{first}\" already is it")
            }
            Rule::MotorMountOffAxis { offset_m, motors: 1 } => write!(
                f,
                "the motor mount must be on the rocket's axis (it is {offset_m} m off it): \
                 thrust off the axis would turn the rocket, which hpr does not fly"
            ),
            Rule::MotorMountOffAxis { offset_m, motors } => write!(
                f,
                "the centre of a cluster of {motors} motors must be on the rocket's axis \
                 (it is {offset_m} m off it): their thrust would turn the rocket, which hpr \
                 does not fly"
            ),
            Rule::MachNotIncreasing { row, previous, got } => write!(
                f,
                "Mach must be strictly increasing: row {row} has Mach {got} after {previous}"
            ),
            Rule::EmptyTable => write!(f, "the table has no rows"),
            Rule::DragModelNotExactlyOne { given } => write!(
                f,
                "give exactly one of \"power_off\", \"power_off_csv\" and \"estimate\" (got {given})"
            ),
            Rule::PowerOnTwice => write!(f, "give at most one of \"power_on\" and \"power_on_csv\""),
            Rule::Airfoil { why } => write!(f, "{why}"),
            Rule::AtMostOneOf { fields } => write!(f, "give at most one of {fields}"),
            Rule::DeployTrigger { got } => write!(
                f,
                "a trigger is \"apogee\", \"burnout\", \"motor_delay\" or one of {{\"time_s\": t}}, \
                 {{\"height_m\": h}}, {{\"delay_s\": d}} with a number 0 or more (got {got})"
            ),
            Rule::NoBodyComponent => write!(f, "has no body component"),
            Rule::FinCount { got, max } => {
                write!(f, "must be between 1 and {max} (got {got})")
            }
            Rule::EmptyCluster => write!(f, "a cluster needs at least one tube"),
            Rule::PositionNotFinite { got } => {
                write!(f, "the resolved position is not finite (got {got})")
            }
            Rule::NoMotorMount => write!(f, "has no motor mount (an inner tube with \"motor_mount\")"),
            Rule::MotorTooWide { motor_diameter_m, mount_inner_diameter_m } => write!(
                f,
                "the motor is too wide: its diameter {motor_diameter_m} m exceeds the mount's \
                 inner diameter {mount_inner_diameter_m} m"
            ),
            Rule::MotorTooLong { motor_length_m, room_m } => write!(
                f,
                "the motor is too long: {motor_length_m} m exceeds the mount's length plus its \
                 overhang, {room_m} m"
            ),
        }
    }
}

/// Everything that can go wrong reading or checking a design.
#[derive(Debug, thiserror::Error)]
pub enum DesignError {
    /// The design file (or a CSV it names) could not be read.
    #[error("{file}: cannot read it: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
    },
    /// JSON syntax, a wrong type, a missing or an unknown field (from serde).
    #[error("{file}: not a JSON design: line {line}, column {column}: {message}")]
    Json {
        file: String,
        line: usize,
        column: usize,
        message: String,
    },
    /// A component that does not fit the format (a wrong type, a missing or an unknown
    /// field), placed by its id and field (see `design::json_errors`).
    #[error("{file}: {at}: {}{message}", field_prefix(.field))]
    JsonAt {
        file: String,
        at: Location,
        field: Option<String>,
        message: String,
    },
    /// A drag CSV that does not parse.
    #[error("{file}: line {line}: {message}")]
    Csv {
        file: String,
        line: usize,
        message: String,
    },
    /// An OpenRocket file (`.ork`) that cannot be read or holds what a design cannot: the
    /// element (a path of components, `stage "Sustainer"/bodytube "Body"/<radius>`) and why.
    #[error("{file}: {element}: {message}")]
    Ork {
        file: String,
        element: String,
        message: String,
    },
    /// A rule of the design broken, with where and what.
    #[error("{file}: {at}: {}{}", field_prefix(.field), tidy_numbers(&.rule.to_string()))]
    Invalid {
        file: String,
        at: Location,
        field: Option<String>,
        rule: Rule,
    },
}

fn field_prefix(field: &Option<String>) -> String {
    match field {
        Some(name) => format!("field \"{name}\": "),
        None => String::new(),
    }
}

/// `text` with every number of more than 12 significant digits (a position summed from
/// several, `1.1501819599999998`) written to 10 (`1.15018196`); shorter ones, what a user
/// typed, as they are.
pub fn tidy_numbers(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(start) = rest.find(|c: char| c.is_ascii_digit()) {
        out.push_str(&rest[..start]);
        let tail = &rest[start..];
        let len = tail
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(tail.len());
        let token = &tail[..len];
        let digits = token.chars().filter(char::is_ascii_digit).count();
        match token.parse::<f64>() {
            Ok(x) if digits > 12 && token.contains('.') => {
                let rounded: f64 = format!("{x:.9e}").parse().unwrap_or(x);
                out.push_str(&rounded.to_string());
            }
            _ => out.push_str(token),
        }
        rest = &tail[len..];
    }
    out.push_str(rest);
    out
}

impl DesignError {
    /// The rule broken, for [`DesignError::Invalid`].
    pub fn rule(&self) -> Option<&Rule> {
        match self {
            DesignError::Invalid { rule, .. } => Some(rule),
            _ => None,
        }
    }

    /// Where the problem is, for [`DesignError::Invalid`].
    pub fn location(&self) -> Option<&Location> {
        match self {
            DesignError::Invalid { at, .. } => Some(at),
            _ => None,
        }
    }

    /// The field at fault, for [`DesignError::Invalid`] errors that name one.
    pub fn field(&self) -> Option<&str> {
        match self {
            DesignError::Invalid { field, .. } => field.as_deref(),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_computed_numbers_are_written_to_ten_digits_and_typed_ones_as_typed() {
        assert_eq!(
            tidy_numbers("outside its parent (0.25 m to 1.1501819599999998 m)"),
            "outside its parent (0.25 m to 1.15018196 m)"
        );
        assert_eq!(
            tidy_numbers("stages[0].components[12]: got -0.1 and 1234.5678"),
            "stages[0].components[12]: got -0.1 and 1234.5678"
        );
        assert_eq!(tidy_numbers("0.30000000000000004 m"), "0.3 m");
    }

    #[test]
    fn an_invalid_field_reads_as_file_component_field_and_rule() {
        let e = DesignError::Invalid {
            file: "design.json".into(),
            at: Location::Component("fins".into()),
            field: Some("span_m".into()),
            rule: Rule::NotPositive { got: -0.1 },
        };
        assert_eq!(
            e.to_string(),
            "design.json: component \"fins\": field \"span_m\": must be positive and finite (got -0.1)"
        );
    }

    #[test]
    fn a_rule_without_a_field_leaves_the_field_out() {
        let e = DesignError::Invalid {
            file: "d.json".into(),
            at: Location::Stage("sustainer".into()),
            field: None,
            rule: Rule::NoBodyComponent,
        };
        assert_eq!(
            e.to_string(),
            "d.json: stage \"sustainer\": has no body component"
        );
    }
}
