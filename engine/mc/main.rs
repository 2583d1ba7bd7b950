//! `hpr-mc`: the command line. Parsing only; the work is in the `hpr_mc` library.

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser, Debug)]
#[command(
    name = "hpr-mc",
    version,
    about = "Monte Carlo 6-DOF flights of high-power rockets, with moving mass",
    args_conflicts_with_subcommands = true,
    after_help = hpr_mc::campaign::cli::EXIT_CODES
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// A scenario file (same as `hpr-mc run SCENARIO.toml`).
    scenario: Option<PathBuf>,
    #[command(flatten)]
    run: hpr_mc::cli::RunArgs,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Mass, center of mass, inertia, center of pressure and static margin of a design.
    Inspect(hpr_mc::cli::InspectArgs),
    /// Fly one flight and print its metrics and events.
    #[command(allow_negative_numbers = true)]
    Fly(Box<hpr_mc::cli::FlyArgs>),
    /// Run a scenario (sweeps × dispersions) and write Parquet.
    Run(hpr_mc::cli::RunCommand),
    /// Read an OpenRocket design (.ork) into hpr's design format (JSON).
    Import(hpr_mc::cli::ImportArgs),
    /// Draw a run's report (report.html) and landing maps again from its Parquet files.
    Report(hpr_mc::cli::ReportArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Some(Command::Inspect(a)) => hpr_mc::cli::inspect(&a),
        Some(Command::Fly(a)) => hpr_mc::cli::fly(&a),
        Some(Command::Run(a)) => hpr_mc::cli::run(&a.scenario, &a.args),
        Some(Command::Import(a)) => hpr_mc::cli::import(&a),
        Some(Command::Report(a)) => hpr_mc::cli::report(&a),
        None => match cli.scenario {
            Some(s) => hpr_mc::cli::run(&s, &cli.run),
            None => {
                eprintln!("hpr-mc: give a scenario file (hpr-mc SCENARIO.toml) or a command (inspect, fly, run, import, report); see hpr-mc --help");
                return ExitCode::from(2);
            }
        },
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("hpr-mc: {e:#}");
            ExitCode::from(2)
        }
    }
}
