//! The physical range of every number a scenario gives: one [`Range`] per kind
//! of quantity, each chosen so that no real scenario meets its bounds and every
//! value inside them keeps the simulation finite and its loops short
//! (`docs/limits.md` gives each bound's reason).
//!
//! A raw field names its range once, for the JSON Schema
//! (`#[schemars(transform = range::SPEED.schema())]` writes `minimum`, `maximum` or
//! their exclusive forms on the number, or on every number of a point or a
//! list), and `compile` checks the value against the same constant, so the
//! schema an editor reads and the errors `check` reports cannot disagree.

use schemars::Schema;
use serde_json::Value;

/// An interval of allowed values: its least and greatest value, each allowed or
/// excluded, and the unit of the quantity (the schema's `unit`, which the
/// report writes beside a swept value).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Range {
    pub(crate) min: f64,
    pub(crate) min_included: bool,
    pub(crate) max: f64,
    pub(crate) max_included: bool,
    /// The unit's symbol (`m`, `s`, `1` for a pure number); empty where the
    /// range serves quantities of several units (each key's description says).
    pub(crate) unit: &'static str,
}

impl Range {
    /// [min, max].
    const fn closed(min: f64, max: f64) -> Self {
        Self {
            min,
            min_included: true,
            max,
            max_included: true,
            unit: "",
        }
    }

    /// (min, max].
    const fn left_open(min: f64, max: f64) -> Self {
        Self {
            min,
            min_included: false,
            max,
            max_included: true,
            unit: "",
        }
    }

    /// [min, max).
    const fn right_open(min: f64, max: f64) -> Self {
        Self {
            min,
            min_included: true,
            max,
            max_included: false,
            unit: "",
        }
    }

    /// (min, max).
    const fn open(min: f64, max: f64) -> Self {
        Self {
            min,
            min_included: false,
            max,
            max_included: false,
            unit: "",
        }
    }

    /// The same range, of a quantity in `unit`.
    const fn unit(self, unit: &'static str) -> Self {
        Self { unit, ..self }
    }

    /// Whether `value` lies in the range (never for NaN).
    pub(crate) fn contains(&self, value: f64) -> bool {
        let above = if self.min_included {
            value >= self.min
        } else {
            value > self.min
        };
        let below = if self.max_included {
            value <= self.max
        } else {
            value < self.max
        };
        above && below
    }

    /// What a value below the range should have been: `a number > 0`, `a number ≥ 1`.
    pub(crate) fn lower(&self) -> String {
        format!("a number {} {}", if self.min_included { "≥" } else { ">" }, self.min)
    }

    /// What a value above the range should have been: `a number ≤ 150`.
    pub(crate) fn upper(&self) -> String {
        format!("a number {} {}", if self.max_included { "≤" } else { "<" }, self.max)
    }

    /// Writes the range into a field's schema, for
    /// `#[schemars(transform = range::SPEED.schema())]`.
    pub(crate) fn schema(self) -> impl FnMut(&mut Schema) {
        move |schema| self.write(schema)
    }

    /// Writes the range on every number of `schema`: the field's own, or each
    /// item's of a list or a point.
    fn write(&self, schema: &mut Schema) {
        let Some(object) = schema.as_object_mut() else {
            return;
        };
        let numeric = |t: &Value| t == "number" || t == "integer";
        let is_number = match &object.get("type") {
            Some(Value::Array(types)) => types.iter().any(numeric),
            Some(t) => numeric(t),
            None => false,
        };
        if is_number {
            let (min_key, max_key) = (
                if self.min_included {
                    "minimum"
                } else {
                    "exclusiveMinimum"
                },
                if self.max_included {
                    "maximum"
                } else {
                    "exclusiveMaximum"
                },
            );
            object.insert(min_key.into(), number(self.min));
            object.insert(max_key.into(), number(self.max));
            if !self.unit.is_empty() {
                object.insert("unit".into(), self.unit.into());
            }
        }
        if let Some(items) = object.get_mut("items").and_then(|i| <&mut Schema>::try_from(i).ok()) {
            self.write(items);
        }
    }

    /// The range in words: `a number from 0 to 1`, `a number > 0 and ≤ 150`.
    pub(crate) fn words(&self) -> String {
        if self.min_included && self.max_included {
            format!("a number from {} to {}", self.min, self.max)
        } else {
            format!("{} and {}", self.lower(), self.upper().trim_start_matches("a number "))
        }
    }
}

/// A bound as JSON: a whole number without a fraction (`1000000`, not `1000000.0`).
fn number(value: f64) -> Value {
    if value.fract() == 0.0 && value.abs() < 9.0e15 {
        Value::from(value as i64)
    } else {
        Value::from(value)
    }
}

// Place and size.

/// A coordinate of a point in the world frame, metres.
pub(crate) const COORDINATE: Range = Range::closed(-1.0e6, 1.0e6).unit("m");
/// A distance at the scale of the map (a grid side, a region's radius, a
/// distance band, a proximity), metres.
pub(crate) const EXTENT: Range = Range::left_open(0.0, 2.0e6).unit("m");
/// Where along its way an agent appears, metres.
pub(crate) const OFFSET: Range = Range::closed(0.0, 1.0e7).unit("m");
/// The side of a grid cell, metres.
pub(crate) const CELL: Range = Range::left_open(0.0, 1.0e4).unit("m");
/// The size of a road user, a lane, a crossing, a conflict distance, metres.
pub(crate) const BODY: Range = Range::left_open(0.0, 100.0).unit("m");
/// The length of an imported SUMO vehicle type, metres: SUMO's rail types are
/// 109.5 to 200 m long by default, and a freight train kilometres.
pub(crate) const VEHICLE_LENGTH: Range = Range::left_open(0.0, 1.0e4).unit("m");
/// A gap or a walk that may be 0, metres.
pub(crate) const GAP: Range = Range::closed(0.0, 1000.0).unit("m");
/// Where a sensor sits on its agent, metres from the agent's centre.
pub(crate) const MOUNT: Range = Range::closed(-100.0, 100.0).unit("m");
/// The radius of an arc or a roundabout, metres.
pub(crate) const RADIUS: Range = Range::closed(1.0, 1.0e6).unit("m");
/// The range of a sensor, metres.
pub(crate) const SENSOR_RANGE: Range = Range::left_open(0.0, 1.0e4).unit("m");
/// The number of lanes of a road.
pub(crate) const LANES: Range = Range::closed(1.0, 16.0).unit("1");

// Angles.

/// A heading or an angle of an arc's start, degrees.
pub(crate) const ANGLE: Range = Range::closed(-360.0, 360.0).unit("°");
/// The angle of an arc's end (within a turn of its start), degrees.
pub(crate) const ARC_END: Range = Range::closed(-720.0, 720.0).unit("°");
/// A field of view, degrees.
pub(crate) const FIELD_OF_VIEW: Range = Range::left_open(0.0, 360.0).unit("°");
/// The angle between two rays that carve free space, degrees.
pub(crate) const RAY_SPACING: Range = Range::closed(0.01, 10.0).unit("°");
/// A change of heading that triggers a message, degrees.
pub(crate) const HEADING_CHANGE: Range = Range::left_open(0.0, 180.0).unit("°");
/// A σ of an angle, degrees.
pub(crate) const ANGLE_SIGMA: Range = Range::closed(0.0, 180.0).unit("°");
/// A σ of a turn rate, degrees per second (the bounds of [`ANGLE_SIGMA`]).
pub(crate) const TURN_RATE_SIGMA: Range = ANGLE_SIGMA.unit("°/s");
/// A process noise σ of a heading, degrees: at least 1e-6, so that its
/// square stays a positive number and the pose filter's matrices stay
/// invertible (σ = 1e-200 squares to 0).
pub(crate) const PROCESS_ANGLE_SIGMA: Range = Range::closed(1.0e-6, 180.0).unit("°/√s");

// Time.

/// The length of a run, seconds.
pub(crate) const DURATION: Range = Range::left_open(0.0, 86_400.0).unit("s");
/// The time between two steps, seconds.
pub(crate) const STEP: Range = Range::closed(0.001, 60.0).unit("s");
/// A time within a run, or a span that may be 0, seconds.
pub(crate) const TIME: Range = Range::closed(0.0, 86_400.0).unit("s");
/// A span that must be positive, seconds.
pub(crate) const SPAN: Range = Range::left_open(0.0, 86_400.0).unit("s");
/// A short reaction or prediction span (headway, horizon, latency), seconds.
pub(crate) const REACTION: Range = Range::left_open(0.0, 60.0).unit("s");
/// A delay that may be 0, seconds.
pub(crate) const LATENCY: Range = Range::closed(0.0, 60.0).unit("s");
/// A time of an imported trace, seconds.
pub(crate) const TRACE_TIME: Range = Range::closed(0.0, 1.0e9).unit("s");
/// A rate of cycles or pictures, Hz.
pub(crate) const RATE: Range = Range::left_open(0.0, 1000.0).unit("Hz");
/// The generation rate of collective perception messages, Hz: ETSI TS 103 324
/// generates a CPM every 100 ms to 1000 ms (50 ms for a roadside unit).
pub(crate) const MESSAGE_RATE: Range = Range::closed(1.0, 20.0).unit("Hz");
/// The size limit of a message, bytes: room for a header (121 bytes), a
/// sensor and a few cells, up to the largest IP packet.
pub(crate) const MESSAGE_BYTES: Range = Range::closed(200.0, 65_535.0).unit("B");
/// A rate that may be 0 (none), Hz.
pub(crate) const RATE_OR_ZERO: Range = Range::closed(0.0, 1000.0).unit("Hz");

// Motion.

/// A speed, m/s.
pub(crate) const SPEED: Range = Range::closed(0.0, 150.0).unit("m/s");
/// A speed that must be positive (a limit, a walking speed, a change), m/s.
pub(crate) const SPEED_POSITIVE: Range = Range::left_open(0.0, 150.0).unit("m/s");
/// An acceleration or a deceleration, m/s².
pub(crate) const ACCELERATION: Range = Range::left_open(0.0, 100.0).unit("m/s²");
/// A factor on a speed (a limit factor, a speed hypothesis).
pub(crate) const SPEED_FACTOR: Range = Range::left_open(0.0, 10.0).unit("1");
/// A non-compliant driver's factor on the speed limit.
pub(crate) const OVERSPEED_FACTOR: Range = Range::closed(1.0, 10.0).unit("1");

// Traffic.

/// Vehicles per km of a route.
pub(crate) const DENSITY: Range = Range::closed(0.0, 500.0).unit("veh/km");
/// Pedestrian arrivals per minute at a crosswalk.
pub(crate) const ARRIVALS: Range = Range::closed(0.0, 600.0).unit("1/min");
/// A relative frequency of a vehicle kind.
pub(crate) const SHARE: Range = Range::closed(0.0, 1.0e6).unit("1");

// Noise.

/// A σ at distance 0, in the unit of what it disturbs (m, m/s): a sensor's
/// noise, whose one schema serves position, size and velocity.
pub(crate) const SIGMA: Range = Range::closed(0.0, 100.0);
/// A σ of a position, m.
pub(crate) const POSITION_SIGMA: Range = SIGMA.unit("m");
/// A σ of a speed reading, m/s.
pub(crate) const SPEED_SIGMA: Range = SIGMA.unit("m/s");
/// A process noise σ of a position, m: at least 1e-6, so that its square
/// stays a positive number and the pose filter's matrices stay invertible.
pub(crate) const PROCESS_SIGMA: Range = Range::closed(1.0e-6, 100.0).unit("m/√s");
/// The scale error of an odometry speed reading, a fraction of the true speed:
/// a speedometer may read up to 10 % (plus 4 km/h) fast and never slow (UNECE
/// Regulation No. 39); odometry off by more is broken, not noisy.
pub(crate) const SPEED_SCALE_ERROR: Range = Range::closed(-0.1, 0.1).unit("1");
/// The offset of a yaw-rate reading, degrees per second: above the 3.75 °/s an
/// automotive yaw-rate sensor may drift over its life before the stability
/// control compensates it.
pub(crate) const YAW_RATE_OFFSET: Range = Range::closed(-5.0, 5.0).unit("°/s");
/// The growth of a σ per metre of distance, in the unit of what it disturbs
/// per metre.
pub(crate) const SIGMA_PER_M: Range = Range::closed(0.0, 1.0);

// Probabilities and the evidence model.

/// A probability or a share.
pub(crate) const PROBABILITY: Range = Range::closed(0.0, 1.0).unit("1");
/// A probability that must be positive (a share of speed).
pub(crate) const PROBABILITY_POSITIVE: Range = Range::left_open(0.0, 1.0).unit("1");
/// The share of seeds a check over seeds requires to hold: above 0, and
/// below 1, since the lower confidence bound of a share is below 1 even with
/// every seed holding (Clopper–Pearson's (1 − c)^(1/n)), so 1 could never pass.
pub(crate) const SHARE_OF_SEEDS: Range = Range::open(0.0, 1.0).unit("1");
/// A probability strictly between 0 and 1.
pub(crate) const PROBABILITY_OPEN: Range = Range::open(0.0, 1.0).unit("1");
/// The probability of occupancy a detection conveys.
pub(crate) const OCCUPIED: Range = Range::open(0.5, 1.0).unit("1");
/// The probability of occupancy a free ray conveys.
pub(crate) const FREE: Range = Range::open(0.0, 0.5).unit("1");
/// A confidence level.
pub(crate) const CONFIDENCE: Range = Range::open(0.5, 1.0).unit("1");
/// The sum of the Dirichlet parameters of the mass model.
pub(crate) const CONCENTRATION: Range = Range::closed(1.0, 1.0e12).unit("1");
/// γ, the growth of misdetection with distance (ε0 + γ/100 < 1 is checked too).
pub(crate) const GAMMA: Range = Range::right_open(0.0, 100.0).unit("%");
/// The hybrid rule's switch: metres (difference) or a ratio ≥ 1.
pub(crate) const SWITCH: Range = Range::closed(0.0, 2.0e6);
/// The numerical tolerance of an invariant.
pub(crate) const TOLERANCE: Range = Range::closed(0.0, 1.0).unit("1");

// Radio.

/// A transmit power, dBm.
pub(crate) const POWER: Range = Range::closed(-100.0, 100.0).unit("dBm");
/// A receiver sensitivity, dBm.
pub(crate) const SENSITIVITY: Range = Range::closed(-200.0, 0.0).unit("dBm");
/// A loss or a σ of shadowing, dB.
pub(crate) const DECIBELS: Range = Range::closed(0.0, 100.0).unit("dB");
/// A carrier frequency, GHz.
pub(crate) const CARRIER: Range = Range::left_open(0.0, 100.0).unit("GHz");
/// An antenna height, metres.
pub(crate) const ANTENNA: Range = Range::left_open(0.0, 1000.0).unit("m");

/// Wall-clock time a system under test may take to answer one step.
pub(crate) const SUT_TIMEOUT: Range = Range::closed(0.001, 3600.0).unit("s");
/// A sensor's index on its agent (a system under test's `sensors`).
pub(crate) const SENSOR_INDEX: Range = Range::right_open(0.0, 1000.0).unit("1");
/// The distance within which a system under test's detection matches a road user.
pub(crate) const SUT_GATE: Range = Range::left_open(0.0, 100.0).unit("m");

// Counts.

/// Sensors in a field's regular layout or drawn at random (also a row or a column).
pub(crate) const SENSOR_COUNT: Range = Range::closed(1.0, 1000.0).unit("1");
/// Independent runs a point pools.
pub(crate) const RUNS: Range = Range::closed(1.0, 1000.0).unit("1");
/// Seeds a check runs over.
pub(crate) const SEEDS: Range = Range::closed(2.0, 10_000.0).unit("1");

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_are_included_or_excluded_as_declared() {
        assert!(PROBABILITY.contains(0.0) && PROBABILITY.contains(1.0));
        assert!(!BODY.contains(0.0) && BODY.contains(100.0) && !BODY.contains(100.5));
        assert!(!OCCUPIED.contains(0.5) && !OCCUPIED.contains(1.0) && OCCUPIED.contains(0.7));
        assert!(!SPEED.contains(f64::NAN) && !SPEED.contains(f64::INFINITY));
    }

    #[test]
    fn words_name_each_side() {
        assert_eq!(PROBABILITY.words(), "a number from 0 to 1");
        assert_eq!(BODY.words(), "a number > 0 and ≤ 100");
        assert_eq!(BODY.lower(), "a number > 0");
        assert_eq!(COORDINATE.upper(), "a number ≤ 1000000");
    }

    #[test]
    fn the_schema_of_a_point_bounds_each_coordinate() {
        let mut schema = schemars::json_schema!({
            "type": "array",
            "items": { "type": "number", "format": "double" },
            "minItems": 2,
            "maxItems": 2
        });
        COORDINATE.write(&mut schema);
        assert_eq!(schema.get("minimum"), None);
        assert_eq!(schema.get("items").unwrap()["minimum"], -1_000_000);
        assert_eq!(schema.get("items").unwrap()["maximum"], 1_000_000);
        let mut optional = schemars::json_schema!({ "type": ["number", "null"] });
        BODY.write(&mut optional);
        assert_eq!(optional.get("exclusiveMinimum").unwrap(), 0);
        assert_eq!(optional.get("maximum").unwrap(), 100);
    }
}
