//! Command-line arguments of `hpr-mc run` (being written).
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(clap::Args, Debug, Default)]
pub struct RunArgs {}

#[derive(clap::Args, Debug)]
pub struct RunCommand {
    pub scenario: PathBuf,
    #[command(flatten)]
    pub args: RunArgs,
}

pub fn run(_scenario: &Path, _args: &RunArgs) -> anyhow::Result<ExitCode> {
    anyhow::bail!("scenario runs are not built yet")
}
