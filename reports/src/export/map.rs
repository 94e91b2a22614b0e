//! A world's roads as an OpenDRIVE road network: reference lines as geometry
//! records, lanes, the links and junctions its routes drive through, and its
//! occluders and crosswalks as objects. Written out by `opendrive`.

use std::collections::{BTreeMap, BTreeSet};

use sightline_dsl::geometry::{Xy, distance};
use sightline_dsl::{Road, World};

/// Two road ends closer than this, metres, meet: a route that joins them is
/// written as a link (1 cm, the chord error of sampled arcs).
const CONTACT: f64 = 0.01;

/// The height given to a building, metres: sightline's occluders are
/// outlines without one.
pub(crate) const BUILDING_HEIGHT: f64 = 10.0;

/// A road network for OpenDRIVE.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Map {
    /// The roads, in the world's order; road k has id k + 1.
    pub roads: Vec<MapRoad>,
    /// The junctions, ids from 1.
    pub junctions: Vec<Junction>,
    /// What the map leaves out, one sentence each.
    pub notes: Vec<String>,
}

/// One road: its reference line, its lanes (all driving along it, right of
/// the reference line), its links and objects.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct MapRoad {
    /// OpenDRIVE id.
    pub id: usize,
    /// sightline's id.
    pub name: String,
    /// The reference line: lane 0's centreline in sightline.
    pub geometry: Vec<Geometry>,
    /// Number of lanes.
    pub lanes: usize,
    /// Lane width, metres.
    pub lane_width: f64,
    /// Speed limit, m/s.
    pub speed_limit: f64,
    /// The junction it is a connecting road of.
    pub junction: Option<usize>,
    /// What its start is linked to.
    pub predecessor: Option<Link>,
    /// What its end is linked to.
    pub successor: Option<Link>,
    /// Buildings and crosswalks placed along it.
    pub objects: Vec<Object>,
}

impl MapRoad {
    /// Length of the reference line, metres.
    pub fn length(&self) -> f64 {
        self.geometry.iter().map(|g| g.length).sum()
    }

    /// The offset of the lanes' inner edge from the reference line, metres:
    /// sightline's lane k lies k widths left of lane 0, OpenDRIVE's lane −1
    /// is the leftmost of the right lanes, so the centre lane lies half a lane
    /// left of the leftmost lane's centreline.
    pub fn lane_offset(&self) -> f64 {
        (self.lanes as f64 - 0.5) * self.lane_width
    }

    /// OpenDRIVE's id of sightline's lane `k` (lane 0 is the rightmost, −n).
    pub fn lane_id(&self, k: usize) -> i64 {
        k as i64 - self.lanes as i64
    }
}

/// What a road end is linked to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Link {
    /// A road's start or end.
    Road {
        /// Its id.
        id: usize,
        /// Whether the link is to its start (else its end).
        start: bool,
    },
    /// A junction.
    Junction(usize),
}

/// A record of a reference line: a line, or an arc when `curvature` ≠ 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Geometry {
    /// Arc length at its start, metres.
    pub s: f64,
    /// Start, metres.
    pub x: f64,
    /// Start, metres.
    pub y: f64,
    /// Heading at its start, radians.
    pub hdg: f64,
    /// Length, metres.
    pub length: f64,
    /// Curvature, 1/m (positive: turning left); 0 for a line.
    pub curvature: f64,
}

impl Geometry {
    /// Position and heading `ds` metres along it.
    pub fn at(&self, ds: f64) -> (Xy, f64) {
        let k = self.curvature;
        let hdg = self.hdg + k * ds;
        if k == 0.0 {
            return ([self.x + ds * self.hdg.cos(), self.y + ds * self.hdg.sin()], hdg);
        }
        let x = self.x + (hdg.sin() - self.hdg.sin()) / k;
        let y = self.y - (hdg.cos() - self.hdg.cos()) / k;
        ([x, y], hdg)
    }
}

/// A junction: the connecting roads from each incoming road.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Junction {
    /// OpenDRIVE id.
    pub id: usize,
    /// Its connections, by connecting road.
    pub connections: Vec<Connection>,
}

/// An incoming road's connection to a connecting road's start.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Connection {
    /// The incoming road's id.
    pub incoming: usize,
    /// The connecting road's id.
    pub connecting: usize,
    /// Lane links (incoming lane id, connecting lane id).
    pub lanes: Vec<(i64, i64)>,
}

/// Kinds of object.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ObjectKind {
    /// An occluder.
    Building,
    /// A pedestrian crossing.
    Crosswalk,
}

/// An object placed along a road, its outline in its local frame (u along
/// the road's heading at `s`, v to its left).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Object {
    /// sightline's id.
    pub name: String,
    /// What it is.
    pub kind: ObjectKind,
    /// Arc length of its origin, metres.
    pub s: f64,
    /// Lateral offset of its origin, metres (left positive).
    pub t: f64,
    /// Its outline's corners (u, v), metres.
    pub corners: Vec<Xy>,
    /// Height, metres.
    pub height: f64,
}

/// Headings closer than this, radians, are one direction: consecutive line
/// records along it are one record. The ASAM checker's tolerance for a
/// redundant line record (`check_asam_xodr_performance_avoid_redundant_info`).
const COLLINEAR: f64 = 1e-6;

/// The reference line of a world road: an arc record for an arc or a ring,
/// line records along a polyline, one per run of collinear segments (an
/// imported road's straight stretch is many short segments).
pub(crate) fn reference(road: &Road) -> Vec<Geometry> {
    if let Some(arc) = road.arc {
        let turn = arc.sweep.signum();
        return vec![Geometry {
            s: 0.0,
            x: arc.center[0] + arc.radius * arc.start.cos(),
            y: arc.center[1] + arc.radius * arc.start.sin(),
            hdg: arc.start + turn * std::f64::consts::FRAC_PI_2,
            length: arc.radius * arc.sweep.abs(),
            curvature: turn / arc.radius,
        }];
    }
    let heading = |a: Xy, b: Xy| (b[1] - a[1]).atan2(b[0] - a[0]);
    let mut records: Vec<Geometry> = Vec::new();
    for pair in road.lanes[0].points().windows(2) {
        let [a, b] = [pair[0], pair[1]];
        match records.last_mut() {
            // The record becomes the chord to `b`: exact at its ends.
            Some(last) if angle_between(last.hdg, heading(a, b)) < COLLINEAR => {
                let start = [last.x, last.y];
                (last.hdg, last.length) = (heading(start, b), distance(start, b));
            }
            last => {
                let s = last.map_or(0.0, |g| g.s + g.length);
                records.push(Geometry {
                    s,
                    x: a[0],
                    y: a[1],
                    hdg: heading(a, b),
                    length: distance(a, b),
                    curvature: 0.0,
                });
            }
        }
    }
    records
}

/// The angle between two headings, radians, from 0 to π.
fn angle_between(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}

/// Position and heading `s` metres along a reference line (clamped to it).
pub(crate) fn pose_at(geometry: &[Geometry], s: f64) -> (Xy, f64) {
    let record = geometry.iter().rev().find(|g| g.s <= s).unwrap_or(&geometry[0]);
    record.at((s - record.s).clamp(0.0, record.length))
}

/// The world's roads as a network. `None` when it has no road.
pub(crate) fn map(world: &World) -> Option<Map> {
    if world.roads.is_empty() {
        return None;
    }
    let mut notes = Vec::new();
    let mut roads: Vec<MapRoad> = world
        .roads
        .iter()
        .enumerate()
        .map(|(i, road)| MapRoad {
            id: i + 1,
            name: road.id.clone(),
            geometry: reference(road),
            lanes: road.lanes.len(),
            lane_width: road.lane_width,
            speed_limit: road.speed_limit,
            junction: None,
            predecessor: None,
            successor: None,
            objects: Vec::new(),
        })
        .collect();
    let junctions = link(world, &mut roads, &mut notes);
    place_objects(world, &mut roads);
    Some(Map {
        roads,
        junctions,
        notes,
    })
}

/// Links the roads that routes drive from one into another where one's end
/// meets the other's start: directly when the link is the only one at both
/// ends, through a junction where roads fan out or in (the roads between an
/// incoming and an outgoing road become its connecting roads). Returns the
/// junctions.
fn link(world: &World, roads: &mut [MapRoad], notes: &mut Vec<String>) -> Vec<Junction> {
    let mut successors: BTreeMap<usize, BTreeSet<usize>> = BTreeMap::new();
    let mut predecessors: BTreeMap<usize, BTreeSet<usize>> = BTreeMap::new();
    for &(from, to) in &world.connections {
        let (a, b) = (&world.roads[from], &world.roads[to]);
        let meets = !a.lanes[0].is_closed()
            && !b.lanes[0].is_closed()
            && distance(a.lanes[0].end(), b.lanes[0].start()) <= CONTACT;
        if meets {
            successors.entry(from).or_default().insert(to);
            predecessors.entry(to).or_default().insert(from);
        } else {
            notes.push(format!(
                "routes drive from road `{}` into `{}` away from its start (a roundabout's ring, or a gap): \
                 the map does not link them",
                a.id, b.id
            ));
        }
    }
    let fans = |set: Option<&BTreeSet<usize>>| set.is_some_and(|s| s.len() > 1);
    let one = |set: Option<&BTreeSet<usize>>| set.filter(|s| s.len() == 1).and_then(|s| s.first().copied());
    // A connecting road leads from one road to one road, and one of them fans.
    let connecting: BTreeMap<usize, (usize, usize)> = (0..roads.len())
        .filter_map(|c| {
            let (p, q) = (one(predecessors.get(&c))?, one(successors.get(&c))?);
            (fans(successors.get(&p)) || fans(predecessors.get(&q))).then_some((c, (p, q)))
        })
        .collect();
    // A connecting road's ends must be ordinary roads.
    let connecting: BTreeMap<usize, (usize, usize)> = connecting
        .iter()
        .filter(|(_, (p, q))| !connecting.contains_key(p) && !connecting.contains_key(q))
        .map(|(&c, &ends)| (c, ends))
        .collect();
    // Junctions: connecting roads that share an incoming or an outgoing road.
    let mut group: BTreeMap<usize, usize> = connecting.keys().map(|&c| (c, c)).collect();
    fn root(group: &BTreeMap<usize, usize>, mut c: usize) -> usize {
        while group[&c] != c {
            c = group[&c];
        }
        c
    }
    for (&c, &(p, q)) in &connecting {
        for (&d, &(p2, q2)) in &connecting {
            if d < c && (p == p2 || q == q2) {
                let (a, b) = (root(&group, c), root(&group, d));
                group.insert(a.max(b), a.min(b));
            }
        }
    }
    let roots: BTreeSet<usize> = connecting.keys().map(|&c| root(&group, c)).collect();
    let junction_of = |c: usize| roots.iter().position(|&r| r == root(&group, c)).map(|k| k + 1);
    let mut junctions: Vec<Junction> = (1..=roots.len())
        .map(|id| Junction {
            id,
            connections: Vec::new(),
        })
        .collect();
    for (&c, &(p, q)) in &connecting {
        let j = junction_of(c).expect("every connecting road has a group");
        let lanes = (0..roads[p].lanes.min(roads[c].lanes))
            .map(|k| (roads[p].lane_id(k), roads[c].lane_id(k)))
            .collect();
        junctions[j - 1].connections.push(Connection {
            incoming: p + 1,
            connecting: c + 1,
            lanes,
        });
        let road = &mut roads[c];
        road.junction = Some(j);
        road.predecessor = Some(Link::Road {
            id: p + 1,
            start: false,
        });
        road.successor = Some(Link::Road { id: q + 1, start: true });
    }
    // The ordinary roads' ends: into a junction, to one road, or unlinked.
    for (r, road) in roads.iter_mut().enumerate() {
        if connecting.contains_key(&r) {
            continue;
        }
        let end = |set: Option<&BTreeSet<usize>>, start: bool| -> Option<Link> {
            let set = set?;
            let in_junctions: BTreeSet<Option<usize>> = set
                .iter()
                .map(|&o| connecting.contains_key(&o).then(|| junction_of(o)).flatten())
                .collect();
            match (in_junctions.len(), in_junctions.first()) {
                (1, Some(Some(j))) => Some(Link::Junction(*j)),
                (1, Some(None)) if set.len() == 1 => Some(Link::Road {
                    id: set.first().copied()? + 1,
                    start,
                }),
                _ => None,
            }
        };
        let successor = end(successors.get(&r), true);
        let predecessor = end(predecessors.get(&r), false);
        // A direct link holds only when the other road links back alone.
        let back = |link: Option<Link>, others: &BTreeMap<usize, BTreeSet<usize>>| match link {
            Some(Link::Road { id, .. }) if others.get(&(id - 1)).is_some_and(|s| s.len() == 1) => link,
            Some(Link::Junction(_)) => link,
            _ => None,
        };
        let (successor, predecessor) = (back(successor, &predecessors), back(predecessor, &successors));
        for (wanted, got, side) in [
            (successors.contains_key(&r), successor.is_some(), "end"),
            (predecessors.contains_key(&r), predecessor.is_some(), "start"),
        ] {
            if wanted && !got {
                notes.push(format!(
                    "the {side} of road `{}` joins roads that do not form a junction of connecting roads: \
                     the map does not link it",
                    road.name
                ));
            }
        }
        road.successor = successor;
        road.predecessor = predecessor;
    }
    junctions
}

/// Places each occluder (a building) and crosswalk on the road whose lane 0
/// passes closest to its centre.
fn place_objects(world: &World, roads: &mut [MapRoad]) {
    let crosswalk_outline = |from: Xy, to: Xy, width: f64| {
        let length = distance(from, to);
        let n = [
            -(to[1] - from[1]) / length * width / 2.0,
            (to[0] - from[0]) / length * width / 2.0,
        ];
        vec![
            [from[0] - n[0], from[1] - n[1]],
            [to[0] - n[0], to[1] - n[1]],
            [to[0] + n[0], to[1] + n[1]],
            [from[0] + n[0], from[1] + n[1]],
        ]
    };
    let buildings = world
        .occluders
        .iter()
        .map(|o| (o.id.clone(), ObjectKind::Building, o.polygon.clone(), BUILDING_HEIGHT));
    let crosswalks = world.crosswalks.iter().map(|c| {
        (
            c.id.clone(),
            ObjectKind::Crosswalk,
            crosswalk_outline(c.from, c.to, c.width),
            0.0,
        )
    });
    for (name, kind, outline, height) in buildings.chain(crosswalks) {
        let n = outline.len() as f64;
        let centre = [
            outline.iter().map(|p| p[0]).sum::<f64>() / n,
            outline.iter().map(|p| p[1]).sum::<f64>() / n,
        ];
        let (road, at) = world
            .roads
            .iter()
            .enumerate()
            .map(|(i, r)| (i, r.lanes[0].project(centre)))
            .min_by(|a, b| a.1.distance.total_cmp(&b.1.distance))
            .expect("a map has a road");
        let geometry = &roads[road].geometry;
        let s = at.offset.clamp(0.0, roads[road].length());
        let (p, h) = pose_at(geometry, s);
        let (u, v) = ([h.cos(), h.sin()], [-h.sin(), h.cos()]);
        let t = (centre[0] - p[0]) * v[0] + (centre[1] - p[1]) * v[1];
        let origin = [p[0] + t * v[0], p[1] + t * v[1]];
        let corners = outline
            .iter()
            .map(|q| {
                let d = [q[0] - origin[0], q[1] - origin[1]];
                [d[0] * u[0] + d[1] * u[1], d[0] * v[0] + d[1] * v[1]]
            })
            .collect();
        roads[road].objects.push(Object {
            name,
            kind,
            s,
            t,
            corners,
            height,
        });
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{FRAC_PI_2, PI};

    use sightline_dsl::geometry::{Arc, Polyline};
    use sightline_dsl::{Experiment, LaneLink};

    use super::*;

    fn road(points: &[Xy], arc: Option<Arc>) -> Road {
        Road {
            id: "r".into(),
            lanes: vec![Polyline::new(points.iter().copied()).unwrap()],
            lane_width: 3.5,
            speed_limit: 10.0,
            links: Vec::<LaneLink>::new(),
            arc,
        }
    }

    #[track_caller]
    fn assert_close(a: f64, b: f64) {
        assert!((a - b).abs() < 1e-9, "{a} ≠ {b}");
    }

    #[test]
    fn a_polyline_is_one_line_record_per_segment() {
        // (0, 0) → (30, 40): 50 m at atan2(40, 30); then (30, 40) → (30, 100): 60 m north.
        let records = reference(&road(&[[0.0, 0.0], [30.0, 40.0], [30.0, 100.0]], None));
        assert_eq!(records.len(), 2);
        let [a, b] = [records[0], records[1]];
        assert_eq!((a.s, a.x, a.y, a.length, a.curvature), (0.0, 0.0, 0.0, 50.0, 0.0));
        assert_close(a.hdg, 0.927_295_218_001_612_2);
        assert_eq!((b.s, b.x, b.y, b.length, b.curvature), (50.0, 30.0, 40.0, 60.0, 0.0));
        assert_close(b.hdg, FRAC_PI_2);
        let (end, hdg) = pose_at(&records, 110.0);
        assert_close(end[0], 30.0);
        assert_close(end[1], 100.0);
        assert_close(hdg, FRAC_PI_2);
    }

    #[test]
    fn collinear_segments_are_one_line_record_exact_at_its_ends() {
        // Three segments east, the second 1e-7 rad off, then one north; a
        // segment west is not collinear with one east.
        let off = [20.0 + 10.0 * 1e-7_f64.cos(), 10.0 * 1e-7_f64.sin()];
        let points = [
            [0.0, 0.0],
            [10.0, 0.0],
            off,
            [40.0, 0.0],
            [40.0, 5.0],
            [40.0, 9.0],
            [30.0, 9.0],
        ];
        let records = reference(&road(&points, None));
        assert_eq!(records.len(), 3, "{records:?}");
        let [east, north, west] = [records[0], records[1], records[2]];
        assert_eq!((east.s, east.x, east.y, east.length), (0.0, 0.0, 0.0, 40.0));
        assert_close(east.hdg, 0.0);
        assert_eq!((north.s, north.x, north.y, north.length), (40.0, 40.0, 0.0, 9.0));
        assert_close(north.hdg, FRAC_PI_2);
        assert_eq!((west.s, west.length), (49.0, 10.0));
        let (end, _) = pose_at(&records, 59.0);
        assert_close(end[0], 30.0);
        assert_close(end[1], 9.0);
        assert!(angle_between(-PI + 1e-8, PI - 1e-8) < COLLINEAR);
        assert_close(angle_between(0.5, -0.5), 1.0);
    }

    #[test]
    fn an_arc_is_one_arc_record() {
        // The urban junction's right turn n_w: centre (−8, 8), r = 6.25 m, from
        // 0° clockwise to −90°: it starts at (−1.75, 8) heading south (−π/2),
        // is 6.25 · π/2 = 9.8175 m long with curvature −1/6.25 = −0.16, and
        // ends at (−8, 1.75) heading west (−π).
        let arc = Arc {
            center: [-8.0, 8.0],
            radius: 6.25,
            start: 0.0,
            sweep: -FRAC_PI_2,
        };
        let records = reference(&road(&arc.points(), Some(arc)));
        assert_eq!(records.len(), 1);
        let g = records[0];
        assert_eq!((g.s, g.x, g.y), (0.0, -1.75, 8.0));
        assert_close(g.hdg, -FRAC_PI_2);
        assert_close(g.length, 9.817_477_042_468_104);
        assert_close(g.curvature, -0.16);
        let (end, hdg) = g.at(g.length);
        assert_close(end[0], -8.0);
        assert_close(end[1], 1.75);
        assert_close(hdg, -PI);
    }

    #[test]
    fn a_ring_is_a_whole_circle() {
        // Radius 20 counter-clockwise from 0°: starts at (20, 0) heading north,
        // 40π m long, curvature 1/20.
        let ring = Arc {
            center: [0.0, 0.0],
            radius: 20.0,
            start: 0.0,
            sweep: 2.0 * PI,
        };
        let g = reference(&road(&ring.points(), Some(ring)))[0];
        assert_eq!((g.x, g.y), (20.0, 0.0));
        assert_close(g.hdg, FRAC_PI_2);
        assert_close(g.length, 40.0 * PI);
        assert_close(g.curvature, 0.05);
    }

    #[test]
    fn lanes_lie_right_of_a_centre_lane_left_of_the_leftmost() {
        let mut road = MapRoad {
            id: 1,
            name: "r".into(),
            geometry: Vec::new(),
            lanes: 2,
            lane_width: 3.5,
            speed_limit: 10.0,
            junction: None,
            predecessor: None,
            successor: None,
            objects: Vec::new(),
        };
        // Lane 0 (the reference line) is OpenDRIVE's −2, centred 3.5 m right of
        // the centre lane at 5.25 m: 5.25 − 3.5 − 1.75 = 0.
        assert_eq!(road.lane_offset(), 5.25);
        assert_eq!((road.lane_id(0), road.lane_id(1)), (-2, -1));
        road.lanes = 1;
        assert_eq!((road.lane_offset(), road.lane_id(0)), (1.75, -1));
    }

    fn world_of(text: &str) -> World {
        let scenario = sightline_dsl::compile("s.yaml", text, &Default::default()).unwrap();
        let Experiment::World(world) = &scenario.points[0].setup.experiment else {
            panic!("a world");
        };
        (**world).clone()
    }

    #[test]
    fn the_urban_junction_has_its_turns_as_connecting_roads() {
        let world = world_of(include_str!("../../../scenarios/urban-falsify.yaml"));
        let map = map(&world).unwrap();
        assert!(map.notes.is_empty(), "{:?}", map.notes);
        assert_eq!(map.junctions.len(), 1);
        // Eight movements through the junction, one lane each.
        assert_eq!(map.junctions[0].connections.len(), 8);
        let by_name = |name: &str| map.roads.iter().find(|r| r.name == name).unwrap();
        let (north_in, n_s, south_out) = (by_name("north_in"), by_name("n_s"), by_name("south_out"));
        assert_eq!(n_s.junction, Some(1));
        assert_eq!(
            n_s.predecessor,
            Some(Link::Road {
                id: north_in.id,
                start: false
            })
        );
        assert_eq!(
            n_s.successor,
            Some(Link::Road {
                id: south_out.id,
                start: true
            })
        );
        assert_eq!(north_in.successor, Some(Link::Junction(1)));
        assert_eq!(south_out.predecessor, Some(Link::Junction(1)));
        assert_eq!(north_in.predecessor, None);
        // Four buildings and four crosswalks, each on a road.
        let objects: Vec<&Object> = map.roads.iter().flat_map(|r| &r.objects).collect();
        assert_eq!(objects.iter().filter(|o| o.kind == ObjectKind::Building).count(), 4);
        assert_eq!(objects.iter().filter(|o| o.kind == ObjectKind::Crosswalk).count(), 4);
    }

    #[test]
    fn objects_keep_their_world_corners() {
        let world = world_of(include_str!("../../../scenarios/urban-falsify.yaml"));
        let map = map(&world).unwrap();
        let mut checked = 0;
        for road in &map.roads {
            for object in &road.objects {
                let (p, h) = pose_at(&road.geometry, object.s);
                let origin = [p[0] - object.t * h.sin(), p[1] + object.t * h.cos()];
                let world_corners: Vec<Xy> = object
                    .corners
                    .iter()
                    .map(|[u, v]| {
                        [
                            origin[0] + u * h.cos() - v * h.sin(),
                            origin[1] + u * h.sin() + v * h.cos(),
                        ]
                    })
                    .collect();
                if object.name == "block_ne" {
                    let expected = [[8.0, 8.0], [150.0, 8.0], [150.0, 150.0], [8.0, 150.0]];
                    for (got, want) in world_corners.iter().zip(expected) {
                        assert_close(got[0], want[0]);
                        assert_close(got[1], want[1]);
                    }
                    checked += 1;
                }
                if object.name == "cw_north" {
                    // From (−6, 11) to (6, 11), 3 m wide.
                    let ys: Vec<f64> = world_corners.iter().map(|c| c[1]).collect();
                    assert!(
                        ys.iter().all(|y| (y - 9.5).abs() < 1e-9 || (y - 12.5).abs() < 1e-9),
                        "{ys:?}"
                    );
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 2, "block_ne and cw_north are placed");
    }

    #[test]
    fn a_roundabout_s_arms_are_left_unlinked_and_said_so() {
        let world = world_of(include_str!("../../../scenarios/roundabout-six-agents.yaml"));
        let map = map(&world).unwrap();
        assert!(map.junctions.is_empty());
        assert!(
            map.roads
                .iter()
                .all(|r| r.predecessor.is_none() && r.successor.is_none())
        );
        assert_eq!(map.notes.len(), 8, "four arms in, four out: {:?}", map.notes);
    }
}
