//! Roads: the declared ones resolved into lane centrelines (a polyline, an arc
//! or a roundabout's ring), then those of `traces.net`, then the drivable lanes
//! of `map`.

use std::collections::HashSet;

use crate::compile::checks::{coordinates, distinct_from_imported, unique_ids};
use crate::compile::context::{Context, Declaration};
use crate::compile::map::Mapped;
use crate::compile::traces::Imported;
use crate::error::ErrorKind;
use crate::geometry::{Arc, Polyline};
use crate::model::{Direction, LaneLink, Road};
use crate::path::Path;
use crate::raw::RawRoad;
use crate::raw::range;

/// The declared roads that compile, then those of `traces.net` and `map`; and whether
/// every declared road compiled. A road that does not is noted in `ctx`, so
/// the routes that name it are not reported as naming a missing road.
pub(super) fn roads(
    ctx: &mut Context<'_>,
    raw: &[RawRoad],
    imported: Option<&Imported>,
    mapped: Option<&Mapped>,
) -> (Vec<Road>, bool) {
    let list = Path::root().key("roads");
    let net_roads = imported.map_or(&[][..], |i| &i.roads);
    let net_ids: HashSet<&str> = net_roads.iter().map(|r| r.id.as_str()).collect();
    let mut ok = unique_ids(ctx, &list, raw.iter().map(|r| r.id.as_str()))
        & distinct_from_imported(
            ctx,
            &list,
            raw.iter().map(|r| r.id.as_str()),
            &net_ids,
            "an edge of `traces.net`",
        );
    let map_roads = mapped.map_or(&[][..], |m| &m.roads);
    let map_ids: HashSet<&str> = map_roads.iter().map(|r| r.id.as_str()).collect();
    ok &= distinct_from_imported(
        ctx,
        &list,
        raw.iter().map(|r| r.id.as_str()),
        &map_ids,
        "a lane of `map`",
    );
    let mut roads = Vec::new();
    for (i, road) in raw.iter().enumerate() {
        let path = list.index(i);
        let shape_ok = ctx.within(&path.key("lanes"), road.lanes.into(), range::LANES)
            & ctx.within(&path.key("lane_width"), road.lane_width, range::BODY)
            & ctx.within(&path.key("speed_limit"), road.speed_limit, range::SPEED_POSITIVE);
        match (shape_ok, reference_line(ctx, road, &path)) {
            (true, Some((reference, arc))) => {
                let lanes = (0..road.lanes)
                    .map(|k| reference.offset_left(f64::from(k) * road.lane_width))
                    .collect();
                roads.push(Road {
                    id: road.id.clone(),
                    lanes,
                    lane_width: road.lane_width,
                    speed_limit: road.speed_limit,
                    links: Vec::new(),
                    arc,
                });
            }
            _ => {
                ctx.declaration_failed(Declaration::Road, &road.id);
                ok = false;
            }
        }
    }
    // Each network's links index its own roads, which follow the declared ones.
    for imported in [net_roads, map_roads] {
        let first = roads.len();
        roads.extend(imported.iter().map(|road| {
            Road {
                links: road
                    .links
                    .iter()
                    .map(|link| LaneLink {
                        to_road: first + link.to_road,
                        ..link.clone()
                    })
                    .collect(),
                ..road.clone()
            }
        }));
    }
    (roads, ok)
}

/// Lane 0's centreline of a road, and the circle it follows when it is an arc
/// or a ring.
fn reference_line(ctx: &mut Context<'_>, road: &RawRoad, path: &Path) -> Option<(Polyline, Option<Arc>)> {
    let given = [road.polyline.is_some(), road.arc.is_some(), road.roundabout.is_some()];
    if given.iter().filter(|&&g| g).count() != 1 {
        ctx.error(
            path,
            ErrorKind::Invalid("give exactly one of `polyline`, `arc`, `roundabout`".into()),
        );
        return None;
    }
    if let Some(points) = &road.polyline {
        let line_path = path.key("polyline");
        if !coordinates(ctx, &line_path, points) {
            return None;
        }
        let line = Polyline::new(points.iter().copied());
        if line.is_none() {
            ctx.error(
                &line_path,
                ErrorKind::Invalid("a polyline needs two distinct points".into()),
            );
        }
        return line.map(|line| (line, None));
    }
    if let Some(a) = &road.arc {
        let arc_path = path.key("arc");
        let ok = coordinates(ctx, &arc_path.key("center"), &[a.center])
            & ctx.within(&arc_path.key("radius"), a.radius, range::RADIUS)
            & ctx.within(&arc_path.key("start_deg"), a.start_deg, range::ANGLE)
            & ctx.expect(
                a.end_deg.is_finite() && a.end_deg != a.start_deg && (a.end_deg - a.start_deg).abs() <= 360.0,
                &arc_path.key("end_deg"),
                "an angle other than start_deg, within 360° of it",
                a.end_deg,
            );
        if !ok {
            return None;
        }
        let circle = Arc {
            center: a.center,
            radius: a.radius,
            start: a.start_deg.to_radians(),
            sweep: (a.end_deg - a.start_deg).to_radians(),
        };
        let line = Polyline::new(circle.points());
        if line.is_none() {
            ctx.error(
                &arc_path.key("end_deg"),
                ErrorKind::Invalid("the arc has no length: its end is too close to its start".into()),
            );
        }
        return line.map(|line| (line, Some(circle)));
    }
    let ring = road.roundabout.as_ref()?;
    let ring_path = path.key("roundabout");
    let inner = ring.radius - f64::from(road.lanes.saturating_sub(1)) * road.lane_width;
    let ok = coordinates(ctx, &ring_path.key("center"), &[ring.center])
        & (ctx.within(&ring_path.key("radius"), ring.radius, range::RADIUS)
            && ctx.expect(
                inner >= range::RADIUS.min,
                &ring_path.key("radius"),
                &format!(
                    "a radius that leaves the innermost lane at least {} m from the centre",
                    range::RADIUS.min
                ),
                ring.radius,
            ));
    let sweep = match ring.direction {
        Direction::Ccw => std::f64::consts::TAU,
        Direction::Cw => -std::f64::consts::TAU,
    };
    let circle = Arc {
        center: ring.center,
        radius: ring.radius,
        start: 0.0,
        sweep,
    };
    ok.then(|| Polyline::new(circle.points()).map(|line| (line, Some(circle))))
        .flatten()
}
