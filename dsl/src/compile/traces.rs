//! The `traces` section: SUMO files read once through the caller's
//! [`Loader`](super::Loader), parsed, checked against each other, and turned into
//! what every sweep point shares (roads, occluders, interaction areas, trace
//! samples); [`trace_motion`] and [`imported_agents`] then build the agents.
//!
//! Choices, documented in `docs/scenario-language.md`:
//! - A vehicle's SUMO position is the centre of its front bumper; its samples are
//!   moved back half its length along its heading to the footprint's centre. A
//!   person's position is taken as its centre.
//! - Scenario time is the trace's time minus `begin`.
//! - The longest gap interpolated across is 1.5 × the trace's sample period (the
//!   shortest interval between two samples of one object): an object missing from
//!   the trace for longer (teleported, riding a vehicle) is out of the scene.
//! - A network's roads are its normal edges (not crossings, walking areas or
//!   connectors), each with its lanes; the road's width and speed limit are lane
//!   0's. A sample's speed limit is that of its lane, internal lanes across
//!   junctions included.

use std::collections::{HashMap, HashSet};

use super::context::Context;
use crate::error::{Error, ErrorKind, utf8_text};
use crate::geometry::{Polyline, counter_clockwise, distance};
use crate::import::Problem;
use crate::import::sumo::{Fcd, FcdObject, Network, parse_fcd, parse_net, parse_poly};
use crate::model::{
    Agent, AgentKind, Area, Import, ImportKind, InteractionArea, LaneLink, Motion, Occluder, Road, TraceSample,
};
use crate::path::Path;
use crate::raw::RawTraces;
use crate::raw::range;

/// Gaps up to this many sample periods are interpolated across.
const GAP_PERIODS: f64 = 1.5;

/// What `traces` imports, read and checked once for every sweep point.
pub(crate) struct Imported {
    /// The trace.
    fcd: Fcd,
    /// The network's roads, their links indexing this list.
    pub(super) roads: Vec<Road>,
    /// The polygons that block sight.
    pub(super) occluders: Vec<Occluder>,
    /// The junctions that become interaction areas.
    pub(super) areas: Vec<InteractionArea>,
    /// The speed limit of every lane of the network, by id, internal lanes too.
    limits: HashMap<String, f64>,
    /// The longest time between two samples interpolated across, seconds.
    max_gap: f64,
    /// The trace's time of scenario time 0, seconds.
    begin: f64,
    /// The files as read, for the evidence.
    pub(super) files: Vec<Import>,
}

/// Reads, parses and checks the files of `traces`; `None` (with the errors
/// recorded) when there is no such section or a file fails.
pub(super) fn load(
    ctx: &mut Context<'_>,
    raw: Option<&RawTraces>,
    loader: Option<&dyn super::Loader>,
) -> Option<Imported> {
    let raw = raw?;
    let at = Path::root().key("traces");
    let mut files = Vec::new();
    let mut reader = Reader {
        ctx: &mut *ctx,
        loader,
        files: &mut files,
    };
    let fcd = reader.read(&at.key("fcd"), &raw.fcd, ImportKind::SumoFcd, parse_fcd);
    let net = raw
        .net
        .as_ref()
        .map(|net| reader.read(&at.key("net"), net, ImportKind::SumoNet, parse_net))
        .transpose();
    let polygons = raw
        .poly
        .as_ref()
        .map(|poly| reader.read(&at.key("poly"), poly, ImportKind::SumoPoly, parse_poly))
        .transpose();
    let begin_ok = ctx.within(&at.key("begin"), raw.begin, range::TRACE_TIME);
    let (Ok(fcd), Ok(net), Ok(polygons), true) = (fcd, net, polygons, begin_ok) else {
        return None;
    };
    let limits: HashMap<String, f64> = net
        .iter()
        .flat_map(|net| net.edges.iter().flat_map(|e| &e.lanes).chain(&net.internal_lanes))
        .map(|lane| (lane.id.clone(), lane.speed))
        .collect();
    let mut ok = net.is_none() || lanes_known(ctx, &at.key("net"), &fcd, &limits);
    let roads = net
        .as_ref()
        .map_or(Some(Vec::new()), |net| net_roads(ctx, &at.key("net"), net));
    let mut occluders = Vec::new();
    for polygon in polygons
        .iter()
        .flatten()
        .filter(|p| raw.occluder_types.contains(&p.kind))
    {
        match counter_clockwise(&polygon.shape) {
            Some(outline) => occluders.push(Occluder {
                id: polygon.id.clone(),
                polygon: outline,
            }),
            None => {
                ctx.error(
                    &at.key("poly"),
                    ErrorKind::Invalid(format!(
                        "polygon `{}` of type `{}` encloses no area: an occluder needs three corners",
                        polygon.id, polygon.kind
                    )),
                );
                ok = false;
            }
        }
    }
    let areas = match &net {
        Some(net) if raw.junction_areas => junction_areas(net),
        _ => Vec::new(),
    };
    if !ok {
        return None;
    }
    Some(Imported {
        max_gap: GAP_PERIODS * sample_period(&fcd),
        fcd,
        roads: roads?,
        occluders,
        areas,
        limits,
        begin: raw.begin,
        files,
    })
}

/// A file failed to load; the error is recorded.
pub(super) struct Failed;

/// Reads imported files, recording each and every failure.
pub(super) struct Reader<'c, 'a, 'f> {
    pub(super) ctx: &'c mut Context<'a>,
    pub(super) loader: Option<&'f dyn super::Loader>,
    pub(super) files: &'f mut Vec<Import>,
}

impl Reader<'_, '_, '_> {
    /// Reads the file `written` (relative to the scenario's directory) and parses
    /// it; a failure to read is an error at `at`, a malformed file an error in it.
    pub(super) fn read<T, E: Problem>(
        &mut self,
        at: &Path,
        written: &str,
        kind: ImportKind,
        parse: impl Fn(&str) -> Result<T, E>,
    ) -> Result<T, Failed> {
        let directory = std::path::Path::new(self.ctx.file)
            .parent()
            .unwrap_or(std::path::Path::new(""));
        let path = directory.join(written);
        let file = path.display().to_string();
        let bytes = match self.loader.map(|loader| loader.load(&path)) {
            Some(Ok(bytes)) => bytes,
            failed => {
                let reason = match failed {
                    Some(Err(error)) => error.to_string(),
                    _ => "this compilation was given no file loader".into(),
                };
                self.ctx.error(at, ErrorKind::Io { file, reason });
                return Err(Failed);
            }
        };
        let parsed = match utf8_text(&bytes) {
            Ok(text) => parse(text).map_err(|e| (e.location(), e.message().to_owned())),
            Err(location) => Err((location, "the file is not UTF-8 text".into())),
        };
        match parsed {
            Ok(value) => {
                self.files.push(Import {
                    kind,
                    path: file,
                    bytes,
                });
                Ok(value)
            }
            Err((location, message)) => {
                self.ctx.errors.push(Error {
                    file,
                    location,
                    path: String::new(),
                    kind: ErrorKind::Import(message),
                });
                Err(Failed)
            }
        }
    }
}

/// Checks that every lane the trace puts a vehicle on is in the network: a
/// trace and a network from different simulations are an error at `at`.
fn lanes_known(ctx: &mut Context<'_>, at: &Path, fcd: &Fcd, limits: &HashMap<String, f64>) -> bool {
    let mut strays = fcd.objects.iter().filter_map(|object| {
        object
            .samples
            .iter()
            .find_map(|s| {
                s.lane
                    .as_ref()
                    .filter(|lane| !limits.contains_key(*lane))
                    .map(|lane| (s, lane))
            })
            .map(|(sample, lane)| (object, sample.time, lane))
    });
    let Some((object, time, lane)) = strays.next() else {
        return true;
    };
    let others = strays.count();
    let more = match others {
        0 => String::new(),
        1 => " (and so is 1 other object)".into(),
        n => format!(" (and so are {n} other objects)"),
    };
    ctx.error(
        at,
        ErrorKind::Invalid(format!(
            "the trace puts `{}` at {time} s on lane `{lane}`, which the network does not have{more}; \
             are the trace and the network from the same simulation?",
            object.id
        )),
    );
    false
}

/// The roads of a network: its normal edges, lane 0 first, linked by its
/// connections.
fn net_roads(ctx: &mut Context<'_>, at: &Path, net: &Network) -> Option<Vec<Road>> {
    let edges: Vec<_> = net.edges.iter().filter(|edge| edge.function.is_empty()).collect();
    let road_of: HashMap<&str, usize> = edges.iter().enumerate().map(|(i, e)| (e.id.as_str(), i)).collect();
    let mut ok = true;
    let mut roads = Vec::new();
    for edge in &edges {
        let mut lanes = edge.lanes.clone();
        lanes.sort_by_key(|lane| lane.index);
        let mut lines = Vec::new();
        for lane in &lanes {
            match Polyline::new(lane.shape.iter().copied()) {
                Some(line) => lines.push(line),
                None => {
                    ctx.error(
                        at,
                        ErrorKind::Invalid(format!("lane `{}` of the network has no length", lane.id)),
                    );
                    ok = false;
                }
            }
        }
        let Some(first) = lanes.first() else {
            ctx.error(
                at,
                ErrorKind::Invalid(format!("edge `{}` of the network has no lanes", edge.id)),
            );
            ok = false;
            continue;
        };
        roads.push(Road {
            id: edge.id.clone(),
            lanes: lines,
            lane_width: first.width,
            speed_limit: first.speed,
            links: Vec::new(),
        });
    }
    if !ok {
        return None;
    }
    // A lane's position among its road's lanes, by road and SUMO index.
    let position = |road: usize, index: u32| {
        let mut indices: Vec<u32> = edges[road].lanes.iter().map(|l| l.index).collect();
        indices.sort_unstable();
        indices.iter().position(|&i| i == index)
    };
    for connection in &net.connections {
        let (Some(&from), Some(&to)) = (
            road_of.get(connection.from.as_str()),
            road_of.get(connection.to.as_str()),
        ) else {
            continue;
        };
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
    Some(roads)
}

/// The junctions of a network that at least three roads enter, as interaction
/// areas with the junction's outline (those without an outline enclosing an area
/// are left out).
fn junction_areas(net: &Network) -> Vec<InteractionArea> {
    let road_of_lane: HashMap<&str, &str> = net
        .edges
        .iter()
        .filter(|edge| edge.function.is_empty())
        .flat_map(|edge| edge.lanes.iter().map(move |lane| (lane.id.as_str(), edge.id.as_str())))
        .collect();
    net.junctions
        .iter()
        .filter(|junction| {
            let roads: HashSet<&str> = junction
                .incoming
                .iter()
                .filter_map(|lane| road_of_lane.get(lane.as_str()).copied())
                .collect();
            roads.len() >= 3
        })
        .filter_map(|junction| {
            counter_clockwise(&junction.shape).map(|outline| InteractionArea {
                id: junction.id.clone(),
                shape: Area::Polygon(outline),
            })
        })
        .collect()
}

/// The shortest interval between two samples of one object, seconds (infinite
/// when no object has two).
fn sample_period(fcd: &Fcd) -> f64 {
    fcd.objects
        .iter()
        .flat_map(|object| object.samples.windows(2).map(|pair| pair[1].time - pair[0].time))
        .filter(|&interval| interval > 0.0)
        .fold(f64::INFINITY, f64::min)
}

impl Imported {
    /// The object of the trace with id `id`.
    pub(super) fn object(&self, id: &str) -> Option<&FcdObject> {
        self.fcd.objects.iter().find(|object| object.id == id)
    }

    /// The ids of the trace's objects, in order of first appearance.
    pub(super) fn ids(&self) -> impl Iterator<Item = &str> {
        self.fcd.objects.iter().map(|object| object.id.as_str())
    }

    /// Whether `object` has a sample in the run's time span [0, `duration`].
    pub(super) fn overlaps(&self, object: &FcdObject, duration: f64) -> bool {
        let first = object.samples.first().map_or(f64::INFINITY, |s| s.time - self.begin);
        let last = object.samples.last().map_or(f64::NEG_INFINITY, |s| s.time - self.begin);
        first <= duration && last >= 0.0
    }
}

/// The motion of an agent of `kind` and `length` replaying `object`.
pub(super) fn trace_motion(imported: &Imported, object: &FcdObject, kind: AgentKind, length: f64) -> Motion {
    let back = if kind.is_vehicle() { length / 2.0 } else { 0.0 };
    let mut samples: Vec<TraceSample> = Vec::with_capacity(object.samples.len());
    for sample in &object.samples {
        let (sin, cos) = sample.heading.sin_cos();
        let [x, y] = sample.position;
        let position = [x - back * cos, y - back * sin];
        let offset = samples
            .last()
            .map_or(0.0, |last| last.offset + distance(last.position, position));
        samples.push(TraceSample {
            time: sample.time - imported.begin,
            position,
            heading: sample.heading,
            speed: sample.speed,
            offset,
            limit: sample
                .lane
                .as_ref()
                .and_then(|lane| imported.limits.get(lane))
                .copied()
                .unwrap_or(f64::INFINITY),
        });
    }
    Motion::Trace {
        path: Polyline::new(samples.iter().map(|s| s.position)),
        samples,
        max_gap: imported.max_gap,
    }
}

/// The objects of the trace no declared agent replays or is named after, within
/// the run's time span, as agents with their kind's footprint, no sensors and
/// not connected.
pub(super) fn imported_agents(imported: &Imported, declared: &HashSet<&str>, duration: f64) -> Vec<Agent> {
    imported
        .fcd
        .objects
        .iter()
        .filter(|object| !declared.contains(object.id.as_str()) && imported.overlaps(object, duration))
        .map(|object| {
            let (length, width) = object.kind.footprint();
            Agent {
                id: object.id.clone(),
                kind: object.kind,
                length,
                width,
                motion: trace_motion(imported, object, object.kind, length),
                connected: false,
                sensors: Vec::new(),
            }
        })
        .collect()
}
