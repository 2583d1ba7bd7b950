//! The rules every thrust curve obeys, whatever file it came from, and the numbers derived
//! from it: the implicit (0 s, 0 N) start, strictly increasing times, no negative thrust,
//! trapezoidal impulse, the NAR/TRA impulse class and the common name.
//!
//! Real files have a few slips that OpenRocket's loader mends (`AbstractMotorLoader.
//! finalizeThrustCurve`) and RocketPy reads past; they are mended here the same way, each
//! with a note naming the line: a zero-thrust sample at 0 s followed by another at 0 s (the
//! zero one dropped), a sample repeating the one before (dropped), the last two samples at
//! the same time with one of them zero (the zero one dropped). A curve whose last sample is
//! not zero stops there: the thrust drops to nothing at that time, as both simulators read
//! it. Any other pair of samples at one time, or a time going back, is refused.
//!
//! Both parsers feed their samples through `CurveBuilder` so that an `.eng` and an `.rse`
//! of the same motor are checked, mended and refused in the same way.

use super::error::{parse_error, MotorError, Rule};

/// Collects samples, checking each as it comes, and remembers the line of the last one.
pub(crate) struct CurveBuilder<'f> {
    file: &'f str,
    times_s: Vec<f64>,
    thrust_n: Vec<f64>,
    last_line: usize,
    /// The line of the sample before the last.
    line_before: usize,
    /// A sample at the same time as the one before it, with another thrust: allowed only
    /// as the curve's last pair (its line and the time before it).
    same_time: Option<(usize, f64)>,
    /// What was mended, for [`Curve::notes`].
    notes: Vec<String>,
}

impl<'f> CurveBuilder<'f> {
    pub(crate) fn new(file: &'f str) -> Self {
        CurveBuilder {
            file,
            times_s: Vec::new(),
            thrust_n: Vec::new(),
            last_line: 0,
            line_before: 0,
            same_time: None,
            notes: Vec::new(),
        }
    }

    /// Whether any sample has been pushed.
    pub(crate) fn is_empty(&self) -> bool {
        self.times_s.is_empty()
    }

    /// Adds one sample read at `line`. The first sample, if after 0 s, is preceded by the
    /// implicit (0 s, 0 N) point.
    pub(crate) fn push(
        &mut self,
        time_s: f64,
        thrust_n: f64,
        line: usize,
        time_field: &str,
        thrust_field: &str,
    ) -> Result<(), MotorError> {
        if time_s < 0.0 {
            return Err(parse_error(
                self.file,
                line,
                time_field,
                Rule::Negative { value: time_s },
            ));
        }
        if thrust_n < 0.0 {
            return Err(parse_error(
                self.file,
                line,
                thrust_field,
                Rule::Negative { value: thrust_n },
            ));
        }
        // A pair at one time is allowed only as the last pair: a sample after it refuses it.
        if let Some((step_line, previous_s)) = self.same_time {
            return Err(parse_error(
                self.file,
                step_line,
                time_field,
                Rule::NonIncreasingTime {
                    previous_s,
                    time_s: previous_s,
                },
            ));
        }
        let previous = self
            .times_s
            .last()
            .copied()
            .zip(self.thrust_n.last().copied());
        match previous {
            None if time_s > 0.0 => {
                self.times_s.push(0.0);
                self.thrust_n.push(0.0);
            }
            Some((previous_s, previous_n)) if time_s == previous_s => {
                if thrust_n == previous_n {
                    self.notes.push(format!(
                        "line {line}: the sample repeats the one before it; dropped"
                    ));
                    return Ok(());
                }
                if time_s == 0.0 && previous_n == 0.0 && self.times_s.len() == 1 {
                    self.notes.push(format!(
                        "line {line}: a second sample at 0 s; the zero-thrust one before it \
                         dropped"
                    ));
                    self.times_s.clear();
                    self.thrust_n.clear();
                } else {
                    self.same_time = Some((line, previous_s));
                }
            }
            Some((previous_s, _)) if time_s < previous_s => {
                return Err(parse_error(
                    self.file,
                    line,
                    time_field,
                    Rule::NonIncreasingTime { previous_s, time_s },
                ));
            }
            _ => {}
        }
        self.times_s.push(time_s);
        self.thrust_n.push(thrust_n);
        self.line_before = self.last_line;
        self.last_line = line;
        Ok(())
    }

    /// The finished curve: it must have samples and deliver impulse. `header_line` is where
    /// the motor began (reported when there are no samples).
    pub(crate) fn finish(
        mut self,
        header_line: usize,
        time_field: &str,
    ) -> Result<Curve, MotorError> {
        if let Some((line, previous_s)) = self.same_time {
            // The last two samples share a time: mended if one of them is zero.
            let n = self.thrust_n.len();
            let (before, last) = (self.thrust_n[n - 2], self.thrust_n[n - 1]);
            let drop = if before == 0.0 {
                n - 2
            } else if last == 0.0 {
                n - 1
            } else {
                return Err(parse_error(
                    self.file,
                    line,
                    time_field,
                    Rule::NonIncreasingTime {
                        previous_s,
                        time_s: previous_s,
                    },
                ));
            };
            self.notes.push(format!(
                "line {line}: the last two samples are both at {previous_s} s, one of them \
                 zero; the zero one dropped"
            ));
            self.times_s.remove(drop);
            self.thrust_n.remove(drop);
            if drop == n - 1 {
                self.last_line = self.line_before;
            }
        }
        let Some(&last) = self.thrust_n.last() else {
            return Err(parse_error(
                self.file,
                header_line,
                "samples",
                Rule::NoSamples,
            ));
        };
        if last != 0.0 {
            let t = self.times_s.last().copied().unwrap_or(0.0);
            self.notes.push(format!(
                "line {}: the curve ends at {last} N; the thrust stops at {t} s, its last \
                 sample (as OpenRocket and RocketPy read it)",
                self.last_line
            ));
        }
        let impulse_ns = trapezoid(&self.times_s, &self.thrust_n);
        if impulse_ns.is_nan() || impulse_ns <= 0.0 {
            return Err(parse_error(
                self.file,
                self.last_line,
                "samples",
                Rule::ZeroImpulse,
            ));
        }
        if impulse_class(impulse_ns).is_none() {
            return Err(parse_error(
                self.file,
                self.last_line,
                "samples",
                Rule::ImpulseBeyondClasses { impulse_ns },
            ));
        }
        Ok(Curve {
            times_s: self.times_s,
            thrust_n: self.thrust_n,
            total_impulse_ns: impulse_ns,
            notes: self.notes,
        })
    }
}

/// A checked curve: times start at 0 and strictly increase, thrust is non-negative and the
/// impulse is positive; after the last sample there is no thrust.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Curve {
    pub(crate) times_s: Vec<f64>,
    pub(crate) thrust_n: Vec<f64>,
    pub(crate) total_impulse_ns: f64,
    /// What was mended in the file's samples (see the module docs).
    pub(crate) notes: Vec<String>,
}

/// ∫F dt of a piecewise-linear curve (exact for it).
pub(crate) fn trapezoid(times_s: &[f64], thrust_n: &[f64]) -> f64 {
    times_s
        .windows(2)
        .zip(thrust_n.windows(2))
        .map(|(t, f)| 0.5 * (f[0] + f[1]) * (t[1] - t[0]))
        .sum()
}

/// NAR/TRA impulse class of a total impulse: `A` up to 2.5 N·s (and anything smaller, the
/// fractional ¼A and ½A classes included), each following letter doubling the upper bound
/// (`B` up to 5 N·s, ..., `M` up to 10 240 N·s, `N` up to 20 480 N·s, ..., `Z`). `None` for a
/// non-finite or non-positive impulse or one beyond class `Z`.
pub fn impulse_class(impulse_ns: f64) -> Option<char> {
    if !impulse_ns.is_finite() || impulse_ns <= 0.0 {
        return None;
    }
    let mut upper_ns = 2.5;
    for letter in 'A'..='Z' {
        if impulse_ns <= upper_ns {
            return Some(letter);
        }
        upper_ns *= 2.0;
    }
    None
}

/// The common name of a motor: the first impulse letter followed by digits in its
/// designation, as manufacturers write it (`411-I175-WH-14A` -> `I175`, `I175WS` -> `I175`,
/// `1597K400-14A` -> `K400`). A designation without one gets the class letter of the
/// integrated impulse and the rounded average thrust.
pub(crate) fn common_name(designation: &str, class: char, average_thrust_n: f64) -> String {
    let chars: Vec<char> = designation.chars().collect();
    for (i, &c) in chars.iter().enumerate() {
        let starts_word = i == 0 || !chars[i - 1].is_ascii_alphabetic();
        if c.is_ascii_uppercase() && starts_word {
            let digits: String = chars[i + 1..]
                .iter()
                .take_while(|d| d.is_ascii_digit())
                .collect();
            if !digits.is_empty() {
                return format!("{c}{digits}");
            }
        }
    }
    format!("{class}{:.0}", average_thrust_n)
}

/// Ejection delays written as `6-8-9-11-12-13` (`.eng`) or `6,8,9` (`.rse`); `P` (plugged)
/// contributes no delay, `0` is a charge with no delay.
pub(crate) fn parse_delays(
    text: &str,
    separator: char,
    file: &str,
    line: usize,
    field: &str,
) -> Result<Vec<f64>, MotorError> {
    let text = text.trim();
    if text.is_empty() {
        return Ok(Vec::new());
    }
    let mut delays = Vec::new();
    for token in text.split(separator).map(str::trim) {
        if token.eq_ignore_ascii_case("P") {
            continue;
        }
        delays.push(super::error::parse_non_negative(token, file, line, field)?);
    }
    Ok(delays)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_class_letter_doubles_its_upper_bound_from_a_at_two_and_a_half_newton_seconds() {
        assert_eq!(impulse_class(0.3), Some('A'));
        assert_eq!(impulse_class(2.5), Some('A'));
        assert_eq!(impulse_class(2.500001), Some('B'));
        assert_eq!(impulse_class(160.0), Some('G'));
        assert_eq!(impulse_class(160.1), Some('H'));
        assert_eq!(impulse_class(10240.0), Some('M'));
        assert_eq!(impulse_class(10240.1), Some('N'));
        assert_eq!(impulse_class(20480.0), Some('N'));
        assert_eq!(impulse_class(2.5 * 2f64.powi(25)), Some('Z'));
        assert_eq!(impulse_class(2.5 * 2f64.powi(25) * 1.01), None);
        assert_eq!(impulse_class(0.0), None);
        assert_eq!(impulse_class(f64::NAN), None);
    }

    #[test]
    fn the_common_name_is_the_first_letter_and_number_of_the_designation() {
        assert_eq!(common_name("411-I175-WH-14A", 'I', 164.6), "I175");
        assert_eq!(common_name("I175WS", 'I', 169.1), "I175");
        assert_eq!(common_name("1597K400-14A", 'K', 397.0), "K400");
        assert_eq!(common_name("L1040DM-P", 'L', 938.1), "L1040");
        assert_eq!(common_name("I216-CL(I)", 'I', 205.2), "I216");
        assert_eq!(common_name("Mystery", 'H', 137.46), "H137");
    }

    #[test]
    fn delays_split_on_the_separator_and_plugged_gives_none() {
        assert_eq!(
            parse_delays("6-8-9-11-12-13", '-', "f", 1, "delays").unwrap(),
            [6.0, 8.0, 9.0, 11.0, 12.0, 13.0]
        );
        assert_eq!(
            parse_delays("P", '-', "f", 1, "delays").unwrap(),
            Vec::<f64>::new()
        );
        assert_eq!(parse_delays("0", '-', "f", 1, "delays").unwrap(), [0.0]);
        assert_eq!(
            parse_delays("5,9,13", ',', "f", 1, "delays").unwrap(),
            [5.0, 9.0, 13.0]
        );
        let err = parse_delays("6--8", '-', "f.eng", 3, "delays")
            .unwrap_err()
            .to_string();
        assert_eq!(err, "f.eng, line 3, delays: `` is not a number");
    }
}
