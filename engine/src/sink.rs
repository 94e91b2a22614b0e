//! Where the engine sends its run record, step by step.

use sightline_dsl::Agent;

use crate::trace::{SemanticStep, WorldStep};

/// Receives a run's record as the run goes, the way ripgrep's `Searcher` reports
/// to a `Sink`: the engine emits borrowed views of each step and keeps nothing of
/// them, so a sink that wants a history keeps what it needs and memory stays
/// bounded by what it keeps.
///
/// Every method has a default that does nothing; implement the ones you need.
/// A perception world calls [`Self::world_step`], a semantic world
/// [`Self::semantic_step`], each at every step in order; a joint world (both
/// models on one scene) calls both at every step, the grid's first; the field
/// experiment has no steps and calls nothing. A sink only observes: recording never changes a
/// run's outcome.
///
/// ```
/// use sightline_engine::trace::SemanticStep;
/// use sightline_engine::{TraceSink, simulate_point};
///
/// /// Counts the semantic messages the RSUs sent.
/// #[derive(Default)]
/// struct Messages(usize);
///
/// impl TraceSink for Messages {
///     fn semantic_step(&mut self, step: &SemanticStep<'_>) {
///         self.0 += step.messages().count();
///     }
/// }
///
/// // The ego reaches the junction after a minute; one run (a pooled point
/// // records its first run only).
/// let text = include_str!("../../scenarios/urban-rsu-semantic.yaml")
///     .replace("duration: 120", "duration: 70")
///     .replace("runs: 5 ", "runs: 1 ");
/// let scenario = sightline_dsl::compile("urban.yaml", &text, &Default::default()).unwrap();
/// let mut messages = Messages::default();
/// let outcome = simulate_point(&scenario, 0, &mut messages);
/// let sightline_engine::Outcome::Semantic(metrics) = outcome else { unreachable!() };
/// assert!(messages.0 > 0);
/// assert_eq!(messages.0 as u64, metrics.messages);
/// ```
pub trait TraceSink {
    /// Called before the steps of sweep point `point` when a run reports the
    /// steps of every point ([`simulate_traced_all`](crate::simulate_traced_all)),
    /// point after point in order.
    fn point(&mut self, _point: usize) {}

    /// Called once before the first step with every agent of the run by index:
    /// the scenario's agents, then any generated traffic. Agent indices in the
    /// step records refer to this list.
    fn start(&mut self, _agents: &[Agent]) {}

    /// Whether the fused grids of `step` should be handed over in its
    /// [`WorldStep`]. Asked at each step a perception world measures (the ego in
    /// the scene), before fusing it; fusing costs the same either way, but keeping
    /// the values costs memory, so say yes only where you keep them.
    fn wants_grids(&self, _step: usize) -> bool {
        false
    }

    /// One step of a perception world.
    fn world_step(&mut self, _step: &WorldStep<'_>) {}

    /// Whether the sink has given up on the run (a system under test that
    /// failed): a perception world then stops stepping, and its outcome is
    /// partial, for a caller that discards it. Asked before each step.
    fn gave_up(&self) -> bool {
        false
    }

    /// One step of a semantic world.
    fn semantic_step(&mut self, _step: &SemanticStep<'_>) {}
}

/// The sink that records nothing: [`simulate`](crate::simulate)'s.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoTrace;

impl TraceSink for NoTrace {}
