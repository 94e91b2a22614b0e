//! The measure phase of a semantic world: each step's view of the ego, each
//! RSU's selection and each packet added to the run's metrics, each road user's
//! encounter with the ego, and every step's record handed to the trace sink.

use sightline_dsl::{Agent, LabelledBy, Semantic, World};

use super::ego::{Ego, EgoView};
use super::message::{Item, baseline_bytes};
use super::metrics::{DELIVERY_BIN, SemanticMetrics};
use super::objects::{CloseApproach, Encounters};
use super::rsu::Selection;
use crate::metrics::Series;
use crate::sink::TraceSink;
use crate::trace::{Approach, Arrival, Packet, PacketKind, SemanticLog};
use crate::world::{AgentState, Visibility};

/// What a run has measured so far.
pub(super) struct Measures {
    metrics: SemanticMetrics,
    /// Road network length, km (lane 0 of every road), for traffic density.
    network_km: f64,
    /// Per step with the ego: objects it knew only through an RSU.
    rsu_only: Series,
    /// Per RSU cycle whose message flags a conflict: the shortest time to it.
    time_to_conflict: Series,
    /// Each road user's encounter with the ego, for the per-object records.
    encounters: Encounters,
    /// Each close approach: the road user's agent index, the step's time and
    /// when a conflict with it was first flagged to the ego.
    approaches: Vec<(usize, f64, Option<f64>)>,
    /// The current step's record.
    log: SemanticLog,
    /// Which labels the labelled share counts.
    labelled_by: LabelledBy,
}

impl Measures {
    /// Nothing measured yet in `world` run with `semantic`, whose scene has
    /// `agents` agents.
    pub(super) fn new(world: &World, semantic: &Semantic, agents: usize) -> Self {
        Self {
            metrics: SemanticMetrics {
                runs: 1,
                generated: (agents - world.agents.len()) as u64,
                ..Default::default()
            },
            network_km: world.roads.iter().map(|r| r.lanes[0].length()).sum::<f64>() / 1000.0,
            rsu_only: Vec::new(),
            time_to_conflict: Vec::new(),
            encounters: Encounters::new(world, semantic, agents),
            approaches: Vec::new(),
            log: SemanticLog::default(),
            labelled_by: semantic.labelled_by,
        }
    }

    /// The messages that reached the ego this step.
    pub(super) fn arrivals(&mut self, arrivals: Vec<Arrival>) {
        self.log.arrivals.extend(arrivals);
    }

    /// A step `dt` long at `time` with the ego in the scene at `ego`, cautious
    /// or not, perceiving `view` of the agents in `states`; `counted`: the step
    /// counts toward the infrastructure contribution.
    pub(super) fn ego_step(
        &mut self,
        (time, dt): (f64, f64),
        ego: AgentState,
        states: &[Option<AgentState>],
        (cautious, counted): (bool, bool),
        view: EgoView,
    ) {
        self.encounters.step(time, ego, states);
        let metrics = &mut self.metrics;
        metrics.steps += 1;
        metrics.duration += dt;
        if cautious {
            metrics.cautious_time += dt;
        }
        for (agent, flagged) in view.approaches {
            metrics.close_approaches += 1;
            metrics.missed_criticals += u64::from(flagged.is_none());
            self.approaches.push((agent, time, flagged));
            self.log.approaches.push(Approach {
                agent,
                flagged: flagged.is_some(),
            });
        }
        if counted {
            let density = (self.network_km > 0.0).then(|| f64::from(view.present) / self.network_km);
            metrics.contribution.push((density, view.through_rsu));
        }
        self.rsu_only.push((time, f64::from(view.through_rsu)));
    }

    /// A counted cycle in which an RSU perceived `count` objects and sent the
    /// ego none of them (no plan received yet, or the ego out of the scene).
    pub(super) fn unsent(&mut self, count: usize) {
        self.metrics.perceived += count as u64;
    }

    /// What an RSU selected at `time`; `shared`: the cycle counts toward the
    /// transmitted and labelled shares.
    pub(super) fn selection(&mut self, time: f64, selection: &Selection, shared: bool) {
        let metrics = &mut self.metrics;
        if shared {
            metrics.perceived += selection.perceived as u64;
        }
        if !selection.baseline.is_empty() {
            metrics.baseline_objects += selection.baseline.len() as u64;
            metrics.baseline_bytes += baseline_bytes(selection.baseline.len()) as u64;
        }
        if shared {
            count_labels(metrics, &selection.items, self.labelled_by);
        }
        let soonest = selection
            .items
            .iter()
            .filter_map(|item| item.labels.conflict)
            .map(|conflict| conflict.time)
            .reduce(f64::min);
        if let Some(soonest) = soonest {
            self.time_to_conflict.push((time, soonest));
        }
    }

    /// A packet sent; a semantic message counts by size and by distance.
    pub(super) fn packet(&mut self, packet: Packet) {
        if let PacketKind::Downlink { bytes, .. } = packet.kind {
            let metrics = &mut self.metrics;
            metrics.bytes += bytes as u64;
            metrics.messages += 1;
            let bin = (packet.link.distance_m / DELIVERY_BIN) as usize;
            if metrics.delivery_by_distance.len() <= bin {
                metrics.delivery_by_distance.resize(bin + 1, Default::default());
            }
            metrics.delivery_by_distance[bin].sent += 1;
            if packet.reception.received {
                metrics.delivered += 1;
                metrics.delivery_by_distance[bin].received += 1;
            }
        }
        self.log.packets.push(packet);
    }

    /// Reports step `step` at `time` to `sink`, and starts the next one.
    pub(super) fn record(&mut self, step: usize, time: f64, states: &[Option<AgentState>], sink: &mut impl TraceSink) {
        sink.semantic_step(&self.log.step(step, time, states));
        self.log.clear();
    }

    /// The run's metrics, with what the `ego` came to know of the `agents` over
    /// it, its road users' records and close approaches labelled with pooled
    /// run `run`: one per
    /// fused grid of `in_grid` (per agent, when it first came into the grid),
    /// each record holding its time in that grid, or one without any grid
    /// when `in_grid` is empty.
    pub(super) fn finish(
        self,
        ego: &Ego,
        agents: &[Agent],
        run: u32,
        in_grid: &[Vec<Option<f64>>],
    ) -> Vec<SemanticMetrics> {
        let mut metrics = self.metrics;
        for known in ego.knowledge() {
            if let Some((received, false)) = known.first_received {
                match known.first_seen {
                    Some(seen) => metrics.anticipation.push(seen - received),
                    None => metrics.never_seen += 1,
                }
            }
            if let (Some((received, false)), Some(seen)) = (known.baseline_received, known.first_seen) {
                metrics.baseline_anticipation.push(seen - received);
            }
        }
        metrics.anticipation.sort_by(f64::total_cmp);
        metrics.baseline_anticipation.sort_by(f64::total_cmp);
        metrics.rsu_only = vec![self.rsu_only];
        metrics.time_to_conflict = vec![self.time_to_conflict];
        metrics.approaches = (self.approaches.iter())
            .map(|&(agent, at, flagged)| CloseApproach {
                run,
                id: agents[agent].id.clone(),
                at,
                flagged,
            })
            .collect();
        let records = |grid: Option<&[Option<f64>]>| self.encounters.records(run, agents, ego.knowledge(), grid);
        if in_grid.is_empty() {
            metrics.objects = records(None);
            return vec![metrics];
        }
        in_grid
            .iter()
            .map(|grid| SemanticMetrics {
                objects: records(Some(grid)),
                ..metrics.clone()
            })
            .collect()
    }
}

fn count_labels(metrics: &mut SemanticMetrics, items: &[Item], by: LabelledBy) {
    metrics.transmitted += items.len() as u64;
    for item in items {
        let labels = &item.labels;
        metrics.labelled += u64::from(labels.labelled(by));
        metrics.labels.nlos_static += u64::from(labels.nlos == Some(Visibility::NlosStatic));
        metrics.labels.nlos_dynamic += u64::from(labels.nlos == Some(Visibility::NlosDynamic));
        metrics.labels.relevant += u64::from(labels.relevant);
        metrics.labels.speeding += u64::from(labels.speeding);
        metrics.labels.conflict += u64::from(labels.conflict.is_some());
    }
}
