//! The one place where results.json meets the other crates: a compiled
//! scenario, its run and its verdicts mapped to the wire types. The engine's,
//! the language's and the oracles' types are destructured field by field, so a
//! field added there is a compile error here until the evidence decides what to
//! do with it.
//!
//! - `document`: [`Results::new`](super::Results::new), the sweeps and the
//!   top-level metrics;
//! - `requirement`: a verdict and the check it judged;
//! - `point`: a point's outcome and the engine's counts behind it;
//! - `objects`: a semantic point's per-object records.

mod document;
mod objects;
mod point;

pub(crate) use objects::object_result;
mod requirement;
mod system;
