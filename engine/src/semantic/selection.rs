//! What a per-object check reads of the per-object records: which records a
//! selection keeps, and each record's value of a property.

use sightline_dsl::{AgentKind, ObjectProperty, ObjectSelection};

use super::objects::{Category, Closest, ObjectRecord};
use crate::math::elapsed;

impl ObjectRecord {
    /// Whether `selection` keeps it: every criterion given matches (an id, a
    /// class, an area it was in, its closest approach nearer than the distance
    /// and within the window).
    pub fn selected_by(&self, selection: &ObjectSelection) -> bool {
        keeps(selection, (&self.id, self.class, &self.areas), self.closest)
    }

    /// Its value of a record property ([`ObjectProperty::of_record`]); `None`
    /// where it has none (see each property), for `warning_time`, which
    /// close approaches carry, and for a system's property, which the
    /// system's record carries.
    pub fn property(&self, property: ObjectProperty) -> Option<f64> {
        let closest = self.closest.map(|c| c.time);
        match property {
            ObjectProperty::WarningTime
            | ObjectProperty::SutLead
            | ObjectProperty::SutAnticipation
            | ObjectProperty::SutDelay => None,
            ObjectProperty::WarningLead => Some(elapsed(closest?, self.first_warning?)),
            ObjectProperty::KnowledgeLead => {
                let known = match (self.first_seen, self.first_v2x) {
                    (Some(seen), Some(told)) => seen.min(told),
                    (seen, told) => seen.or(told)?,
                };
                Some(elapsed(closest?, known))
            }
            ObjectProperty::Anticipation => match self.category {
                Category::SeenFirst => Some(0.0),
                _ => self.anticipation(),
            },
            ObjectProperty::ClosestDistance => self.closest.map(|c| c.distance),
            ObjectProperty::MinTtc => self.min_ttc,
            ObjectProperty::Pet => self.pet,
            ObjectProperty::MaxDrac => self.max_drac,
            ObjectProperty::GridLead => Some(elapsed(closest?, self.first_in_grid?)),
            ObjectProperty::GridOrWarningLead => {
                let first = match (self.first_in_grid, self.first_warning) {
                    (Some(grid), Some(warned)) => grid.min(warned),
                    (grid, warned) => grid.or(warned)?,
                };
                Some(elapsed(closest?, first))
            }
        }
    }
}

/// Whether `selection` keeps a road user with this id, class and regions
/// (`areas`) and this closest approach: every criterion given matches (an id,
/// a class, an area it was in, its closest approach nearer than the distance
/// and within the window).
pub(crate) fn keeps(
    selection: &ObjectSelection,
    (id, class, areas): (&String, AgentKind, &[String]),
    closest: Option<Closest>,
) -> bool {
    (selection.ids.is_empty() || selection.ids.contains(id))
        && (selection.classes.is_empty() || selection.classes.contains(&class))
        && (selection.areas.is_empty() || selection.areas.iter().any(|area| areas.contains(area)))
        && selection
            .closer_than
            .is_none_or(|distance| closest.is_some_and(|closest| closest.distance < distance))
        && selection
            .between
            .is_none_or(|[from, to]| closest.is_some_and(|closest| (from..=to).contains(&closest.time)))
}

#[cfg(test)]
mod tests {
    use sightline_dsl::AgentKind;

    use super::*;
    use crate::semantic::objects::Closest;

    /// A pedestrian on `cw_north`, seen at 4 s, named by V2X at 1.5 s, warned
    /// at 2 s, closest (3 m) at 6 s.
    fn pedestrian() -> ObjectRecord {
        ObjectRecord {
            run: 0,
            id: "CROSSWALK-3".into(),
            class: AgentKind::Pedestrian,
            length: 0.6,
            width: 0.6,
            first_relevant: 1.0,
            first_seen: Some(4.0),
            first_v2x: Some(1.5),
            first_warning: Some(2.0),
            first_in_grid: None,
            closest: Some(Closest {
                time: 6.0,
                distance: 3.0,
                position: [0.0, 11.0],
            }),
            min_ttc: Some(1.5),
            max_drac: Some(2.0),
            pet: None,
            category: Category::WarnedBeforeSeen,
            baseline_v2x: Some(1.0),
            areas: vec!["cw_north".into(), "junction".into()],
        }
    }

    #[test]
    fn properties_by_hand() {
        let p = pedestrian();
        assert_eq!(p.property(ObjectProperty::WarningLead), Some(4.0));
        assert_eq!(p.property(ObjectProperty::KnowledgeLead), Some(4.5));
        assert_eq!(p.property(ObjectProperty::Anticipation), Some(2.5));
        assert_eq!(p.property(ObjectProperty::ClosestDistance), Some(3.0));
        assert_eq!(p.property(ObjectProperty::WarningTime), None);
        assert_eq!(p.property(ObjectProperty::MinTtc), Some(1.5));
        assert_eq!(p.property(ObjectProperty::MaxDrac), Some(2.0));
        assert_eq!(p.property(ObjectProperty::Pet), None);
        // Never warned, never known: no lead; seen first: no anticipation gained.
        let late = ObjectRecord {
            first_warning: None,
            first_seen: Some(7.0),
            first_v2x: None,
            category: Category::SeenFirst,
            ..pedestrian()
        };
        assert_eq!(late.property(ObjectProperty::WarningLead), None);
        assert_eq!(late.property(ObjectProperty::KnowledgeLead), Some(-1.0));
        assert_eq!(late.property(ObjectProperty::Anticipation), Some(0.0));
        let unknown = ObjectRecord {
            first_seen: None,
            category: Category::NeverKnown,
            ..late
        };
        assert_eq!(unknown.property(ObjectProperty::KnowledgeLead), None);
        assert_eq!(unknown.property(ObjectProperty::Anticipation), None);
    }

    /// Closest at 6 s, warned at 2 s: in the grid at 3 s, the grid lead is 3 s
    /// and the earlier warning decides the other (4 s); in the grid at 1 s, the
    /// grid decides (5 s); with neither, neither lead exists, and one in the
    /// grid only after its closest approach has a negative lead.
    #[test]
    fn grid_leads_by_hand() {
        let in_grid = |at: Option<f64>, warned: Option<f64>| ObjectRecord {
            first_in_grid: at,
            first_warning: warned,
            ..pedestrian()
        };
        let p = in_grid(Some(3.0), Some(2.0));
        assert_eq!(p.property(ObjectProperty::GridLead), Some(3.0));
        assert_eq!(p.property(ObjectProperty::GridOrWarningLead), Some(4.0));
        let p = in_grid(Some(1.0), Some(2.0));
        assert_eq!(p.property(ObjectProperty::GridOrWarningLead), Some(5.0));
        let p = in_grid(None, Some(2.0));
        assert_eq!(p.property(ObjectProperty::GridLead), None);
        assert_eq!(p.property(ObjectProperty::GridOrWarningLead), Some(4.0));
        let p = in_grid(Some(7.5), None);
        assert_eq!(p.property(ObjectProperty::GridLead), Some(-1.5));
        assert_eq!(p.property(ObjectProperty::GridOrWarningLead), Some(-1.5));
        let p = in_grid(None, None);
        assert_eq!(p.property(ObjectProperty::GridOrWarningLead), None);
    }

    #[test]
    fn every_criterion_given_must_match() {
        let p = pedestrian();
        let select = |selection: ObjectSelection| p.selected_by(&selection);
        assert!(select(ObjectSelection::default()));
        assert!(select(ObjectSelection {
            classes: vec![AgentKind::Car, AgentKind::Pedestrian],
            areas: vec!["cw_south".into(), "cw_north".into()],
            between: Some([6.0, 8.0]),
            ..Default::default()
        }));
        assert!(!select(ObjectSelection {
            classes: vec![AgentKind::Car],
            ..Default::default()
        }));
        assert!(!select(ObjectSelection {
            areas: vec!["cw_south".into()],
            ..Default::default()
        }));
        assert!(!select(ObjectSelection {
            between: Some([0.0, 5.9]),
            ..Default::default()
        }));
        assert!(select(ObjectSelection {
            closer_than: Some(3.5),
            ..Default::default()
        }));
        assert!(!select(ObjectSelection {
            closer_than: Some(3.0),
            ..Default::default()
        }));
        assert!(select(ObjectSelection {
            ids: vec!["CROSSWALK-3".into()],
            ..Default::default()
        }));
        assert!(!select(ObjectSelection {
            ids: vec!["CROSSWALK-4".into()],
            ..Default::default()
        }));
    }
}
