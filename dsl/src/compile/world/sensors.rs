//! What agents measure: the sensor models agents refer to, and how connected
//! agents localize themselves.

use std::collections::HashMap;

use crate::compile::context::Context;
use crate::model::{Localization, Sensor};
use crate::path::Path;
use crate::raw::{RawScenario, RawSensorModel};

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
    ok.then_some(Localization {
        position_sigma: l.position_sigma,
        heading_sigma: l.heading_sigma_deg.to_radians(),
        filter: l.filter,
        process_position_sigma: l.process_position_sigma,
        process_heading_sigma: l.process_heading_sigma_deg.to_radians(),
    })
}
