//! Tables in files beside the design (drag curves, an airfoil's lift): where a file named in
//! the design is, and the rows of a two-column CSV.
//!
//! The reader is hand-written: the files are two numeric columns with an optional header line
//! and `#` comments, which a split on the comma reads exactly; a CSV crate would add a
//! dependency for no gain in what is accepted.

use super::Builder;
use crate::error::{DesignError, Location, Rule};
use crate::limits::{read_text_limited, MAX_TABLE_FILE_BYTES};
use std::path::{Path, PathBuf};

impl Builder<'_> {
    /// A file named in the design: relative to the design file's directory.
    pub(super) fn path_beside(&self, name: &str) -> PathBuf {
        let base = self.source.and_then(Path::parent).unwrap_or(Path::new(""));
        base.join(name)
    }

    /// The file named `name` by `field` of the design at `at`, read (at most
    /// [`MAX_TABLE_FILE_BYTES`]): its name for errors and its text. A file that cannot be
    /// read is the field's error, naming the file and why.
    pub(super) fn read_beside(
        &self,
        name: &str,
        at: &Location,
        field: &str,
    ) -> Result<(String, String), DesignError> {
        let path = self.path_beside(name);
        let file = path.display().to_string();
        let text =
            read_text_limited(&path, MAX_TABLE_FILE_BYTES, "a table (CSV)").map_err(|e| {
                self.invalid(
                    at,
                    Some(field),
                    Rule::FileUnreadable {
                        file: file.as_str().into(),
                        why: e.to_string().into(),
                    },
                )
            })?;
        Ok((file, text))
    }
}

/// The lines of a CSV that hold something: their 1-based numbers and trimmed text, blank lines
/// and `#` comments left out.
pub(super) fn content_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines()
        .enumerate()
        .map(|(n, l)| (n + 1, l.trim()))
        .filter(|(_, t)| !t.is_empty() && !t.starts_with('#'))
}

/// The rows of a two-column CSV (`what` names the columns for errors, e.g. `mach,cd`): blank
/// lines and `#` comments skipped, a first line that is not two numbers (a header) skipped.
pub(super) fn two_columns(
    text: &str,
    file: &str,
    what: &str,
) -> Result<(Vec<[f64; 2]>, Vec<usize>), DesignError> {
    let mut rows = Vec::new();
    let mut lines = Vec::new();
    let mut header_allowed = true;
    for (line, t) in content_lines(text) {
        let fields: Vec<&str> = t.split(',').map(str::trim).collect();
        let parsed: Option<Vec<f64>> = fields.iter().map(|f| f.parse::<f64>().ok()).collect();
        let bad = |message: String| DesignError::Csv {
            file: file.to_owned(),
            line,
            message,
        };
        match parsed {
            Some(v) if v.len() == 2 => {
                rows.push([v[0], v[1]]);
                lines.push(line);
            }
            Some(v) => {
                return Err(bad(format!(
                    "expected two columns, {what} (got {})",
                    v.len()
                )))
            }
            None if header_allowed => {}
            None => return Err(bad(format!("expected two numbers, {what} (got \"{t}\")"))),
        }
        header_allowed = false;
    }
    Ok((rows, lines))
}
