//! The V2X links of a semantic world, over the TR 36.885 channel: the ego's plan
//! up to each RSU, an RSU's semantic message down to the ego, the ETSI
//! collective perception message it would have sent instead (the baseline the
//! semantic pipeline is compared with), connected road users' own messages to
//! the ego, and the messages on their way.

use rand::rngs::ChaCha8Rng;
use sightline_dsl::{Agent, AgentKind, V2x};

use super::ego::Ego;
use super::message::{Item, semantic_bytes};
use super::pipeline::EgoPlan;
use super::rsu::Rsu;
use crate::idealisation::Idealisation;
use crate::rng::{Purpose, stream};
use crate::trace::{Arrival, Packet, PacketKind};
use crate::v2x::{InFlight, Link, arrival, transmit};
use crate::world::{AgentState, Occluders};

/// The baseline's messages reach an ego that drove as the semantic ones made it.
pub(crate) const BASELINE_REPLAY: Idealisation = Idealisation {
    id: "semantic.baseline-replay",
    text: "The ETSI baseline's messages are evaluated on the semantic run's traffic and ego trajectory, with \
           their own loss draws: the ego drives as the semantic messages' warnings made it, where an ego served \
           by the baseline alone, never warned, might have driven otherwise.",
};

/// Direct messages carry exact states.
pub(crate) const DIRECT_STATES: Idealisation = Idealisation {
    id: "semantic.direct-states",
    text: "A connected road user's message carries its exact state.",
};

/// The radio of a semantic run: the channel, the random streams of the ego's
/// and the connected road users' transmissions, and the semantic messages on
/// their way to the ego. (Each RSU draws its own transmissions.)
pub(super) struct Radio<'a> {
    v2x: &'a V2x,
    /// The ego's agent index.
    ego: usize,
    /// The ego's uplinks.
    ego_channel: ChaCha8Rng,
    /// Connected road users' direct messages.
    cam_channel: ChaCha8Rng,
    in_flight: InFlight<Vec<Item>>,
    /// The baseline's messages on their way: the agents each names.
    baseline_in_flight: InFlight<Vec<usize>>,
}

impl<'a> Radio<'a> {
    /// Nothing sent yet, for ego `ego` in a scene of `agents` agents.
    pub(super) fn new(seed: u64, v2x: &'a V2x, ego: usize, agents: usize) -> Self {
        Self {
            v2x,
            ego,
            ego_channel: stream(seed, Purpose::Channel, ego as u64),
            cam_channel: stream(seed, Purpose::Channel, agents as u64),
            in_flight: InFlight::default(),
            baseline_in_flight: InFlight::default(),
        }
    }

    /// Communicate: the semantic messages that reached the ego by `time`, in
    /// order of arrival.
    pub(super) fn arrivals(&mut self, time: f64) -> Vec<Arrival> {
        self.in_flight
            .arrived(time)
            .into_iter()
            .map(|(at, items)| Arrival { at, items })
            .collect()
    }

    /// The baseline's messages that reached the ego by `time`, in order of
    /// arrival: when each arrived and the agents it names.
    pub(super) fn baseline_arrivals(&mut self, time: f64) -> Vec<(f64, Vec<usize>)> {
        self.baseline_in_flight.arrived(time)
    }

    /// Communicate: the ego at `ego` sends its state and plan at `time` to `rsu`
    /// at `station`, which keeps the plan when it receives it.
    pub(super) fn uplink(
        &mut self,
        rsu: &mut Rsu,
        station: AgentState,
        ego: AgentState,
        occluders: &Occluders,
        time: f64,
    ) -> Packet {
        let channel = &self.v2x.channel;
        let uplink = Link {
            distance_m: (ego.position() - station.position()).length(),
            los: !occluders.block(station.position(), ego.position()),
            tx_antenna_m: channel.vehicle_antenna_m,
            rx_antenna_m: rsu.antenna_m.unwrap_or(channel.rsu_antenna_m),
        };
        let reception = transmit(channel, &uplink, &mut self.ego_channel);
        if reception.received {
            rsu.plan = Some(EgoPlan {
                time,
                offset: ego.offset,
                speed: ego.speed,
            });
        }
        Packet {
            from: self.ego,
            to: rsu.agent,
            kind: PacketKind::Uplink,
            link: uplink,
            reception,
        }
    }

    /// Communicate: `rsu` sends the ego a semantic message naming `items` at
    /// `time`, over the `uplink` link the other way; a received message is on its
    /// way to the ego.
    pub(super) fn downlink(&mut self, rsu: &mut Rsu, uplink: &Link, items: Vec<Item>, time: f64) -> Packet {
        let channel = &self.v2x.channel;
        let downlink = Self::reversed(uplink);
        let bytes = semantic_bytes(items.len());
        let reception = transmit(channel, &downlink, &mut rsu.channel);
        let packet = Packet {
            from: rsu.agent,
            to: self.ego,
            kind: PacketKind::Downlink {
                items: items.clone(),
                bytes,
            },
            link: downlink,
            reception,
        };
        if reception.received {
            let at = arrival(time, self.v2x.latency, downlink.distance_m);
            self.in_flight.send(at, items);
        }
        packet
    }

    /// The ETSI baseline: `rsu` sends the ego a collective perception message
    /// naming the `objects` its inclusion rules chose at `time`, over the
    /// `uplink` link the other way, with the baseline's own loss draws; a
    /// received message is on its way to the ego. Nothing else sees it.
    pub(super) fn baseline_downlink(&mut self, rsu: &mut Rsu, uplink: &Link, objects: Vec<usize>, time: f64) {
        let downlink = Self::reversed(uplink);
        if transmit(&self.v2x.channel, &downlink, &mut rsu.baseline_channel).received {
            let at = arrival(time, self.v2x.latency, downlink.distance_m);
            self.baseline_in_flight.send(at, objects);
        }
    }

    /// An RSU's link to the ego: `uplink` the other way.
    fn reversed(uplink: &Link) -> Link {
        Link {
            tx_antenna_m: uplink.rx_antenna_m,
            rx_antenna_m: uplink.tx_antenna_m,
            ..*uplink
        }
    }

    /// Communicate: every connected road user in the scene sends the ego at
    /// `ego_state` its own state at `time`; the ego hears those received.
    pub(super) fn direct(
        &mut self,
        agents: &[Agent],
        states: &[Option<AgentState>],
        ego_state: AgentState,
        occluders: &Occluders,
        time: f64,
        ego: &mut Ego,
    ) -> Vec<Packet> {
        let channel = &self.v2x.channel;
        let mut packets = Vec::new();
        for (i, state) in states.iter().enumerate() {
            let Some(state) = state else { continue };
            if i == self.ego || !agents[i].connected || agents[i].kind == AgentKind::Rsu {
                continue;
            }
            let distance = (state.position() - ego_state.position()).length();
            let link = Link {
                distance_m: distance,
                los: !occluders.block(state.position(), ego_state.position()),
                tx_antenna_m: channel.vehicle_antenna_m,
                rx_antenna_m: channel.vehicle_antenna_m,
            };
            let reception = transmit(channel, &link, &mut self.cam_channel);
            packets.push(Packet {
                from: i,
                to: self.ego,
                kind: PacketKind::Direct,
                link,
                reception,
            });
            if reception.received {
                ego.hear(i, arrival(time, self.v2x.latency, distance));
            }
        }
        packets
    }
}
