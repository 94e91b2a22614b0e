//! What a SUMO vehicle class is in sightline: its kind and SUMO's default size.
//!
//! The sizes are SUMO's per-class defaults ("Vehicle Type Parameter Defaults" in
//! SUMO's documentation, <https://sumo.dlr.de/docs/Vehicle_Type_Parameter_Defaults.html>),
//! checked against SUMO 1.28.0 itself: each class loaded as a `<vType>` without
//! a size and read back through TraCI (`vehicletype.getLength`, `getWidth`).

use crate::AgentKind;

/// What sightline does with a vehicle class's road users.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Replay {
    /// Replays them as this kind: a road user of the kind it is.
    As(AgentKind),
    /// Replays them as this kind, the nearest sightline has, with a warning:
    /// rail vehicles on streets, as `bus`.
    Nearest(AgentKind),
    /// Leaves them out, with a warning: no road user (ships, aircraft, drones,
    /// containers).
    Drop,
}

/// A SUMO vehicle class: its name, what sightline replays it as, and SUMO's
/// default length and width, metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VehicleClass {
    /// SUMO's name (`passenger`, `bicycle`, …).
    pub name: &'static str,
    /// What sightline replays it as.
    pub replay: Replay,
    /// SUMO's default length, metres.
    pub length: f64,
    /// SUMO's default width, metres.
    pub width: f64,
}

const fn class(name: &'static str, replay: Replay, length: f64, width: f64) -> VehicleClass {
    VehicleClass {
        name,
        replay,
        length,
        width,
    }
}

use AgentKind::{Bicycle, Bus, Car, Motorbike, Pedestrian, Truck};
use Replay::{As, Drop, Nearest};

/// Every vehicle class of SUMO 1.28 with its default size. Vans (`delivery`)
/// and emergency vehicles (whose default body is a van) are `truck`: ETSI's
/// collective perception classes put vans with the light trucks, not the
/// passenger cars.
pub const CLASSES: [VehicleClass; 34] = [
    class("passenger", As(Car), 5.0, 1.8),
    class("private", As(Car), 5.0, 1.8),
    class("taxi", As(Car), 5.0, 1.8),
    class("evehicle", As(Car), 5.0, 1.8),
    class("hov", As(Car), 5.0, 1.8),
    class("vip", As(Car), 5.0, 1.8),
    class("army", As(Car), 5.0, 1.8),
    class("authority", As(Car), 5.0, 1.8),
    class("custom1", As(Car), 5.0, 1.8),
    class("custom2", As(Car), 5.0, 1.8),
    class("ignoring", As(Car), 5.0, 1.8),
    class("delivery", As(Truck), 6.5, 2.16),
    class("emergency", As(Truck), 6.5, 2.16),
    class("truck", As(Truck), 7.1, 2.4),
    class("trailer", As(Truck), 16.5, 2.55),
    class("bus", As(Bus), 12.0, 2.5),
    class("coach", As(Bus), 14.0, 2.6),
    class("motorcycle", As(Motorbike), 2.2, 0.9),
    class("moped", As(Motorbike), 2.1, 0.78),
    class("scooter", As(Motorbike), 1.2, 0.5),
    class("bicycle", As(Bicycle), 1.6, 0.65),
    class("pedestrian", As(Pedestrian), 0.215, 0.478),
    class("wheelchair", As(Pedestrian), 1.2, 0.72),
    class("tram", Nearest(Bus), 22.0, 2.4),
    class("rail_urban", Nearest(Bus), 109.5, 3.0),
    class("subway", Nearest(Bus), 109.5, 3.0),
    class("rail", Nearest(Bus), 135.0, 2.84),
    class("rail_electric", Nearest(Bus), 200.0, 2.95),
    class("rail_fast", Nearest(Bus), 200.0, 2.95),
    class("cable_car", Nearest(Bus), 5.0, 1.8),
    class("ship", Drop, 17.0, 4.0),
    class("aircraft", Drop, 72.7, 79.8),
    class("drone", Drop, 0.5, 0.5),
    class("container", Drop, 6.096, 2.438),
];

/// The class named `name`, `None` for a name SUMO does not know.
pub fn vehicle_class(name: &str) -> Option<&'static VehicleClass> {
    CLASSES.iter().find(|class| class.name == name)
}

/// The class of SUMO's built-in types (`DEFAULT_VEHTYPE`, …), which route files
/// use without declaring.
pub fn builtin_class(type_id: &str) -> Option<&'static VehicleClass> {
    let name = match type_id {
        "DEFAULT_VEHTYPE" => "passenger",
        "DEFAULT_PEDTYPE" => "pedestrian",
        "DEFAULT_BIKETYPE" => "bicycle",
        "DEFAULT_TAXITYPE" => "taxi",
        "DEFAULT_RAILTYPE" => "rail",
        "DEFAULT_CONTAINERTYPE" => "container",
        _ => return None,
    };
    vehicle_class(name)
}

/// The kind a `guiShape` draws, for a type without `vClass` (SUMO then takes
/// `passenger`'s defaults, but draws the shape): `None` for shapes of cars and
/// for shapes sightline has no kind for.
pub fn shape_kind(gui_shape: &str) -> Option<AgentKind> {
    let kind = match gui_shape.split('/').next().unwrap_or_default() {
        "bicycle" => Bicycle,
        "moped" | "motorcycle" | "scooter" => Motorbike,
        "pedestrian" => Pedestrian,
        "bus" => Bus,
        "delivery" | "truck" | "firebrigade" | "emergency" => Truck,
        _ => return None,
    };
    Some(kind)
}

/// Maps a type id that no file declares to a kind by its name (SUMO's FCD
/// carries the type id, not its class): a case-insensitive substring match,
/// first match wins.
///
/// | the id contains                               | kind                    |
/// |-----------------------------------------------|-------------------------|
/// | `truck`, `trailer`, `lorry`, `delivery`, `van`| [`AgentKind::Truck`]      |
/// | `bus` or `coach`                              | [`AgentKind::Bus`]        |
/// | `bicycle`, `bike` (not `motorbike`), `cycl`   | [`AgentKind::Bicycle`]    |
/// | `moto` or `scooter`                           | [`AgentKind::Motorbike`]  |
/// | `ped` or `person`                             | [`AgentKind::Pedestrian`] |
/// | anything else                                 | [`AgentKind::Car`]        |
///
/// ```
/// use sightline_dsl::{AgentKind, import::sumo::kind_of};
/// assert_eq!(kind_of("city_Bus"), AgentKind::Bus);
/// assert_eq!(kind_of("my_bike"), AgentKind::Bicycle);
/// assert_eq!(kind_of("motorbike"), AgentKind::Motorbike);
/// assert_eq!(kind_of("sedan"), AgentKind::Car);
/// ```
pub fn kind_of(vtype: &str) -> AgentKind {
    let vtype = vtype.to_lowercase();
    let has = |needles: &[&str]| needles.iter().any(|needle| vtype.contains(needle));
    if has(&["truck", "trailer", "lorry", "delivery", "van"]) {
        Truck
    } else if has(&["bus", "coach"]) {
        Bus
    } else if has(&["moto", "scooter"]) {
        Motorbike
    } else if has(&["bicycle", "bike", "cycl"]) {
        Bicycle
    } else if has(&["ped", "person"]) {
        Pedestrian
    } else {
        Car
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_rule_maps_its_words() {
        let cases = [
            ("truck", Truck),
            ("semi_TRAILER", Truck),
            ("lorry7", Truck),
            ("delivery", Truck),
            ("Van", Truck),
            ("bus", Bus),
            ("Coach", Bus),
            ("motorcycle", Motorbike),
            ("motorbike", Motorbike),
            ("scooter", Motorbike),
            ("bicycle", Bicycle),
            ("city_bike", Bicycle),
            ("cyclist", Bicycle),
            ("walker_ped", Pedestrian),
            ("person", Pedestrian),
            ("passenger", Car),
            ("", Car),
        ];
        for (vtype, kind) in cases {
            assert_eq!(kind_of(vtype), kind, "{vtype}");
        }
    }

    #[test]
    fn the_first_matching_rule_wins() {
        assert_eq!(kind_of("bus_truck"), Truck);
        assert_eq!(kind_of("delivery_bike"), Truck);
        assert_eq!(kind_of("motorbus"), Bus);
    }

    #[test]
    fn classes_are_unique_and_sized() {
        for (i, class) in CLASSES.iter().enumerate() {
            assert!(CLASSES[..i].iter().all(|c| c.name != class.name), "{}", class.name);
            assert!(class.length > 0.0 && class.width > 0.0);
        }
        // A bicycle is not a car, nor a van (issue 19).
        let bicycle = vehicle_class("bicycle").unwrap();
        assert_eq!(
            (bicycle.replay, bicycle.length, bicycle.width),
            (As(Bicycle), 1.6, 0.65)
        );
        assert_eq!(vehicle_class("delivery").unwrap().replay, As(Truck));
        assert_eq!(builtin_class("DEFAULT_BIKETYPE"), Some(bicycle));
        assert_eq!(builtin_class("car"), None);
        assert_eq!(vehicle_class("e_scooter"), None);
    }

    #[test]
    fn shapes_name_kinds() {
        assert_eq!(shape_kind("bus/coach"), Some(Bus));
        assert_eq!(shape_kind("delivery"), Some(Truck));
        assert_eq!(shape_kind("passenger/van"), None);
        assert_eq!(shape_kind("bicycle"), Some(Bicycle));
    }
}
