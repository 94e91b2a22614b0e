//! A semantic world's per-step records (`/v2x/packets`, `/semantic/messages`,
//! `/semantic/arrivals`, `/semantic/approaches`) written straight into JSON,
//! as `/tf` is ([`agents`](super::agents)): each agent's id is quoted once per
//! recorded point, and a record is written from the engine's step without
//! building its owned [`wire`](crate::mcap::wire) type first. The bytes are
//! the ones serde_json gives those types (a test compares them).

use serde::Serialize;
use sightline_engine::trace::{Approach, Arrival, Item, Packet, PacketKind, Visibility};

/// Each agent's id as a JSON string, by agent index.
#[derive(Default)]
pub(super) struct Ids(Vec<String>);

impl Ids {
    /// The agents' ids, quoted and escaped.
    pub(super) fn new<'a>(ids: impl IntoIterator<Item = &'a str>) -> Self {
        Self(
            ids.into_iter()
                .map(|id| serde_json::to_string(id).expect("a string encodes"))
                .collect(),
        )
    }

    /// Appends agent `index`'s id (`agent<index>` for an index with no agent).
    fn write(&self, out: &mut Vec<u8>, index: usize) {
        match self.0.get(index) {
            Some(id) => out.extend_from_slice(id.as_bytes()),
            None => value(out, &format!("agent{index}")),
        }
    }
}

/// Appends `value` as serde_json writes it.
fn value(out: &mut Vec<u8>, value: &(impl Serialize + ?Sized)) {
    // A number or a string written into a Vec does not fail.
    let _ = serde_json::to_writer(out, value);
}

/// The records of step `step` of point `point`, their agents named by `ids`.
pub(super) struct StepRecords<'a> {
    pub(super) ids: &'a Ids,
    pub(super) point: usize,
    pub(super) step: usize,
}

impl StepRecords<'_> {
    /// Writes `packet` as a [`PacketRecord`](crate::mcap::wire::PacketRecord)
    /// onto `out`.
    pub(super) fn packet(&self, out: &mut Vec<u8>, packet: &Packet) {
        let (kind, bytes): (&[u8], _) = match &packet.kind {
            PacketKind::Uplink => (b"uplink", None),
            PacketKind::Downlink { bytes, .. } => (b"downlink", Some(*bytes as u64)),
            PacketKind::Direct => (b"direct", None),
        };
        self.head(out);
        out.extend_from_slice(br#","from":"#);
        self.ids.write(out, packet.from);
        out.extend_from_slice(br#","to":"#);
        self.ids.write(out, packet.to);
        out.extend_from_slice(br#","kind":""#);
        out.extend_from_slice(kind);
        out.push(b'"');
        if let Some(bytes) = bytes {
            out.extend_from_slice(br#","bytes":"#);
            value(out, &bytes);
        }
        out.extend_from_slice(br#","distance_m":"#);
        value(out, &packet.link.distance_m);
        out.extend_from_slice(br#","los":"#);
        value(out, &packet.link.los);
        if packet.reception.rssi_dbm.is_finite() {
            out.extend_from_slice(br#","rssi_dbm":"#);
            value(out, &packet.reception.rssi_dbm);
        }
        out.extend_from_slice(br#","received":"#);
        value(out, &packet.reception.received);
        out.push(b'}');
    }

    /// Appends the semantic message `packet` carries (`items`, `bytes` long)
    /// as a [`MessageRecord`](crate::mcap::wire::MessageRecord) to `out`.
    pub(super) fn message(&self, out: &mut Vec<u8>, packet: &Packet, items: &[Item], bytes: usize) {
        self.head(out);
        out.extend_from_slice(br#","from":"#);
        self.ids.write(out, packet.from);
        out.extend_from_slice(br#","received":"#);
        value(out, &packet.reception.received);
        out.extend_from_slice(br#","bytes":"#);
        value(out, &(bytes as u64));
        write_items(out, self.ids, items);
        out.push(b'}');
    }

    /// Appends `approach` as an
    /// [`ApproachRecord`](crate::mcap::wire::ApproachRecord) to `out`.
    pub(super) fn approach(&self, out: &mut Vec<u8>, approach: &Approach) {
        self.head(out);
        out.extend_from_slice(br#","agent":"#);
        self.ids.write(out, approach.agent);
        out.extend_from_slice(br#","flagged":"#);
        value(out, &approach.flagged);
        out.push(b'}');
    }

    /// Writes `arrival` as an [`ArrivalRecord`](crate::mcap::wire::ArrivalRecord)
    /// onto `out`.
    pub(super) fn arrival(&self, out: &mut Vec<u8>, arrival: &Arrival) {
        out.extend_from_slice(br#"{"point":"#);
        value(out, &self.point);
        out.extend_from_slice(br#","at":"#);
        value(out, &arrival.at);
        write_items(out, self.ids, &arrival.items);
        out.push(b'}');
    }

    /// Opens a record with its point and step.
    fn head(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(br#"{"point":"#);
        value(out, &self.point);
        out.extend_from_slice(br#","step":"#);
        value(out, &self.step);
    }
}

/// Appends `,"items":[…]`: each of `items` as an
/// [`ItemRecord`](crate::mcap::wire::ItemRecord).
fn write_items(out: &mut Vec<u8>, ids: &Ids, items: &[Item]) {
    out.extend_from_slice(br#","items":["#);
    for (i, item) in items.iter().enumerate() {
        if i > 0 {
            out.push(b',');
        }
        let labels = &item.labels;
        out.extend_from_slice(br#"{"agent":"#);
        ids.write(out, item.agent);
        if let Some(nlos) = labels.nlos {
            out.extend_from_slice(match nlos {
                Visibility::NlosStatic => br#","nlos":"static""#,
                Visibility::NlosDynamic => br#","nlos":"dynamic""#,
                Visibility::Los => br#","nlos":"los""#.as_slice(),
            });
        }
        out.extend_from_slice(br#","relevant":"#);
        value(out, &labels.relevant);
        out.extend_from_slice(br#","speeding":"#);
        value(out, &labels.speeding);
        if let Some(conflict) = labels.conflict {
            out.extend_from_slice(br#","conflict":{"time":"#);
            value(out, &conflict.time);
            out.extend_from_slice(br#","separation":"#);
            value(out, &conflict.separation);
            out.push(b'}');
        }
        out.push(b'}');
    }
    out.push(b']');
}

#[cfg(test)]
mod tests {
    use sightline_engine::trace::{Conflict, Labels, Link, Reception};

    use super::*;
    use crate::mcap::wire::{ApproachRecord, ArrivalRecord, ConflictRecord, ItemRecord, MessageRecord, PacketRecord};

    /// The agents' ids: plain, and ones JSON must escape.
    fn ids() -> (Vec<String>, Ids) {
        let names: Vec<String> = ["ego", "rsu \"north\"", "ped\\1", "bus\u{7}é"].map(String::from).into();
        let ids = Ids::new(names.iter().map(String::as_str));
        (names, ids)
    }

    /// The id the records name agent `index` by (`agent<index>` without one).
    fn name(names: &[String], index: usize) -> String {
        names.get(index).cloned().unwrap_or_else(|| format!("agent{index}"))
    }

    /// Items with every label set and unset, odd numbers, an unknown agent.
    fn items(k: usize) -> Vec<Item> {
        let visibility = [
            None,
            Some(Visibility::NlosStatic),
            Some(Visibility::NlosDynamic),
            Some(Visibility::Los),
        ];
        (0..k)
            .map(|i| Item {
                agent: i * 3 % 6,
                labels: Labels {
                    nlos: visibility[i % 4],
                    relevant: i % 2 == 0,
                    speeding: i % 3 == 0,
                    conflict: (i % 5 != 1).then(|| Conflict {
                        time: 0.1 * i as f64 + 1e-9,
                        separation: 7.0 / (i as f64 + 3.0),
                    }),
                },
            })
            .collect()
    }

    fn item_records(names: &[String], items: &[Item]) -> Vec<ItemRecord> {
        items
            .iter()
            .map(|item| ItemRecord {
                agent: name(names, item.agent),
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

    /// What `write` appends after an earlier message.
    fn written(write: impl FnOnce(&mut Vec<u8>)) -> String {
        let earlier = br#"{"earlier":true}"#;
        let mut out = earlier.to_vec();
        write(&mut out);
        assert_eq!(&out[..earlier.len()], earlier);
        String::from_utf8(out[earlier.len()..].to_vec()).unwrap()
    }

    /// Every record, written directly, is byte for byte what serde_json gives
    /// its wire type: each packet kind, RSSI finite or not, items with and
    /// without labels, ids that need escaping and an index with no agent.
    #[test]
    fn written_json_is_serde_jsons() {
        let (names, ids) = ids();
        for k in 0..9 {
            let records = StepRecords {
                ids: &ids,
                point: k % 3,
                step: 1_000 * k + 7,
            };
            let kind = match k % 3 {
                0 => PacketKind::Uplink,
                1 => PacketKind::Downlink {
                    items: items(k),
                    bytes: 121 * k,
                },
                _ => PacketKind::Direct,
            };
            let packet = Packet {
                from: k % 5,
                to: (k + 2) % 5,
                kind,
                link: Link {
                    distance_m: 12.5 * k as f64 + 0.1,
                    los: k % 2 == 0,
                    tx_antenna_m: 1.5,
                    rx_antenna_m: 5.0,
                },
                reception: Reception {
                    rssi_dbm: [f64::NEG_INFINITY, -87.123_456_789, f64::NAN][k % 3],
                    received: k % 4 != 0,
                },
            };
            let (kind, bytes) = match &packet.kind {
                PacketKind::Uplink => ("uplink", None),
                PacketKind::Downlink { bytes, .. } => ("downlink", Some(*bytes as u64)),
                PacketKind::Direct => ("direct", None),
            };
            let expected = PacketRecord {
                point: records.point,
                step: records.step,
                from: name(&names, packet.from),
                to: name(&names, packet.to),
                kind: kind.into(),
                bytes,
                distance_m: packet.link.distance_m,
                los: packet.link.los,
                rssi_dbm: Some(packet.reception.rssi_dbm).filter(|r| r.is_finite()),
                received: packet.reception.received,
            };
            let json = written(|out| records.packet(out, &packet));
            assert_eq!(json, serde_json::to_string(&expected).unwrap(), "packet {k}");
            if let PacketKind::Downlink { items, bytes } = &packet.kind {
                let expected = MessageRecord {
                    point: records.point,
                    step: records.step,
                    from: name(&names, packet.from),
                    received: packet.reception.received,
                    bytes: *bytes as u64,
                    items: item_records(&names, items),
                };
                let json = written(|out| records.message(out, &packet, items, *bytes));
                assert_eq!(json, serde_json::to_string(&expected).unwrap(), "message {k}");
            }
            let arrival = Arrival {
                at: 0.05 * k as f64 + 1.0 / 3.0,
                items: items(k),
            };
            let expected = ArrivalRecord {
                point: records.point,
                at: arrival.at,
                items: item_records(&names, &arrival.items),
            };
            let json = written(|out| records.arrival(out, &arrival));
            assert_eq!(json, serde_json::to_string(&expected).unwrap(), "arrival {k}");
            let approach = Approach {
                agent: k % 6,
                flagged: k % 2 == 1,
            };
            let expected = ApproachRecord {
                point: records.point,
                step: records.step,
                agent: name(&names, approach.agent),
                flagged: approach.flagged,
            };
            let json = written(|out| records.approach(out, &approach));
            assert_eq!(json, serde_json::to_string(&expected).unwrap(), "approach {k}");
        }
    }
}
