//! What agents measure: the sensor models agents refer to, and how connected
//! agents localize themselves.

use std::collections::HashMap;

use crate::compile::context::{Context, Declaration};
use crate::model::{Localization, Odometry, OdometryModel, OdometryNoise, Sensor};
use crate::path::Path;
use crate::raw::range;
use crate::raw::{RawNoise, RawOdometry, RawScenario, RawSensorModel};

/// The sensor models that compile, by id, and whether all did. A model that
/// does not is noted in `ctx`, so the agents that name it are not reported as
/// naming a missing model.
pub(super) fn sensor_models(ctx: &mut Context<'_>, raw: &RawScenario) -> (HashMap<String, Sensor>, bool) {
    let map = Path::root().key("sensor_models");
    let mut ok = true;
    let mut sensors = HashMap::new();
    for (name, model) in &raw.sensor_models {
        let path = map.key(name);
        match sensor(ctx, name, model, &path) {
            Some(sensor) => {
                sensors.insert(name.clone(), sensor);
            }
            None => {
                ctx.declaration_failed(Declaration::SensorModel, name);
                ok = false;
            }
        }
    }
    (sensors, ok)
}

fn sensor(ctx: &mut Context<'_>, name: &str, raw: &RawSensorModel, path: &Path) -> Option<Sensor> {
    let noise = |ctx: &mut Context<'_>, key: &str, noise: &RawNoise| {
        ctx.within(&path.key(key).key("base"), noise.base, range::SIGMA)
            & ctx.within(&path.key(key).key("per_m"), noise.per_m, range::SIGMA_PER_M)
    };
    let ok = ctx.within(&path.key("range"), raw.range, range::SENSOR_RANGE)
        & ctx.expect(
            range::FIELD_OF_VIEW.contains(raw.fov_deg),
            &path.key("fov_deg"),
            "an angle above 0 and at most 360",
            raw.fov_deg,
        )
        & ctx.probability(&path.key("detection_probability"), raw.detection_probability)
        & noise(ctx, "position_noise", &raw.position_noise)
        & noise(ctx, "size_noise", &raw.size_noise)
        & noise(ctx, "velocity_noise", &raw.velocity_noise)
        & ctx.within(&path.key("ray_spacing_deg"), raw.ray_spacing_deg, range::RAY_SPACING)
        & ctx.within(&path.key("mount").key("x"), raw.mount.x, range::MOUNT)
        & ctx.within(&path.key("mount").key("y"), raw.mount.y, range::MOUNT)
        & ctx.within(&path.key("mount").key("yaw_deg"), raw.mount.yaw_deg, range::ANGLE);
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
    let ok = ctx.within(&path.key("position_sigma"), l.position_sigma, range::POSITION_SIGMA)
        & ctx.within(&path.key("heading_sigma_deg"), l.heading_sigma_deg, range::ANGLE_SIGMA)
        & ctx.within(
            &path.key("process_position_sigma"),
            l.process_position_sigma,
            range::PROCESS_SIGMA,
        )
        & ctx.within(
            &path.key("process_heading_sigma_deg"),
            l.process_heading_sigma_deg,
            range::PROCESS_ANGLE_SIGMA,
        );
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

fn odometry(ctx: &mut Context<'_>, raw: &RawOdometry, path: &Path) -> Option<Odometry> {
    let ok = ctx.within(&path.key("speed_sigma"), raw.speed_sigma, range::SPEED_SIGMA)
        & ctx.within(&path.key("speed_bias"), raw.speed_bias, range::SPEED_SCALE_ERROR)
        & ctx.within(
            &path.key("yaw_rate_sigma_deg"),
            raw.yaw_rate_sigma_deg,
            range::TURN_RATE_SIGMA,
        )
        & ctx.within(
            &path.key("yaw_rate_bias_deg"),
            raw.yaw_rate_bias_deg,
            range::YAW_RATE_OFFSET,
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
