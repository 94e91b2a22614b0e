//! sightline's oracles: every requirement of a scenario checked against the
//! measurements of a run, with the measured value, the threshold and the signed
//! margin by which it holds or fails.
//!
//! This crate owns the judgement, not the measuring (that is `sightline-engine`)
//! nor the evidence files (that is `sightline-reports`). It never prints.
//!
//! A requirement is checked at every sweep point it applies to; its verdict is
//! the worst of those evaluations (an error outranks a failure, a failure a
//! not-exercised evaluation, that a pass), and its reported value is the
//! deciding one: the worst status, then the smallest margin. A check with
//! nothing to judge (an empty population, fewer samples than its minimum, a
//! window the run does not cover) is [`Status::NotExercised`], never a pass;
//! every evaluation carries its sample size n and says what its value is. The oracles read
//! a run only through [`Measurements`], so `sightline replay` judges a
//! recording's values with the same code. [`out_of_domain`] finds the values
//! that no run can give (a share above 1, a NaN), which `merge` and `replay`
//! refuse before judging.
//!
//! [`falsify()`] searches a scenario's `vary` space for a case that breaks a
//! requirement and shrinks it; the caller compiles, simulates and checks each
//! case.
#![warn(missing_docs)]

pub use check::seeds::{SeedStatistics, clopper_pearson_lower, mean_bound, wilson_lower};
pub use domain::{OutOfDomain, Quantity, out_of_domain};
pub use falsify::{Case, Judged, Outcome, Phase, Score, Search, falsify};
pub use known::known_answers;
pub use measurements::Measurements;
pub use verdict::{Evaluation, Status, Verdict, check, headline};

mod check;
mod domain;
mod falsify;
mod known;
mod measurements;
mod verdict;
