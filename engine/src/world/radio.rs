//! The radio of a collective-perception world that declares `v2x`: each
//! cooperating agent other than the ego sends its grid to the ego in messages
//! ([`super::message`]) over the TR 36.885 channel of the semantic pipeline
//! ([`crate::v2x`]), and the ego fuses what arrived, as it ages
//! ([`super::received`]).
//!
//! At every step the ego is in the scene:
//! 1. **send**: a sender in the scene whose generation is due (at a fixed
//!    `rate_hz` from its first step there; at most once a step, as it senses
//!    once a step) encodes the grid it sensed this step and sends each message
//!    on its own: a link from its true position to the ego's, in line of sight
//!    unless an occluder blocks it, from a roadside unit's mast or a vehicle's
//!    antenna to the ego's, one shadowing draw per message from the sender's
//!    channel stream;
//! 2. **receive**: the messages that arrived by now (after `v2x.latency` and
//!    propagation) enter the ego's copy of their sender's grid; a message is
//!    fused from the first step at or after its arrival, so that even an
//!    instant link delivers a step late;
//! 3. **age**: evidence older than `max_age` is dropped, the rest weighed.
//!
//! The ego's copy is kept with the sender's *estimated* pose at sensing time:
//! the grid is sent as the sender placed it, in the world frame.

use rand::rngs::ChaCha8Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use sightline_dsl::{Agent, AgentKind, Grid, Messages, V2x};

use super::evidence::Evidence;
use super::message::{Message, Run, header_bytes, pack, runs};
use super::observe::Observation;
use super::received::{Held, outlived};
use super::sight::Occluders;
use super::state::AgentState;
use crate::idealisation::Idealisation;
use crate::math::Point;
use crate::rng::{Purpose, stream};
use crate::trace::CooperatorStep;
use crate::v2x::{InFlight, Link, arrival, transmit};

/// The grid's encoding is ours.
pub(crate) const GRID_MESSAGES: Idealisation = Idealisation {
    id: "radio.grid-messages",
    text: "A cooperating agent sends its occupancy grid as runs of cells in sightline's own encoding, with a \
           CPM's header sizes (ETSI TR 103 562): ETSI TS 103 324 carries objects and perception regions, not \
           grids.",
};

/// Senders generate at a fixed rate.
pub(crate) const FIXED_RATE: Idealisation = Idealisation {
    id: "radio.fixed-rate",
    text: "Each cooperating agent generates messages at the fixed `v2x.messages.rate_hz`, whatever changed: \
           TS 103 324's generation and object-inclusion rules and its redundancy mitigation are not modelled.",
};

/// Messages are fused at the steps.
pub(crate) const STEP_DELIVERY: Idealisation = Idealisation {
    id: "radio.step-delivery",
    text: "A message is fused from the first step at or after its arrival, placed as its sender placed it when \
           sensing: over a 0.1 s step even an instant link delivers a step late, and nothing predicts where the \
           objects it shows have moved since.",
};

/// Messages from each sender, and how they are doing.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct RadioStats {
    /// The time between steps, seconds.
    pub step: f64,
    /// Messages the cooperating agents sent the ego.
    pub sent: u64,
    /// Of them, received (their power reached the ego's sensitivity).
    pub received: u64,
    /// Bytes of the messages sent.
    pub bytes: u64,
    /// Steps cooperating agents other than the ego were in the scene with it.
    pub sender_steps: u64,
    /// Received messages the ego fused, by age in steps (from sensing to the
    /// first step that fuses them): entry a counts the messages a steps old.
    pub ages: Vec<u64>,
}

impl RadioStats {
    /// Messages the ego fused.
    pub fn fused(&self) -> u64 {
        self.ages.iter().sum()
    }

    /// The mean age of the fused messages, seconds (mean steps × step, so that
    /// equal ages give exactly their value); `None` when none was fused.
    pub fn mean_age(&self) -> Option<f64> {
        let fused = self.fused();
        let steps: u64 = self.ages.iter().enumerate().map(|(a, &count)| a as u64 * count).sum();
        (fused > 0).then(|| steps as f64 / fused as f64 * self.step)
    }

    /// The ages of the fused messages, seconds, ascending.
    pub fn sorted_ages(&self) -> Vec<f64> {
        self.ages
            .iter()
            .enumerate()
            .flat_map(|(a, &count)| std::iter::repeat_n(a as f64 * self.step, count as usize))
            .collect()
    }
}

/// One cooperating agent other than the ego, as a sender, and the ego's copy of
/// its grid.
struct Sender {
    agent: usize,
    channel: ChaCha8Rng,
    /// When its next generation is due; `None` before its first.
    due: Option<f64>,
    /// Its generations so far.
    serial: u32,
    held: Held,
}

/// A received message on its way to the ego.
struct Parcel {
    /// The sender's index among [`Radio::senders`].
    sender: usize,
    serial: u32,
    sensed: f64,
    sensors: Vec<Point>,
    runs: Vec<Run>,
}

/// The radio between the cooperating agents and the ego.
pub(super) struct Radio<'a> {
    v2x: &'a V2x,
    messages: &'a Messages,
    grid: &'a Grid,
    step: f64,
    ego: usize,
    senders: Vec<Sender>,
    in_flight: InFlight<Parcel>,
    stats: RadioStats,
}

impl<'a> Radio<'a> {
    /// Nothing sent yet between `cooperating` (the ego first) in a world
    /// stepping every `step` seconds.
    pub(super) fn new(
        seed: u64,
        (v2x, messages): (&'a V2x, &'a Messages),
        grid: &'a Grid,
        step: f64,
        cooperating: &[usize],
    ) -> Self {
        Self {
            v2x,
            messages,
            grid,
            step,
            ego: cooperating[0],
            senders: cooperating[1..]
                .iter()
                .map(|&agent| Sender {
                    agent,
                    channel: stream(seed, Purpose::Channel, agent as u64),
                    due: None,
                    serial: 0,
                    held: Held::new(grid.cells(), messages),
                })
                .collect(),
            in_flight: InFlight::default(),
            stats: RadioStats {
                step,
                ..RadioStats::default()
            },
        }
    }

    /// Generate at `time`, the ego in the scene (its `states`): the senders in
    /// the scene whose generation is due (at a fixed `rate_hz` from their
    /// first step there, at most once a step), in cooperation order, by agent
    /// index. Each will send the grid it senses this step.
    pub(super) fn generate(&mut self, time: f64, states: &[Option<AgentState>]) -> Vec<usize> {
        let mut due = Vec::new();
        for sender in self.senders.iter_mut().filter(|s| states[s.agent].is_some()) {
            self.stats.sender_steps += 1;
            if sender.due.is_some_and(|due| time + 1e-9 < due) {
                continue;
            }
            // The next generation is due a period after this one was, not after
            // this step: a rate that is not a whole number of steps keeps its mean.
            let period = 1.0 / self.messages.rate_hz;
            let mut next = sender.due.unwrap_or(time) + period;
            while next <= time + 1e-9 {
                next += period;
            }
            sender.due = Some(next);
            sender.serial += 1;
            due.push(sender.agent);
        }
        due
    }

    /// The messages a sender at `position` sends of the grid it sensed,
    /// `observation`. Encoding draws nothing: senders encode in parallel, each
    /// as it senses.
    pub(super) fn encode(&self, observation: &Observation, position: Point) -> Vec<Message> {
        let sensor = observation.sensor_positions.first().copied().unwrap_or(position);
        pack(
            &runs(observation, self.grid),
            self.grid,
            header_bytes(observation.sensor_positions.len()),
            self.messages.max_bytes,
            self.messages.oversize,
            sensor,
        )
    }

    /// Communicate at `time`, the ego in the scene: the senders whose
    /// generation is due send the messages they encoded (`sent`, in
    /// cooperation order, with what each sensed); what arrived by `time` is
    /// taken in, and what is held ages.
    pub(super) fn communicate(
        &mut self,
        time: f64,
        sent: Vec<(&CooperatorStep<'_>, Vec<Message>)>,
        (agents, states): (&[Agent], &[Option<AgentState>]),
        occluders: &Occluders,
    ) {
        let ego = states[self.ego]
            .expect("the radio runs while the ego is in the scene")
            .position();
        let messages = self.messages;
        let channel = &self.v2x.channel;
        // The messages go out in cooperation order, each sender drawing from
        // its own stream.
        for (c, packed) in sent {
            let index = self
                .senders
                .iter()
                .position(|s| s.agent == c.agent)
                .expect("a cooperator sends");
            let position = states[c.agent].expect("a sensing agent is in the scene").position();
            let sender = &mut self.senders[index];
            let link = Link {
                distance_m: (ego - position).length(),
                los: !occluders.block(position, ego),
                tx_antenna_m: agents[c.agent]
                    .antenna_m
                    .unwrap_or(if agents[c.agent].kind == AgentKind::Rsu {
                        channel.rsu_antenna_m
                    } else {
                        channel.vehicle_antenna_m
                    }),
                rx_antenna_m: channel.vehicle_antenna_m,
            };
            for message in packed {
                self.stats.sent += 1;
                self.stats.bytes += u64::from(message.bytes);
                if transmit(channel, &link, &mut sender.channel).received {
                    self.stats.received += 1;
                    self.in_flight.send(
                        arrival(time, self.v2x.latency, link.distance_m),
                        Parcel {
                            sender: index,
                            serial: sender.serial,
                            sensed: time,
                            sensors: c.observation.sensor_positions.clone(),
                            runs: message.runs,
                        },
                    );
                }
            }
        }
        // Each sender's copy takes in its own parcels, in order of arrival, and
        // ages apart from the others': the senders run in parallel.
        let mut arrived: Vec<Vec<Parcel>> = self.senders.iter().map(|_| Vec::new()).collect();
        for (_, parcel) in self.in_flight.arrived(time) {
            // A message past `max_age` on arrival is dropped at once: never fused, so
            // its age is not among the fused messages'.
            let age = time - parcel.sensed;
            if !outlived(age, messages) {
                let age = (age / self.step).round() as usize;
                if self.stats.ages.len() <= age {
                    self.stats.ages.resize(age + 1, 0);
                }
                self.stats.ages[age] += 1;
            }
            arrived[parcel.sender].push(parcel);
        }
        self.senders.par_iter_mut().zip(arrived).for_each(|(sender, parcels)| {
            for parcel in parcels {
                sender
                    .held
                    .receive(parcel.serial, parcel.sensed, &parcel.sensors, &parcel.runs);
            }
            sender.held.age(time, messages);
        });
    }

    /// The ego's copies of the senders' grids that hold evidence, in
    /// cooperation order.
    pub(super) fn received(&self) -> impl Iterator<Item = &dyn Evidence> {
        self.senders
            .iter()
            .filter(|s| !s.held.touched().is_empty())
            .map(|s| &s.held as &dyn Evidence)
    }

    /// The cooperating agents whose evidence the ego holds: they report their
    /// own footprints to it.
    pub(super) fn reporting(&self) -> impl Iterator<Item = usize> + '_ {
        self.senders.iter().filter(|s| s.held.is_live()).map(|s| s.agent)
    }

    /// What went over the radio.
    pub(super) fn finish(self) -> RadioStats {
        self.stats
    }
}
