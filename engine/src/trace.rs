//! The run record: what happened at each step, as borrowed views the engine hands
//! to a [`TraceSink`](crate::TraceSink).
//!
//! This is the engine's event vocabulary: the MCAP writer and the temporal oracles
//! read it, and the engine does not know them. A view lives for one call; the
//! engine keeps nothing of a step once the next begins, so a sink that wants a
//! history copies what it needs.
//!
//! - A perception world (seed 000) reports a [`WorldStep`] per step: every
//!   agent's state, each cooperating agent's estimated pose and observation (its
//!   own grid, sensor positions and [`Sighting`]s: targets
//!   in view, their visibility class, visible fraction and where it placed
//!   those it detected), and,
//!   at steps with the ego, each fusion job's cell tallies of the step. Fused
//!   grids (probability and uncertainty of every observed cell) are handed over
//!   only at the steps the sink asks for with
//!   [`TraceSink::wants_grids`](crate::TraceSink::wants_grids): the roundabout's
//!   grid has 360 000 cells.
//! - A semantic world (seed 002) reports a [`SemanticStep`] per step: every
//!   agent's state, the packets sent (uplink plans, downlink semantic messages
//!   with their labelled items, direct status messages) delivered or dropped, the
//!   messages that reached the ego, and the objects that came within d_min of the
//!   ego with whether a conflict with them had been flagged to it.
//! - A joint world (both on one scene) reports both at every step, the
//!   [`WorldStep`] first.
//! - The field experiment (seed 001) has no steps and reports nothing.
//!
//! Summed over a run, the step records give the run's metrics: a world's cell
//! tallies, observed cells and sightings over the measured steps are its
//! [`WorldMetrics`](crate::outcome::WorldMetrics) counts; a semantic world's
//! downlink packets, deliveries and close approaches are its
//! [`SemanticMetrics`](crate::outcome::SemanticMetrics) counts.

pub use crate::math::{Point, Pose, Vector};
pub use crate::semantic::{Conflict, Item, Labels};
pub use crate::v2x::{Link, Reception};
pub use crate::world::{AgentState, Body, Observation, Observed, Outline, Sighting, Visibility, mount_pose};

use crate::world::CellTally;

/// One step of a perception world.
#[derive(Debug, Clone, Copy)]
pub struct WorldStep<'a> {
    /// The step; step k is at time k · dt.
    pub step: usize,
    /// Its time, seconds.
    pub time: f64,
    /// Every agent's true state by agent index; `None`: not in the scene.
    pub agents: &'a [Option<AgentState>],
    /// The cooperating agents in the scene, in cooperation order (the ego first).
    pub cooperators: &'a [CooperatorStep<'a>],
    /// What the step measured; `None` when the ego is not in the scene: such steps
    /// count in no metric.
    pub measured: Option<Measured<'a>>,
}

/// One cooperating agent at one step.
#[derive(Debug, Clone, Copy)]
pub struct CooperatorStep<'a> {
    /// Its agent index.
    pub agent: usize,
    /// The pose it believes it has and placed its grid with (a roadside unit's
    /// is its true pose).
    pub estimate: Pose,
    /// What it observed: its grid, its sensors' estimated positions, and every
    /// target in view with its visibility class and detection.
    pub observation: &'a Observation,
}

/// What a perception world measured at one step.
#[derive(Debug, Clone, Copy)]
pub struct Measured<'a> {
    /// Counted cells a sensor of the ego observed.
    pub ego_observed: u64,
    /// Counted cells a sensor of any cooperating agent observed (the cells
    /// fused, less those only a self-reported footprint covers).
    pub joint_observed: u64,
    /// One entry per fusion job, in job order.
    pub fused: &'a [FusedStep<'a>],
}

/// One fusion job at one step.
#[derive(Debug, Clone, Copy)]
pub struct FusedStep<'a> {
    /// The step's cell tallies of the fused grid against the truth.
    pub cells: CellTally,
    /// The fused grid, when the sink asked for this step's grids.
    pub grid: Option<FusedGrid<'a>>,
}

/// A fused grid over the cells observed at one step (cells nobody observed have
/// no estimate). The three slices have one entry per observed cell, in the same
/// order.
#[derive(Debug, Clone, Copy)]
pub struct FusedGrid<'a> {
    /// Indices of the observed cells in the grid (row-major from the origin).
    pub cells: &'a [usize],
    /// Fused occupancy probability (pignistic for evidential methods).
    pub probability: &'a [f32],
    /// Fused uncertainty: the Unknown mass, or a Bayesian cell's entropy.
    pub uncertainty: &'a [f32],
}

/// One step of a semantic world.
#[derive(Debug, Clone, Copy)]
pub struct SemanticStep<'a> {
    /// The step; step k is at time k · dt.
    pub step: usize,
    /// Its time, seconds.
    pub time: f64,
    /// Every agent's true state by agent index; `None`: not in the scene.
    pub agents: &'a [Option<AgentState>],
    /// Packets sent this step, in order of sending.
    pub packets: &'a [Packet],
    /// Semantic messages that reached the ego since the previous step, in order
    /// of arrival.
    pub arrivals: &'a [Arrival],
    /// Objects that came within d_min of the ego this step.
    pub approaches: &'a [Approach],
}

impl SemanticStep<'_> {
    /// The semantic messages the RSUs sent this step, with their packets.
    pub fn messages(&self) -> impl Iterator<Item = (&Packet, &[Item])> {
        self.packets.iter().filter_map(|packet| match &packet.kind {
            PacketKind::Downlink { items, .. } => Some((packet, items.as_slice())),
            PacketKind::Uplink | PacketKind::Direct => None,
        })
    }

    /// The shortest time to conflict the RSUs predicted this step (over every
    /// message sent, delivered or not), seconds from now; `None` when no message
    /// flags a conflict.
    pub fn min_time_to_conflict(&self) -> Option<f64> {
        self.messages()
            .flat_map(|(_, items)| items)
            .filter_map(|item| item.labels.conflict)
            .map(|conflict| conflict.time)
            .reduce(f64::min)
    }
}

/// One V2X packet.
#[derive(Debug, Clone, PartialEq)]
pub struct Packet {
    /// The sending agent.
    pub from: usize,
    /// The receiving agent.
    pub to: usize,
    /// What it carries.
    pub kind: PacketKind,
    /// The radio link.
    pub link: Link,
    /// How it arrived: its RSSI and whether it was received.
    pub reception: Reception,
}

/// What a packet carries, and so which link it took.
#[derive(Debug, Clone, PartialEq)]
pub enum PacketKind {
    /// Uplink: the ego's state and plan, to an RSU.
    Uplink,
    /// Downlink: an RSU's semantic message, to the ego.
    Downlink {
        /// The objects it names, with their labels.
        items: Vec<Item>,
        /// Its size on the channel, bytes.
        bytes: usize,
    },
    /// Direct: a connected road user's own state, to the ego.
    Direct,
}

/// A semantic message reaching the ego.
#[derive(Debug, Clone, PartialEq)]
pub struct Arrival {
    /// When it arrived, seconds (after the previous step, at or before this one).
    pub at: f64,
    /// The objects it names, with their labels.
    pub items: Vec<Item>,
}

/// An object coming within d_min of the ego (once per approach).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Approach {
    /// Its agent index.
    pub agent: usize,
    /// Whether a conflict with it had reached the ego before: `false` is a missed
    /// critical.
    pub flagged: bool,
}

/// The owned parts of a semantic step, collected during the step and cleared
/// after it is reported.
#[derive(Debug, Default)]
pub(crate) struct SemanticLog {
    pub(crate) packets: Vec<Packet>,
    pub(crate) arrivals: Vec<Arrival>,
    pub(crate) approaches: Vec<Approach>,
}

impl SemanticLog {
    /// The step's view.
    pub(crate) fn step<'a>(&'a self, step: usize, time: f64, agents: &'a [Option<AgentState>]) -> SemanticStep<'a> {
        SemanticStep {
            step,
            time,
            agents,
            packets: &self.packets,
            arrivals: &self.arrivals,
            approaches: &self.approaches,
        }
    }

    /// Empties the log for the next step.
    pub(crate) fn clear(&mut self) {
        self.packets.clear();
        self.arrivals.clear();
        self.approaches.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::semantic::{Conflict, Labels};
    use crate::v2x::Link;

    fn message(conflicts: &[Option<f64>]) -> Packet {
        let items = conflicts
            .iter()
            .enumerate()
            .map(|(agent, &time)| Item {
                agent,
                labels: Labels {
                    conflict: time.map(|time| Conflict { time, separation: 1.0 }),
                    ..Labels::default()
                },
            })
            .collect();
        Packet {
            from: 9,
            to: 0,
            kind: PacketKind::Downlink { items, bytes: 0 },
            link: Link {
                distance_m: 10.0,
                los: true,
                tx_antenna_m: 5.0,
                rx_antenna_m: 1.5,
            },
            reception: Reception {
                rssi_dbm: -60.0,
                received: false,
            },
        }
    }

    /// Over every message sent, dropped ones included; uplinks carry none.
    #[test]
    fn the_minimum_time_to_conflict_is_over_every_message_sent() {
        let uplink = Packet {
            kind: PacketKind::Uplink,
            ..message(&[])
        };
        let mut log = SemanticLog {
            packets: vec![uplink, message(&[None, Some(2.5)]), message(&[Some(1.5), None])],
            ..SemanticLog::default()
        };
        assert_eq!(log.step(0, 0.0, &[]).messages().count(), 2);
        assert_eq!(log.step(0, 0.0, &[]).min_time_to_conflict(), Some(1.5));
        log.packets.truncate(1);
        assert_eq!(log.step(0, 0.0, &[]).min_time_to_conflict(), None);
    }
}
