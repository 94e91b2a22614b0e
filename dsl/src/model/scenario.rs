//! The scenario as a whole: its sweep points and what each simulates.

use std::collections::BTreeMap;
use std::sync::Arc;

use serde::Serialize;

use super::{Decision, Field, Fusion, Reference, Requirement, World};

/// A compiled scenario file: one or more sweep points, the requirements checked on
/// them and published figures to compare with.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Scenario {
    /// The file as the user named it.
    pub file: String,
    /// Human-readable name.
    pub name: String,
    /// Free text describing the scenario.
    pub description: String,
    /// The sweeps in file order: one for `sweep`, one per entry of `sweeps`, none
    /// without either.
    pub sweeps: Vec<Sweep>,
    /// Every configuration the sweeps simulate, each once, in order of first
    /// appearance: sweep by sweep, each sweep's combinations with its first axis
    /// outermost (one point without a sweep). Combinations that compile to the
    /// same [`Setup`] share one point, which carries each one's [`Label`].
    pub points: Vec<Point>,
    /// Requirements in file order.
    pub requirements: Vec<Requirement>,
    /// Published figures, in file order.
    pub references: Vec<Reference>,
    /// The files the scenario imports (`traces`, `map`), in the order read.
    pub imports: Vec<Import>,
    /// The settings `sightline falsify` varies, in file order (`run` ignores them).
    pub vary: Vec<super::Vary>,
    /// What `sightline run` records into `run.mcap`; `None`: no recording.
    pub record: Option<Record>,
    /// The user's own system judged on what it detects; `None`: the scenario
    /// judges sightline's models only.
    pub system_under_test: Option<super::SystemUnderTest>,
    /// What the run leaves out or cannot vouch for though it runs (elements of
    /// imported files dropped, types read by their names, a trace that does
    /// not cover the run), in the order found.
    pub warnings: Vec<crate::Warning>,
    /// The report as a controlled document (language section `document`).
    pub document: Document,
}

/// The report as a controlled document: who wrote, reviewed and approved it,
/// its version and its paper (language section `document`).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize)]
pub struct Document {
    /// The document's version as the organisation numbers it.
    pub version: Option<String>,
    /// Its author.
    pub author: Option<String>,
    /// Its reviewer.
    pub reviewer: Option<String>,
    /// Its approver.
    pub approver: Option<String>,
    /// The paper it is laid out for when printed.
    pub paper: Paper,
}

/// The paper a report is laid out for when printed.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Paper {
    /// ISO A4, 210 × 297 mm (the default).
    #[default]
    A4,
    /// US Letter, 8.5 × 11 in.
    Letter,
}

impl Paper {
    /// The CSS `@page` size: `A4` or `letter`.
    pub fn css(self) -> &'static str {
        match self {
            Self::A4 => "A4",
            Self::Letter => "letter",
        }
    }
}

/// What `sightline run` records into `run.mcap` (language section `record`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Record {
    /// The recorded point, an index into [`Scenario::points`]: the one the file
    /// names, or else the first until the run is judged (see `named`).
    pub point: usize,
    /// Whether the file names the recorded point (`point` or `where`). When it
    /// does not and the scenario has several points, `sightline run` records
    /// the worst point of the first requirement that fails the run
    /// ([`at_point`](Self::at_point)), or the first point when none does.
    pub named: bool,
    /// Fused grids recorded per simulated second, Hz (0: none).
    pub grid_rate: f64,
    /// Steps between recorded grids (grids at steps 0, `every`, 2 · `every`, …);
    /// `None` when no grid is recorded: a rate of 0, or a point without steps
    /// (the field experiment).
    pub grid_every: Option<usize>,
    /// Whether each cooperating agent's own grid is recorded too, at the grid rate.
    pub agent_grids: bool,
    /// When step 0 happens (`time.start`), nanoseconds since
    /// 1970-01-01T00:00:00Z: the recording's clock. [`DEFAULT_START`] when the
    /// file does not say.
    pub start: u64,
    /// Which points are recorded step by step (`record.points`).
    pub points: RecordedPoints,
    /// With every point recorded: the time from one point's step 0 to the
    /// next's, nanoseconds (the longest point's duration and a second, rounded
    /// up to a whole minute); 0 with one point recorded.
    pub slot: u64,
}

/// Which sweep points a recording holds step by step (`record.points`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RecordedPoints {
    /// One: the point `point` or `where` names, or the worst point of the
    /// first requirement that fails the run (the first point when none does).
    #[default]
    One,
    /// Every sweep point, one after another on the recording's clock.
    All,
}

/// The recording's clock when a scenario gives no `time.start`:
/// 2000-01-01T00:00:00Z, in nanoseconds since 1970-01-01T00:00:00Z. A fixed
/// epoch rather than the run's wall-clock start, so that the same scenario and
/// seed give the same recording, byte for byte (results.json holds its hash).
pub const DEFAULT_START: u64 = 946_684_800_000_000_000;

impl Record {
    /// The same recording of point `point` of `points` instead: grids at the
    /// same rate, at most one per step of that point.
    ///
    /// # Panics
    ///
    /// If `point` is not an index of `points`.
    pub fn at_point(&self, points: &[Point], point: usize) -> Self {
        Self {
            point,
            grid_every: grid_every(&points[point], self.grid_rate),
            ..*self
        }
    }

    /// The points recorded step by step, in the order recorded, of a
    /// scenario of `count` points.
    pub fn recorded(&self, count: usize) -> std::ops::Range<usize> {
        match self.points {
            RecordedPoints::One => self.point..self.point + 1,
            RecordedPoints::All => 0..count,
        }
    }

    /// When step 0 of point `point` is on the recording's clock, nanoseconds
    /// since 1970: `start` for the one recorded point, `start + point · slot`
    /// with every point recorded.
    pub fn start_of(&self, point: usize) -> u64 {
        match self.points {
            RecordedPoints::One => self.start,
            RecordedPoints::All => self.start.saturating_add(self.slot.saturating_mul(point as u64)),
        }
    }

    /// Whether the grids of `step` are recorded.
    pub fn grids_at(&self, step: usize) -> bool {
        self.grid_every.is_some_and(|every| step.is_multiple_of(every))
    }
}

/// Steps between recorded grids of `point` at `grid_rate` grids per simulated
/// second, at most one per step; `None` at a rate of 0 or without steps.
pub(crate) fn grid_every(point: &Point, grid_rate: f64) -> Option<usize> {
    match &point.setup.experiment {
        Experiment::World(world) if grid_rate > 0.0 => Some(((1.0 / world.step / grid_rate).round() as usize).max(1)),
        Experiment::World(_) | Experiment::Field(_) => None,
    }
}

/// A file a scenario imports, as it was read.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Import {
    /// What it holds.
    pub kind: ImportKind,
    /// Its path: the scenario file's directory joined with the path written in
    /// the scenario.
    pub path: String,
    /// Its bytes, which the recording attaches.
    #[serde(skip)]
    pub bytes: Vec<u8>,
    /// SHA-256 of its bytes, by which the evidence names it (results.json's
    /// `inputs`, the recording's `/sightline/scenario`): computed once, as it
    /// is read.
    #[serde(skip)]
    pub sha256: [u8; 32],
    /// Whether the scenario names it under `traces` (else the configuration
    /// `traces.sumocfg` names it).
    pub named: bool,
}

/// Kinds of imported file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ImportKind {
    /// SUMO floating car data (`traces.fcd`).
    SumoFcd,
    /// A SUMO network (`traces.net`).
    SumoNet,
    /// SUMO polygons, points of interest and vehicle types (`traces.poly`, a
    /// configuration's `additional-files`).
    SumoPoly,
    /// A SUMO configuration (`traces.sumocfg`).
    SumoConfig,
    /// SUMO routes, for their vehicle types (`traces.routes`, a
    /// configuration's `route-files`).
    SumoRoutes,
    /// An OpenDRIVE road network (`map.opendrive`).
    OpenDrive,
}

impl ImportKind {
    /// Its key under its section: `fcd`, `net`, `poly`, `sumocfg`, `routes`,
    /// `opendrive`.
    pub fn key(self) -> &'static str {
        match self {
            Self::SumoFcd => "fcd",
            Self::SumoNet => "net",
            Self::SumoPoly => "poly",
            Self::SumoConfig => "sumocfg",
            Self::SumoRoutes => "routes",
            Self::OpenDrive => "opendrive",
        }
    }

    /// The section that names it: `traces` or `map`.
    pub fn section(self) -> &'static str {
        match self {
            Self::SumoFcd | Self::SumoNet | Self::SumoPoly | Self::SumoConfig | Self::SumoRoutes => "traces",
            Self::OpenDrive => "map",
        }
    }

    /// Its name in evidence: `sumo_fcd`, `sumo_net`, `sumo_poly`, `sumo_config`,
    /// `sumo_routes`, `opendrive`.
    pub fn name(self) -> &'static str {
        match self {
            Self::SumoFcd => "sumo_fcd",
            Self::SumoNet => "sumo_net",
            Self::SumoPoly => "sumo_poly",
            Self::SumoConfig => "sumo_config",
            Self::SumoRoutes => "sumo_routes",
            Self::OpenDrive => "opendrive",
        }
    }
}

/// One sweep: settings varied together, one row per combination of values.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sweep {
    /// The swept settings, in file order.
    pub axes: Vec<Axis>,
    /// Its rows, one per combination of values with the first axis outermost:
    /// the index in [`Scenario::points`] of the point that simulates each. A point
    /// another sweep reaches too (the same configuration) is listed by both.
    pub points: Vec<usize>,
}

impl Sweep {
    /// Its rows in order: the point that simulates each and the value of each
    /// axis there, in axis order.
    pub fn rows(&self) -> impl Iterator<Item = (usize, Vec<&serde_json::Value>)> {
        self.points.iter().enumerate().map(|(row, &point)| {
            // The row number written in mixed radix, the last axis the fastest digit.
            let mut rest = row;
            let mut values: Vec<&serde_json::Value> = self
                .axes
                .iter()
                .rev()
                .map(|axis| {
                    let value = &axis.values[rest % axis.values.len()];
                    rest /= axis.values.len();
                    value
                })
                .collect();
            values.reverse();
            (point, values)
        })
    }
}

/// One swept setting and its values.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Axis {
    /// Dotted path of the setting (`field.masses.gamma`).
    pub path: String,
    /// The values, as written.
    pub values: Vec<serde_json::Value>,
}

/// One simulation: a configuration, and every sweep combination that gives it.
///
/// Two combinations are the same configuration when their compiled [`Setup`]s
/// are equal and serialize to the same bytes (so 0 and −0 stay apart). The
/// setup is what the engine is given, and all it is given: equal setups are the
/// same run, bit for bit. Its one name, the fusion label, is compared too, as
/// reports show it as the point's method. The effective settings (see
/// [`Label::settings`]) are not the test: they also hold how a value was written
/// and keys the compiler resolves away, which do not change the run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Point {
    /// Position in [`Scenario::points`].
    pub index: usize,
    /// The combinations that give this configuration, in sweep and row order: one,
    /// or several where sweeps meet; one without assignments without a sweep.
    pub labels: Vec<Label>,
    /// What to simulate.
    pub setup: Setup,
}

impl Point {
    /// A short label such as `field.masses.gamma=6, fusion=Proposed`, each
    /// combination's joined with ` | ` where sweeps meet; empty without a sweep.
    pub fn label(&self) -> String {
        self.labels
            .iter()
            .map(Label::text)
            .filter(|text| !text.is_empty())
            .collect::<Vec<_>>()
            .join(" | ")
    }
}

/// One sweep combination a point stands for.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Label {
    /// The sweep it belongs to (`None` without a sweep).
    pub sweep: Option<usize>,
    /// The value of each sweep axis, in axis order.
    pub assignments: Vec<Assignment>,
    /// The effective settings (defaults filled in), matched by `where`
    /// filters: a point matches when one of its labels does.
    #[serde(skip)]
    pub settings: Settings,
}

/// The effective settings of a combination (defaults filled in) as JSON, top-level
/// section by section (`fusion`, `agents`, …). A section equal in several
/// combinations is shared, so a long sweep holds each distinct section once.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Settings(BTreeMap<String, Arc<serde_json::Value>>);

impl Settings {
    /// Settings of these sections.
    pub fn new(sections: BTreeMap<String, Arc<serde_json::Value>>) -> Self {
        Self(sections)
    }

    /// The setting at a dotted path (`fusion.method`, `agents.ego.speed.target`).
    pub fn get(&self, dotted: &str) -> Option<&serde_json::Value> {
        let mut keys = dotted.split('.');
        let section = self.0.get(keys.next()?)?;
        keys.try_fold(&**section, |node, key| node.get(key))
    }

    /// The names of the sections.
    pub fn sections(&self) -> impl Iterator<Item = &str> {
        self.0.keys().map(String::as_str)
    }
}

impl Label {
    /// Its assignments as `field.masses.gamma=6, fusion=Proposed`; empty without a sweep.
    pub fn text(&self) -> String {
        self.assignments
            .iter()
            .map(|a| format!("{}={}", a.path, a.display))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// How a setting shows in tables and messages: a string unquoted, a whole number
/// without a decimal point (`6`, not `6.0`), a mapping by its `label` or else as
/// `{key=value …}`, a list as JSON.
pub fn display_value(value: &serde_json::Value) -> String {
    use serde_json::Value as J;
    match value {
        J::String(s) => s.clone(),
        J::Number(n) => match n.as_f64() {
            Some(f) if n.is_f64() && f.fract() == 0.0 && f.abs() < 1e15 => format!("{f:.0}"),
            _ => n.to_string(),
        },
        J::Object(map) => match map.get("label") {
            Some(J::String(label)) => label.clone(),
            _ => {
                let pairs: Vec<String> = map.iter().map(|(k, v)| format!("{k}={}", display_value(v))).collect();
                format!("{{{}}}", pairs.join(" "))
            }
        },
        other => other.to_string(),
    }
}

/// A sweep axis's value at one point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Assignment {
    /// Dotted path of the setting.
    pub path: String,
    /// The value as written.
    pub value: serde_json::Value,
    /// The value for tables: a mapping shows its `label`, a string shows unquoted.
    pub display: String,
}

/// Everything one simulation needs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Setup {
    /// Seed of every random stream.
    pub seed: u64,
    /// What is simulated.
    pub experiment: Experiment,
    /// The occupancy grid and how evidence is fused into it: present in the
    /// field experiment and in a world measuring collective perception, `None`
    /// in a semantic world, which fuses no grid.
    pub occupancy: Option<Occupancy>,
}

/// An occupancy grid, the rule that fuses evidence into it and the rule that
/// decides each fused cell (language sections `grid`, `fusion`, `decision`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Occupancy {
    /// The grid.
    pub grid: Grid,
    /// How evidence is fused.
    pub fusion: Fusion,
    /// How a fused cell is turned into a decision.
    pub decision: Decision,
}

/// What a scenario simulates.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Experiment {
    /// The static evidential-grid experiment of seed 001.
    Field(Field),
    /// A traffic scene with agents, sensors and collective perception (seed 000).
    World(Box<World>),
}

/// A regular grid of square cells, axis-aligned in the world frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Grid {
    /// World position of the lower-left corner, metres.
    pub origin: [f64; 2],
    /// Side of a cell, metres.
    pub cell: f64,
    /// Number of cells along x.
    pub cols: usize,
    /// Number of cells along y.
    pub rows: usize,
}

impl Grid {
    /// Number of cells.
    pub fn cells(&self) -> usize {
        self.cols * self.rows
    }

    /// World position of the centre of cell (`col`, `row`), metres.
    pub fn cell_center(&self, col: usize, row: usize) -> [f64; 2] {
        [
            self.origin[0] + (col as f64 + 0.5) * self.cell,
            self.origin[1] + (row as f64 + 0.5) * self.cell,
        ]
    }
}

#[cfg(test)]
mod tests {
    use serde_json::json;

    use super::display_value;

    #[test]
    fn settings_display_as_written() {
        assert_eq!(display_value(&json!(6)), "6");
        assert_eq!(display_value(&json!(6.0)), "6");
        assert_eq!(display_value(&json!(0.25)), "0.25");
        assert_eq!(display_value(&json!("bayes")), "bayes");
        assert_eq!(
            display_value(&json!({"label": "Proposed", "method": "hybrid"})),
            "Proposed"
        );
        assert_eq!(
            display_value(&json!({"method": "hybrid", "switch": {"threshold": 50}})),
            "{method=hybrid switch={threshold=50}}"
        );
        assert_eq!(display_value(&json!([1, 2])), "[1,2]");
    }
}
