//! Scenario campaigns (being written).
pub mod cli;
