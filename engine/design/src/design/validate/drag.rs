//! The drag model: inline Cd(Mach) tables, CSV files beside the design, or an estimate.
//!
//! The CSV reader is hand-written: the files are two numeric columns (`mach,cd`, RocketPy's
//! layout), with an optional header line and `#` comments, which a split on the comma reads
//! exactly; a CSV crate would add a dependency for no gain in what is accepted.

use super::{Builder, DEFAULT_ROUGHNESS_M};
use crate::design::model::DragSpec;
use crate::design::raw::RawDrag;
use crate::error::{DesignError, Location, Rule};
use std::path::{Path, PathBuf};

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
        let power_off = match (&d.power_off, &d.power_off_csv) {
            (Some(rows), _) => self.table(rows, Origin::Inline("power_off"))?,
            (None, Some(csv)) => self.csv(csv)?,
            (None, None) => {
                return Err(self.invalid(&at, None, Rule::DragModelNotExactlyOne { given: 0 }))
            }
        };
        let power_on = match (&d.power_on, &d.power_on_csv) {
            (Some(_), Some(_)) => {
                return Err(self.invalid(&at, Some("power_on_csv"), Rule::PowerOnTwice))
            }
            (Some(rows), None) => self.table(rows, Origin::Inline("power_on"))?,
            (None, Some(csv)) => self.csv(csv)?,
            (None, None) => power_off.clone(),
        };
        Ok(DragSpec::Curves {
            power_off,
            power_on,
        })
    }

    /// The CSV's path: relative to the design file's directory.
    fn csv_path(&self, name: &str) -> PathBuf {
        let base = self.source.and_then(Path::parent).unwrap_or(Path::new(""));
        base.join(name)
    }

    fn csv(&self, name: &str) -> Result<Vec<(f64, f64)>, DesignError> {
        let path = self.csv_path(name);
        let file = path.display().to_string();
        let text = std::fs::read_to_string(&path).map_err(|source| DesignError::Io {
            file: file.clone(),
            source,
        })?;
        let mut rows = Vec::new();
        let mut lines = Vec::new();
        let mut header_allowed = true;
        for (n, line) in text.lines().enumerate() {
            let t = line.trim();
            if t.is_empty() || t.starts_with('#') {
                continue;
            }
            let fields: Vec<&str> = t.split(',').map(str::trim).collect();
            let parsed: Option<Vec<f64>> = fields.iter().map(|f| f.parse::<f64>().ok()).collect();
            match parsed {
                Some(v) if v.len() == 2 => {
                    rows.push([v[0], v[1]]);
                    lines.push(n + 1);
                }
                Some(v) => {
                    return Err(DesignError::Csv {
                        file,
                        line: n + 1,
                        message: format!("expected two columns, mach,cd (got {})", v.len()),
                    });
                }
                None if header_allowed => {}
                None => {
                    return Err(DesignError::Csv {
                        file,
                        line: n + 1,
                        message: format!("expected two numbers, mach,cd (got \"{t}\")"),
                    });
                }
            }
            header_allowed = false;
        }
        self.table(&rows, Origin::Csv { file, lines })
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
