//! A point's outcome: its labels, metrics and sample sizes, and the engine's
//! counts behind them (distance bands, coverage, the mass audit, a world's and
//! a semantic run's counts).

use sightline_dsl::Point;
use sightline_engine::{Outcome, outcome as engine};

use super::objects::object_list;
use super::system::system_detail;
use crate::results::{
    AgeCount, Band, Calibration, CloseApproach, Conflict, Coverage, DeliveryBin, DensityRow, Detail, DistanceRow,
    LabelCounts, LabelResult, MAX_OBJECT_RECORDS, MassAudit, Ordered, PointResult, Radio, ReliabilityBin,
    SemanticCounts, SemanticDetail, Sightings, WorldCounts,
};

pub(super) fn point_result((point, outcome): (&Point, &Outcome)) -> PointResult {
    PointResult {
        index: point.index,
        label: point.label(),
        labels: point
            .labels
            .iter()
            .map(|label| LabelResult {
                sweep: label.sweep,
                label: label.text(),
                settings: Ordered(
                    label
                        .assignments
                        .iter()
                        .map(|a| (a.path.clone(), a.value.clone()))
                        .collect(),
                ),
            })
            .collect(),
        seed: point.setup.seed,
        method: point.setup.occupancy.as_ref().map(|o| o.fusion.rule.method().name()),
        fusion: point.setup.occupancy.as_ref().map(|o| o.fusion.label.clone()),
        metrics: Ordered(
            outcome
                .values()
                .into_iter()
                .map(|(m, v)| (m.name().to_string(), v))
                .collect(),
        ),
        samples: Ordered(
            outcome
                .samples()
                .into_iter()
                .map(|(m, s)| (m.name().to_string(), s.n))
                .collect(),
        ),
        audit: outcome.audit().copied().map(mass_audit),
        detail: match outcome {
            Outcome::Field(o) => Detail::Field {
                bands: o.bands.iter().map(band).collect(),
                coverage: coverage(o.coverage),
            },
            Outcome::World(o) => Detail::World {
                counts: world_counts(&o.metrics),
                semantic: o.semantic.as_deref().map(|m| Box::new(semantic_detail(m, true))),
                system: o.system.as_ref().map(|m| Box::new(system_detail(m))),
            },
            Outcome::Semantic(m) => {
                let SemanticDetail {
                    counts,
                    contribution_by_density,
                    objects,
                } = semantic_detail(m, false);
                Detail::Semantic {
                    counts,
                    contribution_by_density,
                    objects,
                }
            }
        },
    }
}

/// What the semantic pipeline measured; `in_grid`: a joint world's, whose
/// records say when each road user came into the fused grid.
fn semantic_detail(m: &engine::SemanticMetrics, in_grid: bool) -> SemanticDetail {
    SemanticDetail {
        counts: semantic_counts(m),
        contribution_by_density: m.contribution_by_density().into_iter().map(density_row).collect(),
        objects: object_list(&m.objects, in_grid),
    }
}

fn mass_audit(audit: engine::MassAudit) -> MassAudit {
    let engine::MassAudit {
        cells,
        non_finite,
        min_mass,
        max_mass,
        max_sum_error,
    } = audit;
    MassAudit {
        cells,
        non_finite,
        min_mass,
        max_mass,
        max_sum_error,
    }
}

fn band(band: &engine::BandMetrics) -> Band {
    let engine::BandMetrics {
        from,
        to,
        cells,
        accuracy,
        below_threshold,
        false_alarms,
        missed_detections,
        mean_conflict,
    } = *band;
    Band {
        from,
        to,
        cells,
        accuracy,
        below_threshold,
        false_alarms,
        missed_detections,
        mean_conflict,
    }
}

fn coverage(coverage: engine::Coverage) -> Coverage {
    let engine::Coverage {
        sensors,
        min_sources,
        max_sources,
        mean_sources,
    } = coverage;
    Coverage {
        sensors,
        min_sources,
        max_sources,
        mean_sources,
    }
}

fn world_counts(metrics: &engine::WorldMetrics) -> WorldCounts {
    let engine::WorldMetrics {
        steps,
        occupied,
        detected,
        ego_detected,
        false_positives,
        blind_occupied,
        blind_detected,
        footprint_only,
        self_report,
        self_report_detected,
        self_report_only,
        ego_observed,
        joint_observed,
        sightings,
        localization_error,
        mean_uncertainty,
        ref conflict,
        ref calibration,
        ref recall_by_distance,
        ref radio,
    } = *metrics;
    let engine::Sightings {
        los,
        nlos_static,
        nlos_dynamic,
        detected: seen,
        visible: _,
    } = sightings;
    WorldCounts {
        steps,
        occupied,
        detected,
        ego_detected,
        false_positives,
        blind_occupied,
        blind_detected,
        footprint_only,
        self_report,
        self_report_detected,
        self_report_only,
        ego_observed,
        joint_observed,
        sightings: Sightings {
            los,
            nlos_static,
            nlos_dynamic,
            detected: seen,
        },
        localization_error,
        mean_uncertainty,
        conflict: conflict.as_ref().map(|c| {
            let engine::ConflictMetrics {
                mean,
                max,
                total_conflict_cells,
                weighted_cells,
            } = *c;
            Conflict {
                mean,
                max,
                total_conflict_cells,
                weighted_cells,
            }
        }),
        calibration: calibration_table(calibration),
        recall_by_distance: distance_rows(recall_by_distance),
        radio: radio.as_deref().map(radio_counts),
    }
}

fn distance_rows(by_distance: &engine::RecallByDistance) -> Vec<DistanceRow> {
    let last = engine::DISTANCE_BINS - 1;
    by_distance
        .bins
        .iter()
        .enumerate()
        .map(|(i, bin)| DistanceRow {
            from: i as f64 * engine::DISTANCE_BIN,
            to: (i < last).then(|| (i + 1) as f64 * engine::DISTANCE_BIN),
            occupied: bin.occupied,
            detected: bin.detected,
            recall: (bin.occupied > 0).then(|| bin.detected as f64 / bin.occupied as f64),
        })
        .collect()
}

fn radio_counts(radio: &engine::RadioStats) -> Radio {
    Radio {
        sent: radio.sent,
        received: radio.received,
        bytes: radio.bytes,
        sender_steps: radio.sender_steps,
        ages: radio
            .ages
            .iter()
            .enumerate()
            .filter(|&(_, &messages)| messages > 0)
            .map(|(a, &messages)| AgeCount {
                age: a as f64 * radio.step,
                messages,
            })
            .collect(),
    }
}

fn calibration_table(c: &engine::Calibration) -> Calibration {
    // Divided, not multiplied by a width: 3 / 10 is 0.3, 3 × 0.1 is not.
    let edge = |i: usize| i as f64 / engine::RELIABILITY_BINS as f64;
    Calibration {
        cells: c.cells,
        brier_score: c.brier_score(),
        bins: c
            .bins
            .iter()
            .enumerate()
            .map(|(i, b)| ReliabilityBin {
                from: edge(i),
                to: edge(i + 1),
                cells: b.cells,
                mean_probability: b.mean_probability(),
                observed_frequency: b.observed_frequency(),
            })
            .collect(),
    }
}

/// A semantic run's counts; its per-step series (`contribution`, `rsu_only`,
/// `time_to_conflict`) stay out of results.json (the contribution is written
/// by density instead), and its per-object records go in their own list.
fn semantic_counts(metrics: &engine::SemanticMetrics) -> SemanticCounts {
    let engine::SemanticMetrics {
        runs,
        steps,
        duration,
        generated,
        ref anticipation,
        never_seen,
        ref baseline_anticipation,
        contribution: _,
        perceived,
        transmitted,
        labelled,
        labels,
        bytes,
        baseline_bytes,
        baseline_objects,
        messages,
        delivered,
        ref delivery_by_distance,
        close_approaches,
        missed_criticals,
        cautious_time,
        ref approaches,
        rsu_only: _,
        time_to_conflict: _,
        objects: _,
        first_run: _,
    } = *metrics;
    let engine::LabelCounts {
        nlos_static,
        nlos_dynamic,
        relevant,
        speeding,
        conflict,
    } = labels;
    SemanticCounts {
        runs,
        steps,
        duration,
        generated,
        anticipation: anticipation.clone(),
        never_seen,
        baseline_anticipation: baseline_anticipation.clone(),
        perceived,
        transmitted,
        labelled,
        labels: LabelCounts {
            nlos_static,
            nlos_dynamic,
            relevant,
            speeding,
            conflict,
        },
        bytes,
        baseline_bytes,
        baseline_objects,
        messages,
        delivered,
        delivery_by_distance: delivery_by_distance
            .iter()
            .map(|&engine::DeliveryBin { sent, received }| DeliveryBin { sent, received })
            .collect(),
        close_approaches,
        missed_criticals,
        cautious_time,
        approaches: approaches
            .iter()
            .take(MAX_OBJECT_RECORDS)
            .map(|approach| CloseApproach {
                run: approach.run,
                id: approach.id.clone(),
                at: approach.at,
                flagged: approach.flagged,
                warning_time: approach.warning_time(),
            })
            .collect(),
    }
}

fn density_row(row: engine::DensityRow) -> DensityRow {
    let engine::DensityRow {
        from,
        steps,
        median,
        mean,
    } = row;
    DensityRow {
        from,
        steps,
        median,
        mean,
    }
}
