//! Each point's tables: every metric with its sample size, and the counts of
//! its kind of scenario (distance bands and coverage, a world's cell-steps, a
//! semantic run's counts, contribution by density, delivery by distance and
//! close approaches).

use sightline_dsl::Metric;
use sightline_engine::outcome::{DELIVERY_BIN, DENSITY_BIN, quantile};

use super::format::{TableView, metric_unit, number, or_dash};
use super::system::system_table;
use crate::results::{
    CloseApproach, DensityRow, Detail, ObjectCategory, ObjectList, ObjectResult, PointResult, SemanticCounts,
};

const BAND_COLUMNS: [&str; 7] = [
    "distance to nearest sensor",
    "cells",
    "accuracy (1)",
    "below threshold (cells)",
    "false alarms (cells)",
    "missed detections (cells)",
    "mean conflict (1)",
];

/// Every metric the point measures, with its sample size and what it counts.
pub(super) fn samples_table(p: &PointResult) -> TableView {
    let rows = p
        .samples
        .0
        .iter()
        .map(|(name, n)| {
            let population = Metric::ALL
                .iter()
                .find(|m| m.name() == name)
                .map_or("", |m| m.population());
            vec![
                name.clone(),
                population.to_string(),
                metric_unit(name).to_string(),
                // A count over nobody (missed criticals with no close
                // approach) is 0, but nothing was measured.
                or_dash(p.metrics.get(name).filter(|_| *n > 0)),
                number(*n as f64),
            ]
        })
        .collect();
    TableView {
        caption: "Every metric with its sample size n (— where the population is empty)".into(),
        head: ["metric", "n counts", "unit", "value", "n"].map(String::from).to_vec(),
        rows,
        text_columns: 3,
    }
}

/// The summary line and the tables of a point's details.
pub(super) fn point_body(p: &PointResult) -> (String, Vec<TableView>) {
    match &p.detail {
        Detail::Field { bands, coverage: c } => (
            format!(
                "{} sensors; {}–{} observe each cell (mean {:.2})",
                c.sensors, c.min_sources, c.max_sources, c.mean_sources
            ),
            vec![TableView {
                caption: String::new(),
                text_columns: 1,
                head: BAND_COLUMNS.map(String::from).to_vec(),
                rows: bands
                    .iter()
                    .map(|b| {
                        vec![
                            distance_band(b.from, b.to),
                            number(b.cells as f64),
                            or_dash(b.accuracy),
                            number(b.below_threshold as f64),
                            number(b.false_alarms as f64),
                            number(b.missed_detections as f64),
                            or_dash(b.mean_conflict),
                        ]
                    })
                    .collect(),
            }],
        ),
        Detail::World {
            counts: c,
            semantic,
            system,
        } => {
            let s = &c.sightings;
            let rows = [
                ("steps with the ego in the scene", c.steps as f64),
                (
                    "occupied cell-steps (road users that do not cooperate)",
                    c.occupied as f64,
                ),
                ("… decided Occupy", c.detected as f64),
                ("… decided Occupy by the ego alone", c.ego_detected as f64),
                ("free cell-steps decided Occupy", c.false_positives as f64),
                ("occupied cell-steps the ego did not observe", c.blind_occupied as f64),
                ("… decided Occupy", c.blind_detected as f64),
                (
                    "occupied cell-steps decided Occupy by another agent's reported footprint alone (no detection)",
                    c.footprint_only as f64,
                ),
                (
                    "cell-steps of cooperating agents' own bodies (self-report)",
                    c.self_report as f64,
                ),
                ("… decided Occupy", c.self_report_detected as f64),
                ("… of which no sensor observed occupied", c.self_report_only as f64),
                ("cell-steps observed by the ego", c.ego_observed as f64),
                ("cell-steps observed by any cooperating agent", c.joint_observed as f64),
                ("targets in line of sight (sensor–target pairs)", s.los as f64),
                ("… hidden by an occluder", s.nlos_static as f64),
                ("… hidden by other agents", s.nlos_dynamic as f64),
                ("… detected", s.detected as f64),
            ];
            let mut rows: Vec<Vec<String>> = rows.iter().map(|(k, v)| vec![(*k).to_string(), number(*v)]).collect();
            rows.push(vec![
                "mean pose-estimate error, m".into(),
                or_dash(c.localization_error),
            ]);
            if let Some(radio) = &c.radio {
                let fused: u64 = radio.ages.iter().map(|a| a.messages).sum();
                let radio_rows = [
                    ("messages the cooperating agents sent the ego", radio.sent as f64),
                    ("… received", radio.received as f64),
                    ("… fused by the ego before the run ended", fused as f64),
                    ("bytes sent", radio.bytes as f64),
                    (
                        "steps cooperating agents other than the ego were in the scene with it",
                        radio.sender_steps as f64,
                    ),
                ];
                rows.extend(radio_rows.iter().map(|(k, v)| vec![(*k).to_string(), number(*v)]));
            }
            let by_distance = TableView {
                caption: "Occupied-cell recall by distance to the nearest cooperating agent other than the ego \
                          (self-report left out)"
                    .into(),
                text_columns: 1,
                head: [
                    "distance",
                    "occupied cell-steps (n)",
                    "decided Occupy (cell-steps)",
                    "recall (1)",
                ]
                .map(String::from)
                .to_vec(),
                rows: c
                    .recall_by_distance
                    .iter()
                    .map(|r| {
                        vec![
                            distance_band(r.from, r.to),
                            number(r.occupied as f64),
                            number(r.detected as f64),
                            or_dash(r.recall),
                        ]
                    })
                    .collect(),
            };
            let mut tables = vec![counts_table(rows), by_distance];
            tables.extend(system.as_deref().map(system_table));
            let summary = match semantic {
                // A joint world: the pipeline's tables after the grid's.
                Some(s) => {
                    tables.extend(semantic_tables(&s.counts, &s.contribution_by_density));
                    tables.extend(object_tables(&s.objects));
                    format!(
                        "{} steps; the semantic pipeline on the same scene: {} generated road users, {} anticipated \
                         objects",
                        c.steps,
                        s.counts.generated,
                        s.counts.anticipation.len()
                    )
                }
                None => format!("{} steps", c.steps),
            };
            (summary, tables)
        }
        Detail::Semantic {
            counts: c,
            contribution_by_density,
            objects,
        } => (
            format!(
                "{} pooled run(s): {} steps with the ego, {} generated road users, {} anticipated objects",
                c.runs,
                c.steps,
                c.generated,
                c.anticipation.len()
            ),
            {
                let mut tables = semantic_tables(c, contribution_by_density);
                tables.extend(object_tables(objects));
                tables
            },
        ),
    }
}

fn counts_table(rows: Vec<Vec<String>>) -> TableView {
    TableView {
        caption: String::new(),
        text_columns: 1,
        head: vec!["count".into(), "value".into()],
        rows,
    }
}

/// The counts of a semantic run, its contribution by density and its packet
/// delivery by distance.
fn semantic_tables(c: &SemanticCounts, density: &[DensityRow]) -> Vec<TableView> {
    let l = &c.labels;
    let counts = [
        ("steps with the ego in the scene", c.steps as f64),
        (
            "objects anticipated (learned of while hidden, later seen)",
            c.anticipation.len() as f64,
        ),
        ("objects learned of while hidden and never seen", c.never_seen as f64),
        (
            "object-cycles perceived by the RSUs (in the cycles the shares count)",
            c.perceived as f64,
        ),
        ("… sent to the ego", c.transmitted as f64),
        ("… with at least one label", c.labelled as f64),
        ("… labelled NLoS behind an occluder", l.nlos_static as f64),
        ("… labelled NLoS behind road users", l.nlos_dynamic as f64),
        ("… labelled relevant", l.relevant as f64),
        ("… labelled speeding", l.speeding as f64),
        ("… labelled with a predicted conflict", l.conflict as f64),
        ("object-cycles the ETSI baseline sends", c.baseline_objects as f64),
        ("bytes of semantic messages", c.bytes as f64),
        ("bytes of ETSI baseline messages", c.baseline_bytes as f64),
        ("messages sent to the ego", c.messages as f64),
        ("… received", c.delivered as f64),
        ("close approaches (within d_min of the ego)", c.close_approaches as f64),
        ("… with no conflict flagged beforehand", c.missed_criticals as f64),
        ("seconds the ego drove cautiously", c.cautious_time),
    ];
    let by_density = TableView {
        caption: "Objects the ego knows only through an RSU, by traffic density".into(),
        text_columns: 1,
        head: ["objects per km", "steps", "median (objects)", "mean (objects)"]
            .map(String::from)
            .to_vec(),
        rows: density
            .iter()
            .map(|r| {
                vec![
                    format!("{} – {}", number(r.from), number(r.from + DENSITY_BIN)),
                    number(r.steps as f64),
                    number(r.median),
                    number(r.mean),
                ]
            })
            .collect(),
    };
    let by_distance = TableView {
        caption: "Messages to the ego by RSU–ego distance".into(),
        text_columns: 1,
        head: [
            "distance",
            "sent (messages)",
            "received (messages)",
            "delivery ratio (1)",
        ]
        .map(String::from)
        .to_vec(),
        rows: c
            .delivery_by_distance
            .iter()
            .enumerate()
            .filter(|(_, b)| b.sent > 0)
            .map(|(i, b)| {
                let from = i as f64 * DELIVERY_BIN;
                vec![
                    format!("{} – {} m", number(from), number(from + DELIVERY_BIN)),
                    number(b.sent as f64),
                    number(b.received as f64),
                    number(b.received as f64 / b.sent as f64),
                ]
            })
            .collect(),
    };
    let quantiles = [0.0, 0.25, 0.5, 0.75, 0.95, 1.0];
    let anticipation = TableView {
        caption: "Anticipation time, seconds (type 7 quantiles over the pooled objects)".into(),
        text_columns: 0,
        head: [
            "objects",
            "min (s)",
            "25 % (s)",
            "median (s)",
            "75 % (s)",
            "95 % (s)",
            "max (s)",
        ]
        .map(String::from)
        .to_vec(),
        rows: vec![
            std::iter::once(number(c.anticipation.len() as f64))
                .chain(quantiles.iter().map(|&q| or_dash(quantile(&c.anticipation, q))))
                .collect(),
        ],
    };
    let mut tables = vec![
        counts_table(counts.iter().map(|(k, v)| vec![(*k).to_string(), number(*v)]).collect()),
        anticipation,
        by_density,
        by_distance,
    ];
    if !c.approaches.is_empty() {
        tables.push(approach_table(c));
    }
    tables
}

/// The close approaches that give `warning_time`, the least warned first:
/// those never flagged, then by warning time.
fn approach_table(c: &SemanticCounts) -> TableView {
    let mut shown: Vec<&CloseApproach> = c.approaches.iter().collect();
    shown.sort_by(|a, b| match (a.warning_time, b.warning_time) {
        (Some(a), Some(b)) => a.total_cmp(&b),
        (a, b) => a.is_some().cmp(&b.is_some()),
    });
    shown.truncate(REPORT_OBJECT_ROWS);
    TableView {
        caption: format!(
            "Close approaches, the least warned first: {} of {} ({} in results.json); — where no conflict was \
             flagged beforehand",
            shown.len(),
            c.close_approaches,
            c.approaches.len()
        ),
        text_columns: 2,
        head: ["run", "id", "within d_min at (s)", "flagged at (s)", "warning time (s)"]
            .map(String::from)
            .to_vec(),
        rows: shown
            .iter()
            .map(|a| {
                vec![
                    a.run.to_string(),
                    a.id.clone(),
                    number(a.at),
                    or_dash(a.flagged),
                    or_dash(a.warning_time),
                ]
            })
            .collect(),
    }
}

/// Rows of the object table in the report; results.json lists more.
const REPORT_OBJECT_ROWS: usize = 50;

/// The order of the report's object rows: the road users V2X is for first.
const REPORT_ORDER: [ObjectCategory; 4] = [
    ObjectCategory::NeverKnown,
    ObjectCategory::WarnedNeverSeen,
    ObjectCategory::WarnedBeforeSeen,
    ObjectCategory::SeenFirst,
];

/// The relevant road users by category, and the first of their records.
fn object_tables(objects: &ObjectList) -> [TableView; 3] {
    let c = &objects.categories;
    let by_category = TableView {
        caption: format!(
            "Relevant road users by how the ego came to know them (n = {} over the pooled runs)",
            objects.relevant
        ),
        text_columns: 1,
        head: vec!["category".into(), "road users (objects)".into()],
        rows: [
            (
                "warned_before_seen: named by V2X before the ego saw it",
                c.warned_before_seen,
            ),
            ("warned_never_seen: named by V2X, never seen", c.warned_never_seen),
            ("seen_first: seen no later than named", c.seen_first),
            ("never_known: neither named nor seen", c.never_known),
        ]
        .iter()
        .map(|(k, v)| vec![(*k).to_string(), number(*v as f64)])
        .collect(),
    };
    let shown: Vec<&ObjectResult> = REPORT_ORDER
        .iter()
        .flat_map(|&category| objects.records.iter().filter(move |o| o.category == category))
        .take(REPORT_OBJECT_ROWS)
        .collect();
    // Two tables of the same road users, in the same order, so that each
    // prints on A4: when the ego came to know them (in a joint world also
    // when each came into the ego's fused grid), and how close and how
    // critical their encounter was.
    let listed = format!(
        "{} of {} ({} in results.json), never known first, then warned and never seen, warned before seen, seen \
         first; — where it never happened",
        shown.len(),
        objects.relevant,
        objects.records.len()
    );
    let joint = objects.records.iter().any(|o| o.first_in_grid.is_some());
    let identity = |o: &ObjectResult| vec![o.run.to_string(), o.id.clone(), o.class.to_string()];
    let mut head: Vec<String> = [
        "run",
        "id",
        "class",
        "category",
        "relevant (s)",
        "seen (s)",
        "V2X (s)",
        "warned (s)",
    ]
    .map(String::from)
    .to_vec();
    if joint {
        head.push("in grid (s)".into());
    }
    head.push("anticipation (s)".into());
    let knowledge = TableView {
        caption: format!("Relevant road users, when the ego knew them: {listed}"),
        text_columns: 4,
        head,
        rows: shown
            .iter()
            .map(|o| {
                let mut row = identity(o);
                row.extend([
                    o.category.name().to_string(),
                    number(o.first_relevant),
                    or_dash(o.first_seen),
                    or_dash(o.first_v2x),
                    or_dash(o.first_warning),
                ]);
                if joint {
                    row.push(or_dash(o.first_in_grid.flatten()));
                }
                row.push(or_dash(o.anticipation));
                row
            })
            .collect(),
    };
    let encounters = TableView {
        caption: format!("Relevant road users, their closest approach and criticality: {listed}"),
        text_columns: 3,
        head: [
            "run",
            "id",
            "class",
            "closest at (s)",
            "closest (m)",
            "least TTC (s)",
            "PET (s)",
            "max DRAC (m/s²)",
        ]
        .map(String::from)
        .to_vec(),
        rows: shown
            .iter()
            .map(|o| {
                let mut row = identity(o);
                row.extend([
                    or_dash(o.closest.map(|c| c.time)),
                    or_dash(o.closest.map(|c| c.distance)),
                    or_dash(o.min_ttc),
                    or_dash(o.pet),
                    or_dash(o.max_drac),
                ]);
                row
            })
            .collect(),
    };
    [by_category, knowledge, encounters]
}

/// A band of distance: "from – to m", or "≥ from m" when it has no bound.
fn distance_band(from: f64, to: Option<f64>) -> String {
    match to {
        Some(to) => format!("{} – {} m", number(from), number(to)),
        None => format!("≥ {} m", number(from)),
    }
}
