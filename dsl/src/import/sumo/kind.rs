//! Which [`AgentKind`] a SUMO vehicle type stands for.

use crate::AgentKind;

/// Maps a SUMO vehicle type id to a kind by its name, since FCD output carries
/// the type id but not its vehicle class.
///
/// The rule is a case-insensitive substring match, first match wins:
///
/// | the id contains                               | kind                    |
/// |-----------------------------------------------|-------------------------|
/// | `truck`, `trailer`, `lorry` or `delivery`     | [`AgentKind::Truck`]      |
/// | `bus` or `coach`                              | [`AgentKind::Bus`]        |
/// | `moto`, `scooter` or `bike`                   | [`AgentKind::Motorbike`]  |
/// | `ped` or `person`                             | [`AgentKind::Pedestrian`] |
/// | anything else, SUMO's `DEFAULT_VEHTYPE` too   | [`AgentKind::Car`]        |
///
/// Bicycles (SUMO's `DEFAULT_BIKETYPE`) map to a motorbike, the kind with the
/// nearest footprint.
///
/// ```
/// use sightline_dsl::{AgentKind, import::sumo::kind_of};
/// assert_eq!(kind_of("city_Bus"), AgentKind::Bus);
/// assert_eq!(kind_of("DEFAULT_BIKETYPE"), AgentKind::Motorbike);
/// assert_eq!(kind_of("DEFAULT_VEHTYPE"), AgentKind::Car);
/// ```
pub fn kind_of(vtype: &str) -> AgentKind {
    const RULES: [(&[&str], AgentKind); 4] = [
        (&["truck", "trailer", "lorry", "delivery"], AgentKind::Truck),
        (&["bus", "coach"], AgentKind::Bus),
        (&["moto", "scooter", "bike"], AgentKind::Motorbike),
        (&["ped", "person"], AgentKind::Pedestrian),
    ];
    let vtype = vtype.to_lowercase();
    RULES
        .iter()
        .find(|(needles, _)| needles.iter().any(|needle| vtype.contains(needle)))
        .map_or(AgentKind::Car, |&(_, kind)| kind)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_rule_maps_its_words() {
        let cases = [
            ("truck", AgentKind::Truck),
            ("semi_TRAILER", AgentKind::Truck),
            ("lorry7", AgentKind::Truck),
            ("delivery", AgentKind::Truck),
            ("bus", AgentKind::Bus),
            ("Coach", AgentKind::Bus),
            ("motorcycle", AgentKind::Motorbike),
            ("scooter", AgentKind::Motorbike),
            ("DEFAULT_BIKETYPE", AgentKind::Motorbike),
            ("DEFAULT_PEDTYPE", AgentKind::Pedestrian),
            ("person", AgentKind::Pedestrian),
            ("DEFAULT_VEHTYPE", AgentKind::Car),
            ("passenger", AgentKind::Car),
            ("", AgentKind::Car),
        ];
        for (vtype, kind) in cases {
            assert_eq!(kind_of(vtype), kind, "{vtype}");
        }
    }

    #[test]
    fn the_first_matching_rule_wins() {
        // Both "bus" and "truck": trucks come first.
        assert_eq!(kind_of("bus_truck"), AgentKind::Truck);
        // "delivery_bike" is a delivery vehicle before it is a bike.
        assert_eq!(kind_of("delivery_bike"), AgentKind::Truck);
        // "motorbus" holds "bus" before "moto" is tried.
        assert_eq!(kind_of("motorbus"), AgentKind::Bus);
    }
}
