//! A roadside unit of a semantic world: its perception into its local dynamic
//! map (eq. 1), and what its pipeline and the ETSI baseline select to send.

use rand::RngExt;
use rand::rngs::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use sightline_dsl::{Agent, RsuSight, Semantic};

use super::ldm::{Ldm, Measurement};
use super::message::{EtsiSender, Item};
use super::pipeline::{EgoPlan, Pipeline};
use crate::idealisation::Idealisation;
use crate::math::Vector;
use crate::rng::{Purpose, stream};
use crate::world::{self, AgentState, Bodies, Occluders, Visibility, in_view, mount_pose, visibility};

/// Roadside units measure with white noise.
pub(crate) const RSU_MEASUREMENTS: Idealisation = Idealisation {
    id: "semantic.rsu-measurements",
    text: "A roadside unit measures each object it perceives with its sensor's detection probability and \
           independent Gaussian errors of position, speed, length and width; headings are exact and no object \
           is reported that is not there.",
};

/// Roadside units perceive through buildings.
pub(crate) const RSU_RANGE: Idealisation = Idealisation {
    id: "semantic.rsu-range",
    text: "A roadside unit perceives every object within its sensors' range, through buildings and road users \
           (`rsu_sight: range`, seed 002's circular region).",
};

/// The RSU knows the ego's plan.
pub(crate) const EGO_PLAN: Idealisation = Idealisation {
    id: "semantic.ego-plan",
    text: "A roadside unit predicts the ego along its route at the speed the ego last sent, without error.",
};

/// The idealisation of what a roadside unit perceives.
pub(crate) fn rsu_sight_idealisations(sight: RsuSight) -> &'static [Idealisation] {
    match sight {
        RsuSight::Range => &[RSU_RANGE],
        RsuSight::LineOfSight => &[world::ONE_RAY],
    }
}

/// An RSU's state across cycles.
pub(super) struct Rsu {
    /// Its agent index.
    pub(super) agent: usize,
    /// Its longest sensor range, metres.
    pub(super) range: f64,
    /// Its antenna's height, metres, when it is its own (else the channel's).
    pub(super) antenna_m: Option<f64>,
    ldm: Ldm,
    baseline: EtsiSender,
    /// The ego's plan as last received.
    pub(super) plan: Option<EgoPlan>,
    detections: ChaCha8Rng,
    /// Its radio's random stream.
    pub(super) channel: ChaCha8Rng,
    /// Its radio's random stream for the ETSI baseline's messages, kept apart
    /// so that the baseline leaves the semantic pipeline's draws as they are.
    pub(super) baseline_channel: ChaCha8Rng,
}

/// What an RSU selects to send at one cycle.
pub(super) struct Selection {
    /// Objects in its LDM now, the ego excluded.
    pub(super) perceived: usize,
    /// Of those, the objects the ETSI baseline would send, by agent index.
    pub(super) baseline: Vec<usize>,
    /// The objects its pipeline sends, with their labels: its semantic message,
    /// empty when it sends none.
    pub(super) items: Vec<Item>,
}

impl Rsu {
    /// Agent `agent` of `agents` before its first cycle, with its random streams.
    pub(super) fn new(seed: u64, agent: usize, agents: &[Agent], semantic: &Semantic) -> Self {
        Self {
            agent,
            range: agents[agent].sensors.iter().map(|s| s.range).fold(0.0, f64::max),
            antenna_m: agents[agent].antenna_m,
            ldm: Ldm::default(),
            baseline: EtsiSender::new(semantic.baseline),
            plan: None,
            detections: stream(seed, Purpose::Detections, agent as u64),
            channel: stream(seed, Purpose::Channel, agent as u64),
            baseline_channel: stream(seed, Purpose::BaselineChannel, agent as u64),
        }
    }

    /// Sense: one cycle of perception at `time`, noisy measurements into the LDM
    /// (eq. 1).
    pub(super) fn perceive(
        &mut self,
        agents: &[Agent],
        states: &[Option<AgentState>],
        occluders: &Occluders,
        bodies: &Bodies,
        semantic: &Semantic,
        time: f64,
    ) {
        let station = &agents[self.agent];
        let Some(pose) = states[self.agent].map(|s| s.pose) else {
            return;
        };
        for target in bodies.all() {
            let state = states[target.agent].expect("bodies are of present agents");
            let spec = &agents[target.agent];
            let sensor = station.sensors.iter().find(|sensor| {
                let mount = pose * mount_pose(sensor);
                match semantic.rsu_sight {
                    RsuSight::Range => (state.position() - mount.translation).length() <= sensor.range,
                    RsuSight::LineOfSight => {
                        in_view(sensor, mount, state.position()).is_some()
                            && visibility(occluders, bodies, mount.translation, self.agent, target) == Visibility::Los
                    }
                }
            });
            let Some(sensor) = sensor else { continue };
            if self.detections.random::<f64>() >= sensor.detection_probability {
                continue;
            }
            let distance = (state.position() - pose.translation).length();
            let mut noise = |base: f64, per_m: f64| {
                let sigma = base + per_m * distance;
                // σ·z for z ~ N(0, 1) is N(0, σ²), as `Normal` draws it, with
                // no error to handle: the dsl bounds base and per_m, so σ is
                // finite, and a σ it could not be would not panic here.
                if sigma > 0.0 {
                    let z: f64 = StandardNormal.sample(&mut self.detections);
                    sigma * z
                } else {
                    0.0
                }
            };
            let position = state.position()
                + Vector::new(
                    noise(sensor.noise_base, sensor.noise_per_m),
                    noise(sensor.noise_base, sensor.noise_per_m),
                );
            let measurement = Measurement {
                time,
                position,
                speed: (state.speed + noise(sensor.velocity_noise_base, sensor.velocity_noise_per_m)).max(0.0),
                heading: state.heading(),
                length: (spec.length + noise(sensor.size_noise_base, sensor.size_noise_per_m)).max(0.1),
                width: (spec.width + noise(sensor.size_noise_base, sensor.size_noise_per_m)).max(0.1),
                limit: state.limit,
            };
            self.ldm.record(target.agent, spec.kind, measurement);
        }
        self.ldm.forget(time, semantic.history);
    }

    /// How many objects (the ego excluded) the RSU's LDM holds at `time`.
    pub(super) fn perceived(&self, pipeline: &Pipeline<'_>, time: f64) -> usize {
        current(&self.ldm, pipeline, time).count()
    }

    /// Fuse: what the RSU sends at `time` with the ego's `plan`, by its
    /// `pipeline` over its LDM, and what the ETSI baseline would have sent.
    pub(super) fn select(&mut self, pipeline: &Pipeline<'_>, time: f64, plan: &EgoPlan) -> Selection {
        let perceived: Vec<(usize, &Measurement)> = current(&self.ldm, pipeline, time).collect();
        let count = perceived.len();
        let baseline = self.baseline.select(perceived);
        Selection {
            perceived: count,
            baseline,
            items: pipeline.run(&self.ldm, time, plan),
        }
    }
}

/// The objects (the ego excluded) `ldm` holds at `time`, with their latest
/// measurements: what an RSU perceives.
fn current<'l>(ldm: &'l Ldm, pipeline: &Pipeline<'_>, time: f64) -> impl Iterator<Item = (usize, &'l Measurement)> {
    let ego = pipeline.semantic.ego;
    ldm.current(time)
        .filter(move |&(agent, _)| agent != ego)
        .map(|(agent, track)| (agent, track.latest()))
}
