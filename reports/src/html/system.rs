//! A system under test's table: each road user around the ego, when the
//! system's sensors had it in sight, when the system detected it, when the
//! ego saw it, its closest approach and the `sut_*` properties.

use super::format::{TableView, number, or_dash};
use crate::results::{SystemDetail, SystemObjectResult};

/// Rows of the table in the report; results.json lists more.
const REPORT_ROWS: usize = 50;

/// The road users around the ego as the system saw them: the ones it never
/// detected first, then the others, each in agent order.
pub(super) fn system_table(system: &SystemDetail) -> TableView {
    let objects = &system.objects;
    let never = |o: &&SystemObjectResult| o.first_detected.is_none();
    let shown: Vec<&SystemObjectResult> = (objects.records.iter().filter(never))
        .chain(objects.records.iter().filter(|o| !never(o)))
        .take(REPORT_ROWS)
        .collect();
    TableView {
        caption: format!(
            "Road users around the ego, as the system under test saw them: {} of {} ({} in results.json), never \
             detected first; — where it never happened",
            shown.len(),
            objects.listed,
            objects.records.len()
        ),
        text_columns: 2,
        head: [
            "id",
            "class",
            "in sight (s)",
            "detected (s)",
            "seen by ego (s)",
            "closest at (s)",
            "closest (m)",
            "lead (s)",
            "anticipation (s)",
            "delay (s)",
        ]
        .map(String::from)
        .to_vec(),
        rows: shown
            .iter()
            .map(|o| {
                vec![
                    o.id.clone(),
                    o.class.to_string(),
                    or_dash(o.first_in_sight),
                    or_dash(o.first_detected),
                    or_dash(o.first_seen_by_ego),
                    number(o.closest.time),
                    number(o.closest.distance),
                    or_dash(o.lead),
                    or_dash(o.anticipation),
                    or_dash(o.delay),
                ]
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::results::{ClosestApproach, SystemObjectList};

    fn object(id: &str, detected: Option<f64>) -> SystemObjectResult {
        SystemObjectResult {
            id: id.into(),
            class: "car",
            first_in_sight: Some(1.0),
            first_detected: detected,
            first_seen_by_ego: None,
            closest: ClosestApproach {
                time: 4.0,
                distance: 12.5,
                position: [0.0, 0.0],
            },
            lead: detected.map(|d| 4.0 - d),
            anticipation: detected.map(|d| 4.0 - d),
            delay: detected.map(|d| d - 1.0),
            areas: Vec::new(),
        }
    }

    /// The road user never detected comes first, and what never happened is
    /// a dash.
    #[test]
    fn the_undetected_come_first() {
        let table = system_table(&SystemDetail {
            objects: SystemObjectList {
                listed: 1002,
                records: vec![object("a", Some(1.5)), object("b", None)],
                omitted: 1000,
            },
        });
        assert_eq!(
            table.rows[0],
            ["b", "car", "1", "—", "—", "4", "12.5", "—", "—", "—"].map(String::from)
        );
        assert_eq!(
            table.rows[1],
            ["a", "car", "1", "1.5", "—", "4", "12.5", "2.5", "2.5", "0.5"].map(String::from)
        );
        assert!(
            table.caption.contains("2 of 1002 (2 in results.json)"),
            "{}",
            table.caption
        );
    }
}
