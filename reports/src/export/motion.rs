//! What every agent did in one simulation: its pose at each step it was in
//! the scene, collected from the engine's step records and thinned to the
//! vertices a timed trajectory needs.

use sightline_dsl::Agent;
use sightline_engine::TraceSink;
use sightline_engine::trace::{AgentState, SemanticStep, WorldStep};

/// A thinned trajectory stays within this of the simulated one, metres.
pub(crate) const TOLERANCE: f64 = 0.01;

/// Where an agent was at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Sample {
    /// Simulation time, seconds.
    pub time: f64,
    /// Position of the footprint's centre, metres.
    pub position: [f64; 2],
    /// Heading, radians.
    pub heading: f64,
    /// Speed, m/s.
    pub speed: f64,
}

/// Every agent of a run and its samples (a [`TraceSink`]).
#[derive(Debug, Default)]
pub(crate) struct Motions {
    /// The run's agents: the scenario's, then generated traffic.
    pub agents: Vec<Agent>,
    /// Each agent's samples, in time order.
    pub samples: Vec<Vec<Sample>>,
}

impl Motions {
    /// The agents at `time`; once per time (a joint world reports each step
    /// twice, the grid's part and the pipeline's).
    fn step(&mut self, time: f64, agents: &[Option<AgentState>]) {
        for (samples, state) in self.samples.iter_mut().zip(agents) {
            if let Some(state) = state.filter(|_| samples.last().is_none_or(|last| last.time != time)) {
                samples.push(Sample {
                    time,
                    position: [state.pose.translation.x, state.pose.translation.y],
                    heading: state.heading(),
                    speed: state.speed,
                });
            }
        }
    }
}

impl TraceSink for Motions {
    fn start(&mut self, agents: &[Agent]) {
        self.agents = agents.to_vec();
        self.samples = vec![Vec::new(); agents.len()];
    }

    fn world_step(&mut self, step: &WorldStep<'_>) {
        self.step(step.time, step.agents);
    }

    fn semantic_step(&mut self, step: &SemanticStep<'_>) {
        self.step(step.time, step.agents);
    }
}

/// The samples to keep so that moving linearly in time between kept ones
/// strays at most [`TOLERANCE`] from every sample (Douglas–Peucker on time):
/// the first and the last always.
pub(crate) fn thinned(samples: &[Sample]) -> Vec<Sample> {
    let mut keep = vec![false; samples.len()];
    if let (Some(first), Some(last)) = (keep.first_mut(), samples.len().checked_sub(1)) {
        *first = true;
        keep[last] = true;
    }
    let mut spans = vec![(0, samples.len().saturating_sub(1))];
    while let Some((a, b)) = spans.pop() {
        if b <= a + 1 {
            continue;
        }
        let (sa, sb) = (samples[a], samples[b]);
        let worst = (a + 1..b)
            .map(|i| {
                let si = samples[i];
                let f = (si.time - sa.time) / (sb.time - sa.time);
                let x = sa.position[0] + f * (sb.position[0] - sa.position[0]);
                let y = sa.position[1] + f * (sb.position[1] - sa.position[1]);
                (i, (si.position[0] - x).hypot(si.position[1] - y))
            })
            .max_by(|p, q| p.1.total_cmp(&q.1));
        if let Some((i, error)) = worst
            && error > TOLERANCE
        {
            keep[i] = true;
            spans.push((a, i));
            spans.push((i, b));
        }
    }
    samples
        .iter()
        .zip(keep)
        .filter_map(|(sample, kept)| kept.then_some(*sample))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(time: f64, x: f64, y: f64) -> Sample {
        Sample {
            time,
            position: [x, y],
            heading: 0.0,
            speed: 0.0,
        }
    }

    #[test]
    fn constant_speed_on_a_line_keeps_its_ends() {
        let samples: Vec<Sample> = (0..50).map(|k| sample(k as f64 * 0.1, k as f64, 2.0)).collect();
        let kept = thinned(&samples);
        assert_eq!(kept, vec![samples[0], samples[49]]);
    }

    #[test]
    fn a_stop_is_kept() {
        // 1 m/s for 2 s, then standing for 2 s: the corner in time is a vertex.
        let samples: Vec<Sample> = (0..=40)
            .map(|k| {
                let t = k as f64 * 0.1;
                sample(t, t.min(2.0), 0.0)
            })
            .collect();
        let kept = thinned(&samples);
        assert_eq!(kept.len(), 3);
        assert_eq!(kept[1].time, samples[20].time);
    }

    #[test]
    fn one_sample_is_kept() {
        assert_eq!(thinned(&[sample(1.0, 0.0, 0.0)]).len(), 1);
        assert!(thinned(&[]).is_empty());
    }
}
