//! What agents measure: sensor models (range, field of view, noise, mount) and
//! how connected agents localize themselves.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::range;
use crate::model::{OdometryModel, OdometryNoise, PoseFilter};

/// A sensor model, referred to by agents.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a sensor model mapping")]
#[schemars(rename = "SensorModel")]
pub(crate) struct RawSensorModel {
    /// Range, metres.
    #[schemars(transform = range::SENSOR_RANGE.schema())]
    pub range: f64,
    /// Horizontal field of view, degrees (360: all around).
    #[serde(default = "default_fov")]
    #[schemars(transform = range::FIELD_OF_VIEW.schema())]
    pub fov_deg: f64,
    /// Mounting pose in the agent frame (x forward, y left).
    #[serde(default)]
    pub mount: RawMount,
    /// Probability that a visible object in range is detected (0–1).
    #[serde(default = "default_detection_probability")]
    #[schemars(transform = range::PROBABILITY.schema())]
    pub detection_probability: f64,
    /// Standard deviation of a detection's position error, σ(d) = base + per_m · d
    /// (seed 002, eq. 1, with a linear σ(d)).
    #[serde(default)]
    pub position_noise: RawNoise,
    /// Standard deviation of the error of a detection's length and width,
    /// σ(d) = base + per_m · d, metres.
    #[serde(default)]
    pub size_noise: RawNoise,
    /// Standard deviation of a detection's speed error, σ(d) = base + per_m · d, m/s.
    #[serde(default)]
    pub velocity_noise: RawNoise,
    /// Angle between the rays that carve free space, degrees.
    #[serde(default = "default_ray_spacing")]
    #[schemars(transform = range::RAY_SPACING.schema())]
    pub ray_spacing_deg: f64,
}

fn default_fov() -> f64 {
    360.0
}

fn default_detection_probability() -> f64 {
    1.0
}

fn default_ray_spacing() -> f64 {
    0.5
}

/// A mounting pose in the agent frame.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a mount mapping")]
#[schemars(rename = "Mount")]
pub(crate) struct RawMount {
    /// Forward of the agent's centre, metres.
    #[schemars(transform = range::MOUNT.schema())]
    pub x: f64,
    /// Left of the agent's centre, metres.
    #[schemars(transform = range::MOUNT.schema())]
    pub y: f64,
    /// Yaw relative to the agent's heading, degrees.
    #[schemars(transform = range::ANGLE.schema())]
    pub yaw_deg: f64,
}

/// A distance-dependent standard deviation σ(d) = base + per_m · d.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a noise mapping with `base` and `per_m`")]
#[schemars(rename = "Noise")]
pub(crate) struct RawNoise {
    /// σ at distance 0, metres.
    #[schemars(transform = range::SIGMA.schema())]
    pub base: f64,
    /// Growth of σ per metre of distance.
    #[schemars(transform = range::SIGMA_PER_M.schema())]
    pub per_m: f64,
}

/// Self-localization of connected agents.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a localization mapping")]
#[schemars(rename = "Localization")]
pub(crate) struct RawLocalization {
    /// σ of each self-reported x and y measurement, metres.
    #[schemars(transform = range::POSITION_SIGMA.schema())]
    pub position_sigma: f64,
    /// σ of each self-reported heading measurement, degrees.
    #[schemars(transform = range::ANGLE_SIGMA.schema())]
    pub heading_sigma_deg: f64,
    /// How an agent estimates its pose from its measurements.
    pub filter: PoseFilter,
    /// Kalman filter: uncertainty the motion model adds to x and y, metres per √s.
    #[schemars(transform = range::PROCESS_SIGMA.schema())]
    pub process_position_sigma: f64,
    /// Kalman filter: uncertainty the motion model adds to the heading, degrees per √s.
    #[schemars(transform = range::PROCESS_ANGLE_SIGMA.schema())]
    pub process_heading_sigma_deg: f64,
    /// Kalman filter: the odometry its prediction reads.
    pub odometry: RawOdometry,
}

impl Default for RawLocalization {
    fn default() -> Self {
        Self {
            position_sigma: 0.0,
            heading_sigma_deg: 0.0,
            filter: PoseFilter::default(),
            process_position_sigma: 0.1,
            process_heading_sigma_deg: 0.5,
            odometry: RawOdometry::default(),
        }
    }
}

/// The odometry the Kalman filter predicts with: one speed and one yaw-rate
/// reading per step (defaults: typical production-car sensors, sources in
/// docs/scenario-language.md).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "an odometry mapping")]
#[schemars(rename = "Odometry")]
pub(crate) struct RawOdometry {
    /// `exact`: the agent's exact motion; `noisy`: speed and yaw rate read with
    /// the noise and bias below.
    pub model: OdometryModel,
    /// σ of each step's speed reading, m/s.
    #[schemars(transform = range::SPEED_SIGMA.schema())]
    pub speed_sigma: f64,
    /// Scale error of the speed reading, a fraction of the true speed
    /// (0.01: 1 % fast), from −0.1 to 0.1.
    #[schemars(transform = range::SPEED_SCALE_ERROR.schema())]
    pub speed_bias: f64,
    /// σ of each step's yaw-rate reading, degrees per second.
    #[schemars(transform = range::TURN_RATE_SIGMA.schema())]
    pub yaw_rate_sigma_deg: f64,
    /// Offset of the yaw-rate reading, degrees per second, from −5 to 5.
    #[schemars(transform = range::YAW_RATE_OFFSET.schema())]
    pub yaw_rate_bias_deg: f64,
}

impl Default for RawOdometry {
    /// The model's defaults, kept in one place (`model::OdometryNoise`).
    fn default() -> Self {
        let noise = OdometryNoise::default();
        Self {
            model: OdometryModel::default(),
            speed_sigma: noise.speed_sigma,
            speed_bias: noise.speed_bias,
            yaw_rate_sigma_deg: noise.yaw_rate_sigma.to_degrees(),
            yaw_rate_bias_deg: noise.yaw_rate_bias.to_degrees(),
        }
    }
}
