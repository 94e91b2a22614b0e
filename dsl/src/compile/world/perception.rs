//! Collective perception: the ego, the agents that cooperate with it, the
//! inverse sensor model, the pictured step and the region the metrics count.

use crate::compile::checks::{coordinates, known_names};
use crate::compile::context::Context;
use crate::error::ErrorKind;
use crate::model::{Agent, Perception};
use crate::path::Path;
use crate::raw::RawPerception;
use crate::raw::range;

pub(super) fn perception_of(
    ctx: &mut Context<'_>,
    raw: &RawPerception,
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
    let count = raw.cooperating.map_or(available, |c| c as usize);
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
    (ok && snapshot_ok && region_ok).then(|| Perception {
        ego,
        cooperating: std::iter::once(ego).chain(others.take(count - 1)).collect(),
        occupied: model.occupied,
        free: model.free,
        snapshot_step: ((snapshot / step).round() as usize).min(steps),
        region: raw.region.as_ref().map(|r| (r.center, r.radius)),
    })
}
