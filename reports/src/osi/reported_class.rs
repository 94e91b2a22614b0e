//! The class a system under test reports for a detected moving object
//! (docs/osi-sut.md, sightline's mapping): its most probable `candidate`'s
//! `type` and, for a vehicle, `vehicle_classification.type`, as one of
//! sightline's agent kinds; `None` (unknown) where no kind fits or nothing is
//! reported.

use sightline_dsl::AgentKind;

use super::answer::{Candidate, Object};
use sightline_osi::osi3::moving_object::{Type as ObjectType, vehicle_classification::Type as VehicleType};

/// The class `object` reports: that of its most probable candidate, `None`
/// without a candidate or for a type no kind maps to. A candidate without a
/// probability from 0 to 1, or two most probable candidates, are out of
/// protocol: the error says which, for moving object `index`.
pub(super) fn reported_class(index: usize, object: &Object) -> Result<Option<AgentKind>, String> {
    let mut best: Option<(f64, &Candidate)> = None;
    let mut tied = false;
    for (j, candidate) in object.candidate.iter().enumerate() {
        let Some(p) = candidate.probability.filter(|p| (0.0..=1.0).contains(p)) else {
            return Err(format!(
                "moving object {index}'s candidate {j} has no probability from 0 to 1 (candidate.probability)"
            ));
        };
        match best {
            Some((most, _)) if p < most => {}
            Some((most, _)) if p == most => tied = true,
            _ => (best, tied) = (Some((p, candidate)), false),
        }
    }
    match best {
        Some((p, _)) if tied => Err(format!(
            "moving object {index} has two most probable candidates (probability {p}): its class is ambiguous"
        )),
        best => Ok(best.and_then(|(_, candidate)| kind(candidate))),
    }
}

/// The kind of road user `candidate` names; `None` for one sightline does
/// not model (animals, trams, wheelchairs, …) or an unknown or other type.
fn kind(candidate: &Candidate) -> Option<AgentKind> {
    match ObjectType::try_from(candidate.r#type?).ok()? {
        ObjectType::Pedestrian => Some(AgentKind::Pedestrian),
        ObjectType::Vehicle => {
            let vehicle = candidate.vehicle_classification.as_ref()?.r#type?;
            match VehicleType::try_from(vehicle).ok()? {
                VehicleType::SmallCar
                | VehicleType::CompactCar
                | VehicleType::Car
                | VehicleType::LuxuryCar
                | VehicleType::DeliveryVan => Some(AgentKind::Car),
                VehicleType::HeavyTruck
                | VehicleType::Semitractor
                | VehicleType::Semitrailer
                | VehicleType::Trailer => Some(AgentKind::Truck),
                VehicleType::Bus => Some(AgentKind::Bus),
                VehicleType::Motorbike => Some(AgentKind::Motorbike),
                VehicleType::Bicycle => Some(AgentKind::Bicycle),
                _ => None,
            }
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::osi::answer::VehicleClassification;

    fn candidate(probability: f64, kind: ObjectType, vehicle: Option<VehicleType>) -> Candidate {
        Candidate {
            probability: Some(probability),
            r#type: Some(kind as i32),
            vehicle_classification: vehicle.map(|v| VehicleClassification { r#type: Some(v as i32) }),
        }
    }

    fn class(candidates: Vec<Candidate>) -> Result<Option<AgentKind>, String> {
        let object = Object {
            candidate: candidates,
            ..Default::default()
        };
        reported_class(3, &object)
    }

    /// Each row of docs/osi-sut.md's table, one candidate each.
    #[test]
    fn the_mapping_by_hand() {
        use AgentKind::*;
        let vehicle = |v| class(vec![candidate(1.0, ObjectType::Vehicle, Some(v))]).unwrap();
        for v in [
            VehicleType::SmallCar,
            VehicleType::CompactCar,
            VehicleType::Car,
            VehicleType::LuxuryCar,
            VehicleType::DeliveryVan,
        ] {
            assert_eq!(vehicle(v), Some(Car), "{v:?}");
        }
        for v in [
            VehicleType::HeavyTruck,
            VehicleType::Semitractor,
            VehicleType::Semitrailer,
            VehicleType::Trailer,
        ] {
            assert_eq!(vehicle(v), Some(Truck), "{v:?}");
        }
        assert_eq!(
            [VehicleType::Bus, VehicleType::Motorbike, VehicleType::Bicycle].map(vehicle),
            [Some(Bus), Some(Motorbike), Some(Bicycle)]
        );
        for v in [
            VehicleType::Unknown,
            VehicleType::Other,
            VehicleType::Tram,
            VehicleType::Wheelchair,
            VehicleType::StandupScooter,
            VehicleType::LandVehicle,
        ] {
            assert_eq!(vehicle(v), None, "{v:?}");
        }
        assert_eq!(
            class(vec![candidate(0.7, ObjectType::Pedestrian, None)]),
            Ok(Some(Pedestrian))
        );
        // A vehicle without its classification, an animal, nothing reported.
        assert_eq!(class(vec![candidate(0.7, ObjectType::Vehicle, None)]), Ok(None));
        assert_eq!(class(vec![candidate(0.7, ObjectType::Animal, None)]), Ok(None));
        assert_eq!(class(vec![]), Ok(None));
        let unset = Candidate {
            probability: Some(1.0),
            ..Default::default()
        };
        assert_eq!(class(vec![unset]), Ok(None));
    }

    #[test]
    fn the_most_probable_candidate_wins() {
        let candidates = vec![
            candidate(0.2, ObjectType::Pedestrian, None),
            candidate(0.5, ObjectType::Vehicle, Some(VehicleType::Bus)),
            candidate(0.3, ObjectType::Vehicle, Some(VehicleType::Car)),
        ];
        assert_eq!(class(candidates), Ok(Some(AgentKind::Bus)));
    }

    #[test]
    fn a_tie_or_a_probability_outside_0_to_1_is_out_of_protocol() {
        let tie = vec![
            candidate(0.4, ObjectType::Pedestrian, None),
            candidate(0.4, ObjectType::Vehicle, Some(VehicleType::Car)),
            candidate(0.2, ObjectType::Vehicle, Some(VehicleType::Bus)),
        ];
        assert_eq!(
            class(tie),
            Err("moving object 3 has two most probable candidates (probability 0.4): its class is ambiguous".into())
        );
        // A tie below the most probable is none.
        let below = vec![
            candidate(0.2, ObjectType::Pedestrian, None),
            candidate(0.2, ObjectType::Vehicle, Some(VehicleType::Car)),
            candidate(0.6, ObjectType::Vehicle, Some(VehicleType::Bus)),
        ];
        assert_eq!(class(below), Ok(Some(AgentKind::Bus)));
        for p in [f64::NAN, -0.1, 1.5] {
            let error = class(vec![
                candidate(0.3, ObjectType::Pedestrian, None),
                candidate(p, ObjectType::Pedestrian, None),
            ]);
            assert_eq!(
                error,
                Err("moving object 3's candidate 1 has no probability from 0 to 1 (candidate.probability)".into()),
                "{p}"
            );
        }
        let missing = Candidate::default();
        assert!(class(vec![missing]).is_err());
    }
}
