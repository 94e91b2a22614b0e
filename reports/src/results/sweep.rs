//! The sweeps of a run as results.json writes them: the settings each varies,
//! their values, and the point that simulates each row.

use serde::Serialize;

/// One sweep: settings varied together, one row per combination of values.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Sweep {
    /// The swept settings, in file order.
    pub axes: Vec<Axis>,
    /// Its rows, one per combination of values with the first axis outermost:
    /// the index in `sweep` of the point that simulates each.
    pub points: Vec<usize>,
    /// The same rows with the value of each axis there, for the report's tables
    /// and charts (not written: `axes` and `points` give them).
    #[serde(skip)]
    pub rows: Vec<SweepRow>,
}

/// One swept setting and its values.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Axis {
    /// Dotted path of the setting (`field.masses.gamma`).
    pub path: String,
    /// The values, as written.
    pub values: Vec<serde_json::Value>,
    /// The unit of the values, as the language's schema gives the setting
    /// (`s`, `m`, `1` for a pure number); left out for a setting without one
    /// (a name, a count).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unit: Option<String>,
}

/// A row of a sweep: the point that simulates it and each axis's value there.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepRow {
    /// The point's index in `sweep`.
    pub point: usize,
    /// The value of each axis, in axis order.
    pub values: Vec<serde_json::Value>,
}
