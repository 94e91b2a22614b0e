//! The sink that drives a system under test through a run: at each step its
//! agent cooperates, the served sensors' views go to the system, its answer
//! comes back and is judged. The first failure stops the exchange and is
//! kept, named by the step; the run then has no verdict but `error`.

use sightline_dsl::{Agent, SystemUnderTest};
use sightline_engine::TraceSink;
use sightline_engine::outcome::{SystemJudge, SystemMetrics};
use sightline_engine::trace::WorldStep;
use sightline_reports::osi::system::{check_version, detections, sensor_views};

use super::child::{Child, ChildError};

/// Where a failure happened.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum When {
    /// Before the first step: starting, the version announcement.
    Start,
    /// At a step: its index and time, seconds.
    Step(usize, f64),
    /// After the last step.
    End,
}

impl std::fmt::Display for When {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Start => write!(f, "before step 0"),
            Self::Step(step, time) => write!(f, "at step {step} (t = {} s)", Seconds(*time)),
            Self::End => write!(f, "after the last step"),
        }
    }
}

/// A time in seconds to the nanosecond, OSI's resolution, without trailing
/// zeros: `1.2`, not `1.2000000000000002`.
struct Seconds(f64);

impl std::fmt::Display for Seconds {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let fixed = format!("{:.9}", self.0);
        f.write_str(fixed.trim_end_matches('0').trim_end_matches('.'))
    }
}

/// A failure of the system under test, and when.
#[derive(Debug)]
pub struct Failure {
    /// When it happened.
    pub when: When,
    /// What happened.
    pub error: ChildError,
}

/// Drives the system and judges its answers.
pub struct Driver<'s> {
    system: &'s SystemUnderTest,
    child: Option<Child>,
    agents: Vec<Agent>,
    judge: SystemJudge,
    failure: Option<Failure>,
}

impl<'s> Driver<'s> {
    /// Starts `system`, to be judged by `judge`, and checks its protocol's version.
    pub fn start(system: &'s SystemUnderTest, judge: SystemJudge, env: &[(&str, String)]) -> Result<Self, Failure> {
        let fail = |error| Failure {
            when: When::Start,
            error,
        };
        let mut child = Child::start(&system.command, env).map_err(fail)?;
        let announced = child.receive(system.step_timeout).map_err(fail)?;
        check_version(&announced).map_err(|e| fail(e.into()))?;
        Ok(Self {
            system,
            child: Some(child),
            agents: Vec::new(),
            judge,
            failure: None,
        })
    }

    /// One step's exchange: the views out, the answer in and judged.
    fn exchange(&mut self, step: &WorldStep<'_>) -> Result<(), ChildError> {
        let Some(child) = self.child.as_mut() else {
            return Ok(());
        };
        let views = sensor_views(&self.agents, step, self.system.agent, &self.system.sensors);
        if views.is_empty() {
            return Ok(());
        }
        child.send(views);
        let answer = child.receive(self.system.step_timeout)?;
        let detected = detections(&answer, step.time, self.system.min_existence)?;
        self.judge.step(step, &detected);
        Ok(())
    }

    /// Ends the exchange: what the system achieved, or its first failure.
    /// The process is reaped either way.
    pub fn finish(mut self) -> Result<SystemMetrics, Failure> {
        if let Some(failure) = self.failure.take() {
            return Err(failure);
        }
        let child = self.child.take().expect("a child until the first failure");
        child
            .finish(self.system.step_timeout)
            .map_err(|error| Failure { when: When::End, error })?;
        Ok(self.judge.finish())
    }
}

impl TraceSink for Driver<'_> {
    fn start(&mut self, agents: &[Agent]) {
        self.agents = agents.to_vec();
        self.judge.start(agents);
    }

    fn world_step(&mut self, step: &WorldStep<'_>) {
        if self.failure.is_some() {
            return;
        }
        self.judge.observe(step);
        if let Err(error) = self.exchange(step) {
            self.failure = Some(Failure {
                when: When::Step(step.step, step.time),
                error,
            });
            // Killed and reaped now: the rest of the run is not its business.
            self.child = None;
        }
    }

    /// A failed system ends the run: nothing of it is judged.
    fn gave_up(&self) -> bool {
        self.failure.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_time_shows_to_the_nanosecond_without_trailing_zeros() {
        let shown = |time| When::Step(3, time).to_string();
        assert_eq!(shown(0.1 + 0.2), "at step 3 (t = 0.3 s)");
        assert_eq!(shown(0.0), "at step 3 (t = 0 s)");
        assert_eq!(shown(12.0), "at step 3 (t = 12 s)");
        assert_eq!(shown(1.2000000000000002), "at step 3 (t = 1.2 s)");
        assert_eq!(shown(0.000_000_001), "at step 3 (t = 0.000000001 s)");
    }
}
