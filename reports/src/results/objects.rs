//! The per-object record of a semantic point (or of a joint world's
//! pipeline) in results.json: every road user relevant to the ego with its
//! times, closest approach and category (the engine's `semantic::objects`
//! defines each), the counts by category, and the bound that keeps the
//! document small.

use serde::Serialize;

/// Most object records a point lists in results.json and in the recording
/// (about 0.5 MB of JSON); the rest are counted in [`ObjectList::omitted`],
/// and every record, listed or not, counts in the categories and the metrics.
/// A point lists as many close approaches at most
/// ([`SemanticCounts::approaches`](super::SemanticCounts::approaches)).
/// The bundled urban junction's densest point has 519 over its five runs.
pub const MAX_OBJECT_RECORDS: usize = 1000;

/// The relevant road users of a semantic point, over its pooled runs.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct ObjectList {
    /// Relevant road users, over the pooled runs (n of the category counts).
    pub relevant: u64,
    /// Of those, by category.
    pub categories: CategoryCounts,
    /// The first 1000 records (`MAX_OBJECT_RECORDS`), run by run, each run's
    /// in order of becoming relevant.
    pub records: Vec<ObjectResult>,
    /// Records past the first 1000, left out.
    pub omitted: u64,
}

/// Relevant road users by category, over the pooled runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct CategoryCounts {
    /// Named by a V2X message before the ego saw them.
    pub warned_before_seen: u64,
    /// Named by a V2X message, never seen by the ego.
    pub warned_never_seen: u64,
    /// Seen by the ego no later than any V2X message named them.
    pub seen_first: u64,
    /// Neither named nor seen.
    pub never_known: u64,
}

/// How the ego came to know a road user (the names tools read).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ObjectCategory {
    /// A V2X message named it strictly before the ego first saw it.
    WarnedBeforeSeen,
    /// A V2X message named it; the ego never saw it.
    WarnedNeverSeen,
    /// The ego saw it no later than the first V2X message naming it, or no
    /// message named it.
    SeenFirst,
    /// No message named it and the ego never saw it.
    NeverKnown,
}

impl ObjectCategory {
    /// The name as results.json writes it.
    pub fn name(self) -> &'static str {
        match self {
            Self::WarnedBeforeSeen => "warned_before_seen",
            Self::WarnedNeverSeen => "warned_never_seen",
            Self::SeenFirst => "seen_first",
            Self::NeverKnown => "never_known",
        }
    }
}

/// One relevant road user in one pooled run. Times are seconds from the start
/// of the run; `null`: it never happened.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct ObjectResult {
    /// The pooled run (0: the run with the point's own seed).
    pub run: u32,
    /// Its agent id.
    pub id: String,
    /// Its kind (`car`, `truck`, `bus`, `motorbike`, `pedestrian`).
    pub class: &'static str,
    /// Its length, metres.
    pub length: f64,
    /// Its width, metres.
    pub width: f64,
    /// When it came within `semantic.proximity` of the ego, or a message the
    /// ego received named it, whichever came first.
    pub first_relevant: f64,
    /// When the ego first saw it with its own sensors.
    pub first_seen: Option<f64>,
    /// When the first V2X message naming it (an RSU's, or its own) reached the ego.
    pub first_v2x: Option<f64>,
    /// When the first RSU message flagging a conflict with it reached the ego.
    pub first_warning: Option<f64>,
    /// In a joint world, when a cell of its footprint was first decided
    /// occupied in the ego's fused grid (`null`: never); absent elsewhere.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first_in_grid: Option<Option<f64>>,
    /// Its closest approach to the ego (`null` only if never in the scene with it).
    pub closest: Option<ClosestApproach>,
    /// Its least time to collision with the ego, seconds: over the steps it
    /// is within `semantic.proximity` of the ego, the first time the two
    /// oriented boxes, moving on at constant velocity without turning, touch
    /// (0: they overlapped or touched; `null`: never on a collision course).
    pub min_ttc: Option<f64>,
    /// Its greatest deceleration rate to avoid a crash over those steps,
    /// m/s²: the ego's closing speed along its heading over twice the TTC, at
    /// the steps its braking could avoid the contact (`null`: at none).
    pub max_drac: Option<f64>,
    /// Its post-encroachment time with the ego over those steps, seconds: the
    /// least time between one of the two leaving a spot both footprints
    /// covered and the other reaching it (0: they overlapped; `null`: no
    /// common spot).
    pub pet: Option<f64>,
    /// How the ego came to know it.
    pub category: ObjectCategory,
    /// Our anticipation time, seconds: first seen − first V2X
    /// (`warned_before_seen`), closest approach − first V2X, at least 0
    /// (`warned_never_seen`), `null` otherwise.
    pub anticipation: Option<f64>,
    /// When the first message naming it would have reached the ego had the
    /// RSUs sent the ETSI baseline's collective perception messages instead,
    /// seconds (`null`: none would have).
    pub baseline_v2x: Option<f64>,
    /// `anticipation` over the ETSI baseline's messages, seconds.
    pub baseline_anticipation: Option<f64>,
    /// The ids of the crosswalks, interaction areas and declared `areas` its
    /// centre was in with the ego in the scene (left out: none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub areas: Vec<String>,
}

/// Where and when a road user came closest to the ego.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct ClosestApproach {
    /// The time, seconds.
    pub time: f64,
    /// The distance between the centres, metres.
    pub distance: f64,
    /// The road user's centre then [x, y], metres.
    pub position: [f64; 2],
}
