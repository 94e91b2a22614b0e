//! The RSU's map of a world: the ways vehicles may take, which its risk layer
//! predicts them along.

use sightline_dsl::geometry::Polyline;
use sightline_dsl::{Motion, Semantic, World};

use super::risk::{MapRoute, RouteMap, lane_routes};

/// A network's map routes reach this many times the fastest speed limit × the
/// horizon past the lane a vehicle is on: a non-compliant driver at 1.5 × the
/// limit under the 1.1 hypothesis still stays on the map.
const REACH_FACTOR: f64 = 2.0;

/// The RSU's map of `world` (see `semantic::simulate`): with a network, its lanes
/// continued; then the way of every vehicle of the world (a traced one's only
/// without a network) and every traffic route, each once.
pub fn route_map(world: &World, semantic: &Semantic) -> RouteMap {
    let network = world.roads.iter().any(|road| !road.links.is_empty());
    let mut routes = if network {
        let fastest = world.roads.iter().map(|road| road.speed_limit).fold(0.0, f64::max);
        lane_routes(&world.roads, semantic.horizon * REACH_FACTOR * fastest)
    } else {
        Vec::new()
    };
    let mut ways: Vec<&Polyline> = Vec::new();
    let declared = world
        .agents
        .iter()
        .filter(|a| a.kind.is_vehicle())
        .filter(|a| !network || !matches!(a.motion, Motion::Trace { .. }))
        .filter_map(|a| a.motion.path());
    let generated = world
        .traffic
        .iter()
        .flat_map(|t| t.vehicles.iter())
        .flat_map(|v| v.routes.iter().map(|r| &r.path));
    for path in declared.chain(generated) {
        if !ways.contains(&path) {
            ways.push(path);
        }
    }
    routes.extend(ways.into_iter().cloned().map(MapRoute::whole));
    RouteMap::new(routes)
}
