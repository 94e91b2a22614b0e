//! The counts behind a point's metrics, as results.json writes them: the field
//! experiment's distance bands and coverage, the mass audit of fused cells, a
//! perception world's cell-step counts and a semantic run's counts and samples.

use serde::Serialize;

/// Extremes of the fused masses, for the mass-function invariant (for
/// `bayes` the audited vector is (1 − p, p, 0)).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct MassAudit {
    /// Fused cells audited.
    pub cells: u64,
    /// Cells with a NaN or infinite mass.
    pub non_finite: u64,
    /// Smallest finite mass of any cell (`null` when no cell was fused).
    pub min_mass: Option<f64>,
    /// Largest finite mass of any cell.
    pub max_mass: Option<f64>,
    /// Largest |Σ masses − 1| of any finite cell.
    pub max_sum_error: f64,
}

/// The field experiment's metrics in one band of distance to the nearest sensor.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Band {
    /// Lower edge, metres.
    pub from: f64,
    /// Upper edge, metres (`null` for the last, open band).
    pub to: Option<f64>,
    /// Cells in the band.
    pub cells: u64,
    /// Share decided correctly (`null` for an empty band).
    pub accuracy: Option<f64>,
    /// Cells with no decision.
    pub below_threshold: u64,
    /// False alarms.
    pub false_alarms: u64,
    /// Missed detections.
    pub missed_detections: u64,
    /// Mean conflict K over the band's observed cells (evidential methods only).
    pub mean_conflict: Option<f64>,
}

/// How many sensors observe each cell of the field.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Coverage {
    /// Sensors in the field.
    pub sensors: usize,
    /// Fewest sensors observing a cell.
    pub min_sources: usize,
    /// Most sensors observing a cell.
    pub max_sources: usize,
    /// Mean sensors per cell.
    pub mean_sources: f64,
}

/// The cell-step counts of a perception world's run.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct WorldCounts {
    /// Steps counted (the ego in the scene).
    pub steps: u64,
    /// Cell-steps truly occupied by a road user that does not cooperate (not
    /// the ego, an RSU or a cooperating agent's own footprint).
    pub occupied: u64,
    /// Of those, decided Occupy by the fused grid where a sensor found them
    /// occupied (detected: `occupied_recall`).
    pub detected: u64,
    /// Of the `occupied` cell-steps, those the ego's own observation alone
    /// decides Occupy (`ego_occupied_recall`).
    pub ego_detected: u64,
    /// Cell-steps decided Occupy that are truly free.
    pub false_positives: u64,
    /// Of the `occupied` cell-steps, those the ego did not observe itself.
    pub blind_occupied: u64,
    /// Of those, detected as `detected` counts.
    pub blind_detected: u64,
    /// Of the `occupied` cell-steps, those decided Occupy where no sensor
    /// found them occupied: only another agent's reported footprint (where
    /// that agent was) covers them. Counted as correct by `occupied_precision`,
    /// not as detected by the recalls.
    pub footprint_only: u64,
    /// Cell-steps truly occupied by a cooperating agent other than the ego: its
    /// own footprint, which it reports itself.
    pub self_report: u64,
    /// Of those, decided Occupy by the fused grid.
    pub self_report_detected: u64,
    /// Of those, the cell-steps no sensor observed occupied (known only through
    /// self-report).
    pub self_report_only: u64,
    /// Cell-steps a sensor of the ego observed.
    pub ego_observed: u64,
    /// Cell-steps a sensor of any cooperating agent observed (a self-reported
    /// footprint is not observed).
    pub joint_observed: u64,
    /// Sensor–target pairs in range and field of view, by visibility, over the run.
    pub sightings: Sightings,
    /// Mean position error of the cooperating agents' pose estimates, metres.
    pub localization_error: Option<f64>,
    /// Mean uncertainty of the fused cells.
    pub mean_uncertainty: Option<f64>,
    /// Conflict statistics (evidential methods only).
    pub conflict: Option<Conflict>,
    /// How well the fused probabilities are calibrated.
    pub calibration: Calibration,
    /// Occupied-cell recall (self-report left out) by the distance from the
    /// cell to the nearest cooperating agent other than the ego, 25 m bins;
    /// cell-steps with no such agent in the scene are not counted.
    pub recall_by_distance: Vec<DistanceRow>,
    /// What went over the radio (`null` when the scenario declares no `v2x`).
    pub radio: Option<Radio>,
}

/// The occupied cell-steps of one band of distance to the nearest sender.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct DistanceRow {
    /// Nearest distance, metres (included).
    pub from: f64,
    /// Farthest distance, metres (excluded; `null`: no bound).
    pub to: Option<f64>,
    /// Occupied cell-steps of road users that do not cooperate (n).
    pub occupied: u64,
    /// Of them, decided Occupy by the fused grid.
    pub detected: u64,
    /// detected / occupied (`null` when n = 0).
    pub recall: Option<f64>,
}

/// The messages of collective perception over the radio.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Radio {
    /// Messages the cooperating agents sent the ego.
    pub sent: u64,
    /// Of them, received (power at or above the ego's sensitivity).
    pub received: u64,
    /// Bytes of the messages sent, headers included.
    pub bytes: u64,
    /// Steps cooperating agents other than the ego spent in the scene with it.
    pub sender_steps: u64,
    /// The messages the ego fused, by age (seconds from sensing to the first
    /// step that fused them), ages with no message left out.
    pub ages: Vec<AgeCount>,
}

/// How many fused messages were one age.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct AgeCount {
    /// Seconds from sensing to fusion.
    pub age: f64,
    /// Messages fused at that age.
    pub messages: u64,
}

/// How well a world's fused occupancy probabilities p (pignistic for
/// evidential methods) match the truth o over the fused cell-steps,
/// self-report left out.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Calibration {
    /// Cell-steps judged (n).
    pub cells: u64,
    /// Mean (p − o)² (`null` when no cell-step was judged).
    pub brier_score: Option<f64>,
    /// The reliability table: 10 equal bins of p, in order.
    pub bins: Vec<ReliabilityBin>,
}

/// The fused cell-steps whose probability falls in one bin.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct ReliabilityBin {
    /// Lower edge of p (included).
    pub from: f64,
    /// Upper edge of p (excluded, but for the last bin's 1).
    pub to: f64,
    /// Cell-steps in the bin (n).
    pub cells: u64,
    /// Their mean p (`null` for an empty bin).
    pub mean_probability: Option<f64>,
    /// Their share truly occupied (`null` for an empty bin).
    pub observed_frequency: Option<f64>,
}

/// Targets in range and field of view, by what hides them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Sightings {
    /// In line of sight.
    pub los: u64,
    /// Hidden by an occluder.
    pub nlos_static: u64,
    /// Hidden by other agents only.
    pub nlos_dynamic: u64,
    /// Visible targets that were detected.
    pub detected: u64,
}

/// The conflict of an evidential run.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Conflict {
    /// Mean conflict K over observed cells (`null` when no cell is observed).
    pub mean: Option<f64>,
    /// Largest conflict K of any cell.
    pub max: f64,
    /// Cells in total conflict (K = 1).
    pub total_conflict_cells: u64,
    /// Cells fused with the distance-weighted rule.
    pub weighted_cells: u64,
}

/// The counts and samples of a semantic run; the per-step series are left out
/// (they are in run.mcap and in shard files).
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct SemanticCounts {
    /// Independent runs pooled into these measurements.
    pub runs: u32,
    /// Steps with the ego in the scene.
    pub steps: u64,
    /// Simulated seconds with the ego in the scene.
    pub duration: f64,
    /// Vehicles and pedestrians the traffic generator added.
    pub generated: u64,
    /// Anticipation times, seconds, ascending.
    pub anticipation: Vec<f64>,
    /// Objects learned of while hidden that the ego never saw before the run ended.
    pub never_seen: u64,
    /// Anticipation times had the RSUs sent the ETSI baseline's messages
    /// instead, seconds, ascending.
    pub baseline_anticipation: Vec<f64>,
    /// Object-cycles perceived by the RSUs, in the cycles the shares count.
    pub perceived: u64,
    /// Object-cycles sent to the ego, in the cycles the shares count.
    pub transmitted: u64,
    /// Object-cycles sent with at least one label, in the cycles the shares count.
    pub labelled: u64,
    /// Sent object-cycles by label.
    pub labels: LabelCounts,
    /// Bytes of semantic messages sent.
    pub bytes: u64,
    /// Bytes the ETSI baseline would have sent.
    pub baseline_bytes: u64,
    /// Object-cycles the ETSI baseline would have sent.
    pub baseline_objects: u64,
    /// Semantic messages sent to the ego.
    pub messages: u64,
    /// Semantic messages the ego received.
    pub delivered: u64,
    /// Messages sent and received by RSU–ego distance: entry i covers
    /// [i, i + 1) × 25 metres (the engine's `DELIVERY_BIN`).
    pub delivery_by_distance: Vec<DeliveryBin>,
    /// Objects coming within d_min of the ego (once per approach).
    pub close_approaches: u64,
    /// Close approaches with no conflict flagged to the ego beforehand.
    pub missed_criticals: u64,
    /// Seconds the ego drove cautiously after a flagged conflict.
    pub cautious_time: f64,
    /// The first 1000 close approaches (`MAX_OBJECT_RECORDS`), by run, then
    /// in order of time; `close_approaches` counts them all.
    pub approaches: Vec<CloseApproach>,
}

/// A road user coming within d_min of the ego.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct CloseApproach {
    /// The pooled run it happened in (0: the run with the point's own seed).
    pub run: u32,
    /// The road user's agent id.
    pub id: String,
    /// The step it came within d_min of the ego, seconds.
    pub at: f64,
    /// When the first message flagging a conflict with it reached the ego,
    /// seconds; `null` when none did before `at`.
    pub flagged: Option<f64>,
    /// `at − flagged`, seconds (what `per_object: warning_time` judges);
    /// `null` when it was never flagged.
    pub warning_time: Option<f64>,
}

/// Sent object-cycles by label.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct LabelCounts {
    /// NLoS behind a static occluder.
    pub nlos_static: u64,
    /// NLoS behind other road users only.
    pub nlos_dynamic: u64,
    /// Interaction relevance.
    pub relevant: u64,
    /// Dangerous drivers.
    pub speeding: u64,
    /// Predicted conflicts.
    pub conflict: u64,
}

/// Packet delivery in one distance bin.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct DeliveryBin {
    /// Messages sent.
    pub sent: u64,
    /// Messages received.
    pub received: u64,
}

/// Objects known to the ego only through an RSU, in one traffic-density bin.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct DensityRow {
    /// Lower edge of the bin, objects per km (bins are 10 objects per km wide:
    /// the engine's `DENSITY_BIN`).
    pub from: f64,
    /// Steps in the bin.
    pub steps: usize,
    /// Median objects known only through an RSU.
    pub median: f64,
    /// Mean objects known only through an RSU.
    pub mean: f64,
}
