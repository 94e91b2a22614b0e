//! A semantic world's steps in a recording: the semantic messages an RSU sends
//! and the ego receives, every V2X packet, the close approaches, and the step's
//! semantic signals (`/sightline/signals`), its counts added to the running sums.

use sightline_engine::trace::{Item, PacketKind, SemanticStep, Visibility};

use super::Recorder;
use super::channel::{APPROACH, ARRIVAL, MESSAGE, PACKET, SIGNALS};
use crate::mcap::topic;
use crate::mcap::wire::{
    ApproachRecord, ArrivalRecord, ConflictRecord, ItemRecord, MessageRecord, PacketRecord, SemanticSignals,
    SignalsRecord,
};

impl<W> Recorder<'_, W> {
    /// Everything a semantic world's step shows: the messages reaching the
    /// ego, the agents, every packet and semantic message sent, the close
    /// approaches, and the step's signals, its counts added to the running sums.
    /// In a joint world the grid's part of the step has shown the agents, and
    /// its signals join these.
    pub(super) fn publish_semantic_step(&mut self, step: &SemanticStep<'_>) {
        let time = self.at(step.time);
        self.last = time;
        for arrival in step.arrivals {
            let record = ArrivalRecord {
                point: self.record.point,
                at: arrival.at,
                items: self.items(&arrival.items),
            };
            self.publish(topic::ARRIVALS, ARRIVAL, self.at(arrival.at), &record);
        }
        if !self.joint() {
            self.publish_agents(time, step.step, step.agents);
        }
        let mut signals = SemanticSignals {
            packets: 0,
            received: 0,
            messages: 0,
            messages_received: 0,
            arrivals: step.arrivals.len() as u64,
            approaches: step.approaches.len() as u64,
            missed: step.approaches.iter().filter(|a| !a.flagged).count() as u64,
            min_time_to_conflict: step.min_time_to_conflict(),
        };
        for packet in step.packets {
            let received = packet.reception.received;
            signals.packets += 1;
            signals.received += u64::from(received);
            let (kind, bytes) = match &packet.kind {
                PacketKind::Uplink => ("uplink", None),
                PacketKind::Downlink { bytes, .. } => ("downlink", Some(*bytes as u64)),
                PacketKind::Direct => ("direct", None),
            };
            let record = PacketRecord {
                point: self.record.point,
                step: step.step,
                from: self.agent_id(packet.from),
                to: self.agent_id(packet.to),
                kind: kind.into(),
                bytes,
                distance_m: packet.link.distance_m,
                los: packet.link.los,
                rssi_dbm: Some(packet.reception.rssi_dbm).filter(|r| r.is_finite()),
                received,
            };
            self.publish(topic::PACKETS, PACKET, time, &record);
            if let PacketKind::Downlink { items, bytes } = &packet.kind {
                signals.messages += 1;
                signals.messages_received += u64::from(received);
                let record = MessageRecord {
                    point: self.record.point,
                    step: step.step,
                    from: self.agent_id(packet.from),
                    received,
                    bytes: *bytes as u64,
                    items: self.items(items),
                };
                self.publish(topic::MESSAGES, MESSAGE, time, &record);
            }
        }
        for approach in step.approaches {
            let record = ApproachRecord {
                point: self.record.point,
                step: step.step,
                agent: self.agent_id(approach.agent),
                flagged: approach.flagged,
            };
            self.publish(topic::APPROACHES, APPROACH, time, &record);
        }
        if let Some(running) = &mut self.running.semantic {
            running.messages += signals.messages;
            running.delivered += signals.messages_received;
            running.close_approaches += signals.approaches;
            running.missed_criticals += signals.missed;
        }
        let record = SignalsRecord {
            point: self.record.point,
            step: step.step,
            cells: self.pending_cells.take(),
            semantic: Some(signals),
        };
        self.publish(topic::SIGNALS, SIGNALS, time, &record);
        self.publish_requirement_signals(step.step, time);
    }

    fn items(&self, items: &[Item]) -> Vec<ItemRecord> {
        items
            .iter()
            .map(|item| ItemRecord {
                agent: self.agent_id(item.agent),
                nlos: item.labels.nlos.map(|v| {
                    match v {
                        Visibility::NlosStatic => "static",
                        Visibility::NlosDynamic => "dynamic",
                        Visibility::Los => "los",
                    }
                    .to_string()
                }),
                relevant: item.labels.relevant,
                speeding: item.labels.speeding,
                conflict: item.labels.conflict.map(|c| ConflictRecord {
                    time: c.time,
                    separation: c.separation,
                }),
            })
            .collect()
    }
}
