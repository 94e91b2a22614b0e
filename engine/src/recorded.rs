//! What a recording of a point chosen once the run is judged is checked
//! against: the recorded run simulated again alone (a pooled semantic point's
//! first run only) and what the run's outcome holds of it.

use sightline_dsl::{Experiment, Scenario};

use crate::run::{Outcome, simulate_point};
use crate::semantic;
use crate::sink::TraceSink;

/// Simulates again, alone, what a recording of point `point` records,
/// reporting each step to `sink`: the point as [`simulate_point`] simulates it,
/// or, where the point pools several runs of the semantic pipeline, its first
/// run only (the one a recording records; the others report nothing).
/// [`Outcome::holds_recorded`] says whether the point's outcome in a run holds
/// the same.
///
/// # Panics
///
/// If `point` is not an index of [`Scenario::points`].
pub fn simulate_recorded(scenario: &Scenario, point: usize, sink: &mut impl TraceSink) -> Outcome {
    let setup = &scenario.points[point].setup;
    match &setup.experiment {
        Experiment::World(w) if w.perception.is_none() => {
            let s = w
                .semantic
                .as_ref()
                .expect("a world without perception runs the semantic pipeline");
            Outcome::Semantic(semantic::first_run(setup.seed, w, s, sink))
        }
        _ => simulate_point(scenario, point, sink),
    }
}

impl Outcome {
    /// Whether `again`, what [`simulate_recorded`] gives for this outcome's
    /// point, is bit for bit what this outcome holds of the recorded run: the
    /// first run's own measurements where the point pools several runs of the
    /// semantic pipeline, the whole outcome otherwise.
    pub fn holds_recorded(&self, again: &Outcome) -> bool {
        match (self, again) {
            (Self::Semantic(pooled), Self::Semantic(first)) => pooled.first_run.as_deref().unwrap_or(pooled) == first,
            _ => self == again,
        }
    }
}
