//! Collective perception: the ego, the agents that cooperate with it, the
//! inverse sensor model, the pictured step, the region the metrics count, and
//! the messages that carry the grids over the radio.

use crate::compile::checks::{coordinates, known_names};
use crate::compile::context::Context;
use crate::error::ErrorKind;
use crate::model::{
    Agent, MESSAGE_HEADER_BYTES, Messages, Perception, SENSOR_INFORMATION_BYTES, SMALLEST_PAYLOAD_BYTES,
};
use crate::path::Path;
use crate::raw::range;
use crate::raw::{RawMessages, RawPerception, RawV2x};

pub(super) fn perception_of(
    ctx: &mut Context<'_>,
    raw: &RawPerception,
    (v2x, joint): (Option<&RawV2x>, bool),
    agents: &[Agent],
    step: f64,
    steps: usize,
) -> Option<Perception> {
    let path = Path::root().key("perception");
    let Some(ego) = agents.iter().position(|a| a.id == raw.ego) else {
        let known: Vec<&str> = agents.iter().map(|a| a.id.as_str()).collect();
        ctx.error(
            &path.key("ego"),
            ErrorKind::DanglingReference(format!("no agent `{}` ({})", raw.ego, known_names(&raw.ego, &known))),
        );
        return None;
    };
    if agents[ego].sensors.is_empty() {
        ctx.error(
            &path.key("ego"),
            ErrorKind::Invalid(format!("the ego `{}` has no sensors", raw.ego)),
        );
        return None;
    }
    let others = agents
        .iter()
        .enumerate()
        .filter(|&(i, a)| i != ego && a.connected && !a.sensors.is_empty())
        .map(|(i, _)| i);
    let available = 1 + others.clone().count();
    // Checked before who cooperates, so that every error is reported: the
    // header must fit any agent that may send.
    let most_sensors = others.clone().map(|a| agents[a].sensors.len()).max().unwrap_or(0);
    let messages = match v2x {
        None => Some(None),
        Some(v2x) => messages(
            ctx,
            v2x.messages.as_ref().unwrap_or(&RawMessages::default()),
            most_sensors,
            step,
        )
        .map(Some),
    };
    // In a joint world `penetration` is refused as ambiguous (`joint`).
    let penetration = v2x.and_then(|v| v.penetration).filter(|_| !joint);
    if let (Some(_), Some(_)) = (penetration, raw.cooperating) {
        ctx.error(
            &Path::root().key("v2x").key("penetration"),
            ErrorKind::Invalid(
                "`perception.cooperating` already says how many agents cooperate: give one of the two".into(),
            ),
        );
        return None;
    }
    // A share out of range is reported where `v2x` is compiled.
    if penetration.is_some_and(|share| !range::PROBABILITY.contains(share)) {
        return None;
    }
    let count = match (raw.cooperating, penetration) {
        (Some(count), _) => count as usize,
        (None, Some(share)) => 1 + (share * (available - 1) as f64).round() as usize,
        (None, None) => available,
    };
    if !(1..=available).contains(&count) {
        ctx.error(
            &path.key("cooperating"),
            ErrorKind::OutOfRange {
                expected: format!(
                    "from 1 to {available} (the ego and {} connected agents with sensors)",
                    available - 1
                ),
                found: count.to_string(),
            },
        );
        return None;
    }
    if count > 1 && !agents[ego].connected {
        ctx.error(
            &path.key("ego"),
            ErrorKind::Invalid(format!(
                "the ego `{}` receives the grids of {} cooperating agents, so it must be `connected: true`",
                raw.ego,
                count - 1
            )),
        );
        return None;
    }
    let model = &raw.inverse_model;
    let model_path = path.key("inverse_model");
    let ok = ctx.expect(
        range::OCCUPIED.contains(model.occupied),
        &model_path.key("occupied"),
        "a probability above 0.5 and below 1",
        model.occupied,
    ) & ctx.expect(
        range::FREE.contains(model.free),
        &model_path.key("free"),
        "a probability above 0 and below 0.5",
        model.free,
    );
    let duration = step * steps as f64;
    let snapshot = raw.snapshot.unwrap_or(duration / 2.0);
    let snapshot_ok = ctx.expect(
        (0.0..=duration).contains(&snapshot),
        &path.key("snapshot"),
        &format!("a time from 0 to {duration} s"),
        snapshot,
    );
    let region_ok = raw.region.as_ref().is_none_or(|r| {
        coordinates(ctx, &path.key("region").key("center"), &[r.center])
            & ctx.within(&path.key("region").key("radius"), r.radius, range::EXTENT)
    });
    let messages = messages?;
    (ok && snapshot_ok && region_ok).then(|| Perception {
        ego,
        cooperating: std::iter::once(ego).chain(others.take(count - 1)).collect(),
        occupied: model.occupied,
        free: model.free,
        snapshot_step: ((snapshot / step).round() as usize).min(steps),
        region: raw.region.as_ref().map(|r| (r.center, r.radius)),
        messages,
    })
}

/// The messages of collective perception, for senders with at most `sensors`
/// sensors (the most any connected agent with sensors but the ego carries) in
/// a world stepping every `step` seconds.
fn messages(ctx: &mut Context<'_>, raw: &RawMessages, sensors: usize, step: f64) -> Option<Messages> {
    let path = Path::root().key("v2x").key("messages");
    let header = MESSAGE_HEADER_BYTES as f64 + SENSOR_INFORMATION_BYTES as f64 * sensors as f64;
    let smallest = header + SMALLEST_PAYLOAD_BYTES as f64;
    let bytes = raw.max_bytes as f64;
    let ok = (ctx.within(&path.key("rate_hz"), raw.rate_hz, range::MESSAGE_RATE)
        && ctx.expect(
            raw.rate_hz * step <= 1.0 + 1e-9,
            &path.key("rate_hz"),
            &format!(
                "at most {} Hz, one message a step: agents sense once a step",
                1.0 / step
            ),
            raw.rate_hz,
        ))
        & (ctx.within(&path.key("max_bytes"), bytes, range::MESSAGE_BYTES)
            && ctx.expect(
                bytes >= smallest,
                &path.key("max_bytes"),
                &format!(
                    "at least {smallest} bytes: a {MESSAGE_HEADER_BYTES}-byte header, {SENSOR_INFORMATION_BYTES} bytes \
                     for each of {sensors} sensors and one run of cells"
                ),
                bytes,
            ))
        & (ctx.within(&path.key("max_age"), raw.max_age, range::REACTION)
            && ctx.expect(
                raw.max_age >= step,
                &path.key("max_age"),
                &format!("at least one step ({step} s): evidence is fused at the steps"),
                raw.max_age,
            ))
        & raw
            .decay
            .is_none_or(|decay| ctx.within(&path.key("decay"), decay, range::REACTION));
    ok.then_some(Messages {
        rate_hz: raw.rate_hz,
        max_bytes: raw.max_bytes,
        oversize: raw.oversize,
        max_age: raw.max_age,
        decay: raw.decay,
    })
}
