//! The `map` section: an OpenDRIVE file read once through the caller's
//! [`Loader`](super::Loader), parsed, sampled and turned into what every sweep
//! point shares: roads (its drivable lanes), ways for pedestrians (its
//! sidewalks), occluders, interaction areas and crosswalks.
//!
//! Choices, documented in `docs/opendrive.md`:
//! - Each drivable lane, followed through its road's lane sections in its
//!   direction of travel, is one road of one lane, named `road R lane L`; its
//!   links are the lanes it continues into across junctions and road ends.
//! - Its speed limit is the lowest that applies along it; `map.speed_limit`
//!   stands in for stretches without one.
//! - A crosswalk object is walked across its road (perpendicular to the
//!   reference line at its s), over its outline's extent; its width is the
//!   outline's extent along the road.

use std::collections::HashMap;

use super::checks::{distinct, types_among};
use super::context::Context;
use super::reader::{Failed, Named, Reader};
use crate::error::{Error, ErrorKind};
use crate::geometry::{Polyline, Xy, counter_clockwise, distance};
use crate::import::opendrive::{LaneUse, Map, MapObject, build, parse_opendrive};
use crate::model::{Area, Crosswalk, Import, ImportKind, InteractionArea, LaneLink, Occluder, Road};
use crate::path::Path;
use crate::raw::{RawMap, range};

/// The object types of OpenDRIVE 1.8 (and the deprecated ones of 1.4–1.5),
/// which `map.occluder_types` may name.
const OBJECT_TYPES: [&str; 27] = [
    "none",
    "obstacle",
    "pole",
    "tree",
    "vegetation",
    "barrier",
    "building",
    "parkingSpace",
    "patch",
    "railing",
    "trafficIsland",
    "crosswalk",
    "streetLamp",
    "gantry",
    "soundBarrier",
    "roadMark",
    "car",
    "van",
    "bus",
    "trailer",
    "bike",
    "motorbike",
    "tram",
    "train",
    "pedestrian",
    "wind",
    "roadSurface",
];

/// What `map` imports, read and checked once for every sweep point.
pub(crate) struct Mapped {
    /// The drivable lanes as roads of one lane; their links index this list.
    pub(super) roads: Vec<Road>,
    /// The sidewalks as roads of one lane, for pedestrians' routes; their
    /// links index this list.
    pub(super) walkways: Vec<Road>,
    /// The objects that block sight.
    pub(super) occluders: Vec<Occluder>,
    /// The junctions, as interaction areas.
    pub(super) areas: Vec<InteractionArea>,
    /// The crosswalk objects.
    pub(super) crosswalks: Vec<Crosswalk>,
    /// The file as read, for the evidence.
    pub(super) files: Vec<Import>,
}

/// Reads and checks the file of `map`; `None` (with the errors recorded) when
/// there is no such section or it fails.
pub(super) fn load(ctx: &mut Context<'_>, raw: Option<&RawMap>, loader: Option<&dyn super::Loader>) -> Option<Mapped> {
    let raw = raw?;
    let at = Path::root().key("map");
    let scenario_dir = std::path::Path::new(ctx.file)
        .parent()
        .unwrap_or(std::path::Path::new(""));
    let path = scenario_dir.join(&raw.opendrive);
    let mut reader = Reader {
        ctx: &mut *ctx,
        loader,
        imports: Vec::new(),
    };
    let named = Named::Scenario(at.key("opendrive"));
    let map: Result<Map, Failed> = reader.read(&named, &path, ImportKind::OpenDrive, true, |text| {
        parse_opendrive(text).and_then(|network| build(&network))
    });
    let files = reader.imports;
    let mut ok = occluder_types(ctx, &at.key("occluder_types"), &raw.occluder_types);
    let speed_ok = raw
        .speed_limit
        .is_none_or(|limit| ctx.within(&at.key("speed_limit"), limit, range::SPEED_POSITIVE));
    let map = map.ok()?;
    let file = files.first().map(|f| f.path.clone()).unwrap_or_default();
    ok &= speed_ok && speed_limit_needed(ctx, &at, raw, &map, &file);
    let default = raw.speed_limit.unwrap_or(f64::INFINITY);
    let roads = lane_roads(ctx, &file, &map, LaneUse::Drive, default);
    let walkways = lane_roads(ctx, &file, &map, LaneUse::Walk, default);
    if ok && ctx.has(&at.key("occluder_types")) {
        let kinds = distinct(map.objects.iter().map(|o| o.kind.as_str()));
        ok &= types_among(ctx, &at.key("occluder_types"), &raw.occluder_types, &kinds, |kind| {
            format!("no object of type `{kind}` in the imported files")
        });
    }
    let mut occluders = Vec::new();
    let mut crosswalks = Vec::new();
    for object in &map.objects {
        let occludes = raw.occluder_types.contains(&object.kind);
        if !(occludes || object.kind == "crosswalk") {
            continue;
        }
        if object.repeated {
            import_error(
                ctx,
                &file,
                object,
                "is repeated along its road (<repeat>), which sightline does not read; give each copy as an object",
            );
            ok = false;
            continue;
        }
        for (k, area) in object.areas.iter().enumerate() {
            let id = match object.areas.len() {
                1 => format!("road {} object {}", object.road, object.id),
                _ => format!("road {} object {} outline {k}", object.road, object.id),
            };
            if occludes {
                match counter_clockwise(area) {
                    Some(polygon) => occluders.push(Occluder { id, polygon }),
                    None => {
                        import_error(ctx, &file, object, "encloses no area: an occluder needs three corners");
                        ok = false;
                    }
                }
            } else {
                match crosswalk(id, area, object.road_heading) {
                    Some(crosswalk) => crosswalks.push(crosswalk),
                    None => {
                        import_error(
                            ctx,
                            &file,
                            object,
                            "covers no area: a crosswalk needs a length and a width",
                        );
                        ok = false;
                    }
                }
            }
        }
    }
    let areas = if raw.junction_areas {
        map.junctions
            .iter()
            .filter_map(|junction| {
                counter_clockwise(&junction.outline).map(|outline| InteractionArea {
                    id: format!("junction {}", junction.id),
                    shape: Area::Polygon(outline),
                })
            })
            .collect()
    } else {
        Vec::new()
    };
    ok.then_some(Mapped {
        roads: roads?,
        walkways: walkways?,
        occluders,
        areas,
        crosswalks,
        files,
    })
}

/// Checks that every occluder type is one of OpenDRIVE's object types.
fn occluder_types(ctx: &mut Context<'_>, at: &Path, types: &[String]) -> bool {
    types_among(ctx, at, types, &OBJECT_TYPES, |kind| {
        format!("OpenDRIVE has no object type `{kind}`")
    })
}

/// Checks that `map.speed_limit` is given exactly when a drivable lane has a
/// stretch without a speed limit.
fn speed_limit_needed(ctx: &mut Context<'_>, at: &Path, raw: &RawMap, map: &Map, file: &str) -> bool {
    let unlimited: Vec<_> = map
        .lanes
        .iter()
        .filter(|lane| lane.carries == LaneUse::Drive && lane.unlimited)
        .collect();
    match (unlimited.first(), raw.speed_limit) {
        (Some(lane), None) => {
            let more = match unlimited.len() - 1 {
                0 => String::new(),
                n => format!(" (and {n} more)"),
            };
            ctx.error(
                at,
                ErrorKind::Invalid(format!(
                    "lane `{}` of the map ({file}:{}) has no speed limit along some of its length{more}; give \
                     `speed_limit` for lanes without one",
                    lane.name, lane.at
                )),
            );
            false
        }
        (None, Some(_)) => {
            ctx.error_at_key(
                &at.key("speed_limit"),
                ErrorKind::NoEffect("every drivable lane of the map has its own speed limit".into()),
            );
            false
        }
        _ => true,
    }
}

/// An error in the map's file at `object`.
fn import_error(ctx: &mut Context<'_>, file: &str, object: &MapObject, problem: &str) {
    ctx.errors.push(Error {
        file: file.to_owned(),
        location: object.at,
        path: String::new(),
        kind: ErrorKind::Import(format!(
            "object {} of road {} (type `{}`) {problem}",
            object.id, object.road, object.kind
        )),
    });
}

/// The lanes of the map that carry `carries`, as roads of one lane, linked to
/// the lanes of the same list they continue into; `default` is the speed
/// limit of stretches without one. A lane without length is an error in `file`.
fn lane_roads(ctx: &mut Context<'_>, file: &str, map: &Map, carries: LaneUse, default: f64) -> Option<Vec<Road>> {
    let kept: Vec<usize> = (0..map.lanes.len())
        .filter(|&i| map.lanes[i].carries == carries)
        .collect();
    let index: HashMap<usize, usize> = kept.iter().enumerate().map(|(new, &old)| (old, new)).collect();
    kept.iter()
        .map(|&i| {
            let lane = &map.lanes[i];
            let limit = match (lane.speed, lane.unlimited) {
                (Some(speed), false) => speed,
                (Some(speed), true) => speed.min(default),
                (None, _) => default,
            };
            let Some(centre) = Polyline::new(lane.centre.iter().copied()) else {
                ctx.errors.push(Error {
                    file: file.to_owned(),
                    location: lane.at,
                    path: String::new(),
                    kind: ErrorKind::Import(format!("lane `{}` has no length", lane.name)),
                });
                return None;
            };
            Some(Road {
                id: lane.name.clone(),
                lanes: vec![centre],
                lane_width: lane.width,
                speed_limit: limit,
                links: lane
                    .next
                    .iter()
                    .filter_map(|next| index.get(next))
                    .map(|&to_road| LaneLink {
                        from_lane: 0,
                        to_road,
                        to_lane: 0,
                        via: Vec::new(),
                    })
                    .collect(),
                arc: None,
            })
        })
        .collect()
}

/// A crosswalk over `area`, walked across a road heading `road_heading`.
fn crosswalk(id: String, area: &[Xy], road_heading: f64) -> Option<Crosswalk> {
    let (sin, cos) = road_heading.sin_cos();
    let along = |p: &Xy| p[0] * cos + p[1] * sin;
    let across = |p: &Xy| -p[0] * sin + p[1] * cos;
    let range = |f: &dyn Fn(&Xy) -> f64| {
        area.iter()
            .map(f)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)))
    };
    let ((u0, u1), (v0, v1)) = (range(&along), range(&across));
    let (width, u) = (u1 - u0, (u0 + u1) / 2.0);
    let point = |v: f64| [u * cos - v * sin, u * sin + v * cos];
    let (from, to) = (point(v0), point(v1));
    // Checked in the map's frame, where the walk uses them: turned back, a far
    // `u` rounds the kerbs together however far apart `v0` and `v1` lie.
    (width > 1e-6 && distance(from, to) > Crosswalk::MIN_LENGTH).then_some(Crosswalk { id, from, to, width })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_crosswalk_is_walked_between_kerbs_apart_in_the_maps_frame() {
        // A crosswalk 4 m wide along a road heading 1 rad and 7 m across it,
        // its first corner `far` metres along (as `Object::areas` turns it).
        let heading: f64 = 1.0;
        let (sin, cos) = heading.sin_cos();
        let area = |far: f64| {
            [[far, -3.5], [2.0, -3.5], [2.0, 3.5], [-2.0, 3.5]].map(|[u, v]| [u * cos - v * sin, u * sin + v * cos])
        };
        let walked = crosswalk("c".into(), &area(-2.0), heading).unwrap();
        assert!((distance(walked.from, walked.to) - 7.0).abs() < 1e-9);
        // At 1e100 m the across extent survives the projection but the kerbs,
        // turned back into the map's frame, round to one point.
        assert_eq!(crosswalk("c".into(), &area(1e100), heading), None);
    }
}
