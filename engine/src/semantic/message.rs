//! What goes on the channel: the semantic message, its size, and the ETSI
//! collective perception baseline it is compared with.
//!
//! Sizes are ours, of the order of a UPER-encoded Collective Perception Message
//! (ETSI TS 103 324): a header (ITS PDU header, management container with the
//! sender's reference position) of `HEADER_BYTES`, and per object a perceived
//! object container (id, time, position, velocity, acceleration, heading,
//! dimensions, class, with confidences) of `OBJECT_BYTES`. A semantic message
//! adds `LABEL_BYTES` per object: the flags, the time to conflict and the
//! predicted separation. Messages are sized, not encoded.

use std::collections::BTreeMap;

use sightline_dsl::{Baseline, LabelledBy};

use super::ldm::Measurement;
use super::risk::Conflict;
use crate::idealisation::Idealisation;
use crate::world::Visibility;

/// Messages are sized, not encoded.
pub(crate) const SIZED: Idealisation = Idealisation {
    id: "message.sized",
    text: "Messages are sized, not encoded: their size counts toward the bytes sent but does not change their \
           delivery.",
};

/// Bytes of a message's header.
pub const HEADER_BYTES: usize = 40;
/// Bytes per perceived object.
pub const OBJECT_BYTES: usize = 35;
/// Bytes of a semantic message's labels per object.
pub const LABEL_BYTES: usize = 4;

/// The semantic labels of one object (seed 002, section III).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Labels {
    /// Occluded from the ego, and by what; `None`: in line of sight.
    pub nlos: Option<Visibility>,
    /// Interaction relevance.
    pub relevant: bool,
    /// A dangerous driver (speed violation).
    pub speeding: bool,
    /// A predicted conflict with the ego's plan.
    pub conflict: Option<Conflict>,
}

impl Labels {
    /// Whether any label is set, the NLoS flag included.
    pub fn any(&self) -> bool {
        self.nlos.is_some() || self.critical()
    }

    /// Whether a critical label is set: relevance, speeding or a predicted conflict.
    pub fn critical(&self) -> bool {
        self.relevant || self.speeding || self.conflict.is_some()
    }

    /// Whether the object counts as labelled when `by` decides.
    pub fn labelled(&self, by: LabelledBy) -> bool {
        match by {
            LabelledBy::Any => self.any(),
            LabelledBy::Critical => self.critical(),
        }
    }
}

/// One object of a semantic message.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Item {
    /// The object's agent index.
    pub agent: usize,
    /// Its labels.
    pub labels: Labels,
}

/// The size of a semantic message with `objects` objects.
pub fn semantic_bytes(objects: usize) -> usize {
    HEADER_BYTES + objects * (OBJECT_BYTES + LABEL_BYTES)
}

/// The size of a collective perception message with `objects` objects.
pub fn baseline_bytes(objects: usize) -> usize {
    HEADER_BYTES + objects * OBJECT_BYTES
}

/// An ETSI collective perception sender: it includes an object when it moved more
/// than `distance`, changed speed by more than `speed` or heading by more than
/// `heading` since it was last included, or was last included `interval` ago.
#[derive(Debug, Clone)]
pub struct EtsiSender {
    rules: Baseline,
    last: BTreeMap<usize, Measurement>,
}

impl EtsiSender {
    /// A sender that has sent nothing yet.
    pub fn new(rules: Baseline) -> Self {
        Self {
            rules,
            last: BTreeMap::new(),
        }
    }

    /// Decides which of the `perceived` objects (agent index, latest
    /// measurement) go into this message; returns their agent indices.
    pub fn select<'a>(&mut self, perceived: impl IntoIterator<Item = (usize, &'a Measurement)>) -> Vec<usize> {
        let mut included = Vec::new();
        for (agent, now) in perceived {
            let due = self.last.get(&agent).is_none_or(|last| {
                let turn = now.heading - last.heading;
                (now.position - last.position).length() > self.rules.distance
                    || (now.speed - last.speed).abs() > self.rules.speed
                    || turn.sin().atan2(turn.cos()).abs() > self.rules.heading
                    || now.time - last.time >= self.rules.interval - 1e-9
            });
            if due {
                self.last.insert(agent, *now);
                included.push(agent);
            }
        }
        included
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vector;

    fn at(time: f64, x: f64, speed: f64, heading_deg: f64) -> Measurement {
        Measurement {
            time,
            position: Vector::new(x, 0.0),
            speed,
            heading: heading_deg.to_radians(),
            length: 4.5,
            width: 1.8,
            limit: 14.0,
        }
    }

    /// ETSI TS 103 324 inclusion: new objects always; then 4 m, 0.5 m/s, 4° or 1 s.
    #[test]
    fn the_baseline_includes_objects_by_the_etsi_rules() {
        let mut sender = EtsiSender::new(Baseline {
            distance: 4.0,
            speed: 0.5,
            heading: 4f64.to_radians(),
            interval: 1.0,
        });
        assert_eq!(sender.select([(1, &at(0.0, 0.0, 10.0, 0.0))]), [1]);
        assert_eq!(
            sender.select([(1, &at(0.1, 3.9, 10.0, 0.0))]),
            [0usize; 0],
            "moved 3.9 m"
        );
        assert_eq!(sender.select([(1, &at(0.2, 4.1, 10.0, 0.0))]), [1], "moved 4.1 m");
        assert_eq!(sender.select([(1, &at(0.3, 4.2, 10.6, 0.0))]), [1], "0.6 m/s faster");
        assert_eq!(sender.select([(1, &at(0.4, 4.3, 10.6, 4.5))]), [1], "turned 4.5°");
        assert_eq!(
            sender.select([(1, &at(1.3, 4.4, 10.6, 4.5))]),
            [0usize; 0],
            "0.9 s later"
        );
        assert_eq!(sender.select([(1, &at(1.4, 4.4, 10.6, 4.5))]), [1], "1 s later");
    }

    #[test]
    fn sizes_grow_by_object() {
        assert_eq!(semantic_bytes(0), HEADER_BYTES);
        assert_eq!(semantic_bytes(2) - baseline_bytes(2), 2 * LABEL_BYTES);
    }
}
