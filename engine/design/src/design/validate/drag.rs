//! The drag model: inline Cd(Mach) tables, CSV files beside the design, or an estimate.
//!
//! A CSV is two numeric columns (`mach,cd`, RocketPy's layout; read by [`super::files`]), or
//! the aerodynamic export of RASAero II (a header naming `Mach`, `Alpha`, `CD Power-Off` and
//! `CD Power-On` among its columns; the rows at zero angle of attack are read, here).

use super::files::{content_lines, two_columns};
use super::{Builder, DEFAULT_ROUGHNESS_M};
use crate::design::model::DragSpec;
use crate::design::raw::RawDrag;
use crate::error::{DesignError, Location, Rule};

/// Where a table came from, for its errors.
enum Origin<'a> {
    Inline(&'a str),
    Csv { file: String, lines: Vec<usize> },
}

impl Builder<'_> {
    pub(super) fn drag(&self, raw: Option<&RawDrag>) -> Result<DragSpec, DesignError> {
        let at = Location::Drag;
        let Some(d) = raw else {
            return Ok(DragSpec::Estimate {
                roughness_m: DEFAULT_ROUGHNESS_M,
            });
        };
        let given = usize::from(d.power_off.is_some())
            + usize::from(d.power_off_csv.is_some())
            + usize::from(d.estimate.is_some());
        if given != 1 {
            return Err(self.invalid(&at, None, Rule::DragModelNotExactlyOne { given }));
        }
        if let Some(e) = &d.estimate {
            if d.power_on.is_some() || d.power_on_csv.is_some() {
                let field = if d.power_on.is_some() {
                    "power_on"
                } else {
                    "power_on_csv"
                };
                return Err(self.invalid(&at, Some(field), Rule::PowerOnWithoutPowerOff));
            }
            let roughness_m = match e.roughness_m {
                Some(r) => self.non_negative(&at, "estimate.roughness_m", r)?,
                None => DEFAULT_ROUGHNESS_M,
            };
            return Ok(DragSpec::Estimate { roughness_m });
        }
        let (power_off, rasaero_on) = match (&d.power_off, &d.power_off_csv) {
            (Some(rows), _) => (self.table(rows, Origin::Inline("power_off"))?, None),
            (None, Some(csv)) => {
                let off = self.csv(csv, "power_off_csv", Curve::PowerOff)?;
                // A RASAero export holds both curves: its power-on one unless another is given.
                let on = if off.1 {
                    Some(self.csv(csv, "power_off_csv", Curve::PowerOn)?.0)
                } else {
                    None
                };
                (off.0, on)
            }
            (None, None) => {
                return Err(self.invalid(&at, None, Rule::DragModelNotExactlyOne { given: 0 }))
            }
        };
        let power_on = match (&d.power_on, &d.power_on_csv) {
            (Some(_), Some(_)) => {
                return Err(self.invalid(&at, Some("power_on_csv"), Rule::PowerOnTwice))
            }
            (Some(rows), None) => self.table(rows, Origin::Inline("power_on"))?,
            (None, Some(csv)) => self.csv(csv, "power_on_csv", Curve::PowerOn)?.0,
            (None, None) => rasaero_on.unwrap_or_else(|| power_off.clone()),
        };
        Ok(DragSpec::Curves {
            power_off,
            power_on,
        })
    }

    /// A Cd(Mach) table from CSV file `name`, and whether the file is a RASAero export (then
    /// `curve` chooses its column); `field` is the drag's field that names it.
    fn csv(
        &self,
        name: &str,
        field: &str,
        curve: Curve,
    ) -> Result<(Vec<(f64, f64)>, bool), DesignError> {
        let (file, text) = self.read_beside(name, &Location::Drag, field)?;
        if let Some(columns) = RasaeroColumns::of(&text, curve) {
            let (rows, lines) = columns.read(&text, &file)?;
            return Ok((self.table(&rows, Origin::Csv { file, lines })?, true));
        }
        let (rows, lines) = two_columns(&text, &file, "mach,cd")?;
        Ok((self.table(&rows, Origin::Csv { file, lines })?, false))
    }

    /// Checks a Cd(Mach) table: rows present, Mach >= 0 and strictly increasing, Cd >= 0.
    fn table(&self, rows: &[[f64; 2]], origin: Origin<'_>) -> Result<Vec<(f64, f64)>, DesignError> {
        let fail = |row: usize, field: String, rule: Rule| match &origin {
            Origin::Inline(_) => self.invalid(&Location::Drag, Some(&field), rule),
            Origin::Csv { file, lines } => DesignError::Csv {
                file: file.clone(),
                line: lines.get(row).copied().unwrap_or(0),
                message: rule.to_string(),
            },
        };
        let name = match &origin {
            Origin::Inline(n) => *n,
            Origin::Csv { .. } => "csv",
        };
        if rows.is_empty() {
            return Err(match &origin {
                Origin::Inline(_) => self.invalid(&Location::Drag, Some(name), Rule::EmptyTable),
                Origin::Csv { file, .. } => DesignError::Csv {
                    file: file.clone(),
                    line: 0,
                    message: Rule::EmptyTable.to_string(),
                },
            });
        }
        for (i, [mach, cd]) in rows.iter().copied().enumerate() {
            if !(mach >= 0.0 && mach.is_finite()) {
                return Err(fail(
                    i,
                    format!("{name}[{i}][0]"),
                    Rule::Negative { got: mach },
                ));
            }
            if !(cd >= 0.0 && cd.is_finite()) {
                return Err(fail(
                    i,
                    format!("{name}[{i}][1]"),
                    Rule::Negative { got: cd },
                ));
            }
            if i > 0 && mach <= rows[i - 1][0] {
                let rule = Rule::MachNotIncreasing {
                    row: i,
                    previous: rows[i - 1][0],
                    got: mach,
                };
                return Err(fail(i, name.to_owned(), rule));
            }
        }
        Ok(rows.iter().map(|r| (r[0], r[1])).collect())
    }
}

/// Which of a RASAero export's drag columns a table reads.
#[derive(Clone, Copy)]
enum Curve {
    PowerOff,
    PowerOn,
}

/// Where a RASAero II export keeps what a table reads: the Mach number, the drag
/// coefficient of one curve, and the angle of attack (degrees) if the file has it.
struct RasaeroColumns {
    mach: usize,
    cd: usize,
    alpha: Option<usize>,
    width: usize,
}

impl RasaeroColumns {
    /// The columns, if the first line of `text` that is not blank or a comment is a RASAero
    /// header: it names `Mach` and both `CD Power-Off` and `CD Power-On` (any case).
    fn of(text: &str, curve: Curve) -> Option<RasaeroColumns> {
        let (_, header) = content_lines(text).next()?;
        let names: Vec<String> = header
            .split(',')
            .map(|f| f.trim().trim_matches('"').trim().to_ascii_lowercase())
            .collect();
        let find = |n: &str| names.iter().position(|x| x == n);
        let (off, on) = (find("cd power-off")?, find("cd power-on")?);
        Some(RasaeroColumns {
            mach: find("mach")?,
            cd: match curve {
                Curve::PowerOff => off,
                Curve::PowerOn => on,
            },
            alpha: find("alpha"),
            width: names.len(),
        })
    }

    /// The rows at zero angle of attack (all rows if the file has no `Alpha`), with their
    /// line numbers.
    fn read(&self, text: &str, file: &str) -> Result<(Vec<[f64; 2]>, Vec<usize>), DesignError> {
        let mut rows = Vec::new();
        let mut lines = Vec::new();
        for (line, t) in content_lines(text).skip(1) {
            let fields: Vec<&str> = t.split(',').map(|f| f.trim().trim_matches('"')).collect();
            let bad = |message: String| DesignError::Csv {
                file: file.to_owned(),
                line,
                message,
            };
            if fields.len() < self.width {
                return Err(bad(format!(
                    "a RASAero export's row needs its {} columns (got {})",
                    self.width,
                    fields.len()
                )));
            }
            let number = |i: usize| {
                fields[i]
                    .parse::<f64>()
                    .map_err(|_| bad(format!("expected a number (got \"{}\")", fields[i])))
            };
            if let Some(a) = self.alpha {
                if number(a)? != 0.0 {
                    continue;
                }
            }
            rows.push([number(self.mach)?, number(self.cd)?]);
            lines.push(line);
        }
        if rows.is_empty() && self.alpha.is_some() {
            return Err(DesignError::Csv {
                file: file.to_owned(),
                line: 0,
                message: "a RASAero export without rows at Alpha 0".to_owned(),
            });
        }
        Ok((rows, lines))
    }
}
