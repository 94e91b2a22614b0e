//! The compiled scenario: typed, validated, defaults filled in. Nothing downstream
//! re-validates it.

mod field;
mod fusion;
mod metric;
mod metric_values;
mod requirement;
mod scenario;
mod semantic;
mod system;
mod trend;
mod unit;
mod v2x;
mod vary;
mod world;

pub use field::{ErrorModel, Field, Layout, Masses, Truth};
pub use fusion::{
    Decision, DecisionRule, Fusion, FusionMethod, Rule, SourceCombination, Switch, SwitchMeasure, WeightScaling,
    Weighting,
};
pub use metric::{JointPart, Metric};
pub use requirement::{
    Bound, Check, Comparison, Invariant, ObjectProperty, ObjectSelection, OverSeeds, RateBound, Reference, Requirement,
    Signal, Statistic, Temporal,
};
pub(crate) use scenario::grid_every;
pub use scenario::{
    Assignment, Axis, DEFAULT_START, Document, Experiment, Grid, Import, ImportKind, Label, Occupancy, Paper, Point,
    Record, RecordedPoints, Scenario, Settings, Setup, Sweep, display_value,
};
pub use semantic::{
    Area, Baseline, Caution, Crosswalk, Driving, Following, InteractionArea, LabelledBy, PedestrianTraffic, RiskScope,
    RsuSight, Semantic, ShareCycles, Traffic, TrafficRoute, VehicleTraffic,
};
pub use system::SystemUnderTest;
pub use trend::Trend;
pub use unit::{Unit, ValueDomain};
pub use v2x::{
    Channel, MESSAGE_HEADER_BYTES, Messages, Oversize, PathLossModel, SENSOR_INFORMATION_BYTES, SMALLEST_PAYLOAD_BYTES,
    V2x,
};
pub use vary::{Domain, MAX_WHOLE_END, RANGE_STEPS, Vary};
pub use world::{
    Agent, AgentKind, Direction, Entry, LaneLink, Localization, Motion, Occluder, Odometry, OdometryModel,
    OdometryNoise, Perception, PoseFilter, Road, Sensor, TraceSample, World,
};
