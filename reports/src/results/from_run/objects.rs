//! A semantic point's (or a joint world's pipeline's) per-object records,
//! mapped to results.json: counted by category, and listed up to
//! [`MAX_OBJECT_RECORDS`].

use sightline_engine::outcome as engine;

use crate::results::{CategoryCounts, ClosestApproach, MAX_OBJECT_RECORDS, ObjectCategory, ObjectList, ObjectResult};

/// The records of a point; `in_grid`: the point fuses a grid (a joint
/// world), whose times each record gives.
pub(super) fn object_list(records: &[engine::ObjectRecord], in_grid: bool) -> ObjectList {
    let count = |category| records.iter().filter(|r| r.category == category).count() as u64;
    ObjectList {
        relevant: records.len() as u64,
        categories: CategoryCounts {
            warned_before_seen: count(engine::Category::WarnedBeforeSeen),
            warned_never_seen: count(engine::Category::WarnedNeverSeen),
            seen_first: count(engine::Category::SeenFirst),
            never_known: count(engine::Category::NeverKnown),
        },
        records: records
            .iter()
            .take(MAX_OBJECT_RECORDS)
            .map(|record| object_result(record, in_grid))
            .collect(),
        omitted: records.len().saturating_sub(MAX_OBJECT_RECORDS) as u64,
    }
}

/// One record, with its time in the grid where the point fuses one
/// (`in_grid`); also what the recording and the report show of it.
pub(crate) fn object_result(record: &engine::ObjectRecord, in_grid: bool) -> ObjectResult {
    let engine::ObjectRecord {
        run,
        ref id,
        class,
        length,
        width,
        first_relevant,
        first_seen,
        first_v2x,
        first_warning,
        first_in_grid,
        closest,
        min_ttc,
        max_drac,
        pet,
        category,
        baseline_v2x,
        ref areas,
    } = *record;
    ObjectResult {
        run,
        id: id.clone(),
        class: class.name(),
        length,
        width,
        first_relevant,
        first_seen,
        first_v2x,
        first_warning,
        first_in_grid: in_grid.then_some(first_in_grid),
        closest: closest.map(
            |engine::Closest {
                 time,
                 distance,
                 position,
             }| ClosestApproach {
                time,
                distance,
                position,
            },
        ),
        min_ttc,
        max_drac,
        pet,
        category: match category {
            engine::Category::WarnedBeforeSeen => ObjectCategory::WarnedBeforeSeen,
            engine::Category::WarnedNeverSeen => ObjectCategory::WarnedNeverSeen,
            engine::Category::SeenFirst => ObjectCategory::SeenFirst,
            engine::Category::NeverKnown => ObjectCategory::NeverKnown,
        },
        anticipation: record.anticipation(),
        baseline_v2x,
        baseline_anticipation: record.baseline_anticipation(),
        areas: areas.clone(),
    }
}
