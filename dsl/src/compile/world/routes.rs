//! Routes: a list of road ids checked for connectivity and resolved into one
//! path on one lane, with the speed limit of each part.

use std::collections::HashMap;

use crate::compile::checks::known_names;
use crate::compile::context::{Context, Declaration};
use crate::error::ErrorKind;
use crate::geometry::{Polyline, Xy, distance};
use crate::model::Road;
use crate::path::Path;

/// The most roads a route may name. A drive across a city names some tens
/// (bundled: at most 3); each road adds a speed limit that every vehicle on the
/// route keeps and looks up as it moves.
pub(crate) const MAX_ROUTE_ROADS: usize = 1_000;

/// Roads and where each id is, so that a route is resolved in time linear in
/// its length, whatever the number of roads.
pub(super) struct RoadIndex<'a> {
    roads: &'a [Road],
    by_id: HashMap<&'a str, usize>,
}

impl<'a> RoadIndex<'a> {
    pub(super) fn new(roads: &'a [Road]) -> Self {
        let mut by_id = HashMap::with_capacity(roads.len());
        for (i, road) in roads.iter().enumerate() {
            // The first of two roads of one id (refused where they are declared).
            by_id.entry(road.id.as_str()).or_insert(i);
        }
        Self { roads, by_id }
    }

    /// The index of the road of id `id`.
    pub(super) fn position(&self, id: &str) -> Option<usize> {
        self.by_id.get(id).copied()
    }

    /// Whether there are no roads.
    pub(super) fn is_empty(&self) -> bool {
        self.roads.is_empty()
    }
}

/// Resolves a route into one polyline on lane `lane` of each road, with the speed
/// limit of each part. Road a connects to road b across a junction when a links
/// that lane to b's (roads of a SUMO network), or else when a's last point lies
/// within one lane width of b (a ring is left where b's first point projects onto
/// it).
pub(super) fn route_path(
    ctx: &mut Context<'_>,
    route: &[String],
    lane: u32,
    path: &Path,
    index: &RoadIndex<'_>,
) -> Option<(Polyline, Vec<(f64, f64)>)> {
    let roads = index.roads;
    if route.is_empty() {
        ctx.error(path, ErrorKind::Invalid("a route names at least one road".into()));
        return None;
    }
    if route.len() > MAX_ROUTE_ROADS {
        ctx.error(
            path,
            ErrorKind::TooLarge(format!(
                "{} roads in a route exceed the limit of {MAX_ROUTE_ROADS}; name each road of the way once",
                route.len()
            )),
        );
        return None;
    }
    let mut parts: Vec<(&Road, &Polyline)> = Vec::new();
    for (i, id) in route.iter().enumerate() {
        let Some(road) = index.position(id).map(|i| &roads[i]) else {
            if ctx.is_failed(Declaration::Road, id) {
                // The road's own errors say why; the route is not at fault.
                return None;
            }
            let known: Vec<&str> = roads.iter().map(|r| r.id.as_str()).collect();
            ctx.error(
                &path.index(i),
                ErrorKind::DanglingReference(format!("no road `{id}` ({})", known_names(id, &known))),
            );
            return None;
        };
        let Some(centreline) = road.lanes.get(lane as usize) else {
            ctx.error(
                &path.index(i),
                ErrorKind::Invalid(format!("road `{id}` has no lane {lane} (it has {})", road.lanes.len())),
            );
            return None;
        };
        parts.push((road, centreline));
    }
    if parts.last().is_some_and(|(_, line)| line.is_closed()) {
        ctx.error(
            &path.index(route.len() - 1),
            ErrorKind::Invalid("a route cannot end on a roundabout: name the road that leaves it".into()),
        );
        return None;
    }
    let mut way = Way::default();
    let mut limits = Vec::new();
    let mut entry = 0.0;
    for (i, &(road, line)) in parts.iter().enumerate() {
        // Where this road is left, and where the next one is entered: a ring is
        // left where the next road starts; any other road at its end, onto the
        // closest point of the next.
        let link = parts.get(i + 1).and_then(|&(next_road, _)| {
            road.links.iter().find(|link| {
                link.from_lane == lane as usize
                    && link.to_lane == lane as usize
                    && roads[link.to_road].id == next_road.id
            })
        });
        let (exit, next_entry) = match parts.get(i + 1) {
            None => (line.length(), 0.0),
            Some(_) if link.is_some() => (line.length(), 0.0),
            Some(&(next_road, next)) => {
                let (exit, gap, next_entry) = if line.is_closed() {
                    let at = line.project(next.start());
                    (at.offset, at.distance, 0.0)
                } else {
                    let at = next.project(line.end());
                    (line.length(), at.distance, at.offset)
                };
                let tolerance = road.lane_width.max(next_road.lane_width);
                if gap > tolerance {
                    ctx.error(
                        &path.index(i + 1),
                        ErrorKind::DanglingReference(format!(
                            "road `{}` does not connect to `{}`: they are {gap:.2} m apart where one should \
                             join the other (at most the lane width, {tolerance} m)",
                            road.id, next_road.id
                        )),
                    );
                    return None;
                }
                (exit, next_entry)
            }
        };
        if line.is_closed() && exit < entry {
            way.extend(line.slice(entry, line.length()));
            way.extend(line.slice(0.0, exit));
        } else {
            way.extend(line.slice(entry, exit));
        }
        limits.push((way.length, road.speed_limit));
        // The path across the junction drives at the next road's limit.
        way.extend(link.iter().flat_map(|link| link.via.iter().copied()));
        entry = next_entry;
    }
    let Some(polyline) = Polyline::new(way.points) else {
        ctx.error(path, ErrorKind::Invalid("the route has no length".into()));
        return None;
    };
    Some((polyline, limits))
}

/// The points of a route as they are joined, and their length so far (kept as
/// they come, so that each road's end is found in constant time).
#[derive(Default)]
struct Way {
    points: Vec<Xy>,
    length: f64,
}

impl Way {
    fn extend(&mut self, points: impl IntoIterator<Item = Xy>) {
        for point in points {
            if let Some(&last) = self.points.last() {
                self.length += distance(last, point);
            }
            self.points.push(point);
        }
    }
}
