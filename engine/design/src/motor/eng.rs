//! RASP `.eng` files: a header line of seven fields (name, diameter mm, length mm, delays,
//! propellant kg, total kg, manufacturer) followed by `time thrust` samples, `;` comments
//! anywhere. Hand-parsed: the format is line-oriented and has no grammar a crate would add to.
//!
//! Accepted quirks (all seen in real files): CRLF, LF or CR line endings, a UTF-8 byte-order
//! mark, tab-separated fields, trailing spaces, leading and trailing comments, a bare `;`
//! after the last sample, no final newline, comments after a value on the same line, and
//! several motors in one file (each new header starts a motor).

use super::curve::{parse_delays, CurveBuilder};
use super::error::{
    parse_error, parse_mm_as_m, parse_non_negative, parse_number, MotorError, Rule,
};
use super::{Motor, MotorFormat};

/// The header's seven fields, in file order.
const HEADER_FIELDS: usize = 7;

/// Every motor in the RASP text `text`. `file` names the file in errors; its stem becomes
/// each motor's [`Motor::source`].
pub fn parse_eng(text: &str, file: &str) -> Result<Vec<Motor>, MotorError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut motors = Vec::new();
    let mut current: Option<Block> = None;
    let mut line_count = 0;
    for (index, raw) in lines(text).enumerate() {
        let line = index + 1;
        line_count = line;
        let content = raw.split(';').next().unwrap_or("");
        let fields: Vec<&str> = content.split_whitespace().collect();
        if fields.is_empty() {
            continue;
        }
        let is_header = fields.len() == HEADER_FIELDS;
        match current.take() {
            Some(mut block) if fields.len() == 2 => {
                let time_s = parse_number(fields[0], file, line, "time")?;
                let thrust_n = parse_number(fields[1], file, line, "thrust")?;
                block.curve.push(time_s, thrust_n, line, "time", "thrust")?;
                current = Some(block);
            }
            Some(block) if is_header && !block.curve.is_empty() => {
                motors.push(block.finish(file)?);
                current = Some(Block::start(&fields, file, line)?);
            }
            Some(_) => {
                return Err(parse_error(
                    file,
                    line,
                    "sample (time thrust)",
                    Rule::FieldCount {
                        expected: 2,
                        found: fields.len(),
                    },
                ));
            }
            None if is_header => current = Some(Block::start(&fields, file, line)?),
            None => {
                return Err(parse_error(
                    file,
                    line,
                    "header",
                    Rule::FieldCount {
                        expected: HEADER_FIELDS,
                        found: fields.len(),
                    },
                ));
            }
        }
    }
    match current {
        Some(block) => motors.push(block.finish(file)?),
        None => {
            return Err(parse_error(
                file,
                line_count.max(1),
                "header",
                Rule::NoHeader,
            ))
        }
    }
    Ok(motors)
}

/// Lines split on `\n` (a trailing `\r` removed), or on `\r` for a file with no `\n`.
fn lines(text: &str) -> Box<dyn Iterator<Item = &str> + '_> {
    if text.contains('\n') {
        Box::new(text.split('\n').map(|l| l.strip_suffix('\r').unwrap_or(l)))
    } else {
        Box::new(text.split('\r'))
    }
}

/// A motor being read: its header and the samples so far.
struct Block<'f> {
    header_line: usize,
    designation: String,
    diameter_m: f64,
    length_m: f64,
    delays_s: Vec<f64>,
    propellant_mass_kg: f64,
    total_mass_kg: f64,
    manufacturer: String,
    curve: CurveBuilder<'f>,
}

impl<'f> Block<'f> {
    fn start(fields: &[&str], file: &'f str, line: usize) -> Result<Self, MotorError> {
        let diameter_m = parse_mm_as_m(fields[1], file, line, "diameter (header field 2, mm)")?;
        let length_m = parse_mm_as_m(fields[2], file, line, "length (header field 3, mm)")?;
        let delays_s = parse_delays(fields[3], '-', file, line, "delays (header field 4, s)")?;
        let propellant_mass_kg = parse_non_negative(
            fields[4],
            file,
            line,
            "propellant mass (header field 5, kg)",
        )?;
        let total_mass_kg =
            parse_non_negative(fields[5], file, line, "total mass (header field 6, kg)")?;
        if propellant_mass_kg > total_mass_kg {
            return Err(parse_error(
                file,
                line,
                "total mass (header field 6, kg)",
                Rule::PropellantExceedsTotal {
                    propellant_kg: propellant_mass_kg,
                    total_kg: total_mass_kg,
                },
            ));
        }
        Ok(Block {
            header_line: line,
            designation: fields[0].to_string(),
            diameter_m,
            length_m,
            delays_s,
            propellant_mass_kg,
            total_mass_kg,
            manufacturer: fields[6].to_string(),
            curve: CurveBuilder::new(file),
        })
    }

    fn finish(self, file: &str) -> Result<Motor, MotorError> {
        let curve = self.curve.finish(self.header_line, "time")?;
        Ok(Motor::assemble(
            self.designation,
            self.manufacturer,
            self.diameter_m,
            self.length_m,
            self.delays_s,
            self.propellant_mass_kg,
            self.total_mass_kg,
            curve,
            file,
            MotorFormat::Eng,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        parse_eng(text, "test.eng").unwrap_err().to_string()
    }

    #[test]
    fn a_minimal_file_gets_the_implicit_zero_point_and_its_header_in_si_units() {
        let motors = parse_eng("X1 29 100 4-P 0.05 0.1 ACME\n1 10\n2 0", "dir/test.eng").unwrap();
        assert_eq!(motors.len(), 1);
        let m = &motors[0];
        assert_eq!(m.times_s(), [0.0, 1.0, 2.0]);
        assert_eq!(m.thrust_n(), [0.0, 10.0, 0.0]);
        assert_eq!(m.delays_s, [4.0]);
        assert_eq!(m.diameter_m, 0.029);
        assert_eq!(m.length_m, 0.1);
        assert_eq!(m.source, "test");
        // Triangle of base 2 s and height 10 N.
        assert_eq!(m.total_impulse_ns(), 10.0);
    }

    #[test]
    fn a_sample_at_time_zero_is_kept_without_an_extra_point() {
        let m = &parse_eng("X 29 100 0 0.05 0.1 A\n0 5\n1 5\n1.5 0\n", "t.eng").unwrap()[0];
        assert_eq!(m.times_s(), [0.0, 1.0, 1.5]);
        assert_eq!(m.total_impulse_ns(), 5.0 + 1.25);
    }

    #[test]
    fn cr_only_line_endings_and_inline_comments_are_read() {
        let m = &parse_eng(
            "; c\rX 29 100 P 0.05 0.1 A ; hdr\r1 10 ; peak\r2 0\r;",
            "t.eng",
        )
        .unwrap()[0];
        assert_eq!(m.times_s(), [0.0, 1.0, 2.0]);
        assert!(m.delays_s.is_empty());
    }

    #[test]
    fn the_slips_openrocket_mends_are_mended_and_noted_with_their_line() {
        // OpenRocket's `finalizeThrustCurve`: a zero at 0 s before another sample at 0 s,
        // a repeated sample, and the last two samples at one time with one zero.
        let m = &parse_eng(
            "X 29 100 0 0.05 0.1 A\n0 0\n0 120\n0.5 140\n0.5 140\n1.2 100\n1.2 0\n",
            "t.eng",
        )
        .unwrap()[0];
        assert_eq!(m.times_s(), [0.0, 0.5, 1.2]);
        assert_eq!(m.thrust_n(), [120.0, 140.0, 100.0]);
        // 0.5 (120 + 140)/2 + 0.7 (140 + 100)/2 = 65 + 84.
        assert!((m.total_impulse_ns() - 149.0).abs() < 1e-12);
        assert_eq!(m.burn_time_s(), 1.2);
        assert_eq!(
            m.notes,
            [
                "line 3: a second sample at 0 s; the zero-thrust one before it dropped",
                "line 5: the sample repeats the one before it; dropped",
                "line 7: the last two samples are both at 1.2 s, one of them zero; the zero one \
                 dropped",
                "line 6: the curve ends at 100 N; the thrust stops at 1.2 s, its last sample (as \
                 OpenRocket and RocketPy read it)",
            ]
        );
        // A clean file has no notes.
        let clean = &parse_eng("X 29 100 0 0.05 0.1 A\n1 10\n2 0\n", "t.eng").unwrap()[0];
        assert!(clean.notes.is_empty());
    }

    #[test]
    fn a_curve_that_stops_at_a_thrust_burns_out_there_and_its_tables_drop_to_nothing() {
        use crate::motor::{MotorOptions, MotorTables};
        let m = &parse_eng("X 29 100 0 0.05 0.1 A\n1 10\n2 10\n", "t.eng").unwrap()[0];
        assert_eq!(m.burn_time_s(), 2.0);
        assert_eq!(m.total_impulse_ns(), 15.0);
        let tables = MotorTables::new(m, &MotorOptions::default()).unwrap();
        let before = tables.eval(2.0 - 1e-9);
        assert!((before.thrust_n - 10.0).abs() < 1e-9);
        // Propellant burns with the impulse: 1e-8 N·s of 15 left, of 0.05 kg.
        assert!((before.propellant_kg - 0.05 * 1e-8 / 15.0).abs() < 1e-12);
        let after = tables.eval(2.0);
        assert_eq!((after.thrust_n, after.propellant_kg), (0.0, 0.0));
    }

    #[test]
    fn a_size_that_is_no_size_in_metres_is_refused_with_its_file_line_and_field() {
        // 1e-323 mm is positive as written, but 1e-326 m underflows to 0 (the least
        // subnormal is about 4.9e-324): the header's own fault, not the motor's tables'.
        let e = parse_eng("X 29 1e-323 0 0.05 0.1 A\n1 10\n2 0", "test.eng").unwrap_err();
        match &e {
            MotorError::Parse {
                file,
                line: 1,
                field,
                rule: Rule::NotPositiveInMetres { value_mm, value_m },
            } => {
                assert_eq!(file, "test.eng");
                assert_eq!(field, "length (header field 3, mm)");
                assert_eq!((*value_mm, *value_m), (1e-323, 0.0));
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(
            e.to_string(),
            "test.eng, line 1, length (header field 3, mm): 1e-323 mm is 0 m: a size must be a positive, finite number of metres"
        );
        assert_eq!(
            err("X 5e-322 100 0 0.05 0.1 A\n1 10\n2 0"),
            "test.eng, line 1, diameter (header field 2, mm): 5e-322 mm is 0 m: a size must be a positive, finite number of metres"
        );
        // The least size that survives: 1e-320 mm is 1e-323 m, a subnormal but positive.
        let m = parse_eng("X 29 1e-320 0 0.05 0.1 A\n1 10\n2 0", "test.eng").unwrap();
        assert!(m[0].length_m > 0.0);
    }

    #[test]
    fn two_blocks_give_two_motors() {
        let motors = parse_eng(
            "A1 29 100 0 0.05 0.1 A\n1 10\n2 0\nB2 38 200 0 0.1 0.2 B\n1 20\n3 0\n",
            "t.eng",
        )
        .unwrap();
        assert_eq!(motors.len(), 2);
        assert_eq!(motors[1].designation, "B2");
        assert_eq!(motors[1].total_impulse_ns(), 30.0);
    }

    #[test]
    fn each_broken_rule_is_reported_with_file_line_and_field() {
        assert_eq!(
            err("; c\nX 29 100 0 0.05 0.1\n1 10\n2 0"),
            "test.eng, line 2, header: expected 7 whitespace-separated fields, found 6"
        );
        assert_eq!(
            err("X 29 100 0 0.05 0.1 A\n1 10\n0.5 20\n2 0"),
            "test.eng, line 3, time: time 0.5 s does not exceed the previous time 1 s (times must strictly increase)"
        );
        assert_eq!(
            err("X 29 100 0 0.05 0.1 A\n1 10\n1 20\n2 0"),
            "test.eng, line 3, time: time 1 s does not exceed the previous time 1 s (times must strictly increase)"
        );
        assert_eq!(
            err("X 29 100 0 0.05 0.1 A\n1 -10\n2 0"),
            "test.eng, line 2, thrust: -10 must not be negative"
        );
        assert_eq!(err("X 29 100 0 0.05 0.1 A\n1 10\n2 0 3"), "test.eng, line 3, sample (time thrust): expected 2 whitespace-separated fields, found 3");
        assert_eq!(
            err("X 29 100 0 0.05 0.1 A\n1 1O\n2 0"),
            "test.eng, line 2, thrust: `1O` is not a number"
        );
        assert_eq!(
            err("X 29 100 0 0.05 0.1 A\n1 inf\n2 0"),
            "test.eng, line 2, thrust: `inf` is not a finite number"
        );
        // A pair at one time with no zero, at the end, is refused as one in the middle is.
        assert_eq!(
            err("X 29 100 0 0.05 0.1 A\n1 10\n2 10\n2 5\n"),
            "test.eng, line 4, time: time 2 s does not exceed the previous time 2 s (times must strictly increase)"
        );
        // A zero at 0 s then a second sample at 0 s is mended; a third at 0 s is not.
        assert_eq!(
            err("X 29 100 0 0.05 0.1 A\n0 0\n0 5\n0 6\n1 0\n"),
            "test.eng, line 4, time: time 0 s does not exceed the previous time 0 s (times must strictly increase)"
        );
        assert_eq!(
            err("X 0 100 0 0.05 0.1 A\n1 10\n2 0"),
            "test.eng, line 1, diameter (header field 2, mm): 0 must be greater than zero"
        );
        assert_eq!(
            err("X 29 100 0 0.5 0.1 A\n1 10\n2 0"),
            "test.eng, line 1, total mass (header field 6, kg): propellant mass 0.5 kg exceeds the total motor mass 0.1 kg"
        );
        assert_eq!(
            err("X 29 100 0 0.05 0.1 A\n;\n"),
            "test.eng, line 1, samples: the motor has no thrust samples"
        );
        assert_eq!(err(";only\n;comments\n"), "test.eng, line 3, header: no motor header line (the file holds only comments or nothing)");
        assert_eq!(
            err("X 29 100 0 0.05 0.1 A\n1 0\n2 0"),
            "test.eng, line 3, samples: the thrust curve delivers no impulse"
        );
        assert_eq!(
            err("X 29 100 0 0.05 0.1 A\n-1 0\n2 0"),
            "test.eng, line 2, time: -1 must not be negative"
        );
    }
}
