//! The top-level metrics of results.json (a value with its n, or one table per
//! sweep) and the map they and a point's metrics are written as, in insertion
//! order.

use std::borrow::Cow;

use schemars::{JsonSchema, Schema, SchemaGenerator, json_schema};
use serde::{Serialize, Serializer};

/// A metric in the top-level `metrics` map.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[serde(untagged)]
pub enum MetricEntry {
    /// The value of a scenario without sweep, with its n.
    Measured(Measured),
    /// The values over each sweep, one table per sweep.
    Tables(Vec<Table>),
}

/// A metric's value and its sample size.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Measured {
    /// The value (`null` where it is undefined: an empty population).
    pub value: Option<f64>,
    /// The number of samples it is computed over.
    pub n: u64,
}

/// A metric over one sweep: one row per combination of its values, the axis
/// values, then the metric (`null` where it is undefined) and its n.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Table {
    /// Index of the sweep in `sweeps`.
    pub sweep: usize,
    /// The axis paths, then `value` and `n`.
    pub columns: Vec<String>,
    /// One row per combination (a point several sweeps share is a row of each).
    pub rows: Vec<Vec<serde_json::Value>>,
}

/// A map that serializes its entries in insertion order.
#[derive(Debug, Clone, PartialEq)]
pub struct Ordered<T>(pub Vec<(String, T)>);

impl<T: Copy> Ordered<T> {
    /// The value under `key`.
    pub fn get(&self, key: &str) -> Option<T> {
        self.0.iter().find(|(k, _)| k == key).map(|(_, v)| *v)
    }
}

impl<T: Serialize> Serialize for Ordered<T> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_map(self.0.iter().map(|(k, v)| (k, v)))
    }
}

/// A JSON object whose every value is a `T` (the keys are the map's own).
impl<T: JsonSchema> JsonSchema for Ordered<T> {
    fn inline_schema() -> bool {
        true
    }

    fn schema_name() -> Cow<'static, str> {
        format!("Map_of_{}", T::schema_name()).into()
    }

    fn json_schema(generator: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "type": "object",
            "additionalProperties": generator.subschema_for::<T>(),
        })
    }
}

/// The unit of a metric by name (`1` for a name that is not a metric).
pub(crate) fn metric_unit(name: &str) -> &'static str {
    sightline_dsl::Metric::ALL
        .iter()
        .find(|m| m.name() == name)
        .map_or("1", |m| m.unit().symbol())
}
