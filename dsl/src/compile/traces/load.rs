//! Everything `traces` imports, read and checked once for every sweep point:
//! the files, the network's scene, the objects' bodies, the roadside units,
//! and the warnings about what is left out.
//!
//! Choices, documented in `docs/scenario-language.md`:
//! - Scenario time is the trace's time minus `begin`.
//! - The longest gap interpolated across is 1.5 × the trace's sample period (the
//!   shortest interval between two samples of one object): an object missing from
//!   the trace for longer (teleported, riding a vehicle) is out of the scene.
//! - A sample's speed limit is that of its lane, internal lanes across junctions
//!   included.

use std::collections::HashMap;

use super::files::{Files, read_files};
use super::network::{FILE_START, scene};
use super::objects::{Body, InFile, PoiRsu, bodies, poi_rsus};
use crate::compile::Loader;
use crate::compile::checks::{distinct, imported_id_problem, known_names, types_among};
use crate::compile::context::Context;
use crate::error::{Error, ErrorKind, Location, Warning};
use crate::geometry::counter_clockwise;
use crate::import::sumo::{Fcd, FcdObject};
use crate::model::{Crosswalk, Import, InteractionArea, Occluder, Road};
use crate::path::Path;
use crate::raw::range;
use crate::raw::{RawPoiRsus, RawTraces};

/// Gaps up to this many sample periods are interpolated across.
const GAP_PERIODS: f64 = 1.5;

/// What `traces` imports, read and checked once for every sweep point.
pub(crate) struct Imported {
    /// The trace.
    fcd: Fcd,
    /// Each object's body, `None` when it is left out.
    bodies: Vec<Option<Body>>,
    /// The network's roads, their links indexing this list.
    pub(crate) roads: Vec<Road>,
    /// The polygons that block sight.
    pub(crate) occluders: Vec<Occluder>,
    /// The junctions that become interaction areas.
    pub(crate) areas: Vec<InteractionArea>,
    /// The network's crossings.
    pub(crate) crosswalks: Vec<Crosswalk>,
    /// The network's walking areas, as named areas.
    pub(crate) walking_areas: Vec<InteractionArea>,
    /// The points of interest that are roadside units.
    pub(crate) rsus: Vec<PoiRsu>,
    /// Their sensors, as `traces.rsus.sensors` names them.
    pub(crate) rsu_sensors: Vec<String>,
    /// The speed limit of every lane of the network, by id, internal lanes too.
    pub(super) limits: HashMap<String, f64>,
    /// The longest time between two samples interpolated across, seconds.
    pub(super) max_gap: f64,
    /// The trace's time of scenario time 0, seconds.
    pub(super) begin: f64,
    /// The trace's file, as read.
    fcd_file: String,
    /// The files as read, for the evidence.
    pub(crate) files: Vec<Import>,
    /// What is left out or read by a guess.
    pub(crate) warnings: Vec<Warning>,
}

/// Reads, parses and checks the files of `traces`; `None` (with the errors
/// recorded) when there is no such section or a file fails.
pub(crate) fn load(ctx: &mut Context<'_>, raw: Option<&RawTraces>, loader: Option<&dyn Loader>) -> Option<Imported> {
    let raw = raw?;
    let at = Path::root().key("traces");
    let files = read_files(ctx, raw, loader);
    let begin_ok = ctx.within(&at.key("begin"), raw.begin, range::TRACE_TIME);
    let rsus_ok = raw
        .rsus
        .as_ref()
        .is_none_or(|rsus| rsus_declared(ctx, &at.key("rsus"), rsus));
    let (Some(files), true, true) = (files, begin_ok, rsus_ok) else {
        return None;
    };
    let Files {
        fcd,
        net,
        others,
        fcd_file,
        imports,
    } = files;
    let misnamed = fcd
        .objects
        .iter()
        .find_map(|o| imported_id_problem(&o.id).map(|why| (o.location, why)));
    if let Some((location, why)) = misnamed {
        import_error(ctx, (fcd_file, location, why));
        return None;
    }
    let mut warnings = Vec::new();
    let bodies = match bodies(&fcd.objects, &others, &fcd_file) {
        Ok((bodies, found)) => {
            warnings.extend(found);
            Some(bodies)
        }
        Err(problem) => {
            import_error(ctx, problem);
            None
        }
    };
    let rsus = match poi_rsus(&others, raw.rsus.as_ref().map(|r| r.poi_type.as_str()), net.as_ref()) {
        Ok((rsus, _)) if rsus.is_empty() && raw.rsus.is_some() => {
            let kinds = distinct(others.iter().flat_map(|(_, a)| &a.pois).map(|p| p.kind.as_str()));
            let poi_type = raw.rsus.as_ref().map(|r| r.poi_type.as_str()).unwrap_or_default();
            ctx.error(
                &at.key("rsus").key("poi_type"),
                ErrorKind::DanglingReference(format!(
                    "no point of interest of type `{poi_type}` in the additional files ({})",
                    known_names(poi_type, &kinds)
                )),
            );
            None
        }
        Ok((rsus, found)) => {
            warnings.extend(found);
            Some(rsus)
        }
        Err(problem) => {
            import_error(ctx, problem);
            None
        }
    };
    for (file, additional) in &others {
        for (name, count, location) in &additional.ignored {
            warnings.push(Warning {
                file: file.clone(),
                location: *location,
                message: format!(
                    "{count} <{name}> element{}: not read",
                    if *count == 1 { "" } else { "s" }
                ),
            });
        }
    }
    let limits: HashMap<String, f64> = net
        .iter()
        .flat_map(|net| net.edges.iter().flat_map(|e| &e.lanes).chain(&net.internal_lanes))
        .map(|lane| (lane.id.clone(), lane.speed))
        .collect();
    // A network the scenario names, else the configuration that names it.
    let net_at = match (&raw.net, &raw.sumocfg) {
        (None, Some(_)) => at.key("sumocfg"),
        _ => at.key("net"),
    };
    let mut ok = net.is_none() || lanes_known(ctx, &net_at, &fcd, &limits);
    let scene = net.as_ref().map(|net| scene(net, raw.junction_areas));
    if let (Some(scene), Some(net_file)) = (&scene, imports.iter().find(|i| i.kind == crate::ImportKind::SumoNet)) {
        warnings.extend(scene.dropped.iter().map(|message| Warning {
            file: net_file.path.clone(),
            location: FILE_START,
            message: message.clone(),
        }));
    }
    if ctx.has(&at.key("occluder_types")) {
        let kinds = distinct(others.iter().flat_map(|(_, a)| &a.polygons).map(|p| p.kind.as_str()));
        ok &= types_among(ctx, &at.key("occluder_types"), &raw.occluder_types, &kinds, |kind| {
            format!("no polygon of type `{kind}` in the imported files")
        });
    }
    let mut occluders = Vec::new();
    for (file, additional) in &others {
        let mut left: Vec<(&str, Location, usize)> = Vec::new();
        for polygon in &additional.polygons {
            if !raw.occluder_types.contains(&polygon.kind) {
                match left.iter_mut().find(|(kind, ..)| *kind == polygon.kind) {
                    Some((_, _, count)) => *count += 1,
                    None => left.push((&polygon.kind, polygon.location, 1)),
                }
                continue;
            }
            match counter_clockwise(&polygon.shape) {
                Some(outline) => occluders.push(Occluder {
                    id: polygon.id.clone(),
                    polygon: outline,
                }),
                None => {
                    ctx.errors.push(Error {
                        file: file.clone(),
                        location: polygon.location,
                        path: String::new(),
                        kind: ErrorKind::Import(format!(
                            "polygon `{}` of type `{}` encloses no area: an occluder needs three corners",
                            polygon.id, polygon.kind
                        )),
                    });
                    ok = false;
                }
            }
        }
        warnings.extend(left.into_iter().map(|(kind, location, count)| Warning {
            file: file.clone(),
            location,
            message: format!(
                "{count} polygon{} of type `{kind}`: not among `traces.occluder_types`, so {} not block sight",
                if count == 1 { "" } else { "s" },
                if count == 1 { "does" } else { "do" }
            ),
        }));
    }
    let (Some(bodies), Some(rsus), true) = (bodies, rsus, ok) else {
        return None;
    };
    // By file, then where in it (the readers find them file by file).
    warnings.sort_by(|a, b| (&a.file, a.location).cmp(&(&b.file, b.location)));
    let scene = scene.unwrap_or_else(|| super::network::Scene {
        roads: Vec::new(),
        areas: Vec::new(),
        crosswalks: Vec::new(),
        walking_areas: Vec::new(),
        dropped: Vec::new(),
    });
    Some(Imported {
        max_gap: GAP_PERIODS * sample_period(&fcd),
        fcd,
        bodies,
        roads: scene.roads,
        occluders,
        areas: scene.areas,
        crosswalks: scene.crosswalks,
        walking_areas: scene.walking_areas,
        rsus,
        rsu_sensors: raw.rsus.as_ref().map(|r| r.sensors.clone()).unwrap_or_default(),
        limits,
        begin: raw.begin,
        fcd_file,
        files: imports,
        warnings,
    })
}

/// Records a problem found in an imported file.
fn import_error(ctx: &mut Context<'_>, (file, location, message): InFile) {
    ctx.errors.push(Error {
        file,
        location,
        path: String::new(),
        kind: ErrorKind::Import(message),
    });
}

/// Checks `traces.rsus`: a type and at least one sensor.
fn rsus_declared(ctx: &mut Context<'_>, at: &Path, rsus: &RawPoiRsus) -> bool {
    if rsus.sensors.is_empty() {
        ctx.error(
            &at.key("sensors"),
            ErrorKind::Invalid("a roadside unit needs at least one sensor model".into()),
        );
        return false;
    }
    true
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
    pub(crate) fn object(&self, id: &str) -> Option<&FcdObject> {
        self.fcd.objects.iter().find(|object| object.id == id)
    }

    /// The ids of the trace's objects, in order of first appearance.
    pub(crate) fn ids(&self) -> impl Iterator<Item = &str> {
        self.fcd.objects.iter().map(|object| object.id.as_str())
    }

    /// The trace's objects with their bodies (`None`: left out), in order of
    /// first appearance.
    pub(super) fn objects(&self) -> impl Iterator<Item = (&FcdObject, Option<Body>)> {
        self.fcd.objects.iter().zip(self.bodies.iter().copied())
    }

    /// Whether `object` has a sample in the run's time span [0, `duration`].
    pub(crate) fn overlaps(&self, object: &FcdObject, duration: f64) -> bool {
        let first = object.samples.first().map_or(f64::INFINITY, |s| s.time - self.begin);
        let last = object.samples.last().map_or(f64::NEG_INFINITY, |s| s.time - self.begin);
        first <= duration && last >= 0.0
    }

    /// A warning when the trace does not cover the run's steps, at 0, `step`,
    /// … up to `duration`: its first sample of a road user comes later than
    /// the first step, its last earlier than the last step, or two of its
    /// successive timesteps within the run lie further apart, by more than a
    /// sample period (or a step, when longer).
    pub(crate) fn coverage(&self, duration: f64, step: f64) -> Option<Warning> {
        let times = self
            .fcd
            .objects
            .iter()
            .flat_map(|o| [o.samples.first(), o.samples.last()]);
        let (first, last) = times
            .flatten()
            .map(|s| s.time - self.begin)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), t| (lo.min(t), hi.max(t)));
        let period = if self.max_gap.is_finite() {
            self.max_gap / GAP_PERIODS
        } else {
            0.0
        };
        let tolerance = period.max(step) + 1e-9;
        let last_step = ((duration / step).round() - 1.0).max(0.0) * step;
        let (span, location) = if first > last {
            ("no road user at all".to_owned(), Location::new(1, 1))
        } else if first > tolerance || last < last_step - tolerance {
            let span = format!("road users from {} s to {} s only", round(first), round(last));
            (span, Location::new(1, 1))
        } else {
            let hole = self.fcd.timesteps.windows(2).find(|pair| {
                let (before, after) = (pair[0].time - self.begin, pair[1].time - self.begin);
                after - before > tolerance && before < last_step && after > 0.0
            })?;
            let (before, after) = (hole[0].time - self.begin, hole[1].time - self.begin);
            let span = format!("no timestep from {} s to {} s", round(before), round(after));
            (span, hole[1].location)
        };
        Some(Warning {
            file: self.fcd_file.clone(),
            location,
            message: format!(
                "the trace does not cover the run: it has {span} of the run's 0 s to {} s (scenario time, \
                 `traces.begin` {} s); the requirements are not exercised where it has none",
                round(duration),
                round(self.begin)
            ),
        })
    }
}

/// `value` to the millisecond, without trailing zeros.
fn round(value: f64) -> f64 {
    (value * 1000.0).round() / 1000.0
}
