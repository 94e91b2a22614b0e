//! A semantic world's steps in a recording: the semantic messages an RSU sends
//! and the ego receives, every V2X packet, the close approaches, and the step's
//! semantic signals (`/sightline/signals`), its counts added to the running sums.

use sightline_engine::trace::{PacketKind, SemanticStep};

use super::Recorder;
use super::channel::{APPROACH, ARRIVAL, MESSAGE, PACKET, SIGNALS};
use super::records::StepRecords;
use crate::mcap::topic;
use crate::mcap::wire::{SemanticSignals, SignalsRecord};

impl<W> Recorder<'_, W> {
    /// Everything a semantic world's step shows: the messages reaching the
    /// ego, the agents, every packet and semantic message sent, the close
    /// approaches, and the step's signals, its counts added to the running sums.
    /// In a joint world the grid's part of the step has shown the agents, and
    /// its signals join these.
    pub(super) fn publish_semantic_step(&mut self, step: &SemanticStep<'_>) {
        let time = self.at(step.time);
        self.last = time;
        // Taken for the step: the records name agents by them while the
        // recorder writes the agents too.
        let ids = std::mem::take(&mut self.ids);
        let records = StepRecords {
            ids: &ids,
            point: self.record.point,
            step: step.step,
        };
        for arrival in step.arrivals {
            let at = self.at(arrival.at);
            self.out
                .written(topic::ARRIVALS, ARRIVAL, at, |out| records.arrival(out, arrival));
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
            self.out
                .written(topic::PACKETS, PACKET, time, |out| records.packet(out, packet));
            if let PacketKind::Downlink { items, bytes } = &packet.kind {
                signals.messages += 1;
                signals.messages_received += u64::from(received);
                self.out.written(topic::MESSAGES, MESSAGE, time, |out| {
                    records.message(out, packet, items, *bytes);
                });
            }
        }
        for approach in step.approaches {
            self.out
                .written(topic::APPROACHES, APPROACH, time, |out| records.approach(out, approach));
        }
        self.ids = ids;
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
}
