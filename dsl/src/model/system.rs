//! The user's own system under test (language section `system_under_test`).

use serde::Serialize;

/// An external program judged on what it detects: sightline drives it over
/// ASAM OSI, step by step (docs/osi-sut.md).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SystemUnderTest {
    /// The program and its arguments, run without a shell.
    pub command: Vec<String>,
    /// The cooperating agent it serves, by index in the world's agents.
    pub agent: usize,
    /// The agent's id.
    pub agent_id: String,
    /// The agent's sensors it serves, by index on the agent, ascending.
    pub sensors: Vec<usize>,
    /// Wall-clock seconds it may take to answer one step.
    pub step_timeout: f64,
    /// Metres within which a detection matches a road user.
    pub gate: f64,
    /// Detections below this existence probability are not judged.
    pub min_existence: f64,
}

impl SystemUnderTest {
    /// The command as a user would type it, to name the system in messages.
    pub fn name(&self) -> String {
        self.command.join(" ")
    }
}
