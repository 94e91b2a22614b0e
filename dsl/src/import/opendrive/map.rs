//! A network sampled into what a scenario uses: each lane a road user can
//! travel as a centreline in its direction of travel, followed from lane
//! section to lane section and linked to the lanes it continues into; each
//! junction's outline; each object's areas.

use std::collections::HashMap;

use super::geometry::ReferenceLine;
use super::junctions::{Contact, Junction};
use super::lanes::{Lane, LaneDirection, LaneSection, LaneUse, Speed, linear, value_at};
use super::network::{Element, Network, Road};
use super::xml::OpenDriveError;
use crate::Location;
use crate::geometry::{MAX_CHORD_ERROR, Xy, convex_hull};

/// The longest step between two samples of a lane, metres.
const MAX_STEP: f64 = 1.0;

/// The step along a cubic reference line (poly3, paramPoly3), metres.
const CUBIC_STEP: f64 = 0.5;

/// The shortest step, metres, however sharp a curve.
const MIN_STEP: f64 = 0.05;

/// The most points the sampled lanes of one map may hold.
pub const MAX_POINTS: f64 = 5.0e6;

/// A map: the lanes road users travel, junctions and objects.
#[derive(Debug, Clone, PartialEq)]
pub struct Map {
    /// Every lane a road user can travel, once per direction of travel.
    pub lanes: Vec<MapLane>,
    /// Every junction with connecting roads, as the outline of their lanes.
    pub junctions: Vec<JunctionArea>,
    /// Every object with an area.
    pub objects: Vec<MapObject>,
}

/// A lane followed in one direction of travel through a road's lane sections.
#[derive(Debug, Clone, PartialEq)]
pub struct MapLane {
    /// Its name in routes: `road R lane L`, with `section K` before `lane`
    /// when it starts in another lane section than the road's first in its
    /// direction (K counting the road's sections from 0 in file order), and
    /// ` reversed` after when it runs against its lane's direction.
    pub name: String,
    /// Whether vehicles or pedestrians travel it.
    pub carries: LaneUse,
    /// Its centreline in its direction of travel, metres.
    pub centre: Vec<Xy>,
    /// Its mean width, metres.
    pub width: f64,
    /// The lowest speed limit along it, m/s; `None` when nothing limits it.
    pub speed: Option<f64>,
    /// Whether some stretch of it has no speed limit (none given, `no limit`
    /// or `undefined`).
    pub unlimited: bool,
    /// The lanes (indices into [`Map::lanes`]) it continues into at its end.
    pub next: Vec<usize>,
    /// Where its lane is written, in the section it starts in.
    pub at: Location,
}

/// A junction's area.
#[derive(Debug, Clone, PartialEq)]
pub struct JunctionArea {
    /// Its id.
    pub id: String,
    /// The convex hull of its connecting roads' drivable lanes, counter-clockwise.
    pub outline: Vec<Xy>,
}

/// An object's areas.
#[derive(Debug, Clone, PartialEq)]
pub struct MapObject {
    /// Its road's id.
    pub road: String,
    /// Its id.
    pub id: String,
    /// Its `type`.
    pub kind: String,
    /// Its areas (polygons of three corners or more).
    pub areas: Vec<Vec<Xy>>,
    /// The heading of its road's reference line at its s, radians.
    pub road_heading: f64,
    /// Whether it is repeated along the road (`<repeat>`), which is not read.
    pub repeated: bool,
    /// Where it is written.
    pub at: Location,
}

/// Which way along s a lane is travelled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Way {
    Along,
    Against,
}

/// One lane of one lane section, travelled one way.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct Segment {
    road: usize,
    section: usize,
    lane: i32,
    way: Way,
}

/// A lane of a lane section, sampled.
#[derive(Debug, Clone, Default)]
struct Sampled {
    centre: Vec<Xy>,
    widths: Vec<f64>,
}

/// Samples `network` into a [`Map`].
pub fn build(network: &Network) -> Result<Map, OpenDriveError> {
    let plans: Vec<Vec<(f64, usize)>> = network.roads.iter().map(samples_of).collect();
    let points: Vec<f64> = network
        .roads
        .iter()
        .zip(&plans)
        .map(|(road, plan)| {
            let lanes = road
                .lanes
                .sections
                .iter()
                .map(|s| s.left.len() + s.right.len() + 1)
                .max()
                .unwrap_or(1);
            plan.iter().map(|&(_, n)| n as f64).sum::<f64>() * lanes as f64
        })
        .collect();
    let total: f64 = points.iter().sum();
    if total > MAX_POINTS {
        let (largest, most) = points
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(b.1))
            .expect("a map over the limit has a road");
        let road = &network.roads[largest];
        return Err(OpenDriveError {
            location: road.at,
            message: format!(
                "the map's lanes would take {total:.0} points to sample, more than the limit of {MAX_POINTS:.0} \
                 (road {} alone {most:.0}: its lanes are sampled every 5 cm to 1 m, finer on tighter curves); \
                 use a smaller map",
                road.id
            ),
        });
    }
    let sampled: Vec<Vec<HashMap<i32, Sampled>>> = network
        .roads
        .iter()
        .zip(&plans)
        .map(|(road, plan)| sample_road(road, plan))
        .collect();
    let lanes = chains(network, &sampled);
    let mut connecting: HashMap<&str, Vec<usize>> = HashMap::new();
    for (r, road) in network.roads.iter().enumerate() {
        if let Some(junction) = &road.junction {
            connecting.entry(junction.as_str()).or_default().push(r);
        }
    }
    let junctions = network
        .junctions
        .iter()
        .filter_map(|junction| {
            let points: Vec<Xy> = connecting
                .get(junction.id.as_str())
                .into_iter()
                .flatten()
                .flat_map(|&r| drivable_borders(&network.roads[r], &sampled[r]))
                .collect();
            let outline = convex_hull(points);
            (outline.len() >= 3).then(|| JunctionArea {
                id: junction.id.clone(),
                outline,
            })
        })
        .collect();
    let objects = network
        .roads
        .iter()
        .filter(|road| !road.objects.is_empty())
        .flat_map(|road| {
            let reference = ReferenceLine::new(&road.reference);
            road.objects.iter().map(move |object| {
                let origin = reference.pose(object.s.min(road.length));
                MapObject {
                    road: road.id.clone(),
                    id: object.id.clone(),
                    kind: object.kind.clone(),
                    areas: object.areas(origin, |s| reference.pose(s.clamp(0.0, road.length))),
                    road_heading: origin.heading,
                    repeated: object.repeated,
                    at: object.at,
                }
            })
        })
        .filter(|object| !object.areas.is_empty())
        .collect();
    Ok(Map {
        lanes,
        junctions,
        objects,
    })
}

/// Where a road is sampled: (s, number of steps from the previous s) from 0
/// to its length, with every record's start among them.
fn samples_of(road: &Road) -> Vec<(f64, usize)> {
    let mut breaks: Vec<f64> = vec![0.0, road.length];
    breaks.extend(road.reference.iter().map(|g| g.s));
    breaks.extend(road.lanes.offsets.iter().map(|o| o.s));
    for section in &road.lanes.sections {
        breaks.push(section.s);
        breaks.extend(
            section
                .lanes()
                .flat_map(|lane| lane.widths.iter().map(|w| section.s + w.s)),
        );
    }
    breaks.retain(|s| (0.0..=road.length).contains(s));
    breaks.sort_by(f64::total_cmp);
    breaks.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let straight_lanes = linear(&road.lanes.offsets)
        && road
            .lanes
            .sections
            .iter()
            .all(|s| s.lanes().all(|lane| linear(&lane.widths)));
    let mut plan = vec![(0.0, 0)];
    for pair in breaks.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let geometry = &road.reference[road.reference.partition_point(|g| g.s <= (a + b) / 2.0).max(1) - 1];
        let step = match geometry.max_curvature() {
            Some(k) if k == 0.0 && straight_lanes => f64::INFINITY,
            Some(k) if k > 0.0 => (4.0 * MAX_CHORD_ERROR / k).sqrt().clamp(MIN_STEP, MAX_STEP),
            Some(_) => MAX_STEP,
            None => CUBIC_STEP,
        };
        let steps = ((b - a) / step).ceil().max(1.0) as usize;
        plan.push((b, steps));
    }
    plan
}

/// The s values of `plan` within [from, to], both ends included.
fn positions(plan: &[(f64, usize)], from: f64, to: f64) -> Vec<f64> {
    let mut out = Vec::new();
    for pair in plan.windows(2) {
        let ((a, _), (b, steps)) = (pair[0], pair[1]);
        if b <= from + 1e-9 || a >= to - 1e-9 {
            continue;
        }
        for i in 0..steps {
            let s = a + (b - a) * i as f64 / steps as f64;
            if s >= from - 1e-9 && s <= to + 1e-9 {
                out.push(s);
            }
        }
    }
    out.push(to);
    if out.first().is_none_or(|&s| s > from + 1e-9) {
        out.insert(0, from);
    }
    out
}

/// The end of lane section `k` of `road`.
fn section_end(road: &Road, k: usize) -> f64 {
    road.lanes.sections.get(k + 1).map_or(road.length, |next| next.s)
}

/// Every lane of every lane section of `road`, sampled at `plan`'s positions
/// within the section: its centreline along s and its width there.
fn sample_road(road: &Road, plan: &[(f64, usize)]) -> Vec<HashMap<i32, Sampled>> {
    let reference = ReferenceLine::new(&road.reference);
    road.lanes
        .sections
        .iter()
        .enumerate()
        .map(|(k, section)| {
            let mut lanes: HashMap<i32, Sampled> = HashMap::new();
            for s in positions(plan, section.s, section_end(road, k)) {
                let pose = reference.pose(s);
                let offset = value_at(&road.lanes.offsets, s);
                for (side, sign) in [(&section.left, 1.0), (&section.right, -1.0)] {
                    let mut inner = offset;
                    for lane in side {
                        let width = value_at(&lane.widths, s - section.s).max(0.0);
                        let outer = inner + sign * width;
                        let entry = lanes.entry(lane.id).or_default();
                        entry.centre.push(pose.left((inner + outer) / 2.0));
                        entry.widths.push(width);
                        inner = outer;
                    }
                }
            }
            lanes
        })
        .collect()
}

/// The borders of the drivable lanes of a road: both edges of each, at every sample.
fn drivable_borders<'a>(road: &'a Road, sampled: &'a [HashMap<i32, Sampled>]) -> impl Iterator<Item = Xy> + 'a {
    road.lanes
        .sections
        .iter()
        .zip(sampled)
        .flat_map(move |(section, lanes)| {
            section
                .lanes()
                .filter(|lane| lane.carries == LaneUse::Drive)
                .flat_map(move |lane| {
                    let sampled = &lanes[&lane.id];
                    let centre = &sampled.centre;
                    centre.iter().enumerate().flat_map(move |(i, &point)| {
                        // The lane's direction at this sample, from its neighbours.
                        let (a, b) = (centre[i.saturating_sub(1)], centre[(i + 1).min(centre.len() - 1)]);
                        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                        let norm = dx.hypot(dy).max(1e-12);
                        let half = sampled.widths[i] / 2.0;
                        let (nx, ny) = (-dy / norm * half, dx / norm * half);
                        [[point[0] + nx, point[1] + ny], [point[0] - nx, point[1] - ny]]
                    })
                })
        })
}

/// The ways lane `lane` of `road` is travelled, its own first.
fn ways(road: &Road, lane: &Lane) -> Vec<Way> {
    let along = (lane.id < 0) != road.left_hand;
    let (own, other) = if along {
        (Way::Along, Way::Against)
    } else {
        (Way::Against, Way::Along)
    };
    match (lane.carries, lane.direction) {
        (LaneUse::Other, _) => Vec::new(),
        (LaneUse::Walk, _) | (_, LaneDirection::Both) => vec![own, other],
        (_, LaneDirection::Standard) => vec![own],
        (_, LaneDirection::Reversed) => vec![other],
    }
}

/// The lane it continues into within its road, from `segment`.
fn next_in_road(network: &Network, segment: Segment) -> Option<Segment> {
    let road = &network.roads[segment.road];
    let sections = &road.lanes.sections;
    let lane = sections[segment.section].lane(segment.lane)?;
    let (next_section, links) = match segment.way {
        Way::Along => (segment.section + 1, &lane.successors),
        Way::Against => (segment.section.checked_sub(1)?, &lane.predecessors),
    };
    let section: &LaneSection = sections.get(next_section)?;
    let fits = |id: i32| {
        section
            .lane(id)
            .is_some_and(|next| next.carries == lane.carries && ways(road, next).contains(&segment.way))
    };
    let id = if links.is_empty() {
        Some(lane.id).filter(|&id| fits(id))
    } else {
        links.iter().map(|&(id, _)| id).find(|&id| fits(id))
    }?;
    Some(Segment {
        section: next_section,
        lane: id,
        ..segment
    })
}

/// Every lane travelled, followed through its road's lane sections, with its
/// links into the lanes of the roads it meets.
fn chains(network: &Network, sampled: &[Vec<HashMap<i32, Sampled>>]) -> Vec<MapLane> {
    let mut segments: Vec<Segment> = Vec::new();
    for (r, road) in network.roads.iter().enumerate() {
        for (k, section) in road.lanes.sections.iter().enumerate() {
            for lane in section.lanes() {
                for way in ways(road, lane) {
                    segments.push(Segment {
                        road: r,
                        section: k,
                        lane: lane.id,
                        way,
                    });
                }
            }
        }
    }
    let continued: std::collections::HashSet<Segment> =
        segments.iter().filter_map(|&s| next_in_road(network, s)).collect();
    let mut lanes: Vec<MapLane> = Vec::new();
    // Each chain's segments, and the chain each first segment starts.
    let mut members: Vec<Vec<Segment>> = Vec::new();
    let mut starting: HashMap<Segment, usize> = HashMap::new();
    for &first in segments.iter().filter(|s| !continued.contains(s)) {
        let mut chain = vec![first];
        while let Some(next) = next_in_road(network, *chain.last().expect("a chain has a segment")) {
            if chain.contains(&next) {
                break;
            }
            chain.push(next);
        }
        starting.insert(first, lanes.len());
        lanes.push(chain_lane(network, sampled, &chain));
        members.push(chain);
    }
    let roads: HashMap<&str, usize> = network
        .roads
        .iter()
        .enumerate()
        .map(|(i, r)| (r.id.as_str(), i))
        .collect();
    let junctions: HashMap<&str, &Junction> = network.junctions.iter().map(|j| (j.id.as_str(), j)).collect();
    for (i, chain) in members.iter().enumerate() {
        let last = *chain.last().expect("a chain has a segment");
        lanes[i].next = links_from(network, (&roads, &junctions), last)
            .into_iter()
            .filter_map(|segment| starting.get(&segment).copied())
            .collect();
    }
    lanes
}

/// The map lane made of `chain`'s segments.
fn chain_lane(network: &Network, sampled: &[Vec<HashMap<i32, Sampled>>], chain: &[Segment]) -> MapLane {
    let first = chain[0];
    let road = &network.roads[first.road];
    let lane = road.lanes.sections[first.section]
        .lane(first.lane)
        .expect("a segment's lane exists");
    let opening = match first.way {
        Way::Along => 0,
        Way::Against => road.lanes.sections.len() - 1,
    };
    let section = if first.section == opening {
        String::new()
    } else {
        format!(" section {}", first.section)
    };
    let reversed = if ways(road, lane).first() == Some(&first.way) {
        ""
    } else {
        " reversed"
    };
    let mut centre: Vec<Xy> = Vec::new();
    let (mut width_sum, mut width_count) = (0.0, 0usize);
    let (mut speed, mut unlimited) = (None::<f64>, false);
    for segment in chain {
        let data = &sampled[segment.road][segment.section][&segment.lane];
        let mut points = data.centre.clone();
        if segment.way == Way::Against {
            points.reverse();
        }
        let skip = usize::from(
            centre
                .last()
                .is_some_and(|&last| crate::geometry::distance(last, points[0]) < 1e-9),
        );
        centre.extend(&points[skip..]);
        width_sum += data.widths.iter().sum::<f64>();
        width_count += data.widths.len();
        let own = road.lanes.sections[segment.section]
            .lane(segment.lane)
            .expect("a segment's lane exists");
        for limit in limits(road, segment.section, own) {
            match limit {
                Some(limit) => speed = Some(speed.map_or(limit, |s: f64| s.min(limit))),
                None => unlimited = true,
            }
        }
    }
    MapLane {
        name: format!("road {}{section} lane {}{reversed}", road.id, lane.id),
        carries: lane.carries,
        centre,
        width: width_sum / width_count.max(1) as f64,
        speed,
        unlimited,
        next: Vec::new(),
        at: lane.at,
    }
}

/// The speed limits that apply along `lane` of lane section `k` of `road`:
/// the lane's own (`<speed>`), else the road's (`<type><speed>`) over the
/// section; `None` for a stretch without one.
fn limits(road: &Road, k: usize, lane: &Lane) -> Vec<Option<f64>> {
    let (from, to) = (road.lanes.sections[k].s, section_end(road, k));
    let over = |speeds: &[Speed], offset: f64| -> Vec<Option<f64>> {
        let first = speeds.partition_point(|sp| sp.s + offset <= from).max(1) - 1;
        speeds
            .iter()
            .skip(first)
            .filter(|sp| sp.s + offset < to || speeds.len() == 1)
            .map(|sp| sp.limit)
            .collect()
    };
    let found = if lane.speeds.is_empty() {
        over(&road.speeds, 0.0)
    } else {
        over(&lane.speeds, from)
    };
    if found.is_empty() { vec![None] } else { found }
}

/// The first segments of the lanes a lane ending with `last` continues into
/// in the roads its road meets at that end; `roads` and `junctions` index the
/// network's by id.
fn links_from(
    network: &Network,
    (roads, junctions): (&HashMap<&str, usize>, &HashMap<&str, &Junction>),
    last: Segment,
) -> Vec<Segment> {
    let road = &network.roads[last.road];
    let sections = &road.lanes.sections;
    let (end, lanes_section) = match last.way {
        Way::Along if last.section + 1 == sections.len() => (Contact::End, &sections[last.section]),
        Way::Against if last.section == 0 => (Contact::Start, &sections[0]),
        _ => return Vec::new(),
    };
    let Some(lane) = lanes_section.lane(last.lane) else {
        return Vec::new();
    };
    let Some(link) = road.link_at(end) else {
        return Vec::new();
    };
    let entering = |road_index: usize, contact: Contact, id: i32| {
        let target = &network.roads[road_index];
        Segment {
            road: road_index,
            section: match contact {
                Contact::Start => 0,
                Contact::End => target.lanes.sections.len() - 1,
            },
            lane: id,
            way: match contact {
                Contact::Start => Way::Along,
                Contact::End => Way::Against,
            },
        }
    };
    let index = |id: &str| roads.get(id).copied();
    match link.element {
        Element::Road(contact) => {
            let ids = if end == Contact::End {
                &lane.successors
            } else {
                &lane.predecessors
            };
            let Some(target) = index(&link.id) else {
                return Vec::new();
            };
            ids.iter().map(|&(id, _)| entering(target, contact, id)).collect()
        }
        Element::Junction => junctions
            .get(link.id.as_str())
            .into_iter()
            .flat_map(|j| &j.connections)
            .filter(|c| c.incoming == road.id)
            .flat_map(|c| {
                let target = index(&c.target);
                c.lane_links
                    .iter()
                    .filter(|&&(from, _, _)| from == lane.id)
                    .filter_map(move |&(_, to, _)| Some(entering(target?, c.contact, to)))
            })
            .collect(),
    }
}
