//! The agents that replay a trace: the motion of each, and the objects no
//! declared agent replays.
//!
//! A vehicle's SUMO position is the centre of its front bumper; its samples are
//! moved back half its length along its heading to the footprint's centre. A
//! person's position is taken as its centre.

use std::collections::HashSet;

use super::load::Imported;
use crate::geometry::{Polyline, distance};
use crate::import::sumo::FcdObject;
use crate::model::{Agent, AgentKind, Motion, TraceSample};

/// The motion of an agent of `kind` and `length` replaying `object`.
pub(crate) fn trace_motion(imported: &Imported, object: &FcdObject, kind: AgentKind, length: f64) -> Motion {
    let back = if kind.is_vehicle() { length / 2.0 } else { 0.0 };
    let mut samples: Vec<TraceSample> = Vec::with_capacity(object.samples.len());
    for sample in &object.samples {
        let (sin, cos) = sample.heading.sin_cos();
        let [x, y] = sample.position;
        let position = [x - back * cos, y - back * sin];
        let offset = samples
            .last()
            .map_or(0.0, |last| last.offset + distance(last.position, position));
        samples.push(TraceSample {
            time: sample.time - imported.begin,
            position,
            heading: sample.heading,
            speed: sample.speed,
            offset,
            limit: sample
                .lane
                .as_ref()
                .and_then(|lane| imported.limits.get(lane))
                .copied()
                .unwrap_or(f64::INFINITY),
        });
    }
    Motion::Trace {
        path: Polyline::new(samples.iter().map(|s| s.position)),
        samples,
        max_gap: imported.max_gap,
    }
}

/// The objects of the trace no declared agent replays or is named after, within
/// the run's time span, as agents with their type's kind and size, no sensors
/// and not connected.
pub(crate) fn imported_agents(imported: &Imported, declared: &HashSet<&str>, duration: f64) -> Vec<Agent> {
    imported
        .objects()
        .filter(|(object, _)| !declared.contains(object.id.as_str()) && imported.overlaps(object, duration))
        .filter_map(|(object, body)| {
            let body = body?;
            Some(Agent {
                id: object.id.clone(),
                kind: body.kind,
                length: body.length,
                width: body.width,
                motion: trace_motion(imported, object, body.kind, body.length),
                connected: false,
                sensors: Vec::new(),
                antenna_m: None,
            })
        })
        .collect()
}
