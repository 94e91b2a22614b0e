//! A model that runs on a perception world's scene, step by step, beside
//! collective perception: the semantic pipeline of a joint world. The world's
//! loop moves the scene once and hands every step to its [`StepLayer`], which
//! sees what the grid sees (the agents' states and bodies), may restrain how
//! they drive from the next step on, learns which road users each fusion
//! job's grid decided occupied, and reports its own record to the sink after
//! the grid's.
//!
//! A perception world alone runs with `()`, the layer that does nothing.

use super::motion::Kinematics;
use super::sight::Bodies;
use super::state::AgentState;
use crate::sink::TraceSink;

/// Work another model does at each step of a world's loop, on the same scene.
pub(crate) trait StepLayer {
    /// Step `k`, every agent moved (`states`, their footprints `bodies`):
    /// the layer's sense, communicate and fuse phases; a restraint it puts on
    /// an agent through `kinematics` applies from the next step on.
    fn step(&mut self, k: usize, states: &[Option<AgentState>], bodies: &Bodies, kinematics: &mut Kinematics<'_>);

    /// Whether it reads [`Self::in_grid`]: collecting the road users a grid
    /// decides occupied costs a little, so the fuse phase does it only then.
    fn reads_grid(&self) -> bool;

    /// At `time`, fusion job `job`'s grid decided occupied at least one
    /// counted cell of each road user in `owners` (agent indices, in chunk
    /// order, repeated once per cell).
    fn in_grid(&mut self, job: usize, time: f64, owners: &[usize]);

    /// Step `k`'s record to `sink`, after the grid's.
    fn record(&mut self, k: usize, states: &[Option<AgentState>], sink: &mut impl TraceSink);
}

/// No other model: a perception world alone.
impl StepLayer for () {
    fn step(&mut self, _: usize, _: &[Option<AgentState>], _: &Bodies, _: &mut Kinematics<'_>) {}

    fn reads_grid(&self) -> bool {
        false
    }

    fn in_grid(&mut self, _: usize, _: f64, _: &[usize]) {}

    fn record(&mut self, _: usize, _: &[Option<AgentState>], _: &mut impl TraceSink) {}
}
