//! The bundled motor library and look-up by name.
//!
//! Every file of `engine/design/motors/` is compiled into the crate with `include_str!`, so
//! the binary finds its motors wherever it runs and nothing is read from disk unless a path
//! is given. The files are parsed once, on first use. A motor's `.eng` and `.rse` share a
//! file stem and are the same motor: look-ups by stem or name return the `.eng` and never
//! call the pair ambiguous; the `.rse` is reached by its full file name.

use std::path::Path;
use std::sync::OnceLock;

use super::{Motor, MotorError, MotorFormat};

/// One bundled file: its name in `engine/design/motors/` and its text.
#[derive(Debug, Clone, Copy)]
pub struct BundledFile {
    pub file_name: &'static str,
    pub text: &'static str,
}

macro_rules! bundled {
    ($name:literal) => {
        BundledFile {
            file_name: $name,
            text: include_str!(concat!("../../motors/", $name)),
        }
    };
}

/// Every bundled thrust-curve file, `.eng` and `.rse`.
pub static BUNDLED_FILES: &[BundledFile] = &[
    bundled!("AeroTech_H128W.eng"),
    bundled!("AeroTech_H148.eng"),
    bundled!("AeroTech_H238T.eng"),
    bundled!("AeroTech_I161W.eng"),
    bundled!("AeroTech_I175WS.eng"),
    bundled!("AeroTech_I284W.eng"),
    bundled!("AeroTech_J350W.eng"),
    bundled!("AeroTech_J570W.eng"),
    bundled!("AeroTech_K1100T.eng"),
    bundled!("AeroTech_K550W.eng"),
    bundled!("AeroTech_L1040DM.eng"),
    bundled!("AeroTech_L1170FJ.eng"),
    bundled!("AeroTech_M1939W.eng"),
    bundled!("Cesaroni_1597K400-14A.eng"),
    bundled!("Cesaroni_I175.eng"),
    bundled!("Cesaroni_I216.eng"),
    bundled!("Cesaroni_J295.eng"),
    bundled!("Cesaroni_K445.eng"),
    bundled!("Cesaroni_K660.eng"),
    bundled!("Cesaroni_L1115.eng"),
    bundled!("Cesaroni_M1670.eng"),
    bundled!("Loki_K960-LW.eng"),
    bundled!("AeroTech_I175WS.rse"),
    bundled!("AeroTech_J570W.rse"),
    bundled!("Cesaroni_I175.rse"),
    bundled!("Cesaroni_M1670.rse"),
];

/// The library's README: provenance, licences and the integrated values of every file.
pub const BUNDLED_README: &str = include_str!("../../motors/README.md");

/// A parsed bundled file.
struct Entry {
    stem: &'static str,
    file_name: &'static str,
    motor: Motor,
}

/// Every bundled file, parsed once. A file that failed to parse would be left out (the
/// tests check that every one parses).
fn entries() -> &'static [Entry] {
    static ENTRIES: OnceLock<Vec<Entry>> = OnceLock::new();
    ENTRIES.get_or_init(|| {
        BUNDLED_FILES
            .iter()
            .filter_map(|f| {
                let motor = Motor::parse(f.text.as_bytes(), f.file_name).ok()?;
                let stem = f.file_name.rsplit_once('.').map_or(f.file_name, |(s, _)| s);
                Some(Entry {
                    stem,
                    file_name: f.file_name,
                    motor,
                })
            })
            .collect()
    })
}

/// One entry per stem: the `.eng` where there is one, else the `.rse`.
fn primaries() -> impl Iterator<Item = &'static Entry> {
    let all = entries();
    all.iter().filter(move |e| {
        e.motor.format == MotorFormat::Eng
            || !all
                .iter()
                .any(|o| o.stem == e.stem && o.motor.format == MotorFormat::Eng)
    })
}

/// The bundled motors, one per file stem (`.eng` preferred), sorted by stem.
pub fn bundled() -> Vec<(&'static str, Motor)> {
    let mut list: Vec<_> = primaries().map(|e| (e.stem, e.motor.clone())).collect();
    list.sort_by(|a, b| a.0.cmp(b.0));
    list
}

/// The motor named `wanted` (designation or common name) in the file at `path`.
fn from_file_by_name(path: &str, wanted: &str) -> Result<Motor, MotorError> {
    let all = Motor::all_from_file(path)?;
    let key = normalized(wanted);
    let mut hits: Vec<Motor> = all
        .iter()
        .filter(|m| {
            !key.is_empty()
                && (normalized(&m.designation) == key || normalized(&m.common_name) == key)
        })
        .cloned()
        .collect();
    match hits.len() {
        1 => Ok(hits.remove(0)),
        0 => match wanted.trim().parse::<usize>() {
            Ok(k) if (1..=all.len()).contains(&k) => Ok(all[k - 1].clone()),
            _ => Err(MotorError::NotInFile {
                file: path.to_string(),
                name: wanted.to_string(),
                designations: all.iter().map(|m| m.designation.clone()).collect(),
            }),
        },
        count => Err(MotorError::AmbiguousInFile {
            file: path.to_string(),
            name: wanted.to_string(),
            count,
        }),
    }
}

/// Upper-case letters and digits only: `411-I175-WH-14A` and `411i175wh14a` compare equal.
fn normalized(name: &str) -> String {
    name.chars()
        .filter(char::is_ascii_alphanumeric)
        .map(|c| c.to_ascii_uppercase())
        .collect()
}

/// A motor by file path, bundled file name or stem, designation or common name.
///
/// In order, the first that matches wins:
/// 1. an existing file (`.eng` or `.rse`, holding exactly one motor), or `FILE#NAME`, the
///    motor of that file whose designation or common name is `NAME` (ignoring case and
///    punctuation), or `FILE#K`, its K-th (from 1), for a file of several (ThrustCurve's
///    downloads can hold one per test);
/// 2. a bundled file name, case-insensitive (`Cesaroni_I175.rse`);
/// 3. a bundled file stem, case-insensitive (`cesaroni_i175`, the `.eng`);
/// 4. a designation, ignoring case and punctuation (`411-I175-WH-14A`, `I175WS`, `M1670-BS`);
/// 5. a common name (`M1670`, `K400`).
///
/// A step that matches several distinct motors is an error listing them all
/// ([`MotorError::Ambiguous`]); nothing matching is [`MotorError::NotFound`].
pub fn find(name_or_path: &str) -> Result<Motor, MotorError> {
    let name = name_or_path.trim();
    if !name.is_empty() && Path::new(name).is_file() {
        return Motor::from_file(name);
    }
    if let Some((path, wanted)) = name.rsplit_once('#') {
        if Path::new(path).is_file() {
            return from_file_by_name(path, wanted);
        }
    }
    if let Some(e) = entries()
        .iter()
        .find(|e| e.file_name.eq_ignore_ascii_case(name))
    {
        return Ok(e.motor.clone());
    }
    let lower = name.to_ascii_lowercase();
    if name.contains(['/', '\\']) || lower.ends_with(".eng") || lower.ends_with(".rse") {
        return Err(MotorError::NoSuchFile {
            file: name.to_string(),
        });
    }
    let key = normalized(name);
    let by_stem = |e: &Entry| e.stem.eq_ignore_ascii_case(name);
    let by_designation = |e: &Entry| !key.is_empty() && normalized(&e.motor.designation) == key;
    let by_common_name = |e: &Entry| !key.is_empty() && normalized(&e.motor.common_name) == key;
    let tiers: [&dyn Fn(&Entry) -> bool; 3] = [&by_stem, &by_designation, &by_common_name];
    for matches in tiers {
        let mut hits: Vec<&Entry> = primaries().filter(|e| matches(e)).collect();
        hits.sort_by(|a, b| a.stem.cmp(b.stem));
        match hits.as_slice() {
            [] => continue,
            [one] => return Ok(one.motor.clone()),
            many => {
                return Err(MotorError::Ambiguous {
                    name: name.to_string(),
                    candidates: many
                        .iter()
                        .map(|e| {
                            format!(
                                "{} {} (file {})",
                                e.motor.manufacturer_name(),
                                e.motor.designation,
                                e.stem
                            )
                        })
                        .collect(),
                })
            }
        }
    }
    Err(MotorError::NotFound {
        name: name.to_string(),
        available: bundled().into_iter().map(|(s, _)| s.to_string()).collect(),
    })
}
