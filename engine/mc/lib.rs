//! `hpr_mc`: the application around the physics. It owns the command line ([`cli`]), the
//! scenario files, variants and their seeded sampling, the campaign run loop, statistics and
//! the Parquet output ([`campaign`]). The physics is `hpr_design` and `hpr_sim`.

pub mod campaign;
pub mod chart;
pub mod cli;
pub mod flight_plot;
pub mod report;
