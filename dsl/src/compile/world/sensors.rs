//! What agents measure: the sensor models agents refer to, and how connected
//! agents localize themselves.

use std::collections::HashMap;

use crate::compile::context::Context;
use crate::model::{Localization, Odometry, OdometryModel, OdometryNoise, Sensor};
use crate::path::Path;
use crate::raw::{RawOdometry, RawScenario, RawSensorModel};

pub(super) fn sensor_models(ctx: &mut Context<'_>, raw: &RawScenario) -> Option<HashMap<String, Sensor>> {
    let map = Path::root().key("sensor_models");
    let mut ok = true;
    let mut sensors = HashMap::new();
    for (name, model) in &raw.sensor_models {
        let path = map.key(name);
        match sensor(ctx, name, model, &path) {
            Some(sensor) => {
                sensors.insert(name.clone(), sensor);
            }
            None => ok = false,
        }
    }
    ok.then_some(sensors)
}

fn sensor(ctx: &mut Context<'_>, name: &str, raw: &RawSensorModel, path: &Path) -> Option<Sensor> {
    let ok = ctx.positive(&path.key("range"), raw.range)
        & ctx.expect(
            raw.fov_deg > 0.0 && raw.fov_deg <= 360.0,
            &path.key("fov_deg"),
            "an angle above 0 and at most 360",
            raw.fov_deg,
        )
        & ctx.probability(&path.key("detection_probability"), raw.detection_probability)
        & ctx.non_negative(&path.key("position_noise").key("base"), raw.position_noise.base)
        & ctx.non_negative(&path.key("position_noise").key("per_m"), raw.position_noise.per_m)
        & ctx.non_negative(&path.key("size_noise").key("base"), raw.size_noise.base)
        & ctx.non_negative(&path.key("size_noise").key("per_m"), raw.size_noise.per_m)
        & ctx.non_negative(&path.key("velocity_noise").key("base"), raw.velocity_noise.base)
        & ctx.non_negative(&path.key("velocity_noise").key("per_m"), raw.velocity_noise.per_m)
        & ctx.expect(
            raw.ray_spacing_deg > 0.0 && raw.ray_spacing_deg <= 10.0,
            &path.key("ray_spacing_deg"),
            "an angle above 0 and at most 10",
            raw.ray_spacing_deg,
        )
        & ctx.finite(&path.key("mount").key("x"), raw.mount.x)
        & ctx.finite(&path.key("mount").key("y"), raw.mount.y)
        & ctx.finite(&path.key("mount").key("yaw_deg"), raw.mount.yaw_deg);
    ok.then(|| Sensor {
        model: name.to_string(),
        range: raw.range,
        fov: raw.fov_deg.to_radians(),
        mount_x: raw.mount.x,
        mount_y: raw.mount.y,
        mount_yaw: raw.mount.yaw_deg.to_radians(),
        detection_probability: raw.detection_probability,
        noise_base: raw.position_noise.base,
        noise_per_m: raw.position_noise.per_m,
        size_noise_base: raw.size_noise.base,
        size_noise_per_m: raw.size_noise.per_m,
        velocity_noise_base: raw.velocity_noise.base,
        velocity_noise_per_m: raw.velocity_noise.per_m,
        ray_spacing: raw.ray_spacing_deg.to_radians(),
    })
}

pub(super) fn localization(ctx: &mut Context<'_>, raw: &RawScenario) -> Option<Localization> {
    let path = Path::root().key("localization");
    let l = &raw.localization;
    let ok = ctx.non_negative(&path.key("position_sigma"), l.position_sigma)
        & ctx.non_negative(&path.key("heading_sigma_deg"), l.heading_sigma_deg)
        & ctx.positive(&path.key("process_position_sigma"), l.process_position_sigma)
        & ctx.positive(&path.key("process_heading_sigma_deg"), l.process_heading_sigma_deg);
    // Checked whatever the rest gives, so that every error is reported at once.
    let odometry = odometry(ctx, &l.odometry, &path.key("odometry"))?;
    ok.then_some(Localization {
        position_sigma: l.position_sigma,
        heading_sigma: l.heading_sigma_deg.to_radians(),
        filter: l.filter,
        process_position_sigma: l.process_position_sigma,
        process_heading_sigma: l.process_heading_sigma_deg.to_radians(),
        odometry,
    })
}

/// The largest scale error of a speed reading either way: a speedometer may
/// read up to 10 % (plus 4 km/h) fast and never slow (UNECE Regulation No. 39);
/// odometry off by more is broken, not noisy.
const MAX_SPEED_BIAS: f64 = 0.1;

/// The largest yaw-rate offset, degrees per second: above the 3.75 °/s an
/// automotive yaw-rate sensor may drift over its life before the stability
/// control compensates it.
const MAX_YAW_RATE_BIAS_DEG: f64 = 5.0;

fn odometry(ctx: &mut Context<'_>, raw: &RawOdometry, path: &Path) -> Option<Odometry> {
    let ok = ctx.non_negative(&path.key("speed_sigma"), raw.speed_sigma)
        & ctx.expect(
            raw.speed_bias.abs() <= MAX_SPEED_BIAS,
            &path.key("speed_bias"),
            &format!("a fraction from −{MAX_SPEED_BIAS} to {MAX_SPEED_BIAS}"),
            raw.speed_bias,
        )
        & ctx.non_negative(&path.key("yaw_rate_sigma_deg"), raw.yaw_rate_sigma_deg)
        & ctx.expect(
            raw.yaw_rate_bias_deg.abs() <= MAX_YAW_RATE_BIAS_DEG,
            &path.key("yaw_rate_bias_deg"),
            &format!("a rate from −{MAX_YAW_RATE_BIAS_DEG} to {MAX_YAW_RATE_BIAS_DEG} °/s"),
            raw.yaw_rate_bias_deg,
        );
    ok.then_some(match raw.model {
        OdometryModel::Exact => Odometry::Exact,
        OdometryModel::Noisy => Odometry::Noisy(OdometryNoise {
            speed_sigma: raw.speed_sigma,
            speed_bias: raw.speed_bias,
            yaw_rate_sigma: raw.yaw_rate_sigma_deg.to_radians(),
            yaw_rate_bias: raw.yaw_rate_bias_deg.to_radians(),
        }),
    })
}
