//! Predictive risk (seed 002, section III-D): speed hypotheses, trajectories
//! along the map's paths over the horizon, and conflicts with the ego's plan.
//!
//! Our readings where the paper leaves room:
//! - "precomputed road waypoints" are the map's routes: a vehicle may follow any
//!   route whose first stretch (its `home`) passes within `LANE_TOLERANCE` of its
//!   position with a heading within `HEADING_TOLERANCE`; routes sharing a
//!   position and diverging later are the branches "when multiple feasible paths
//!   exist". Off every route, it keeps its heading. Past a route's end, it goes
//!   straight on. Which routes the map holds is the semantic run's choice (see
//!   `simulate.rs`); [`lane_routes`] builds them from a road network.
//! - A dangerous driver's aggressive profile drives at v_max + δ̄, the mean speed
//!   at which it exceeded the limit in the window (at least its current speed).
//! - Conflict (eq. 3) is tested on the segments between prediction samples, not
//!   only at the samples, so a fast crossing is not missed between two samples.

use sightline_dsl::geometry::{Polyline, Xy, distance};
use sightline_dsl::{LaneLink, Road};

use super::ldm::Track;
use crate::math::Point;

/// Largest distance from a route for a vehicle to be on it, metres.
pub const LANE_TOLERANCE: f64 = 2.0;

/// Largest heading difference for a vehicle to follow a route, radians (45°).
pub const HEADING_TOLERANCE: f64 = std::f64::consts::FRAC_PI_4;

/// Positions every `dt` seconds from now (index 0) to the horizon.
pub type Trajectory = Vec<Point>;

/// Most routes [`lane_routes`] builds from one lane.
pub const MAX_BRANCHES: usize = 64;

/// A route of the map.
#[derive(Debug, Clone, PartialEq)]
pub struct MapRoute {
    /// The path.
    pub path: Polyline,
    /// How far from its start a vehicle must be to follow it, metres: a lane
    /// and the junction after it for a route built from a network, the whole
    /// path otherwise. Further on, the routes that start there take over.
    pub home: f64,
}

impl MapRoute {
    /// A route a vehicle may follow from anywhere along it.
    pub fn whole(path: Polyline) -> Self {
        let home = path.length();
        Self { path, home }
    }
}

/// The routes of the map, each with the bounding box of its home stretch for a
/// quick rejection.
pub struct RouteMap {
    routes: Vec<(MapRoute, [f64; 4])>,
}

impl RouteMap {
    /// A map of `routes`.
    pub fn new(routes: impl IntoIterator<Item = MapRoute>) -> Self {
        let routes = routes
            .into_iter()
            .map(|route| {
                let bounds = route.path.slice(0.0, route.home).iter().fold(
                    [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY],
                    |[x0, y0, x1, y1], p| [x0.min(p[0]), y0.min(p[1]), x1.max(p[0]), y1.max(p[1])],
                );
                (route, bounds)
            })
            .collect();
        Self { routes }
    }

    /// The routes a vehicle at `position` heading `heading` may follow, with its
    /// offset along each.
    pub fn branches(&self, position: Point, heading: f64) -> Vec<(&Polyline, f64)> {
        self.routes
            .iter()
            .filter(|(_, [x0, y0, x1, y1])| {
                position.x >= x0 - LANE_TOLERANCE
                    && position.x <= x1 + LANE_TOLERANCE
                    && position.y >= y0 - LANE_TOLERANCE
                    && position.y <= y1 + LANE_TOLERANCE
            })
            .filter_map(|(route, _)| {
                let path = &route.path;
                let at = path.project([position.x, position.y]);
                let turn = path.heading_at(at.offset) - heading;
                let aligned = turn.cos() >= HEADING_TOLERANCE.cos();
                let home = at.offset <= route.home;
                (home && at.distance <= LANE_TOLERANCE && aligned).then_some((path, at.offset))
            })
            .collect()
    }
}

/// The routes of a road network: every lane of every road, continued through
/// each of its links across the junction into the next lane, and on, branching at
/// every fork, until the route reaches `reach` metres past the junction after the
/// lane it starts on (the home stretch). At most [`MAX_BRANCHES`] routes start on
/// one lane; a route ends early at a lane without links, or where the lane's
/// routes have taken [`MAX_ROUTE_POINTS`] points from the lanes and junctions
/// they continue through (a cycle of short lanes would take them forever).
pub fn lane_routes(roads: &[Road], reach: f64) -> Vec<MapRoute> {
    let mut routes = Vec::new();
    for road in roads {
        for lane in 0..road.lanes.len() {
            let mut branches = Branches {
                roads,
                reach,
                start: routes.len(),
                routes: &mut routes,
            };
            branches.build(road, lane);
        }
    }
    routes
}

/// Most points the routes from one lane take from the lanes and junctions they
/// continue through.
pub const MAX_ROUTE_POINTS: usize = 1 << 16;

/// The routes from one lane, built depth first.
struct Branches<'a> {
    roads: &'a [Road],
    reach: f64,
    routes: &'a mut Vec<MapRoute>,
    /// Where the lane's routes start in `routes`.
    start: usize,
}

/// A lane on the route being built, with the links from it still to follow.
struct Step<'a> {
    links: Vec<&'a LaneLink>,
    /// How many of `links` have been followed.
    followed: usize,
    /// The route's length up to the end of this lane, metres.
    length: f64,
    /// The length of the route's home stretch, once past the first junction.
    home: Option<f64>,
    /// How many points the route had before this lane's junction and lane.
    kept: usize,
}

impl<'a> Branches<'a> {
    /// Builds the routes that start on lane `lane` of `road`: the route grows by
    /// a junction and a lane at each step down, and one is kept at each lane
    /// that ends it (no links, or `reach` past the home stretch).
    fn build(&mut self, road: &'a Road, lane: usize) {
        let mut points = road.lanes[lane].points().to_vec();
        let length = points.windows(2).map(|p| distance(p[0], p[1])).sum::<f64>();
        let mut budget = MAX_ROUTE_POINTS;
        let links = Self::links(road, lane);
        if links.is_empty() {
            self.keep(&points, length, None);
            return;
        }
        let mut stack = vec![Step {
            links,
            followed: 0,
            length,
            home: None,
            kept: points.len(),
        }];
        while let Some(step) = stack.last_mut() {
            if self.routes.len() - self.start >= MAX_BRANCHES {
                return;
            }
            let Some(&link) = step.links.get(step.followed) else {
                points.truncate(step.kept);
                stack.pop();
                continue;
            };
            step.followed += 1;
            let next = &self.roads[link.to_road];
            let lane = &next.lanes[link.to_lane];
            let kept = points.len();
            let mut length = step.length;
            append(&mut points, &mut length, &link.via);
            let home = step.home.unwrap_or(length);
            append(&mut points, &mut length, lane.points());
            budget = budget.saturating_sub(link.via.len() + lane.points().len());
            let links = Self::links(next, link.to_lane);
            if links.is_empty() || length - home >= self.reach || budget == 0 {
                self.keep(&points, length, Some(home));
                if budget == 0 {
                    return;
                }
                points.truncate(kept);
            } else {
                stack.push(Step {
                    links,
                    followed: 0,
                    length,
                    home: Some(home),
                    kept,
                });
            }
        }
    }

    /// The links from lane `lane` of `road`.
    fn links(road: &'a Road, lane: usize) -> Vec<&'a LaneLink> {
        road.links.iter().filter(|link| link.from_lane == lane).collect()
    }

    /// Keeps the route through `points`, `length` metres long, whose home
    /// stretch is `home` metres (the whole route when `None`).
    fn keep(&mut self, points: &[Xy], length: f64, home: Option<f64>) {
        if let Some(path) = Polyline::new(points.iter().copied()) {
            let home = home.unwrap_or(length).min(path.length());
            self.routes.push(MapRoute { path, home });
        }
    }
}

/// Appends `more` to `points`, adding what they add to `length`.
fn append(points: &mut Vec<Xy>, length: &mut f64, more: &[Xy]) {
    for &p in more {
        if let Some(&last) = points.last() {
            *length += distance(last, p);
        }
        points.push(p);
    }
}

/// Positions along `path` from `offset` at constant `speed`, every `dt` up to
/// `horizon`; straight on past its end.
pub fn along(path: &Polyline, offset: f64, speed: f64, horizon: f64, dt: f64) -> Trajectory {
    let end = path.length();
    let exit = path.point_at(end);
    let exit_heading = path.heading_at(end);
    samples(horizon, dt)
        .map(|t| {
            let s = offset + speed * t;
            if s <= end {
                let [x, y] = path.point_at(s);
                Point::new(x, y)
            } else {
                Point::new(exit[0], exit[1]) + Point::new(exit_heading.cos(), exit_heading.sin()) * (s - end)
            }
        })
        .collect()
}

/// Positions at constant `velocity` from `position`, every `dt` up to `horizon`.
pub fn straight(position: Point, velocity: Point, horizon: f64, dt: f64) -> Trajectory {
    samples(horizon, dt).map(|t| position + velocity * t).collect()
}

fn samples(horizon: f64, dt: f64) -> impl Iterator<Item = f64> {
    let n = (horizon / dt).round() as usize;
    (0..=n).map(move |k| k as f64 * dt)
}

/// The speeds a vehicle is predicted at, and whether it is a dangerous driver
/// (seed 002, eq. 2): a compliant vehicle gets `factors` × v; a dangerous one
/// its speed v and the aggressive v_max + δ̄.
pub fn hypotheses(track: &Track, factors: &[f64], window: f64, threshold: f64) -> (Vec<f64>, bool) {
    let now = track.latest();
    match track.mean_violation(window) {
        Some(mean) if mean > threshold => (vec![now.speed, (now.limit + mean).max(now.speed)], true),
        _ => (factors.iter().map(|f| f * now.speed).collect(), false),
    }
}

/// A predicted conflict.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Conflict {
    /// Time until the centres first come within d_min, seconds.
    pub time: f64,
    /// Smallest predicted distance between the centres, metres.
    pub separation: f64,
}

/// Seed 002, eq. 3: the first time in the horizon at which the two trajectories
/// (same sampling `dt`) come within `d_min`, with their smallest separation.
/// Between samples both move linearly.
pub fn conflict(ego: &[Point], other: &[Point], dt: f64, d_min: f64) -> Option<Conflict> {
    let mut first: Option<f64> = None;
    let mut separation = f64::INFINITY;
    for (k, (e, o)) in ego.windows(2).zip(other.windows(2)).enumerate() {
        let a = o[0] - e[0];
        let b = (o[1] - e[1]) - a;
        // |a + b u|, u in [0, 1]: closest approach and first entry into the d_min disc.
        let bb = b.dot(b);
        let u_closest = if bb > 0.0 {
            (-a.dot(b) / bb).clamp(0.0, 1.0)
        } else {
            0.0
        };
        separation = separation.min((a + b * u_closest).length());
        if first.is_none() {
            let c = a.dot(a) - d_min * d_min;
            let entry = if c <= 0.0 {
                Some(0.0)
            } else if bb > 0.0 {
                let half = a.dot(b);
                let discriminant = half * half - bb * c;
                (discriminant >= 0.0)
                    .then(|| (-half - discriminant.sqrt()) / bb)
                    .filter(|u| (0.0..=1.0).contains(u))
            } else {
                None
            };
            first = entry.map(|u| (k as f64 + u) * dt);
        }
    }
    first.map(|time| Conflict { time, separation })
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    /// The ego drives east along y = 0 at 10 m/s from x = −30; another vehicle
    /// drives north along x = 0 at 10 m/s from y = −30. Both reach the origin at
    /// 3 s; the centres are within 2 m when 10√2 · (3 − t) ≤ 2, from
    /// t = 3 − 0.1414 = 2.859 s; the separation reaches 0.
    #[test]
    fn crossing_trajectories_conflict_at_the_right_time() {
        let ego = straight(Point::new(-30.0, 0.0), Point::new(10.0, 0.0), 3.0, 0.1);
        let other = straight(Point::new(0.0, -30.0), Point::new(0.0, 10.0), 3.0, 0.1);
        let found = conflict(&ego, &other, 0.1, 2.0).unwrap();
        assert_relative_eq!(found.time, 3.0 - 2.0 / 200f64.sqrt(), epsilon = 1e-9);
        assert!(found.separation < 1e-9);
        // One second later, the other is 10 m behind: never within 2 m.
        let late = straight(Point::new(0.0, -40.0), Point::new(0.0, 10.0), 3.0, 0.1);
        assert_eq!(conflict(&ego, &late, 0.1, 2.0), None);
    }

    /// Sampled every 1 s, two vehicles pass each other between samples: only the
    /// segment test sees it.
    #[test]
    fn conflicts_between_samples_are_found() {
        let ego = straight(Point::new(0.0, 0.0), Point::new(15.0, 0.0), 2.0, 1.0);
        let other = straight(Point::new(37.5, 1.0), Point::new(-15.0, 0.0), 2.0, 1.0);
        // Gap 37.5 − 30 t along x, 1 across: 37.5, 7.5 and 22.5 m at the samples,
        // within 2 m when |37.5 − 30 t| ≤ √3.
        let found = conflict(&ego, &other, 1.0, 2.0).unwrap();
        assert_relative_eq!(found.time, (37.5 - 3f64.sqrt()) / 30.0, epsilon = 1e-9);
        assert_relative_eq!(found.separation, 1.0, epsilon = 1e-9);
    }

    /// Over its 5 s window a car exceeds a 10 m/s limit by 3 m/s on average:
    /// dangerous (3 > 2), predicted at its speed and at v_max + δ̄ = 13 m/s. At
    /// 1 m/s over, it is compliant and gets 0.7, 1.0 and 1.1 times its speed.
    #[test]
    fn an_overspeeding_vehicle_gets_the_aggressive_hypothesis() {
        use sightline_dsl::AgentKind;

        use crate::semantic::ldm::{Ldm, Measurement};
        let hypotheses_at = |excess: f64| {
            let mut ldm = Ldm::default();
            for k in 0..=50 {
                let time = f64::from(k) * 0.1;
                let speed = 10.0 + excess;
                let m = Measurement {
                    time,
                    position: Point::new(speed * time, 0.0),
                    speed,
                    heading: 0.0,
                    length: 4.5,
                    width: 1.8,
                    limit: 10.0,
                };
                ldm.record(1, AgentKind::Car, m);
            }
            let track = ldm.current(5.0).next().unwrap().1.clone();
            hypotheses(&track, &[0.7, 1.0, 1.1], 5.0, 2.0)
        };
        let (speeds, dangerous) = hypotheses_at(3.0);
        assert!(dangerous);
        assert_eq!(speeds.len(), 2);
        assert_relative_eq!(speeds[1], 13.0, epsilon = 1e-9);
        let (speeds, dangerous) = hypotheses_at(1.0);
        assert!(!dangerous);
        assert_relative_eq!(speeds[0], 0.7 * 11.0, epsilon = 1e-9);
        assert_relative_eq!(speeds[2], 1.1 * 11.0, epsilon = 1e-9);
    }

    #[test]
    fn along_follows_the_path_then_goes_straight() {
        let path = Polyline::new([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]]).unwrap();
        let trajectory = along(&path, 5.0, 10.0, 2.0, 0.5);
        assert_eq!(trajectory.len(), 5);
        assert_relative_eq!(trajectory[1].x, 10.0);
        assert_relative_eq!(trajectory[2].y, 5.0);
        // 20 m from offset 5: 5 m past the end, straight on north.
        assert_relative_eq!(trajectory[4].y, 15.0);
    }

    #[test]
    fn branches_are_the_aligned_routes_through_a_position() {
        let east = Polyline::new([[-50.0, 0.0], [50.0, 0.0]]).unwrap();
        let turn = Polyline::new([[-50.0, 0.0], [0.0, 0.0], [0.0, 50.0]]).unwrap();
        let west = Polyline::new([[50.0, 0.5], [-50.0, 0.5]]).unwrap();
        let map = RouteMap::new([east, turn, west].map(MapRoute::whole));
        let found = map.branches(Point::new(-20.0, 0.3), 0.0);
        assert_eq!(found.len(), 2, "east and turn, not the opposite lane");
        assert!(found.iter().all(|&(_, offset)| (offset - 30.0).abs() < 1e-9));
    }

    fn road(id: &str, line: [Xy; 2], links: Vec<sightline_dsl::LaneLink>) -> Road {
        Road {
            id: id.into(),
            lanes: vec![Polyline::new(line).unwrap()],
            lane_width: 3.2,
            speed_limit: 13.9,
            links,
            arc: None,
        }
    }

    fn link(to_road: usize, via: Vec<Xy>) -> sightline_dsl::LaneLink {
        sightline_dsl::LaneLink {
            from_lane: 0,
            to_road,
            to_lane: 0,
            via,
        }
    }

    /// A lane 100 m east into a junction that forks north (road 1) and east
    /// (road 2), both 100 m: with a 30 m reach, two routes start on it, each its
    /// 100 m, the 10 m across the junction and the next lane; the next lanes
    /// have no links and are routes of their own.
    #[test]
    fn lane_routes_branch_at_forks_and_reach_past_the_junction() {
        let roads = [
            road(
                "in",
                [[0.0, 0.0], [100.0, 0.0]],
                vec![
                    link(1, vec![[100.0, 0.0], [105.0, 0.0], [110.0, 5.0]]),
                    link(2, vec![[100.0, 0.0], [110.0, 0.0]]),
                ],
            ),
            road("north", [[110.0, 5.0], [110.0, 105.0]], Vec::new()),
            road("east", [[110.0, 0.0], [210.0, 0.0]], Vec::new()),
        ];
        let routes = lane_routes(&roads, 30.0);
        let summary: Vec<(Xy, f64)> = routes.iter().map(|r| (r.path.end(), r.home)).collect();
        let across = 105.0 + 50f64.sqrt();
        assert_eq!(summary.len(), 4);
        assert_eq!(summary[0].0, [110.0, 105.0]);
        assert_relative_eq!(summary[0].1, across);
        assert_eq!(summary[1], ([210.0, 0.0], 110.0));
        assert_eq!(summary[2], ([110.0, 105.0], 100.0));
        assert_eq!(summary[3], ([210.0, 0.0], 100.0));
        // A vehicle on the first lane has both branches; one on the east lane only
        // its own route, not the tail of the first lane's.
        let map = RouteMap::new(routes);
        assert_eq!(map.branches(Point::new(50.0, 0.0), 0.0).len(), 2);
        let east = map.branches(Point::new(150.0, 0.0), 0.0);
        assert_eq!(east.len(), 1);
        assert_relative_eq!(east[0].1, 40.0);
    }

    /// A 1 mm lane linked to itself twice, with a 100 m reach: the route from
    /// it would go round 100 000 times and fork at every turn. It ends where the
    /// lane's routes have taken their points, one route of at most that many
    /// points past its own lane, and the recursion this replaced overflowed the
    /// stack.
    #[test]
    fn lane_routes_end_a_cycle_of_short_lanes_at_the_points_limit() {
        let roads = [road(
            "loop",
            [[0.0, 0.0], [0.001, 0.0]],
            vec![link(0, Vec::new()), link(0, Vec::new())],
        )];
        let routes = lane_routes(&roads, 100.0);
        assert_eq!(routes.len(), 1);
        let points = routes[0].path.points().len();
        assert!(points <= 2 + MAX_ROUTE_POINTS, "{points} points");
        assert!(
            points >= MAX_ROUTE_POINTS / 2,
            "{points} points: ended before the limit"
        );
        assert!(routes[0].path.length() < 100.0);
    }
}
