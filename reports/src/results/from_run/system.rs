//! A system under test's per-object record, mapped to results.json: listed
//! up to [`MAX_OBJECT_RECORDS`].

use sightline_dsl::ObjectProperty;
use sightline_engine::outcome as engine;

use crate::results::{ClosestApproach, MAX_OBJECT_RECORDS, SystemDetail, SystemObjectList, SystemObjectResult};

/// What the system showed of each road user around the ego.
pub(super) fn system_detail(metrics: &engine::SystemMetrics) -> SystemDetail {
    let objects = &metrics.objects;
    SystemDetail {
        objects: SystemObjectList {
            listed: objects.len() as u64,
            records: objects.iter().take(MAX_OBJECT_RECORDS).map(system_object).collect(),
            omitted: objects.len().saturating_sub(MAX_OBJECT_RECORDS) as u64,
        },
    }
}

/// One road user's record.
fn system_object(object: &engine::SystemObject) -> SystemObjectResult {
    let engine::SystemObject {
        ref id,
        class,
        first_in_sight,
        first_detected,
        first_seen_by_ego,
        closest,
        ref areas,
    } = *object;
    SystemObjectResult {
        id: id.clone(),
        class: class.name(),
        first_in_sight,
        first_detected,
        first_seen_by_ego,
        closest: ClosestApproach {
            time: closest.time,
            distance: closest.distance,
            position: closest.position,
        },
        lead: object.property(ObjectProperty::SutLead),
        anticipation: object.property(ObjectProperty::SutAnticipation),
        delay: object.property(ObjectProperty::SutDelay),
        areas: areas.clone(),
    }
}
