//! Occluders: the declared buildings and walls, then the polygons of
//! `traces.poly` and the objects of `map` that block sight.

use std::collections::HashSet;

use crate::compile::checks::{coordinates, distinct_from_imported, unique_ids};
use crate::compile::context::Context;
use crate::compile::map::Mapped;
use crate::compile::traces::Imported;
use crate::error::ErrorKind;
use crate::geometry::counter_clockwise;
use crate::model::Occluder;
use crate::path::Path;
use crate::raw::RawOccluder;

/// The declared occluders, then the polygons of `traces.poly` and the objects
/// of `map` that block sight.
pub(super) fn occluders(
    ctx: &mut Context<'_>,
    raw: &[RawOccluder],
    imported: Option<&Imported>,
    mapped: Option<&Mapped>,
) -> Option<Vec<Occluder>> {
    let list = Path::root().key("occluders");
    let polygons = imported.map_or(&[][..], |i| &i.occluders);
    let polygon_ids: HashSet<&str> = polygons.iter().map(|o| o.id.as_str()).collect();
    let mut ok = unique_ids(ctx, &list, raw.iter().map(|o| o.id.as_str()))
        & distinct_from_imported(
            ctx,
            &list,
            raw.iter().map(|o| o.id.as_str()),
            &polygon_ids,
            "a polygon of `traces.poly`",
        );
    let objects = mapped.map_or(&[][..], |m| &m.occluders);
    let object_ids: HashSet<&str> = objects.iter().map(|o| o.id.as_str()).collect();
    ok &= distinct_from_imported(
        ctx,
        &list,
        raw.iter().map(|o| o.id.as_str()),
        &object_ids,
        "an object of `map`",
    );
    let mut occluders = Vec::new();
    for (i, occluder) in raw.iter().enumerate() {
        let path = list.index(i);
        let polygon_path = path.key("polygon");
        if !coordinates(ctx, &polygon_path, &occluder.polygon) {
            ok = false;
            continue;
        }
        let Some(polygon) = counter_clockwise(&occluder.polygon) else {
            ctx.error(
                &polygon_path,
                ErrorKind::Invalid("an occluder needs at least three corners enclosing an area".into()),
            );
            ok = false;
            continue;
        };
        occluders.push(Occluder {
            id: occluder.id.clone(),
            polygon,
        });
    }
    occluders.extend_from_slice(polygons);
    occluders.extend_from_slice(objects);
    ok.then_some(occluders)
}
