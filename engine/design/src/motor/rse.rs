//! RockSim `.rse` files: XML `<engine-database><engine-list><engine ...><data><eng-data
//! t= f= m= cg=/>...`. Parsed with `roxmltree` (a small, fuzzed, read-only XML tree) so that
//! attribute order, spacing, line breaks inside tags, entities and comments are handled as
//! XML says, and every node keeps its position for the error's line number.
//!
//! Read: `code` (designation), `mfg`, `dia` and `len` (mm), `propWt` and `initWt` (g),
//! `delays` (comma-separated, `P` = plugged) and each sample's `t` (s) and `f` (N). The
//! per-sample `m` and `cg` columns are not used: the propellant mass is `propWt`, burned in
//! proportion to impulse (see [`super::tables`]), like a `.eng` file's.

use roxmltree::{Document, Node};

use super::curve::{parse_delays, CurveBuilder};
use super::error::{
    parse_error, parse_mm_as_m, parse_non_negative, parse_number, MotorError, Rule,
};
use super::{Motor, MotorFormat};

/// Every `<engine>` in the RockSim text `text`. `file` names the file in errors; its stem
/// becomes each motor's [`Motor::source`].
pub fn parse_rse(text: &str, file: &str) -> Result<Vec<Motor>, MotorError> {
    let doc = Document::parse(text).map_err(|e| MotorError::Xml {
        file: file.to_string(),
        line: e.pos().row as usize,
        message: e.to_string(),
    })?;
    let src = Source::new(text);
    let root = doc.root_element();
    if !root.has_tag_name("engine-database") {
        return Err(parse_error(
            file,
            src.line(root.range().start),
            "<engine-database>",
            Rule::MissingElement,
        ));
    }
    let Some(list) = root.children().find(|n| n.has_tag_name("engine-list")) else {
        return Err(parse_error(
            file,
            src.line(root.range().start),
            "<engine-list>",
            Rule::MissingElement,
        ));
    };
    let motors = list
        .children()
        .filter(|n| n.has_tag_name("engine"))
        .map(|engine| read_engine(&src, engine, file))
        .collect::<Result<Vec<_>, _>>()?;
    if motors.is_empty() {
        return Err(parse_error(
            file,
            src.line(list.range().start),
            "<engine>",
            Rule::MissingElement,
        ));
    }
    Ok(motors)
}

/// The start of each line of the document, so that an offset's line is found by bisection
/// (roxmltree's `text_pos_at` counts from the start each time: read for every sample of a
/// long curve, quadratic in the curve's length).
struct Source {
    line_starts: Vec<usize>,
}

impl Source {
    fn new(text: &str) -> Self {
        Source {
            line_starts: std::iter::once(0)
                .chain(text.match_indices('\n').map(|(i, _)| i + 1))
                .collect(),
        }
    }

    /// 1-based line of byte offset `pos`.
    fn line(&self, pos: usize) -> usize {
        self.line_starts.partition_point(|&s| s <= pos)
    }
}

/// An attribute's text and line, or an error naming it.
fn attribute<'a>(
    doc: &Source,
    node: Node<'a, '_>,
    name: &str,
    file: &str,
) -> Result<(&'a str, usize), MotorError> {
    match node.attribute_node(name) {
        Some(a) => Ok((a.value(), doc.line(a.range_value().start))),
        None => Err(parse_error(
            file,
            doc.line(node.range().start),
            name,
            Rule::MissingAttribute,
        )),
    }
}

fn read_engine(doc: &Source, engine: Node, file: &str) -> Result<Motor, MotorError> {
    let (code, line) = attribute(doc, engine, "code", file)?;
    let designation = code.trim();
    if designation.is_empty() {
        return Err(parse_error(file, line, "code", Rule::Empty));
    }
    let (mfg, _) = attribute(doc, engine, "mfg", file)?;
    let (dia, line) = attribute(doc, engine, "dia", file)?;
    let diameter_m = parse_mm_as_m(dia.trim(), file, line, "dia (mm)")?;
    let (len, line) = attribute(doc, engine, "len", file)?;
    let length_m = parse_mm_as_m(len.trim(), file, line, "len (mm)")?;
    let (prop, line) = attribute(doc, engine, "propWt", file)?;
    let propellant_mass_kg = parse_non_negative(prop.trim(), file, line, "propWt (g)")? / 1000.0;
    let (init, line) = attribute(doc, engine, "initWt", file)?;
    let total_mass_kg = parse_non_negative(init.trim(), file, line, "initWt (g)")? / 1000.0;
    if propellant_mass_kg > total_mass_kg {
        return Err(parse_error(
            file,
            line,
            "initWt (g)",
            Rule::PropellantExceedsTotal {
                propellant_kg: propellant_mass_kg,
                total_kg: total_mass_kg,
            },
        ));
    }
    let delays_s = match engine.attribute_node("delays") {
        Some(a) => parse_delays(
            a.value(),
            ',',
            file,
            doc.line(a.range_value().start),
            "delays (s)",
        )?,
        None => Vec::new(),
    };

    let Some(data) = engine.children().find(|n| n.has_tag_name("data")) else {
        return Err(parse_error(
            file,
            doc.line(engine.range().start),
            "<data>",
            Rule::MissingElement,
        ));
    };
    let mut curve = CurveBuilder::new(file);
    for sample in data.children().filter(|n| n.has_tag_name("eng-data")) {
        let (t, line) = attribute(doc, sample, "t", file)?;
        let time_s = parse_number(t.trim(), file, line, "t (s)")?;
        let (f, line) = attribute(doc, sample, "f", file)?;
        let thrust_n = parse_number(f.trim(), file, line, "f (N)")?;
        curve.push(time_s, thrust_n, line, "t (s)", "f (N)")?;
    }
    let curve = curve.finish(doc.line(data.range().start), "t (s)")?;
    Ok(Motor::assemble(
        designation.to_string(),
        mfg.trim().to_string(),
        diameter_m,
        length_m,
        delays_s,
        propellant_mass_kg,
        total_mass_kg,
        curve,
        file,
        MotorFormat::Rse,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEAD: &str = r#"<engine-database><engine-list>
<engine code="T1" mfg="ACME" dia="29." len="100." propWt="50" initWt="100" delays="P">
<data>
"#;
    const TAIL: &str = "</data></engine></engine-list></engine-database>";

    fn with_samples(samples: &str) -> String {
        format!("{HEAD}{samples}{TAIL}")
    }

    #[test]
    fn a_minimal_file_reads_grams_and_millimetres_into_si_units() {
        let text =
            with_samples("<eng-data t=\"1\" f=\"10\"/>\n<eng-data f=\"0\" t=\"2.\" m=\"0\"/>\n");
        let motors = parse_rse(&text, "a/b.rse").unwrap();
        let m = &motors[0];
        assert_eq!(m.designation, "T1");
        assert_eq!(m.manufacturer, "ACME");
        assert_eq!(m.diameter_m, 0.029);
        assert_eq!(m.propellant_mass_kg, 0.05);
        assert_eq!(m.total_mass_kg, 0.1);
        assert!(m.delays_s.is_empty());
        assert_eq!(m.times_s(), [0.0, 1.0, 2.0]);
        assert_eq!(m.total_impulse_ns(), 10.0);
        assert_eq!(m.source, "b");
        assert_eq!(m.format, MotorFormat::Rse);
    }

    #[test]
    fn a_drop_to_zero_at_burnout_written_as_two_samples_at_one_time_is_mended_as_in_an_eng() {
        // The same curve and the same mending as the `.eng` reader's (one `CurveBuilder`).
        let text = with_samples(
            "<eng-data t=\"0.5\" f=\"10\"/>\n<eng-data t=\"1\" f=\"10\"/>\n<eng-data t=\"1\" f=\"0\"/>\n",
        );
        let m = &parse_rse(&text, "t.rse").unwrap()[0];
        assert_eq!(m.times_s(), [0.0, 0.5, 1.0]);
        assert_eq!(m.thrust_n(), [0.0, 10.0, 10.0]);
        assert_eq!(m.total_impulse_ns(), 2.5 + 5.0);
        assert_eq!(m.notes.len(), 2, "{:?}", m.notes);
        assert!(m.notes[0].starts_with("line 6: the last two samples are both at 1 s"));
    }

    #[test]
    fn each_broken_rule_is_reported_with_file_line_and_field() {
        let err = |s: &str| {
            parse_rse(&with_samples(s), "t.rse")
                .unwrap_err()
                .to_string()
        };
        assert_eq!(
            err("<eng-data t=\"1\" f=\"10\"/>\n<eng-data t=\"1\" f=\"5\"/>"),
            "t.rse, line 5, t (s): time 1 s does not exceed the previous time 1 s (times must strictly increase)"
        );
        assert_eq!(
            err("<eng-data t=\"1\" f=\"-3\"/>"),
            "t.rse, line 4, f (N): -3 must not be negative"
        );
        assert_eq!(
            err("<eng-data t=\"1\"/>"),
            "t.rse, line 4, f: required attribute is missing"
        );
        assert_eq!(
            err("<eng-data t=\"x\" f=\"0\"/>"),
            "t.rse, line 4, t (s): `x` is not a number"
        );
        assert_eq!(
            err(""),
            "t.rse, line 3, samples: the motor has no thrust samples"
        );
        let text = "<engine-database>\n<engine-list/></engine-database>";
        assert_eq!(
            parse_rse(text, "t.rse").unwrap_err().to_string(),
            "t.rse, line 2, <engine>: required element is missing"
        );
        let bad = parse_rse(
            "<engine-database>\n<engine-list>\n</engine-database>",
            "t.rse",
        )
        .unwrap_err();
        assert!(matches!(bad, MotorError::Xml { line: 3, .. }), "{bad}");
    }
}
