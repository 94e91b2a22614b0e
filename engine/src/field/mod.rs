//! The static field experiment of seed 001: a ground-truth occupancy field, fixed
//! sensors reporting a mass vector for every cell in range, fusion, decision.

mod experiment;
mod layout;
mod sensor;
mod truth;

pub use experiment::{Sampling, run};

pub(crate) use experiment::IDEALISATIONS;
pub(crate) use sensor::error_model_idealisations;
