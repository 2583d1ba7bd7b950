//! The fuzzing harness: mutated designs, OpenRocket files, motors, scenarios, soundings and
//! tables through hpr-mc's library, for as long as you like.
//!
//! ```sh
//! cargo run --release --example fuzz -- --cases 100000            # seed 1, 2 workers
//! cargo run --release --example fuzz -- --cases 1000000 --seed 7 --workers 2 --out fuzz-out
//! cargo run --release --example fuzz -- --replay tests/fuzz_corpus  # saved cases, in-process
//! ```
//!
//! Cases are made by `harness.rs` (case `k` of a seed is always the same input) and run in
//! worker processes, each a copy of this program (`--worker`), one case at a time and
//! in-process: a panic is caught and reported. Around them this process watches: a worker
//! that dies (an abort: a stack overflow, an allocation past the memory budget, a signal)
//! or stays on one case longer than the time budget (a hang; the worker is killed) is
//! reported with its case, and a new worker takes up the next case. Every failure's input
//! is saved in the output directory (`<kind>-s<seed>-k<case>.<ext>`, and a `.report` saying
//! what happened), ready for `--replay` and for the regression corpus (`tests/fuzz_corpus`,
//! which `cargo test` replays). Exit code 0: no failure; 1: some; 2: bad arguments.
//!
//! Budgets: `--timeout-s` (default 60) per case; `--memory-mb` (default 3072) of live heap
//! per worker, enforced by the allocator below (an allocation past it fails, which aborts
//! the worker: reported, not hidden).

mod harness;

use harness::{Bases, Outcome};
use std::alloc::{GlobalAlloc, Layout, System};
use std::collections::BTreeMap;
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// The system allocator with a ceiling on live bytes (`usize::MAX` until a worker sets it).
struct Budgeted;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static CEILING: AtomicUsize = AtomicUsize::new(usize::MAX);

unsafe impl GlobalAlloc for Budgeted {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let size = layout.size();
        if LIVE.fetch_add(size, Ordering::Relaxed) + size > CEILING.load(Ordering::Relaxed) {
            LIVE.fetch_sub(size, Ordering::Relaxed);
            return std::ptr::null_mut();
        }
        let p = unsafe { System.alloc(layout) };
        if p.is_null() {
            LIVE.fetch_sub(size, Ordering::Relaxed);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let old = layout.size();
        if new_size > old {
            let more = new_size - old;
            if LIVE.fetch_add(more, Ordering::Relaxed) + more > CEILING.load(Ordering::Relaxed) {
                LIVE.fetch_sub(more, Ordering::Relaxed);
                return std::ptr::null_mut();
            }
            let p = unsafe { System.realloc(ptr, layout, new_size) };
            if p.is_null() {
                LIVE.fetch_sub(more, Ordering::Relaxed);
            }
            p
        } else {
            let p = unsafe { System.realloc(ptr, layout, new_size) };
            if !p.is_null() {
                LIVE.fetch_sub(old - new_size, Ordering::Relaxed);
            }
            p
        }
    }
}

#[global_allocator]
static ALLOCATOR: Budgeted = Budgeted;

#[derive(Debug, Clone)]
struct Args {
    cases: u64,
    seed: u64,
    workers: u64,
    timeout_s: f64,
    memory_mb: usize,
    out: PathBuf,
    replay: Vec<PathBuf>,
    /// Worker mode: run cases `from, from + stride, ...` below `cases`.
    worker: bool,
    from: u64,
    stride: u64,
}

fn parse_args() -> Result<Args, String> {
    let mut a = Args {
        cases: 10_000,
        seed: 1,
        workers: 2,
        timeout_s: 60.0,
        memory_mb: 3072,
        out: PathBuf::from("fuzz-out"),
        replay: vec![],
        worker: false,
        from: 0,
        stride: 1,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = |name: &str| it.next().ok_or(format!("{name} needs a value"));
        let num = |s: String, name: &str| {
            s.replace('_', "")
                .parse::<u64>()
                .map_err(|_| format!("{name}: a whole number, got {s}"))
        };
        match flag.as_str() {
            "--cases" => a.cases = num(value("--cases")?, "--cases")?,
            "--seed" => a.seed = num(value("--seed")?, "--seed")?,
            "--workers" => a.workers = num(value("--workers")?, "--workers")?.max(1),
            "--timeout-s" => {
                a.timeout_s = value("--timeout-s")?
                    .parse()
                    .map_err(|_| "--timeout-s: a number".to_string())?
            }
            "--memory-mb" => a.memory_mb = num(value("--memory-mb")?, "--memory-mb")? as usize,
            "--out" => a.out = PathBuf::from(value("--out")?),
            "--replay" => a.replay.push(PathBuf::from(value("--replay")?)),
            "--worker" => a.worker = true,
            "--from" => a.from = num(value("--from")?, "--from")?,
            "--stride" => a.stride = num(value("--stride")?, "--stride")?.max(1),
            "--help" | "-h" => {
                return Err(
                    "usage: fuzz --cases N [--seed S] [--workers W] [--timeout-s T] \
                     [--memory-mb M] [--out DIR]   |   fuzz --replay FILE_OR_DIR"
                        .into(),
                )
            }
            other => return Err(format!("unknown argument {other} (see --help)")),
        }
    }
    Ok(a)
}

fn main() {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("fuzz: {e}");
            std::process::exit(2);
        }
    };
    let code = if args.worker {
        worker(&args)
    } else if !args.replay.is_empty() {
        replay(&args)
    } else {
        supervise(&args)
    };
    std::process::exit(code);
}

/// Where the last panic was, for its report (the hook keeps the output quiet).
static PANIC_AT: std::sync::Mutex<String> = std::sync::Mutex::new(String::new());

fn quiet_panics() {
    std::panic::set_hook(Box::new(|info| {
        if let Ok(mut at) = PANIC_AT.lock() {
            *at = info
                .location()
                .map(|l| format!("{}:{}", l.file(), l.line()))
                .unwrap_or_default();
        }
    }));
}

/// One line of text (a failure's detail on the worker's protocol).
fn one_line(s: &str) -> String {
    let s: String = s.chars().take(400).collect();
    s.replace(['\n', '\r'], " ")
}

/// Worker: run the cases, saying `s K` before case K and `d K WORD` after it (`f K WORD
/// DETAIL` for a failure).
fn worker(a: &Args) -> i32 {
    CEILING.store(a.memory_mb.saturating_mul(1 << 20), Ordering::Relaxed);
    quiet_panics();
    let bases = Bases::load();
    let scratch = a.out.join(format!("scratch-{}", a.from % a.stride));
    let scratch = match harness::prepare_scratch(&scratch).and_then(|_| scratch.canonicalize()) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("fuzz: can't lay out {}: {e}", scratch.display());
            return 2;
        }
    };
    let stdout = std::io::stdout();
    let mut k = a.from;
    while k < a.cases {
        // The runner gone (its pipe closed), the worker ends too.
        {
            let mut o = stdout.lock();
            if writeln!(o, "s {k}").and_then(|_| o.flush()).is_err() {
                return 3;
            }
        }
        let case = harness::generate(&bases, a.seed, k);
        let outcome = harness::run(&case, &scratch);
        let mut o = stdout.lock();
        let line = match &outcome {
            Outcome::Panic(m) => {
                let at = PANIC_AT.lock().map(|s| s.clone()).unwrap_or_default();
                format!("f {k} panic {} at {at}", one_line(m))
            }
            Outcome::Impossible(m) => format!("f {k} impossible {}", one_line(m)),
            other => format!("d {k} {} {}", other.word(), case.target.name()),
        };
        if writeln!(o, "{line}").and_then(|_| o.flush()).is_err() {
            return 3;
        }
        k += a.stride;
    }
    0
}

/// A failure found.
#[derive(Debug)]
struct Failure {
    case: u64,
    kind: String,
    detail: String,
}

/// One worker process and what it is doing.
struct Slot {
    child: Option<Child>,
    /// Its next case (where a new worker starts).
    next: u64,
    /// The case it is running and since when.
    current: Option<(u64, Instant)>,
    /// The case it was killed for (a hang), if it was.
    killed_for: Option<u64>,
    done: bool,
    stderr_file: PathBuf,
}

fn spawn(
    a: &Args,
    slot: usize,
    from: u64,
    stderr_file: &Path,
    tx: &mpsc::Sender<(usize, Option<String>)>,
) -> Child {
    let exe = std::env::current_exe().expect("this program's path");
    let err = std::fs::File::create(stderr_file).expect("a worker's error file");
    let mut child = Command::new(exe)
        .args([
            "--worker",
            "--cases",
            &a.cases.to_string(),
            "--seed",
            &a.seed.to_string(),
            "--from",
            &from.to_string(),
            "--stride",
            &a.workers.to_string(),
            "--memory-mb",
            &a.memory_mb.to_string(),
            "--out",
            &a.out.display().to_string(),
        ])
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(err)
        .spawn()
        .expect("a worker process");
    let out = child.stdout.take().expect("its output");
    let tx = tx.clone();
    std::thread::spawn(move || {
        for line in BufReader::new(out).lines() {
            match line {
                Ok(l) => {
                    if tx.send((slot, Some(l))).is_err() {
                        return;
                    }
                }
                Err(_) => break,
            }
        }
        let _ = tx.send((slot, None));
    });
    child
}

/// Save case `k`'s input and what happened to it.
fn save(a: &Args, bases: &Bases, f: &Failure) -> PathBuf {
    let case = harness::generate(bases, a.seed, f.case);
    let name = format!(
        "{}-s{}-k{}.{}",
        case.target.name(),
        a.seed,
        f.case,
        case.target.extension()
    );
    let path = a.out.join(&name);
    let _ = std::fs::write(&path, &case.bytes);
    let mut report = path.clone().into_os_string();
    report.push(".report");
    let _ = std::fs::write(
        PathBuf::from(report),
        format!(
            "{}: {}\nbase: {}\nmutation: {}\nreproduce: cargo run --release --example fuzz -- --replay {}\n",
            f.kind,
            f.detail,
            case.base,
            case.mutation,
            path.display()
        ),
    );
    path
}

fn tail(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(3)..].join(" | ")
}

fn supervise(a: &Args) -> i32 {
    let _ = std::fs::create_dir_all(&a.out);
    let bases = Bases::load();
    let started = Instant::now();
    println!(
        "fuzz: {} cases from seed {} on {} workers (time budget {} s a case, memory {} MiB a worker)",
        a.cases, a.seed, a.workers, a.timeout_s, a.memory_mb
    );
    let counts: Vec<String> = bases
        .counts()
        .iter()
        .map(|(t, n)| format!("{} {n}", t.name()))
        .collect();
    println!("fuzz: bundled files mutated: {}", counts.join(", "));
    let (tx, rx) = mpsc::channel::<(usize, Option<String>)>();
    let mut slots: Vec<Slot> = (0..a.workers as usize)
        .map(|w| {
            let stderr_file = a.out.join(format!("worker-{w}.stderr"));
            Slot {
                child: None,
                next: w as u64,
                current: None,
                killed_for: None,
                done: w as u64 >= a.cases,
                stderr_file,
            }
        })
        .collect();
    for (w, s) in slots.iter_mut().enumerate() {
        if !s.done {
            s.child = Some(spawn(a, w, s.next, &s.stderr_file, &tx));
        }
    }
    let mut outcomes: BTreeMap<String, u64> = BTreeMap::new();
    let mut by_target: BTreeMap<String, BTreeMap<String, u64>> = BTreeMap::new();
    let mut failures: Vec<Failure> = vec![];
    let mut finished = 0u64;
    let mut last_report = Instant::now();
    let timeout = Duration::from_secs_f64(a.timeout_s);
    while slots.iter().any(|s| !s.done) {
        match rx.recv_timeout(Duration::from_millis(500)) {
            Ok((w, Some(line))) => {
                let mut parts = line.splitn(4, ' ');
                let (tag, k) = (parts.next().unwrap_or(""), parts.next().unwrap_or(""));
                let k: u64 = k.parse().unwrap_or(u64::MAX);
                let s = &mut slots[w];
                match tag {
                    "s" => s.current = Some((k, Instant::now())),
                    "d" => {
                        let word = parts.next().unwrap_or("?").to_string();
                        let target = parts.next().unwrap_or("?").to_string();
                        *outcomes.entry(word.clone()).or_default() += 1;
                        *by_target
                            .entry(target)
                            .or_default()
                            .entry(word)
                            .or_default() += 1;
                        s.current = None;
                        s.next = k + a.workers;
                        finished += 1;
                    }
                    "f" => {
                        let kind = parts.next().unwrap_or("?").to_string();
                        let detail = parts.next().unwrap_or("").to_string();
                        *outcomes.entry(kind.clone()).or_default() += 1;
                        let f = Failure {
                            case: k,
                            kind,
                            detail,
                        };
                        let path = save(a, &bases, &f);
                        println!(
                            "fuzz: case {k}: {} {} (saved {})",
                            f.kind,
                            f.detail,
                            path.display()
                        );
                        failures.push(f);
                        s.current = None;
                        s.next = k + a.workers;
                        finished += 1;
                    }
                    _ => {}
                }
            }
            Ok((w, None)) => {
                // The worker's output ended: it finished, died, or was killed.
                let s = &mut slots[w];
                let status = s.child.take().and_then(|mut c| c.wait().ok());
                let failure = match (s.current.take(), s.killed_for) {
                    (Some((c, _)), Some(k)) if c == k => Some((
                        c,
                        "hang".to_string(),
                        format!("still running after {} s", a.timeout_s),
                    )),
                    // Killed for a case that ended meanwhile, on the next one's start: that
                    // one is run again.
                    (Some((c, _)), Some(_)) => {
                        s.next = c;
                        None
                    }
                    (Some((c, _)), None) => Some((
                        c,
                        "abort".to_string(),
                        format!(
                            "the worker ended with {:?}: {}",
                            status,
                            tail(&s.stderr_file)
                        ),
                    )),
                    (None, _) => None,
                };
                if let Some((k, kind, detail)) = failure {
                    *outcomes.entry(kind.clone()).or_default() += 1;
                    let f = Failure {
                        case: k,
                        kind,
                        detail,
                    };
                    let path = save(a, &bases, &f);
                    println!(
                        "fuzz: case {k}: {} {} (saved {})",
                        f.kind,
                        f.detail,
                        path.display()
                    );
                    failures.push(f);
                    finished += 1;
                    s.next = k + a.workers;
                }
                s.killed_for = None;
                if s.next < a.cases {
                    s.child = Some(spawn(a, w, s.next, &s.stderr_file, &tx));
                } else {
                    s.done = true;
                }
            }
            Err(mpsc::RecvTimeoutError::Timeout) => {}
            Err(mpsc::RecvTimeoutError::Disconnected) => break,
        }
        for s in &mut slots {
            if let (Some((k, since)), None) = (s.current, s.killed_for) {
                if since.elapsed() > timeout {
                    s.killed_for = Some(k);
                    if let Some(c) = s.child.as_mut() {
                        let _ = c.kill();
                    }
                }
            }
        }
        if last_report.elapsed() > Duration::from_secs(30) {
            last_report = Instant::now();
            let secs = started.elapsed().as_secs_f64();
            println!(
                "fuzz: {finished}/{} cases, {:.0} s, {:.0} cases/s, {} failures",
                a.cases,
                secs,
                finished as f64 / secs,
                failures.len()
            );
        }
    }
    let secs = started.elapsed().as_secs_f64();
    println!();
    println!(
        "fuzz: {finished} cases from seed {} in {secs:.1} s ({:.0} cases/s) on {} workers",
        a.seed,
        finished as f64 / secs,
        a.workers
    );
    let words: Vec<String> = outcomes.iter().map(|(k, n)| format!("{k} {n}")).collect();
    println!("fuzz: outcomes: {}", words.join(", "));
    for (t, m) in &by_target {
        let words: Vec<String> = m.iter().map(|(k, n)| format!("{k} {n}")).collect();
        println!("fuzz:   {t}: {}", words.join(", "));
    }
    println!(
        "fuzz: failures (panics, aborts, hangs, accepted impossibilities): {}",
        failures.len()
    );
    for f in &failures {
        println!("fuzz:   case {}: {} {}", f.case, f.kind, f.detail);
    }
    i32::from(!failures.is_empty())
}

/// Run saved cases in this process and say what each did.
fn replay(a: &Args) -> i32 {
    quiet_panics();
    let scratch = a.out.join("scratch-replay");
    let scratch = match harness::prepare_scratch(&scratch).and_then(|_| scratch.canonicalize()) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("fuzz: can't lay out {}: {e}", scratch.display());
            return 2;
        }
    };
    let mut paths = vec![];
    for p in &a.replay {
        if p.is_dir() {
            let mut inside: Vec<PathBuf> = std::fs::read_dir(p)
                .map(|d| d.flatten().map(|e| e.path()).collect())
                .unwrap_or_default();
            inside.sort();
            paths.extend(inside.into_iter().filter(|p| {
                p.is_file()
                    && p.file_name()
                        .and_then(|n| n.to_str())
                        .is_some_and(|n| !n.ends_with(".report") && !n.ends_with(".stderr"))
            }));
        } else {
            paths.push(p.clone());
        }
    }
    let mut failed = 0;
    for p in paths {
        let Some(case) = harness::saved_case(&p) else {
            println!(
                "{}: not a saved case (its name starts with its kind)",
                p.display()
            );
            continue;
        };
        let t0 = Instant::now();
        let o = harness::run(&case, &scratch);
        let ms = t0.elapsed().as_secs_f64() * 1e3;
        if o.is_failure() {
            failed += 1;
        }
        let what = match &o {
            Outcome::Refused(e) | Outcome::Panic(e) | Outcome::Impossible(e) => one_line(e),
            _ => String::new(),
        };
        println!(
            "{} ({}): {} {what} [{ms:.0} ms]",
            p.display(),
            case.target.name(),
            o.word()
        );
    }
    i32::from(failed > 0)
}
