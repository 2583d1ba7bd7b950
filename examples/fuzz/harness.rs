//! The fuzzing harness's cases: what is mutated, how, and what a case must do.
//!
//! A case is one input of one kind ([`Target`]): a design (JSON), an OpenRocket file, a motor
//! (`.eng`, `.rse`), a scenario (TOML), a sounding, a drag or lift table (CSV). It is made
//! from a bundled file of that kind (`validation/designs`, the motors of
//! `engine/design/motors`, `scenarios/`, `validation/soundings`, the tables beside the
//! designs and in `validation/rocketpy/data`) by mutations that know its structure: a JSON
//! or TOML value replaced by a number that breaks a rule (zero, negative, tiny, huge,
//! non-finite), by another type, removed, duplicated many times or nested thousands deep; an
//! XML element's text or attribute replaced, the element removed, repeated or nested; a line
//! of a table or a thrust curve changed field by field, removed or repeated (a curve of
//! 200,000 samples); and over any of these, the text truncated, its bytes flipped, random
//! bytes inserted, a byte-order mark, a file past its size limit, or nothing but random
//! bytes. [`generate`] makes case `k` of seed `s` the same every time, so a case is its
//! `(seed, k)`, and a failure's input is saved as a file besides.
//!
//! [`run`] writes a case to a file and passes it through the library's entry points, in this
//! process, as the command line does (`Design::load`, which imports a `.ork`,
//! `Motor::all_from_file` and `MotorTables::new`, `Scenario::load` and `Prepared::new` and
//! `fly_chunk`, a bounded read and `Sounding::parse` and `over_site`), flies what is accepted (a design on its motor, a
//! motor in the reference rocket, a scenario's first variants, a sounding's air and wind),
//! and judges the result: an error is a refusal (fine); a panic is a failure; so is an
//! accepted input that is impossible (a mass that is not positive and finite, a center of
//! pressure ahead of the nose tip, a flight whose figures are not finite...). Aborts and
//! hangs cannot be caught in-process: the runner (`examples/fuzz/main.rs`) runs cases in
//! worker processes under a time and a memory budget and sees them die.
//!
//! Weather files (NetCDF, binary): every `.nc` file under `validation/` ([`weather_bases`])
//! is mutated as bytes and as its format's header fields (the classic format's big-endian
//! counts and sizes, HDF5's little-endian offsets and lengths), its values overwritten with
//! NaN, infinities and fill marks, and read by `hpr_sim::weather::SiteWeather` over the
//! site its grid covers ([`run_weather`]); what it accepts becomes the air and the wind of
//! a flight.

use hpr_design::motor::{Motor, MotorOptions, MotorTables};
use hpr_design::Design;
use hpr_mc::campaign::fly::{fly_chunk, Prepared};
use hpr_mc::campaign::scenario::Scenario;
use hpr_sim::{Environment, Rail, SimOptions, Simulation};
use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use serde_json::Value;
use std::panic::AssertUnwindSafe;
use std::path::{Path, PathBuf};

/// The repository's root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The kinds of input.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Target {
    Design,
    Ork,
    Eng,
    Rse,
    Scenario,
    Sounding,
    DragCsv,
    AirfoilCsv,
    /// A forecast or reanalysis file (NetCDF).
    Weather,
}

impl Target {
    /// The kinds a case is made of.
    pub const GENERATED: [Target; 9] = [
        Target::Design,
        Target::Ork,
        Target::Eng,
        Target::Rse,
        Target::Scenario,
        Target::Sounding,
        Target::DragCsv,
        Target::AirfoilCsv,
        Target::Weather,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Target::Design => "design",
            Target::Ork => "ork",
            Target::Eng => "eng",
            Target::Rse => "rse",
            Target::Scenario => "scenario",
            Target::Sounding => "sounding",
            Target::DragCsv => "drag",
            Target::AirfoilCsv => "airfoil",
            Target::Weather => "weather",
        }
    }

    /// The file extension a saved case of this kind takes.
    pub fn extension(self) -> &'static str {
        match self {
            Target::Design => "json",
            Target::Ork => "ork",
            Target::Eng => "eng",
            Target::Rse => "rse",
            Target::Scenario => "toml",
            Target::Sounding => "txt",
            Target::DragCsv | Target::AirfoilCsv => "csv",
            Target::Weather => "nc",
        }
    }

    /// The kind of a saved case, from its file name's first word (`design-...`).
    pub fn of_file(name: &str) -> Option<Target> {
        let word = name.split(['-', '.']).next()?;
        Target::GENERATED.iter().copied().find(|t| t.name() == word)
    }

    /// The most hpr-mc reads of a file of this kind (a case past it must be refused).
    fn limit(self) -> u64 {
        use hpr_design::limits::*;
        match self {
            Target::Design | Target::Ork => MAX_DESIGN_FILE_BYTES,
            Target::Eng | Target::Rse => MAX_MOTOR_FILE_BYTES,
            Target::Scenario => MAX_SCENARIO_FILE_BYTES,
            Target::Sounding => MAX_SOUNDING_FILE_BYTES,
            Target::DragCsv | Target::AirfoilCsv => MAX_TABLE_FILE_BYTES,
            // Weather files may be large (2 GiB); cases stay within the design's bound.
            Target::Weather => MAX_DESIGN_FILE_BYTES,
        }
    }
}

/// One input: its kind, the bundled file it was made from and how.
#[derive(Debug, Clone)]
pub struct Case {
    pub target: Target,
    pub base: String,
    pub mutation: String,
    pub bytes: Vec<u8>,
}

/// What a case did.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// Accepted, its checks passed (and `flown`: a flight of it too).
    Accepted { flown: bool },
    /// Refused with an error (the error's text).
    Refused(String),
    /// A panic (its message): a failure.
    Panic(String),
    /// Accepted but impossible (what is): a failure.
    Impossible(String),
}

impl Outcome {
    pub fn is_failure(&self) -> bool {
        matches!(self, Outcome::Panic(_) | Outcome::Impossible(_))
    }

    /// One word for counts: `accepted`, `flown`, `refused`, `panic`, `impossible`.
    pub fn word(&self) -> &'static str {
        match self {
            Outcome::Accepted { flown: false } => "accepted",
            Outcome::Accepted { flown: true } => "flown",
            Outcome::Refused(_) => "refused",
            Outcome::Panic(_) => "panic",
            Outcome::Impossible(_) => "impossible",
        }
    }
}

/// The bundled files cases are made from: (name, text) per kind.
pub struct Bases {
    pub designs: Vec<(String, String)>,
    pub orks: Vec<(String, String)>,
    pub engs: Vec<(String, String)>,
    pub rses: Vec<(String, String)>,
    pub scenarios: Vec<(String, String)>,
    pub soundings: Vec<(String, String)>,
    pub drags: Vec<(String, String)>,
    pub airfoils: Vec<(String, String)>,
    /// The NetCDF files, as bytes.
    pub weathers: Vec<(String, Vec<u8>)>,
}

/// Every file under `dir` (not recursing) whose name ends in `ext`, as (name, text).
fn files(dir: &Path, ext: &str) -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = std::fs::read_dir(dir)
        .map(|d| {
            d.filter_map(|e| {
                let p = e.ok()?.path();
                let name = p.file_name()?.to_str()?.to_string();
                (name.ends_with(ext) && p.is_file())
                    .then(|| std::fs::read_to_string(&p).ok().map(|t| (name, t)))?
            })
            .collect()
        })
        .unwrap_or_default();
    out.sort();
    out
}

impl Bases {
    pub fn load() -> Bases {
        let r = root();
        let designs_dir = r.join("validation/designs");
        let mut designs = files(&designs_dir, ".json");
        designs.extend(
            files(&designs_dir.join("random"), ".json")
                .into_iter()
                .map(|(n, t)| (format!("random/{n}"), t)),
        );
        let motors = hpr_design::motor::BUNDLED_FILES;
        let of = |ext: &str| {
            motors
                .iter()
                .filter(|f| f.file_name.ends_with(ext))
                .map(|f| (f.file_name.to_string(), f.text.to_string()))
                .collect::<Vec<_>>()
        };
        let mut drags = files(&designs_dir.join("calisto"), ".csv");
        drags.extend(files(&r.join("validation/rocketpy/data"), "DragCurve.csv"));
        Bases {
            designs,
            orks: files(&designs_dir, ".ork"),
            engs: of(".eng"),
            rses: of(".rse"),
            scenarios: files(&r.join("scenarios"), ".toml"),
            soundings: files(&r.join("validation/soundings"), ".txt"),
            drags,
            airfoils: files(&r.join("validation/rocketpy/data"), "-radians.txt"),
            weathers: weather_bases()
                .into_iter()
                .filter_map(|p| {
                    let name = p.strip_prefix(&r).ok()?.display().to_string();
                    Some((name, std::fs::read(&p).ok()?))
                })
                .collect(),
        }
    }

    fn of(&self, t: Target) -> &[(String, String)] {
        match t {
            Target::Design => &self.designs,
            Target::Ork => &self.orks,
            Target::Eng => &self.engs,
            Target::Rse => &self.rses,
            Target::Scenario => &self.scenarios,
            Target::Sounding => &self.soundings,
            Target::DragCsv => &self.drags,
            Target::AirfoilCsv => &self.airfoils,
            // Binary: see [`Bases::weathers`].
            Target::Weather => &[],
        }
    }

    /// How many bundled files of each kind there are.
    pub fn counts(&self) -> Vec<(Target, usize)> {
        Target::GENERATED
            .iter()
            .map(|&t| match t {
                Target::Weather => (t, self.weathers.len()),
                _ => (t, self.of(t).len()),
            })
            .collect()
    }
}

/// The NetCDF files under `validation/` a weather reader's cases would be made from.
pub fn weather_bases() -> Vec<PathBuf> {
    let mut out = vec![];
    let mut stack = vec![root().join("validation")];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).into_iter().flatten().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "nc") {
                out.push(p);
            }
        }
    }
    out
}

/// The sites the bundled weather files cover: Bella Lui's, and the same at 20 degrees west
/// (the ensemble's grid is relabelled 340 degrees east of ERA5's).
const WEATHER_SITES: [(f64, f64); 2] = [(47.213476, 9.003336), (47.213476, -10.996664)];

/// Read `bytes` as a weather file over the site its grid covers, at its first time and
/// member, and judge what it gives: an error is a refusal; air or wind that is not finite,
/// or an atmosphere the profile's own rules refuse, is impossible; the rest may fly.
pub fn run_weather(bytes: &[u8], _scratch: &Path) -> Option<Outcome> {
    use hpr_sim::weather::{SiteWeather, WeatherError};
    let mut read = SiteWeather::from_bytes(bytes, WEATHER_SITES[0].0, WEATHER_SITES[0].1);
    if matches!(read, Err(WeatherError::Outside { .. })) {
        read = SiteWeather::from_bytes(bytes, WEATHER_SITES[1].0, WEATHER_SITES[1].1);
    }
    let w = match read {
        Ok(w) => w,
        Err(e) => return Some(refused(e)),
    };
    let Some(&time) = w.times_s().first() else {
        return Some(Outcome::Impossible(
            "a weather file read with no times".into(),
        ));
    };
    let site = match w.over_site(time, 0, 407.0) {
        Ok(s) => s,
        Err(e) => return Some(refused(e)),
    };
    let finite = site.air.pressure_pa.is_finite()
        && site
            .air
            .rows
            .iter()
            .all(|r| r.height_m.is_finite() && r.temperature_k.is_finite())
        && site
            .wind
            .iter()
            .all(|r| r.speed_m_s.is_finite() && r.from_deg.is_finite());
    if !finite {
        return Some(Outcome::Impossible(format!(
            "the air or the wind over the site is not finite: {:?}",
            site.air.rows.first()
        )));
    }
    let air = site.air_model();
    if let Err(e) = air.check() {
        return Some(Outcome::Impossible(format!(
            "an atmosphere its own rules refuse was accepted: {e}"
        )));
    }
    let wind = match site.wind() {
        Ok(w) => w,
        Err(e) => return Some(refused(e)),
    };
    if !fly_too(bytes) {
        return Some(Outcome::Accepted { flown: false });
    }
    let design = match Design::load(root().join("validation/designs/example-minimal.json")) {
        Ok(d) => d,
        Err(e) => return Some(Outcome::Impossible(format!("the example: {e}"))),
    };
    let motor = match hpr_design::motor::find("Cesaroni_I175") {
        Ok(m) => m,
        Err(e) => return Some(Outcome::Impossible(format!("the I175: {e}"))),
    };
    let env = Environment {
        elevation_m: 407.0,
        wind,
        air,
        ..Environment::default()
    };
    Some(fly(design, motor, env).unwrap_or(Outcome::Accepted { flown: false }))
}

// ---------------------------------------------------------------------------------------
// Generation.

/// Case `k` of `seed`: always the same.
pub fn generate(bases: &Bases, seed: u64, k: u64) -> Case {
    let mut key = [0u8; 32];
    key[..8].copy_from_slice(&seed.to_le_bytes());
    key[8..16].copy_from_slice(&k.to_le_bytes());
    key[16..24].copy_from_slice(b"hpr-fuzz");
    let mut rng = ChaCha8Rng::from_seed(key);
    let target = Target::GENERATED[rng.random_range(0..Target::GENERATED.len())];
    if target == Target::Weather && !bases.weathers.is_empty() {
        let (base, bytes) = &bases.weathers[rng.random_range(0..bases.weathers.len())];
        let mut m = Mutator {
            rng,
            notes: vec![],
            limit: target.limit(),
        };
        let bytes = m.netcdf(bytes.clone());
        return Case {
            target,
            base: base.clone(),
            mutation: m.notes.join("; "),
            bytes,
        };
    }
    // Without weather files, another kind.
    let target = if target == Target::Weather {
        Target::Design
    } else {
        target
    };
    let choices = bases.of(target);
    let (base, text) = &choices[rng.random_range(0..choices.len())];
    let mut m = Mutator {
        rng,
        notes: vec![],
        limit: target.limit(),
    };
    let bytes = m.mutate(target, text);
    Case {
        target,
        base: base.clone(),
        mutation: m.notes.join("; "),
        bytes,
    }
}

/// The most bytes one repetition or nesting may add to a case (8 MiB), and the size past
/// which no further mutation is stacked: the harness's own inputs stay bounded (a block
/// nested 50,000 deep and then repeated 2,000 times would be gigabytes before hpr-mc sees
/// it). Inputs past hpr-mc's size limits are made on purpose, by padding, to be refused.
const MAX_GROWTH: usize = 8 << 20;

/// How many copies of `len` bytes fit in [`MAX_GROWTH`] (at least 1), at most `n`.
fn copies(n: usize, len: usize) -> usize {
    n.min(MAX_GROWTH / len.max(1)).max(1)
}

struct Mutator {
    rng: ChaCha8Rng,
    notes: Vec<String>,
    limit: u64,
}

/// Numbers that break rules, as text.
const NASTY: &[&str] = &[
    "0",
    "-0",
    "-0.0",
    "-1",
    "1",
    "1e-300",
    "5e-324",
    "1e300",
    "-1e300",
    "1e30",
    "1e9",
    "1e6",
    "-1e6",
    "1e-9",
    "2e-3",
    "1000",
    "9007199254740993",
    "4294967296",
    "-2147483649",
    "0.5",
    "100",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "Infinity",
    "1e999",
    "-1e999",
    "0x10",
    "1_000",
    "",
    " ",
    "abc",
    "1,5",
    "1.2.3",
    "--1",
    "+1",
];

/// Strings that break rules, for string fields (paths, names, kinds).
const NASTY_STRINGS: &[&str] = &[
    "",
    " ",
    "x",
    "/dev/zero",
    "/dev/urandom",
    "/",
    ".",
    "..",
    "../../../../../../etc/passwd",
    "nonexistent.json",
    "Cesaroni_I175",
    "AeroTech_K550W.eng",
    "I175",
    "apogee",
    "burnout",
    "nose_cone",
    "fin_set",
    "strict",
    "openrocket",
    "rk4",
    "adaptive",
    "normal",
    "uniform",
    "lognormal",
    "é ü 日本",
    "\u{feff}",
    "\u{0}",
    "a\nb",
    "ballast",
];

impl Mutator {
    fn chance(&mut self, p: f64) -> bool {
        self.rng.random_bool(p)
    }

    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            self.rng.random_range(0..n)
        }
    }

    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }

    /// A count for repetition or nesting: mostly small, sometimes thousands.
    fn count(&mut self) -> usize {
        match self.below(10) {
            0..=5 => 2 + self.below(8),
            6..=7 => 10 + self.below(200),
            8 => 1000 + self.below(5000),
            _ => 10_000 + self.below(100_000),
        }
    }

    /// A number that breaks rules, or the old one scaled (`old` if it is one).
    fn number_text(&mut self, old: Option<f64>) -> String {
        match (self.below(4), old) {
            (0, Some(x)) => {
                let f = *self.pick(&[1e3, 1e-3, -1.0, 0.5, 2.0, 1e6, 1e-6, 10.0, 0.1]);
                format!("{}", x * f)
            }
            (1, Some(x)) => format!("{}", x * (0.5 + self.rng.random::<f64>())),
            (2, _) => {
                let bits: u64 = self.rng.random();
                let v = f64::from_bits(bits);
                if v.is_finite() {
                    format!("{v:e}")
                } else {
                    "1e308".into()
                }
            }
            _ => self.pick(NASTY).to_string(),
        }
    }

    /// A few numbers of `text` scaled by factors from 0.5 to 2: a file that mostly stays
    /// valid, so that what is accepted (and flown) varies too.
    fn gentle(&mut self, text: &str) -> String {
        let spans = number_spans(text);
        let mut out = text.to_string();
        let n = 1 + self.below(3);
        // From the last span back, so that earlier offsets stay right.
        let mut chosen: Vec<(usize, usize)> = (0..n)
            .filter(|_| !spans.is_empty())
            .map(|_| *self.pick(&spans))
            .collect();
        chosen.sort();
        chosen.dedup();
        for (a, b) in chosen.into_iter().rev() {
            if let Ok(x) = out[a..b].parse::<f64>() {
                let f = 0.5 + 1.5 * self.rng.random::<f64>();
                let y = x * f;
                self.notes.push(format!("number at {a}: {x} × {f:.3}"));
                out.replace_range(a..b, &format!("{y}"));
            }
        }
        out
    }

    /// Mutate `text` of kind `t`: its structure (mostly), its bytes, or both.
    fn mutate(&mut self, t: Target, text: &str) -> Vec<u8> {
        if self.chance(0.3) {
            return self.gentle(text).into_bytes();
        }
        let structured = self.below(10) < 9;
        let mut out = text.as_bytes().to_vec();
        if structured {
            let rounds = 1 + self.below(3);
            for _ in 0..rounds {
                if out.len() > 2 * MAX_GROWTH {
                    break;
                }
                let current = String::from_utf8_lossy(&out).into_owned();
                out = match t {
                    Target::Design => self.json(&current).into_bytes(),
                    Target::Scenario => self.toml(&current).into_bytes(),
                    Target::Ork | Target::Rse => self.xml(&current).into_bytes(),
                    _ => self.lines(&current).into_bytes(),
                };
            }
        }
        if !structured || self.chance(0.15) {
            out = self.bytes(out);
        }
        if t == Target::Ork && self.chance(0.3) {
            out = self.container(out);
        }
        out
    }

    // --- NetCDF ---------------------------------------------------------------------------

    /// A weather file broken as its format breaks: one to three of a header field set to an
    /// edge (the classic format's big-endian counts, sizes and offsets; HDF5's
    /// little-endian 8-byte addresses and lengths), a value overwritten with a NaN, an
    /// infinity or a fill mark, a cut, or the bytes' own mutations.
    fn netcdf(&mut self, mut b: Vec<u8>) -> Vec<u8> {
        let rounds = 1 + self.below(3);
        for _ in 0..rounds {
            if b.is_empty() {
                break;
            }
            let hdf5 = b.starts_with(b"\x89HDF");
            match self.below(6) {
                0 | 1 => {
                    // A header field: within the first 4 KiB, aligned as the format aligns.
                    let width = if hdf5 { 8 } else { 4 };
                    let span = b.len().min(4096) / width;
                    if span == 0 {
                        continue;
                    }
                    let at = self.below(span) * width;
                    let value: u64 = *self.pick(&[
                        0,
                        1,
                        2,
                        0x7fff_ffff,
                        0xffff_ffff,
                        0x8000_0000,
                        u64::MAX,
                        b.len() as u64,
                        b.len() as u64 * 4,
                    ]);
                    let bytes = if hdf5 {
                        value.to_le_bytes().to_vec()
                    } else {
                        (value as u32).to_be_bytes().to_vec()
                    };
                    b[at..at + width].copy_from_slice(&bytes);
                    self.notes
                        .push(format!("header field at {at} set to {value:#x}"));
                }
                2 => {
                    // A value: a float's NaN or infinity, a short's fill or its extremes.
                    let at = self.below(b.len().saturating_sub(4).max(1));
                    let pattern: [u8; 4] = *self.pick(&[
                        [0x7f, 0xc0, 0x00, 0x00],
                        [0x7f, 0x80, 0x00, 0x00],
                        [0xff, 0x80, 0x00, 0x00],
                        [0x80, 0x01, 0x80, 0x01],
                        [0x7f, 0xff, 0x7f, 0xff],
                    ]);
                    let end = (at + 4).min(b.len());
                    let n = end - at;
                    b[at..end].copy_from_slice(&pattern[..n]);
                    self.notes
                        .push(format!("value at {at} set to {pattern:02x?}"));
                }
                3 => {
                    let at = self.below(b.len() + 1);
                    b.truncate(at);
                    self.notes.push(format!("cut at {at}"));
                }
                _ => b = self.bytes(b),
            }
        }
        b
    }

    // --- bytes ---------------------------------------------------------------------------

    fn bytes(&mut self, mut b: Vec<u8>) -> Vec<u8> {
        match self.below(9) {
            0 => {
                let at = self.below(b.len() + 1);
                b.truncate(at);
                self.notes.push(format!("truncated at {at}"));
            }
            1 => {
                let n = 1 + self.below(16);
                for _ in 0..n {
                    if !b.is_empty() {
                        let i = self.below(b.len());
                        b[i] ^= 1 << self.below(8);
                    }
                }
                self.notes.push(format!("{n} bits flipped"));
            }
            2 => {
                let at = self.below(b.len() + 1);
                let n = 1 + self.below(64);
                let junk: Vec<u8> = (0..n).map(|_| self.rng.random()).collect();
                b.splice(at..at, junk);
                self.notes.push(format!("{n} random bytes at {at}"));
            }
            3 => {
                let n = self.below(4096);
                b = (0..n).map(|_| self.rng.random()).collect();
                self.notes.push(format!("{n} random bytes"));
            }
            4 => {
                b.splice(0..0, [0xef, 0xbb, 0xbf]);
                self.notes.push("byte-order mark".into());
            }
            5 => {
                // Random printable text.
                let n = self.below(2000);
                b = (0..n)
                    .map(|_| *self.pick(b" \n\t,.-+0123456789eE[]{}<>=\"#;abcxyz"))
                    .collect();
                self.notes.push(format!("{n} random characters"));
            }
            6 if self.chance(0.02) => {
                // Past the kind's size limit: must be refused, never read whole.
                let n = self.limit as usize + 1 - b.len().min(self.limit as usize);
                b.extend(std::iter::repeat_n(b' ', n));
                self.notes.push(format!("padded past {} bytes", self.limit));
            }
            7 => {
                let n = copies(2 + self.below(30), b.len());
                let once = b.clone();
                for _ in 1..n {
                    b.extend_from_slice(&once);
                }
                self.notes.push(format!("repeated {n} times"));
            }
            _ => {
                let at = self.below(b.len() + 1);
                b.insert(at, 0);
                self.notes.push(format!("NUL at {at}"));
            }
        }
        b
    }

    /// An OpenRocket document put in a ZIP or a gzip stream.
    fn container(&mut self, b: Vec<u8>) -> Vec<u8> {
        use std::io::Write;
        if self.chance(0.5) {
            let mut out = std::io::Cursor::new(Vec::new());
            let mut zip = zip::ZipWriter::new(&mut out);
            let options = zip::write::SimpleFileOptions::default()
                .compression_method(zip::CompressionMethod::Deflated);
            let name = if self.chance(0.8) { "rocket.ork" } else { "x" };
            let _ = zip.start_file(name, options);
            let _ = zip.write_all(&b);
            if self.chance(0.2) {
                let _ = zip.start_file("decals/a.png", options);
                let _ = zip.write_all(b"\x89PNG");
            }
            let _ = zip.finish();
            self.notes.push("zipped".into());
            let mut z = out.into_inner();
            if self.chance(0.2) {
                let at = self.below(z.len() + 1);
                z.truncate(at);
                self.notes.push(format!("ZIP truncated at {at}"));
            }
            z
        } else {
            let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
            let _ = gz.write_all(&b);
            self.notes.push("gzipped".into());
            gz.finish().unwrap_or_default()
        }
    }

    // --- JSON ----------------------------------------------------------------------------

    fn json(&mut self, text: &str) -> String {
        let Ok(mut v) = serde_json::from_str::<Value>(text) else {
            return self.textual_numbers(text);
        };
        let mut paths = vec![];
        json_paths(&v, String::new(), &mut paths);
        if paths.is_empty() {
            return text.to_string();
        }
        let path = self.pick(&paths).clone();
        let op = self.below(9);
        let Some(node) = v.pointer_mut(&path) else {
            return text.to_string();
        };
        match op {
            0 | 1 => {
                let old = node.as_f64();
                let new = self.number_text(old);
                *node = serde_json::from_str(&new).unwrap_or(Value::String(new.clone()));
                self.notes.push(format!("{path} = {new}"));
            }
            2 => {
                let new = self.pick(NASTY_STRINGS).to_string();
                self.notes.push(format!("{path} = {new:?}"));
                *node = Value::String(new);
            }
            3 => {
                let others = [
                    Value::Null,
                    Value::Bool(true),
                    Value::Array(vec![]),
                    Value::Object(Default::default()),
                    serde_json::json!([0.0, 0.1]),
                    serde_json::json!({"type": "body_tube"}),
                ];
                let new = others[self.below(others.len())].clone();
                self.notes.push(format!("{path} = {new}"));
                *node = new;
            }
            4 => {
                let (parent, key) = path.rsplit_once('/').unwrap_or(("", ""));
                if let Some(p) = v.pointer_mut(parent) {
                    match p {
                        Value::Object(m) => {
                            m.remove(key);
                        }
                        Value::Array(a) => {
                            if let Ok(i) = key.parse::<usize>() {
                                if i < a.len() {
                                    a.remove(i);
                                }
                            }
                        }
                        _ => {}
                    }
                }
                self.notes.push(format!("{path} removed"));
            }
            5 => {
                let n = self.count();
                let (parent, key) = path.rsplit_once('/').unwrap_or(("", ""));
                if let Some(Value::Array(a)) = v.pointer_mut(parent) {
                    if let Ok(i) = key.parse::<usize>() {
                        if i < a.len() {
                            let item = a[i].clone();
                            let len = serde_json::to_string(&item).map_or(1, |t| t.len());
                            let n = copies(n.min(20_000), len);
                            a.splice(i..i, std::iter::repeat_n(item, n));
                            self.notes.push(format!("{path} repeated {n} times"));
                        }
                    }
                } else if let Some(Value::Object(m)) = v.pointer_mut(parent) {
                    let item = m.get(key).cloned().unwrap_or(Value::Null);
                    m.insert(format!("{key}_x"), item);
                    self.notes.push(format!("{path} copied to {key}_x"));
                }
            }
            6 => {
                // At most 2,000 deep: the harness's own JSON values recurse to print and drop
                // (serde_json's parser refuses past 128).
                let n = self.count().min(2_000);
                let mut inner = std::mem::take(node);
                for _ in 0..n {
                    inner = if n.is_multiple_of(2) {
                        Value::Array(vec![inner])
                    } else {
                        serde_json::json!({ "children": [inner] })
                    };
                }
                *node = inner;
                self.notes.push(format!("{path} nested {n} deep"));
            }
            7 => {
                if let Value::Object(m) = node {
                    let key = self.pick(&["unknown", "id", "type", "mass_kg", "position", "x"]);
                    m.insert(key.to_string(), Value::from(1.0));
                    self.notes.push(format!("{path}/{key} added"));
                } else {
                    let n = self.count().min(100_000);
                    *node = Value::String("x".repeat(n));
                    self.notes.push(format!("{path} = a string of {n}"));
                }
            }
            _ => {
                let s = serde_json::to_string(&v).unwrap_or_default();
                return self.textual_numbers(&s);
            }
        }
        serde_json::to_string_pretty(&v).unwrap_or_default()
    }

    /// A random number token of `text` replaced by a nasty one (non-finite ones included,
    /// which a JSON value cannot hold).
    fn textual_numbers(&mut self, text: &str) -> String {
        let spans = number_spans(text);
        if spans.is_empty() {
            return text.to_string();
        }
        let (a, b) = *self.pick(&spans);
        let old = text[a..b].parse::<f64>().ok();
        let new = self.number_text(old);
        self.notes.push(format!("number at {a} = {new}"));
        format!("{}{}{}", &text[..a], new, &text[b..])
    }

    // --- TOML ----------------------------------------------------------------------------

    fn toml(&mut self, text: &str) -> String {
        let Ok(mut t) = text.parse::<toml::Table>() else {
            return self.textual_numbers(text);
        };
        let mut paths = vec![];
        toml_paths(&toml::Value::Table(t.clone()), vec![], &mut paths);
        if paths.is_empty() {
            return text.to_string();
        }
        let path = self.pick(&paths).clone();
        let shown = path.join(".");
        let op = self.below(8);
        let mut table = toml::Value::Table(std::mem::take(&mut t));
        let new_value = match op {
            0..=2 => {
                let old = toml_get(&table, &path).and_then(|v| match v {
                    toml::Value::Float(f) => Some(*f),
                    toml::Value::Integer(i) => Some(*i as f64),
                    _ => None,
                });
                let s = self.number_text(old);
                let v = match s.parse::<i64>() {
                    Ok(i) if self.chance(0.5) => toml::Value::Integer(i),
                    _ => match s.to_ascii_lowercase().as_str() {
                        "nan" => toml::Value::Float(f64::NAN),
                        "inf" | "infinity" | "1e999" => toml::Value::Float(f64::INFINITY),
                        "-inf" | "-1e999" => toml::Value::Float(f64::NEG_INFINITY),
                        _ => s
                            .parse::<f64>()
                            .map(toml::Value::Float)
                            .unwrap_or(toml::Value::String(s.clone())),
                    },
                };
                Some(v)
            }
            3 => Some(toml::Value::String(self.pick(NASTY_STRINGS).to_string())),
            4 => {
                let others = [
                    toml::Value::Boolean(true),
                    toml::Value::Array(vec![]),
                    toml::Value::Table(Default::default()),
                    toml::Value::Integer(i64::MAX),
                    toml::Value::Integer(-1),
                    toml::Value::Integer(0),
                ];
                Some(others[self.below(others.len())].clone())
            }
            5 => {
                // A long list: a sweep of many values, or an array of tables repeated.
                let item = toml_get(&table, &path)
                    .cloned()
                    .unwrap_or(toml::Value::Float(1.0));
                let item = match item {
                    toml::Value::Array(a) if !a.is_empty() => a[0].clone(),
                    other => other,
                };
                let n = copies(self.count().min(200_000), item.to_string().len() + 2);
                let items: Vec<toml::Value> = (0..n)
                    .map(|i| match &item {
                        toml::Value::Float(f) => toml::Value::Float(f * (1.0 + i as f64 * 1e-4)),
                        other => other.clone(),
                    })
                    .collect();
                self.notes.push(format!("{shown} = a list of {n}"));
                Some(toml::Value::Array(items))
            }
            6 => None,
            _ => {
                let n = self.count().min(50);
                let mut inner = toml_get(&table, &path)
                    .cloned()
                    .unwrap_or(toml::Value::Float(1.0));
                for _ in 0..n {
                    inner = toml::Value::Array(vec![inner]);
                }
                self.notes.push(format!("{shown} nested {n} deep"));
                Some(inner)
            }
        };
        match new_value {
            Some(v) => {
                if op <= 4 {
                    self.notes.push(format!("{shown} = {v}"));
                }
                toml_set(&mut table, &path, Some(v));
            }
            None => {
                self.notes.push(format!("{shown} removed"));
                toml_set(&mut table, &path, None);
            }
        }
        let out = match table {
            toml::Value::Table(t) => toml::to_string(&t).unwrap_or_default(),
            _ => String::new(),
        };
        if self.chance(0.1) {
            return self.textual_numbers(&out);
        }
        out
    }

    // --- XML -----------------------------------------------------------------------------

    fn xml(&mut self, text: &str) -> String {
        let Ok(doc) = roxmltree::Document::parse(text) else {
            return self.lines(text);
        };
        // Element ranges, text ranges and attribute value ranges, with a name each.
        let mut elements = vec![];
        let mut values = vec![];
        for node in doc.descendants() {
            if node.is_element() && node.parent().is_some_and(|p| p.is_element()) {
                elements.push((node.range(), node.tag_name().name().to_string()));
                for a in node.attributes() {
                    values.push((a.range_value(), format!("@{}", a.name())));
                }
            } else if node.is_text() && !node.text().unwrap_or("").trim().is_empty() {
                let name = node
                    .parent()
                    .map(|p| p.tag_name().name().to_string())
                    .unwrap_or_default();
                values.push((node.range(), name));
            }
        }
        let op = self.below(8);
        if (op <= 3 || elements.is_empty()) && !values.is_empty() {
            let (r, name) = self.pick(&values).clone();
            let old = text[r.clone()].trim().parse::<f64>().ok();
            let new = if old.is_some() || self.chance(0.5) {
                self.number_text(old)
            } else {
                self.pick(NASTY_STRINGS).to_string()
            };
            let new = new.replace('<', "&lt;").replace('"', "&quot;");
            self.notes.push(format!("<{name}> = {new:?}"));
            return format!("{}{}{}", &text[..r.start], new, &text[r.end..]);
        }
        if elements.is_empty() {
            return text.to_string();
        }
        let (r, name) = self.pick(&elements).clone();
        let element = &text[r.clone()];
        match op {
            4 => {
                self.notes.push(format!("<{name}> removed"));
                format!("{}{}", &text[..r.start], &text[r.end..])
            }
            5 => {
                let n = copies(self.count().min(20_000), element.len());
                self.notes.push(format!("<{name}> repeated {n} times"));
                format!(
                    "{}{}{}",
                    &text[..r.start],
                    element.repeat(n + 1),
                    &text[r.end..]
                )
            }
            6 => {
                let open = format!("<{name}>");
                let close = format!("</{name}>");
                let n = copies(self.count(), open.len() + close.len());
                self.notes
                    .push(format!("<{name}> nested {n} deep in itself"));
                let mut s = String::with_capacity(text.len() + n * (open.len() + close.len()));
                s.push_str(&text[..r.start]);
                for _ in 0..n {
                    s.push_str(&open);
                }
                s.push_str(element);
                for _ in 0..n {
                    s.push_str(&close);
                }
                s.push_str(&text[r.end..]);
                s
            }
            _ => {
                // Moved: taken out and put back elsewhere among the elements.
                let (r2, other) = self.pick(&elements).clone();
                if r2.start >= r.end || r2.end <= r.start {
                    self.notes.push(format!("<{name}> put before <{other}>"));
                    let mut s = String::new();
                    if r2.start >= r.end {
                        s.push_str(&text[..r.start]);
                        s.push_str(&text[r.end..r2.start]);
                        s.push_str(element);
                        s.push_str(&text[r2.start..]);
                    } else {
                        s.push_str(&text[..r2.start]);
                        s.push_str(element);
                        s.push_str(&text[r2.start..r.start]);
                        s.push_str(&text[r.end..]);
                    }
                    s
                } else {
                    text.to_string()
                }
            }
        }
    }

    // --- lines and fields ------------------------------------------------------------------

    fn lines(&mut self, text: &str) -> String {
        let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
        if lines.is_empty() {
            return text.to_string();
        }
        let i = self.below(lines.len());
        match self.below(7) {
            0..=2 => {
                // A field replaced (fields split on white space or commas).
                let line = lines[i].clone();
                let spans = field_spans(&line);
                if let Some(&(a, b)) = (!spans.is_empty()).then(|| self.pick(&spans)) {
                    let old = line[a..b].parse::<f64>().ok();
                    let new = self.number_text(old);
                    self.notes
                        .push(format!("line {} field at {a} = {new:?}", i + 1));
                    lines[i] = format!("{}{}{}", &line[..a], new, &line[b..]);
                }
            }
            3 => {
                let n = 1 + self.below(lines.len().min(20));
                let end = (i + n).min(lines.len());
                lines.drain(i..end);
                self.notes.push(format!("lines {}..{} removed", i + 1, end));
            }
            4 => {
                let line = lines[i].clone();
                let n = copies(self.count().min(200_000), line.len() + 1);
                lines.splice(i..i, std::iter::repeat_n(line, n));
                self.notes
                    .push(format!("line {} repeated {n} times", i + 1));
            }
            5 => {
                // Many samples: a line of numbers continued with rising first fields.
                let line = lines[i].clone();
                let nums: Vec<f64> = line
                    .split(|c: char| c.is_whitespace() || c == ',')
                    .filter_map(|f| f.parse().ok())
                    .collect();
                if nums.len() >= 2 {
                    let n = copies(self.count().min(200_000), 24 * nums.len());
                    let step = 1e-5 + self.rng.random::<f64>() * 1e-3;
                    let rows: Vec<String> = (1..=n)
                        .map(|k| {
                            let mut r = nums.clone();
                            r[0] += step * k as f64;
                            r.iter()
                                .map(|x| format!("{x}"))
                                .collect::<Vec<_>>()
                                .join(" ")
                        })
                        .collect();
                    lines.splice(i + 1..i + 1, rows);
                    self.notes.push(format!("{n} rows after line {}", i + 1));
                }
            }
            _ => {
                let j = self.below(lines.len());
                lines.swap(i, j);
                self.notes
                    .push(format!("lines {} and {} swapped", i + 1, j + 1));
            }
        }
        let mut out = lines.join("\n");
        if text.ends_with('\n') {
            out.push('\n');
        }
        out
    }
}

/// JSON pointers of every node but the root.
fn json_paths(v: &Value, here: String, out: &mut Vec<String>) {
    match v {
        Value::Object(m) => {
            for (k, c) in m {
                let p = format!("{here}/{}", k.replace('~', "~0").replace('/', "~1"));
                out.push(p.clone());
                json_paths(c, p, out);
            }
        }
        Value::Array(a) => {
            for (i, c) in a.iter().enumerate() {
                let p = format!("{here}/{i}");
                out.push(p.clone());
                json_paths(c, p, out);
            }
        }
        _ => {}
    }
}

/// Key paths of every TOML value but the root (array items by index).
fn toml_paths(v: &toml::Value, here: Vec<String>, out: &mut Vec<Vec<String>>) {
    match v {
        toml::Value::Table(t) => {
            for (k, c) in t {
                let mut p = here.clone();
                p.push(k.clone());
                out.push(p.clone());
                toml_paths(c, p, out);
            }
        }
        toml::Value::Array(a) => {
            for (i, c) in a.iter().enumerate().take(50) {
                let mut p = here.clone();
                p.push(format!("#{i}"));
                out.push(p.clone());
                toml_paths(c, p, out);
            }
        }
        _ => {}
    }
}

fn toml_get<'a>(v: &'a toml::Value, path: &[String]) -> Option<&'a toml::Value> {
    let mut cur = v;
    for k in path {
        cur = match (cur, k.strip_prefix('#')) {
            (toml::Value::Array(a), Some(i)) => a.get(i.parse::<usize>().ok()?)?,
            (toml::Value::Table(t), None) => t.get(k)?,
            _ => return None,
        };
    }
    Some(cur)
}

/// Set (or with `None` remove) the value at `path`.
fn toml_set(v: &mut toml::Value, path: &[String], new: Option<toml::Value>) {
    let Some((last, parents)) = path.split_last() else {
        return;
    };
    let mut cur = v;
    for k in parents {
        cur = match (cur, k.strip_prefix('#')) {
            (toml::Value::Array(a), Some(i)) => {
                match i.parse::<usize>().ok().and_then(|i| a.get_mut(i)) {
                    Some(x) => x,
                    None => return,
                }
            }
            (toml::Value::Table(t), None) => match t.get_mut(k) {
                Some(x) => x,
                None => return,
            },
            _ => return,
        };
    }
    match (cur, last.strip_prefix('#')) {
        (toml::Value::Array(a), Some(i)) => {
            if let Ok(i) = i.parse::<usize>() {
                if i < a.len() {
                    match new {
                        Some(x) => a[i] = x,
                        None => {
                            a.remove(i);
                        }
                    }
                }
            }
        }
        (toml::Value::Table(t), None) => match new {
            Some(x) => {
                t.insert(last.clone(), x);
            }
            None => {
                t.remove(last);
            }
        },
        _ => {}
    }
}

/// Byte spans of the number tokens of `text`.
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let b = text.as_bytes();
    let mut out = vec![];
    let mut i = 0;
    while i < b.len() {
        let starts =
            b[i].is_ascii_digit() || (b[i] == b'-' && i + 1 < b.len() && b[i + 1].is_ascii_digit());
        let after_word = i > 0 && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_');
        if starts && !after_word {
            let a = i;
            i += 1;
            while i < b.len()
                && (b[i].is_ascii_digit() || matches!(b[i], b'.' | b'e' | b'E' | b'-' | b'+'))
            {
                i += 1;
            }
            out.push((a, i));
        } else {
            i += 1;
        }
    }
    out
}

/// Byte spans of a line's fields (split on white space and commas).
fn field_spans(line: &str) -> Vec<(usize, usize)> {
    let mut out = vec![];
    let mut start = None;
    for (i, c) in line.char_indices() {
        let sep = c.is_whitespace() || c == ',';
        match (sep, start) {
            (false, None) => start = Some(i),
            (true, Some(a)) => {
                out.push((a, i));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(a) = start {
        out.push((a, line.len()));
    }
    out
}

// ---------------------------------------------------------------------------------------
// Running.

/// The flights a case may fly: the default integrator, to 600 s, no samples kept.
fn short_options() -> SimOptions {
    SimOptions {
        keep_samples: false,
        ..SimOptions::default()
    }
}

/// Lay out `scratch` (a directory of one worker's own) as the repository is laid out around
/// the files a case is written to, `scratch/case/`: `scratch/validation` is the
/// repository's (a scenario's `../validation/designs/...` resolves there), and
/// `scratch/case/calisto` the Calisto design's tables.
pub fn prepare_scratch(scratch: &Path) -> std::io::Result<()> {
    let case = scratch.join("case");
    std::fs::create_dir_all(&case)?;
    let link = |target: PathBuf, at: PathBuf| -> std::io::Result<()> {
        if at.symlink_metadata().is_err() {
            std::os::unix::fs::symlink(target, at)?;
        }
        Ok(())
    };
    link(root().join("validation"), scratch.join("validation"))?;
    link(
        root().join("validation/designs/calisto"),
        case.join("calisto"),
    )
}

/// Run `case` through the library, catching a panic; `scratch` is a directory of this
/// worker's own laid out by [`prepare_scratch`]: the case is written there as a file and
/// read back through the library's readers, with their size limits.
pub fn run(case: &Case, scratch: &Path) -> Outcome {
    let result = std::panic::catch_unwind(AssertUnwindSafe(|| run_inner(case, scratch)));
    match result {
        Ok(o) => o,
        Err(payload) => {
            let msg = payload
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "(a panic without a message)".into());
            Outcome::Panic(msg)
        }
    }
}

/// Refused with `e`'s text, which must say something.
fn refused(e: impl std::fmt::Display) -> Outcome {
    let text = e.to_string();
    if text.trim().is_empty() {
        Outcome::Impossible("refused with an empty message".into())
    } else {
        Outcome::Refused(text)
    }
}

/// Whether to fly an accepted input too (most are: flights are where hangs hide).
fn fly_too(bytes: &[u8]) -> bool {
    // Decided by the input, so that a replayed case does the same.
    let h = bytes.iter().fold(0xcbf29ce484222325u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x100000001b3)
    });
    h % 4 != 0
}

fn run_inner(case: &Case, scratch: &Path) -> Outcome {
    let r = root();
    let file = scratch
        .join("case")
        .join(format!("fuzz-case.{}", case.target.extension()));
    if let Err(e) = std::fs::write(&file, &case.bytes) {
        return Outcome::Impossible(format!("can't write {}: {e}", file.display()));
    }
    match case.target {
        Target::Design | Target::Ork => design_case(Design::load(&file), fly_too(&case.bytes)),
        Target::Eng | Target::Rse => {
            let motors = match Motor::all_from_file(&file) {
                Ok(m) => m,
                Err(e) => return refused(e),
            };
            let mut flown = false;
            for (i, m) in motors.into_iter().enumerate() {
                if let Some(o) = motor_impossible(&m) {
                    return o;
                }
                // A command flies one motor of a file of several (`FILE#K`): the tables of
                // the first few are built, as many commands would.
                if i >= 3 {
                    continue;
                }
                if let Err(e) = MotorTables::new(&m, &MotorOptions::default()) {
                    return refused(e);
                }
                if fly_too(&case.bytes) && !flown {
                    let design =
                        match Design::load(r.join("validation/designs/example-minimal.json")) {
                            Ok(d) => d,
                            Err(e) => return Outcome::Impossible(format!("the example: {e}")),
                        };
                    match fly(design, m, Environment::default()) {
                        Some(bad @ Outcome::Impossible(_)) => return bad,
                        Some(Outcome::Accepted { flown: f }) => flown = f,
                        _ => {}
                    }
                }
            }
            Outcome::Accepted { flown }
        }
        Target::Scenario => {
            let s = match Scenario::load(&file) {
                Ok(s) => s,
                Err(e) => return refused(e),
            };
            // A few variants are flown, whatever the scenario asks for.
            let s = match s.with_overrides(None, None) {
                Ok(s) => s,
                Err(e) => return refused(e),
            };
            let p = match Prepared::new(s) {
                Ok(p) => p,
                Err(e) => return refused(e),
            };
            let total = p.plan.total();
            if !fly_too(&case.bytes) {
                return Outcome::Accepted { flown: false };
            }
            let ids: Vec<u64> = [0, total / 2, total.saturating_sub(1)]
                .into_iter()
                .filter(|&i| i < total)
                .collect();
            let variants: Vec<_> = ids.iter().map(|&i| p.plan.variant(i)).collect();
            for (v, res) in variants.iter().zip(fly_chunk(&p, &variants)) {
                for (m, x) in p.metrics.iter().zip(&res.metrics) {
                    if let Some(x) = x {
                        if !x.is_finite() {
                            return Outcome::Impossible(format!(
                                "variant {}: metric {} is {x}",
                                v.id, m.name
                            ));
                        }
                    }
                }
                if res.error.as_deref().is_some_and(|e| e.trim().is_empty()) {
                    return Outcome::Impossible(format!("variant {}: an empty error", v.id));
                }
            }
            Outcome::Accepted { flown: true }
        }
        Target::Sounding => {
            // As a scenario's `environment.sounding` and `fly --sounding` read it.
            let limit = hpr_design::limits::MAX_SOUNDING_FILE_BYTES;
            let text = match hpr_design::limits::read_text_limited(&file, limit, "a sounding") {
                Ok(t) => t,
                Err(e) => return refused(e),
            };
            let site =
                match hpr_sim::sounding::Sounding::parse(&text).and_then(|s| s.over_site(None)) {
                    Ok(s) => s,
                    Err(e) => return refused(e),
                };
            if !site.elevation_m.is_finite() || !site.air.pressure_pa.is_finite() {
                return Outcome::Impossible(format!(
                    "site at {} m, {} Pa",
                    site.elevation_m, site.air.pressure_pa
                ));
            }
            let wind = match hpr_sim::wind::Wind::table(&site.wind) {
                Ok(w) => w,
                Err(e) => return refused(e),
            };
            let air = hpr_sim::AirModel::Profile(std::sync::Arc::new(site.air));
            if let Err(e) = air.check() {
                return refused(e);
            }
            if !fly_too(&case.bytes) {
                return Outcome::Accepted { flown: false };
            }
            let env = Environment {
                elevation_m: site.elevation_m,
                wind,
                air,
                ..Environment::default()
            };
            let design = match Design::load(r.join("validation/designs/example-minimal.json")) {
                Ok(d) => d,
                Err(e) => return Outcome::Impossible(format!("the example: {e}")),
            };
            let motor = match hpr_design::motor::find("Cesaroni_I175") {
                Ok(m) => m,
                Err(e) => return Outcome::Impossible(format!("the I175: {e}")),
            };
            fly(design, motor, env).unwrap_or(Outcome::Accepted { flown: false })
        }
        Target::DragCsv | Target::AirfoilCsv => {
            let example = r.join("validation/designs/example-minimal.json");
            let mut v: Value = match std::fs::read_to_string(&example)
                .ok()
                .and_then(|t| serde_json::from_str(&t).ok())
            {
                Some(v) => v,
                None => return Outcome::Impossible("the example does not read".into()),
            };
            let name = file.display().to_string();
            if case.target == Target::DragCsv {
                v["drag"] = serde_json::json!({ "power_off_csv": name });
            } else if let Some(fins) = v.pointer_mut("/stages/0/components/1/children/0") {
                fins["airfoil"] = serde_json::json!({ "csv": name, "angles": "radians" });
            }
            design_case(
                Design::from_json_str(&v.to_string(), Some(&example)),
                fly_too(&case.bytes),
            )
        }
        Target::Weather => run_weather(&case.bytes, scratch)
            .unwrap_or(Outcome::Refused("no weather reader in this build".into())),
    }
}

/// A motor the parser accepted must be a motor: samples in order, thrust and masses sane.
fn motor_impossible(m: &Motor) -> Option<Outcome> {
    let t = m.times_s();
    let f = m.thrust_n();
    let bad = |what: String| {
        Some(Outcome::Impossible(format!(
            "motor {}: {what}",
            m.designation
        )))
    };
    if t.is_empty() || t.len() != f.len() {
        return bad(format!("{} times for {} thrusts", t.len(), f.len()));
    }
    if t.windows(2)
        .any(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
        || t.iter().any(|x| !x.is_finite())
    {
        return bad("sample times not finite and increasing".into());
    }
    if f.iter().any(|x| !(x.is_finite() && *x >= 0.0)) {
        return bad("a thrust not finite or negative".into());
    }
    let i = m.total_impulse_ns();
    if !(i.is_finite() && i > 0.0 && m.burn_time_s().is_finite() && m.burn_time_s() > 0.0) {
        return bad(format!("impulse {i} N·s over {} s", m.burn_time_s()));
    }
    let (p, total) = (m.propellant_mass_kg, m.total_mass_kg);
    if !(p.is_finite() && total.is_finite() && p >= 0.0 && total >= p) {
        return bad(format!("propellant {p} kg of {total} kg"));
    }
    None
}

/// Judge a design the validation gave: its masses, centers and surfaces, and (if `fly`) a
/// flight on its own motor (or the I175).
fn design_case(d: Result<Design, hpr_design::DesignError>, fly_it: bool) -> Outcome {
    let d = match d {
        Ok(d) => d,
        Err(e) => return refused(e),
    };
    let dry = hpr_design::mass::dry(&d);
    let bad = |what: String| Outcome::Impossible(format!("design \"{}\": {what}", d.name));
    // Zero is a mass (every part's mass lumped elsewhere: the motor flies alone).
    if !(dry.mass_kg.is_finite() && dry.mass_kg >= 0.0) {
        return bad(format!("dry mass {} kg", dry.mass_kg));
    }
    // The airframe's extent, shoulders included; parts may lie outside it (OpenRocket draws
    // them so) by at most its length, so the center of mass lies within that reach.
    let shoulder = |s: Option<hpr_design::design::Shoulder>| s.map_or(0.0, |s| s.length_m);
    let (lo, hi) = d
        .components
        .iter()
        .filter(|c| c.is_body())
        .map(|c| match &c.kind {
            hpr_design::ComponentKind::NoseCone(n) => {
                (c.x_top_m, c.x_bottom_m() + shoulder(n.shoulder))
            }
            hpr_design::ComponentKind::Transition(t) => (
                c.x_top_m - shoulder(t.fore_shoulder),
                c.x_bottom_m() + shoulder(t.aft_shoulder),
            ),
            _ => (c.x_top_m, c.x_bottom_m()),
        })
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (t, u)| {
            (a.min(t), b.max(u))
        });
    let reach = hi - lo;
    let slack = 1e-9 * hi.abs().max(1.0);
    let cg = dry.cg_m.x;
    if !(cg.is_finite() && cg >= lo - reach - slack && cg <= hi + reach + slack) {
        return bad(format!(
            "center of mass {cg} m outside the reach of its airframe ({lo} to {hi} m)"
        ));
    }
    if !(d.length_m.is_finite() && d.length_m > 0.0 && d.reference_diameter_m > 0.0) {
        return bad(format!(
            "length {} m, reference diameter {} m",
            d.length_m, d.reference_diameter_m
        ));
    }
    match hpr_design::aero::AeroModel::from_design(&d) {
        Ok(a) => {
            for s in &a.surfaces {
                if !(s.x_cp_m.is_finite() && s.x_cp_m >= -slack) {
                    return bad(format!(
                        "surface \"{}\": center of pressure {} m, ahead of the nose tip",
                        s.id, s.x_cp_m
                    ));
                }
                if !s.cn_alpha(0.0).is_finite() {
                    return bad(format!(
                        "surface \"{}\": normal-force slope not finite",
                        s.id
                    ));
                }
            }
        }
        Err(e) => return refused(e),
    }
    if !fly_it {
        return Outcome::Accepted { flown: false };
    }
    let motor_name = d.default_motor.clone().unwrap_or("Cesaroni_I175".into());
    let motor = match hpr_design::motor::find(&motor_name) {
        Ok(m) => m,
        Err(e) => return refused(e),
    };
    fly(d, motor, Environment::default()).unwrap_or(Outcome::Accepted { flown: false })
}

/// Fly `design` on `motor` off a roomy vertical rail in `env`: `None` if the set-up is
/// refused (an answer, not a fault), else the flight judged.
fn fly(design: Design, motor: Motor, env: Environment) -> Option<Outcome> {
    let rail = Rail {
        length_m: 2.0,
        ..Rail::default()
    };
    let sim = Simulation::new(design, motor, env, rail)
        .and_then(|s| s.with_options(short_options()))
        .ok()?;
    match sim.run(&mut ()) {
        Err(e) => Some(refused(e)),
        Ok(f) => {
            let m = &f.metrics;
            let figures = [
                ("max speed", Some(m.max_speed_m_s)),
                ("max Mach", Some(m.max_mach)),
                ("max acceleration", Some(m.max_accel_m_s2)),
                ("apogee", m.apogee_m),
                ("apogee time", m.apogee_time_s),
                ("landing time", m.landing_time_s),
                ("landing speed", m.landing_speed_m_s),
                ("liftoff margin", m.static_margin_liftoff_cal),
            ];
            for (what, x) in figures {
                if let Some(x) = x {
                    if !x.is_finite() {
                        return Some(Outcome::Impossible(format!("flight: {what} {x}")));
                    }
                }
            }
            if let Some(a) = m.apogee_m {
                if a < -1e-6 {
                    return Some(Outcome::Impossible(format!(
                        "flight: apogee {a} m below the pad"
                    )));
                }
            }
            if let Some([x, y]) = m.landing_position_m {
                if !(x.is_finite() && y.is_finite()) {
                    return Some(Outcome::Impossible(format!("flight: landing at {x}, {y}")));
                }
            }
            Some(Outcome::Accepted { flown: true })
        }
    }
}

/// A saved case (a file of the regression corpus or of a run's failures): its kind from
/// its name, its bytes.
pub fn saved_case(path: &Path) -> Option<Case> {
    let name = path.file_name()?.to_str()?;
    let target = Target::of_file(name)?;
    Some(Case {
        target,
        base: name.to_string(),
        mutation: "saved".into(),
        bytes: std::fs::read(path).ok()?,
    })
}
