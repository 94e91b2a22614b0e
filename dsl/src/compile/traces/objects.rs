//! The road users of a trace: each object's kind and size from its type; and
//! the roadside units the points of interest stand for.
//!
//! Choices, documented in `docs/scenario-language.md`:
//! - An object's type is looked up among the `<vType>`s of the route and
//!   additional files. Its kind is its `vClass`'s (`passenger` when absent, as
//!   SUMO takes it; a person's type `pedestrian`), or the kind its `guiShape`
//!   draws when it has no `vClass`; its size its `length` and `width`, else its
//!   class's SUMO default. SUMO's built-in types (`DEFAULT_VEHTYPE`, …) are
//!   known without a declaration. A type declared nowhere is read by its name
//!   ([`kind_of`]) with that kind's default size, with a warning.

use std::collections::{BTreeMap, HashMap};

use crate::compile::checks::imported_id_problem;
use crate::error::{Location, Warning};
use crate::geometry::{Polyline, Xy};
use crate::import::sumo::{
    Additional, FcdObject, Network, PoiAt, Replay, VType, builtin_class, kind_of, shape_kind, vehicle_class,
};
use crate::model::AgentKind;

/// A problem in an imported file: the file, where in it, and what.
pub(super) type InFile = (String, Location, String);

/// What a pass found, with its warnings, or the problem that stopped it.
pub(super) type Found<T> = Result<(T, Vec<Warning>), InFile>;

/// What an object of the trace is: its kind and footprint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Body {
    /// Its kind.
    pub(crate) kind: AgentKind,
    /// Footprint length, metres.
    pub(crate) length: f64,
    /// Footprint width, metres.
    pub(crate) width: f64,
}

/// Each object's body (`None`: left out), and the warnings about the types.
pub(super) fn bodies<'a>(
    objects: &'a [FcdObject],
    others: &[(String, Additional)],
    fcd_file: &str,
) -> Found<Vec<Option<Body>>> {
    let mut types: HashMap<&str, (&str, &VType)> = HashMap::new();
    for (file, additional) in others {
        for vtype in &additional.vtypes {
            if let Some((first_file, first)) = types.insert(&vtype.id, (file, vtype)) {
                let message = format!(
                    "type `{}` is declared again (first at {first_file}:{})",
                    vtype.id, first.location
                );
                return Err((file.clone(), vtype.location, message));
            }
        }
    }
    // Per type needing a warning: where its first object is in the trace, the
    // message, that object's location, and how many objects have the type.
    let mut noted: HashMap<&str, (usize, String, Location, usize)> = HashMap::new();
    let mut note = |order: usize, vtype: &'a str, object: &FcdObject, message: String| {
        noted.entry(vtype).or_insert((order, message, object.location, 0)).3 += 1;
    };
    let bodies = objects
        .iter()
        .enumerate()
        .map(|(order, object)| {
            let default_class = if object.is_person { "pedestrian" } else { "passenger" };
            let (class, vtype) = match types.get(object.vtype.as_str()) {
                Some((_, vtype)) => (vehicle_class(vtype.vclass.unwrap_or(default_class)), Some(*vtype)),
                None => (builtin_class(&object.vtype), None),
            };
            let Some(class) = class else {
                let kind = if object.is_person {
                    AgentKind::Pedestrian
                } else {
                    kind_of(&object.vtype)
                };
                let (length, width) = kind.footprint();
                note(
                    order,
                    &object.vtype,
                    object,
                    format!(
                        "type `{}` is declared in no route or additional file: read by its name as `{}`, \
                         {length} × {width} m",
                        object.vtype,
                        kind.name()
                    ),
                );
                return Some(Body { kind, length, width });
            };
            let kind = match class.replay {
                Replay::As(kind) => kind,
                Replay::Nearest(kind) => {
                    note(
                        order,
                        &object.vtype,
                        object,
                        format!(
                            "type `{}` is of class `{}`, which sightline has no kind for: replayed as `{}`",
                            object.vtype,
                            class.name,
                            kind.name()
                        ),
                    );
                    kind
                }
                Replay::Drop => {
                    note(
                        order,
                        &object.vtype,
                        object,
                        format!(
                            "type `{}` is of class `{}`, no road user: left out",
                            object.vtype, class.name
                        ),
                    );
                    return None;
                }
            };
            let kind = match vtype
                .filter(|t| t.vclass.is_none())
                .and_then(|t| t.gui_shape.as_deref())
            {
                Some(shape) if !object.is_person => shape_kind(shape).unwrap_or(kind),
                _ if object.is_person => AgentKind::Pedestrian,
                _ => kind,
            };
            Some(Body {
                kind,
                length: vtype.and_then(|t| t.length).unwrap_or(class.length),
                width: vtype.and_then(|t| t.width).unwrap_or(class.width),
            })
        })
        .collect();
    // One warning per type, at its first object, in order of first appearance.
    let mut noted: Vec<_> = noted.into_values().collect();
    noted.sort_by_key(|(order, ..)| *order);
    let warnings = noted
        .into_iter()
        .map(|(_, message, location, count)| Warning {
            file: fcd_file.to_owned(),
            location,
            message: format!("{message} ({count} object{})", if count == 1 { "" } else { "s" }),
        })
        .collect();
    Ok((bodies, warnings))
}

/// A roadside unit a point of interest stands for.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PoiRsu {
    /// The point's id.
    pub(crate) id: String,
    /// Where it stands, metres.
    pub(crate) position: Xy,
    /// Its height, metres, when it gives one.
    pub(crate) antenna_m: Option<f64>,
}

/// The points of interest of type `poi_type` as roadside units (a point on a
/// lane needs the lane); the others are listed as left out, per type.
pub(super) fn poi_rsus(
    others: &[(String, Additional)],
    poi_type: Option<&str>,
    net: Option<&Network>,
) -> Found<Vec<PoiRsu>> {
    let mut rsus = Vec::new();
    let mut left: BTreeMap<(&str, &str), (Location, usize)> = BTreeMap::new();
    for (file, additional) in others {
        for poi in &additional.pois {
            if Some(poi.kind.as_str()) != poi_type {
                left.entry((file, &poi.kind)).or_insert((poi.location, 0)).1 += 1;
                continue;
            }
            if let Some(why) = imported_id_problem(&poi.id) {
                return Err((
                    file.clone(),
                    poi.location,
                    format!("a roadside unit's point of interest: {why}"),
                ));
            }
            let position = match &poi.at {
                PoiAt::Point(point) => *point,
                PoiAt::Lane { lane, pos, pos_lat } => {
                    let shape = net
                        .into_iter()
                        .flat_map(|net| net.edges.iter().flat_map(|e| &e.lanes).chain(&net.internal_lanes))
                        .find(|l| &l.id == lane)
                        .and_then(|l| Polyline::new(l.shape.iter().copied()));
                    let Some(shape) = shape else {
                        let message = format!(
                            "point of interest `{}` stands on lane `{lane}`, which {}",
                            poi.id,
                            if net.is_some() {
                                "the network does not have"
                            } else {
                                "needs a network (`traces.net`)"
                            }
                        );
                        return Err((file.clone(), poi.location, message));
                    };
                    let along = if *pos < 0.0 { shape.length() + pos } else { *pos };
                    let [x, y] = shape.point_at(along);
                    let (sin, cos) = shape.heading_at(along).sin_cos();
                    [x - pos_lat * sin, y + pos_lat * cos]
                }
            };
            rsus.push(PoiRsu {
                id: poi.id.clone(),
                position,
                antenna_m: poi.height,
            });
        }
    }
    let warnings = left
        .into_iter()
        .map(|((file, kind), (location, count))| {
            let what = if kind.is_empty() {
                "without a type".to_owned()
            } else {
                format!("of type `{kind}`")
            };
            let plural = if count == 1 { "" } else { "s" };
            Warning {
                file: file.to_owned(),
                location,
                message: format!(
                    "{count} point{plural} of interest {what}: no roadside unit (`traces.rsus.poi_type`), left out"
                ),
            }
        })
        .collect();
    Ok((rsus, warnings))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::import::sumo::{parse_additional, parse_fcd};

    const FCD: &str = r#"<fcd-export>
<timestep time="0">
  <vehicle id="b0" x="0" y="0" angle="90" type="bike" speed="5"/>
  <vehicle id="v0" x="0" y="0" angle="90" type="van" speed="5"/>
  <vehicle id="c0" x="0" y="0" angle="90" type="DEFAULT_VEHTYPE" speed="5"/>
  <vehicle id="t0" x="0" y="0" angle="90" type="tram" speed="5"/>
  <vehicle id="s0" x="0" y="0" angle="90" type="boat" speed="5"/>
  <vehicle id="m0" x="0" y="0" angle="90" type="mystery_bus" speed="5"/>
  <vehicle id="m1" x="0" y="0" angle="90" type="mystery_bus" speed="5"/>
  <person id="p0" x="0" y="0" angle="90" type="walker" speed="1"/>
  <vehicle id="g0" x="0" y="0" angle="90" type="drawn" speed="5"/>
</timestep>
</fcd-export>"#;

    const TYPES: &str = r#"<routes>
  <vType id="bike" vClass="bicycle"/>
  <vType id="van" vClass="delivery" length="5.2"/>
  <vType id="tram" vClass="tram"/>
  <vType id="boat" vClass="ship"/>
  <vType id="walker" vClass="pedestrian" width="0.6"/>
  <vType id="drawn" guiShape="bicycle"/>
</routes>"#;

    fn resolve() -> (Vec<Option<Body>>, Vec<Warning>) {
        let fcd = parse_fcd(FCD).unwrap();
        let others = vec![("t.rou.xml".to_string(), parse_additional(TYPES).unwrap())];
        bodies(&fcd.objects, &others, "t.fcd.xml").unwrap()
    }

    #[test]
    fn types_give_kinds_and_sizes_with_sumo_defaults() {
        let (bodies, _) = resolve();
        let body = |kind, length, width| Some(Body { kind, length, width });
        assert_eq!(
            bodies,
            [
                body(AgentKind::Bicycle, 1.6, 0.65),
                body(AgentKind::Truck, 5.2, 2.16),
                body(AgentKind::Car, 5.0, 1.8),
                body(AgentKind::Bus, 22.0, 2.4),
                None,
                body(AgentKind::Bus, 12.0, 2.55),
                body(AgentKind::Bus, 12.0, 2.55),
                body(AgentKind::Pedestrian, 0.215, 0.6),
                // No vClass: SUMO's passenger size, drawn as a bicycle.
                body(AgentKind::Bicycle, 5.0, 1.8),
            ]
        );
    }

    #[test]
    fn types_read_by_name_or_left_out_are_warned_about_once() {
        let (_, warnings) = resolve();
        let lines: Vec<String> = warnings.iter().map(ToString::to_string).collect();
        assert_eq!(
            lines,
            [
                "t.fcd.xml:6:3: warning: type `tram` is of class `tram`, which sightline has no kind for: \
                 replayed as `bus` (1 object)",
                "t.fcd.xml:7:3: warning: type `boat` is of class `ship`, no road user: left out (1 object)",
                "t.fcd.xml:8:3: warning: type `mystery_bus` is declared in no route or additional file: read by \
                 its name as `bus`, 12 × 2.55 m (2 objects)",
            ]
        );
    }

    #[test]
    fn a_type_declared_twice_is_an_error() {
        let fcd = parse_fcd(FCD).unwrap();
        let others = vec![
            ("a.rou.xml".to_string(), parse_additional(TYPES).unwrap()),
            (
                "b.add.xml".to_string(),
                parse_additional("<additional>\n<vType id=\"van\"/></additional>").unwrap(),
            ),
        ];
        let (file, location, message) = bodies(&fcd.objects, &others, "t.fcd.xml").unwrap_err();
        assert_eq!(
            format!("{file}:{location}: {message}"),
            "b.add.xml:2:1: type `van` is declared again (first at a.rou.xml:3:3)"
        );
    }

    #[test]
    fn points_of_interest_of_the_type_become_roadside_units() {
        let text = r#"<additional>
  <poi id="r1" type="rsu" x="10" y="20"><param key="height" value="6"/></poi>
  <poi id="t1" type="tree" x="0" y="0"/>
  <poi id="t2" type="tree" x="0" y="0"/>
</additional>"#;
        let others = vec![("a.add.xml".to_string(), parse_additional(text).unwrap())];
        let (rsus, warnings) = poi_rsus(&others, Some("rsu"), None).unwrap();
        assert_eq!(
            rsus,
            [PoiRsu {
                id: "r1".into(),
                position: [10.0, 20.0],
                antenna_m: Some(6.0)
            }]
        );
        assert_eq!(
            warnings[0].to_string(),
            "a.add.xml:3:3: warning: 2 points of interest of type `tree`: no roadside unit \
             (`traces.rsus.poi_type`), left out"
        );
        let on_lane = r#"<additional><poi id="r2" type="rsu" lane="x_0" pos="5"/></additional>"#;
        let others = vec![("b.add.xml".to_string(), parse_additional(on_lane).unwrap())];
        let (file, location, message) = poi_rsus(&others, Some("rsu"), None).unwrap_err();
        assert_eq!(
            format!("{file}:{location}: {message}"),
            "b.add.xml:1:13: point of interest `r2` stands on lane `x_0`, which needs a network (`traces.net`)"
        );
    }
}
