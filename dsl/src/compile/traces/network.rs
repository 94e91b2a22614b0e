//! What a SUMO network gives the scene: roads (the lanes vehicles may use),
//! interaction areas (the junctions where paths meet or cross), crosswalks
//! (its crossings) and named areas (its walking areas).
//!
//! Choices, documented in `docs/scenario-language.md`:
//! - A road is a normal edge with its lanes for vehicles: a sidewalk
//!   (`allow="pedestrian"`) is no lane of it. Its width and speed limit are
//!   those of its first lane open to cars (`passenger`), else of its first lane
//!   for vehicles (a bike path). An edge with sidewalks only is no road.
//! - A junction is an interaction area when two paths across it from different
//!   roads lead into the same road (a merge, as at each junction of a
//!   roundabout) or cross; its outline is the junction's shape, or else the
//!   convex hull of those paths.
//! - A crossing is a crosswalk from the first to the last point of its lane, as
//!   wide as the lane. A walking area (the kerb corners where people wait and
//!   turn) is no crosswalk, since people there are not on the roadway: it is a
//!   named area requirements can select road users by (`areas`), and, inside
//!   the junction's outline, part of its interaction area.

use std::collections::{HashMap, HashSet};

use crate::error::Location;
use crate::geometry::{Polyline, Xy, counter_clockwise, distance};
use crate::import::sumo::{Connection, Edge, Network};
use crate::model::{Area, Crosswalk, InteractionArea, LaneLink, Road};

/// What a network gives the scene, and what it leaves out.
pub(super) struct Scene {
    /// The roads, their links indexing this list.
    pub(super) roads: Vec<Road>,
    /// The junctions that are interaction areas.
    pub(super) areas: Vec<InteractionArea>,
    /// The crossings.
    pub(super) crosswalks: Vec<Crosswalk>,
    /// The walking areas.
    pub(super) walking_areas: Vec<InteractionArea>,
    /// What is left out, each a message.
    pub(super) dropped: Vec<String>,
}

/// The scene of `net`; junctions become areas when `junction_areas`.
pub(super) fn scene(net: &Network, junction_areas: bool) -> Scene {
    let mut dropped = Vec::new();
    let roads = roads(net, &mut dropped);
    let areas = if junction_areas {
        interaction_areas(net, &mut dropped)
    } else {
        Vec::new()
    };
    let (crosswalks, walking_areas) = pedestrian_areas(net, &mut dropped);
    Scene {
        roads,
        areas,
        crosswalks,
        walking_areas,
        dropped,
    }
}

/// The roads: normal edges with their lanes for vehicles, linked by the
/// network's connections between those lanes.
fn roads(net: &Network, dropped: &mut Vec<String>) -> Vec<Road> {
    // Each road's edge and SUMO lane indices, in order.
    let mut kept: Vec<(&Edge, Vec<u32>)> = Vec::new();
    let mut sidewalks_only = Vec::new();
    for edge in net.edges.iter().filter(|edge| edge.function.is_empty()) {
        let mut lanes: Vec<_> = edge.lanes.iter().filter(|l| l.is_for_vehicles()).collect();
        lanes.sort_by_key(|lane| lane.index);
        if lanes.is_empty() {
            sidewalks_only.push(edge.id.as_str());
            continue;
        }
        kept.push((edge, lanes.iter().map(|l| l.index).collect()));
    }
    if !sidewalks_only.is_empty() {
        dropped.push(format!(
            "{} of the network: no lane for vehicles, so no road (people on them are replayed)",
            listed("edge", &sidewalks_only)
        ));
    }
    let road_of: HashMap<&str, usize> = kept.iter().enumerate().map(|(i, (e, _))| (e.id.as_str(), i)).collect();
    let mut roads: Vec<Road> = kept
        .iter()
        .map(|(edge, indices)| {
            let lanes: Vec<_> = indices
                .iter()
                .filter_map(|&i| edge.lanes.iter().find(|l| l.index == i))
                .collect();
            let main = lanes.iter().find(|l| l.permits("passenger")).unwrap_or(&lanes[0]);
            Road {
                id: edge.id.clone(),
                // A lane's shape has two points or more, but they may coincide.
                lanes: lanes
                    .iter()
                    .map(|l| Polyline::new(l.shape.iter().copied()).unwrap_or_else(|| point_lane(l.shape[0])))
                    .collect(),
                lane_width: main.width,
                speed_limit: main.speed,
                links: Vec::new(),
                arc: None,
            }
        })
        .collect();
    for connection in &net.connections {
        let (Some(&from), Some(&to)) = (
            road_of.get(connection.from.as_str()),
            road_of.get(connection.to.as_str()),
        ) else {
            continue;
        };
        let position = |road: usize, index: u32| kept[road].1.iter().position(|&i| i == index);
        let (Some(from_lane), Some(to_lane)) = (position(from, connection.from_lane), position(to, connection.to_lane))
        else {
            continue;
        };
        roads[from].links.push(LaneLink {
            from_lane,
            to_road: to,
            to_lane,
            via: connection.via.clone(),
        });
    }
    roads
}

/// A lane of no length at `point`, a millimetre long, for a lane whose shape's
/// points coincide (netconvert writes none; the road keeps its lane count).
fn point_lane(point: Xy) -> Polyline {
    Polyline::new([point, [point[0] + 1e-3, point[1]]]).expect("the points differ")
}

/// The junctions where paths from two roads meet or cross, as interaction areas.
fn interaction_areas(net: &Network, dropped: &mut Vec<String>) -> Vec<InteractionArea> {
    let edge_of_lane: HashMap<&str, &str> = net
        .edges
        .iter()
        .filter(|edge| edge.function.is_empty())
        .flat_map(|edge| edge.lanes.iter().map(move |lane| (lane.id.as_str(), edge.id.as_str())))
        .collect();
    let normal: HashSet<&str> = edge_of_lane.values().copied().collect();
    let mut by_edge: HashMap<&str, Vec<&Connection>> = HashMap::new();
    for connection in &net.connections {
        by_edge.entry(connection.from.as_str()).or_default().push(connection);
    }
    let mut areas = Vec::new();
    let mut without_outline = Vec::new();
    for junction in &net.junctions {
        let incoming: HashSet<&str> = junction
            .incoming
            .iter()
            .filter_map(|lane| edge_of_lane.get(lane.as_str()).copied())
            .collect();
        let mut incoming: Vec<&str> = incoming.into_iter().collect();
        incoming.sort_unstable();
        let paths: Vec<&Connection> = incoming
            .iter()
            .flat_map(|edge| by_edge.get(edge).into_iter().flatten().copied())
            .filter(|c| normal.contains(c.to.as_str()))
            .collect();
        if !conflicting(&paths) {
            continue;
        }
        let outline = counter_clockwise(&junction.shape)
            .or_else(|| counter_clockwise(&convex_hull(paths.iter().flat_map(|c| c.via.iter().copied()))));
        match outline {
            Some(outline) => areas.push(InteractionArea {
                id: junction.id.clone(),
                shape: Area::Polygon(outline),
            }),
            None => without_outline.push(junction.id.as_str()),
        }
    }
    if !without_outline.is_empty() {
        dropped.push(format!(
            "{} of the network: paths meet there, but neither its shape nor its internal lanes enclose an \
             area, so no interaction area",
            listed("junction", &without_outline)
        ));
    }
    areas
}

/// Whether two of `paths` from different roads lead into the same road or cross.
fn conflicting(paths: &[&Connection]) -> bool {
    paths.iter().enumerate().any(|(i, a)| {
        paths[i + 1..]
            .iter()
            .any(|b| a.from != b.from && (a.to == b.to || crosses(&a.via, &b.via)))
    })
}

/// Whether two polylines cross (touching ends aside).
fn crosses(a: &[Xy], b: &[Xy]) -> bool {
    a.windows(2)
        .any(|s| b.windows(2).any(|t| segments_cross(s[0], s[1], t[0], t[1])))
}

/// Whether segments pq and rs cross at a point inside both.
fn segments_cross(p: Xy, q: Xy, r: Xy, s: Xy) -> bool {
    let cross = |o: Xy, a: Xy, b: Xy| (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    let (d1, d2) = (cross(r, s, p), cross(r, s, q));
    let (d3, d4) = (cross(p, q, r), cross(p, q, s));
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone chain).
fn convex_hull(points: impl Iterator<Item = Xy>) -> Vec<Xy> {
    let mut points: Vec<Xy> = points.collect();
    points.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let turn = |o: Xy, a: Xy, b: Xy| (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    let mut hull: Vec<Xy> = Vec::with_capacity(2 * points.len());
    for pass in [points.clone(), points.iter().rev().copied().collect()] {
        let start = hull.len();
        for point in pass {
            while hull.len() >= start + 2 && turn(hull[hull.len() - 2], hull[hull.len() - 1], point) <= 0.0 {
                hull.pop();
            }
            hull.push(point);
        }
        hull.pop();
    }
    hull
}

/// The crossings as crosswalks and the walking areas as named areas.
fn pedestrian_areas(net: &Network, dropped: &mut Vec<String>) -> (Vec<Crosswalk>, Vec<InteractionArea>) {
    let mut crosswalks = Vec::new();
    let mut walking_areas = Vec::new();
    let mut degenerate = Vec::new();
    for edge in &net.edges {
        let Some(lane) = edge.lanes.first() else { continue };
        match edge.function.as_str() {
            "crossing" => {
                let (from, to) = (lane.shape[0], lane.shape[lane.shape.len() - 1]);
                if distance(from, to) > Crosswalk::MIN_LENGTH {
                    crosswalks.push(Crosswalk {
                        id: edge.id.clone(),
                        from,
                        to,
                        width: lane.width,
                    });
                } else {
                    degenerate.push(edge.id.as_str());
                }
            }
            "walkingarea" => match counter_clockwise(&lane.shape) {
                Some(outline) => walking_areas.push(InteractionArea {
                    id: edge.id.clone(),
                    shape: Area::Polygon(outline),
                }),
                None => degenerate.push(edge.id.as_str()),
            },
            _ => {}
        }
    }
    if !degenerate.is_empty() {
        dropped.push(format!(
            "{} of the network (crossings or walking areas) enclose no area, so no crosswalk or area",
            listed("edge", &degenerate)
        ));
    }
    (crosswalks, walking_areas)
}

/// `n edges `a`, `b`, …` naming at most five.
pub(super) fn listed(what: &str, ids: &[&str]) -> String {
    const SHOWN: usize = 5;
    let names: Vec<String> = ids.iter().take(SHOWN).map(|id| format!("`{id}`")).collect();
    let more = if ids.len() > SHOWN { ", …" } else { "" };
    let plural = if ids.len() == 1 { "" } else { "s" };
    format!("{} {what}{plural} ({}{more})", ids.len(), names.join(", "))
}

/// Where a network warning is located: its file's first line.
pub(super) const FILE_START: Location = Location::new(1, 1);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_cross_inside_only() {
        assert!(segments_cross([0.0, 0.0], [2.0, 2.0], [0.0, 2.0], [2.0, 0.0]));
        // Touching at an end is not crossing (paths that share a lane's end).
        assert!(!segments_cross([0.0, 0.0], [1.0, 1.0], [1.0, 1.0], [2.0, 0.0]));
        assert!(!segments_cross([0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]));
    }

    #[test]
    fn the_convex_hull_of_a_square_and_its_centre() {
        let hull = convex_hull([[0.0, 0.0], [2.0, 2.0], [1.0, 1.0], [2.0, 0.0], [0.0, 2.0]].into_iter());
        assert_eq!(hull, [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]);
        assert_eq!(convex_hull([[0.0, 0.0], [1.0, 1.0]].into_iter()).len(), 2);
    }

    #[test]
    fn listing_names_at_most_five() {
        assert_eq!(listed("edge", &["a"]), "1 edge (`a`)");
        assert_eq!(
            listed("junction", &["a", "b", "c", "d", "e", "f"]),
            "6 junctions (`a`, `b`, `c`, `d`, `e`, …)"
        );
    }
}
