//! The per-object record of a system under test (issue 21): for every road
//! user around the perception world's ego, when the system's served sensors
//! first had it in sight, when a judged detection of the system first matched
//! it, when the ego's own sensors first had it in sight, and its closest
//! approach to the ego; what the `sut_*` per-object properties read. The
//! run's agents and regions, which the judge reads too, are a [`Roster`].
//!
//! The definitions, sightline's choice (docs/osi-sut.md), on the truth and the
//! run's clock (seconds from its start):
//! - **listed**: every agent other than the ego, the system's host and the
//!   roadside units that is in the scene together with the ego at some step,
//!   in agent order.
//! - **first in sight**, **first detected**: the step at which a served
//!   sensor first has it in sight and a judged detection first matches it, as
//!   the [`SystemJudge`](crate::outcome::SystemJudge) defines both for
//!   `sut_recall` and `sut_latency`.
//! - **first seen by the ego**: the first step at which one of the ego's own
//!   sensors has it in range and field of view with a visible fraction above
//!   0 (the ego may be another agent than the host: a system serving a
//!   roadside unit should tell the ego what it cannot see).
//! - **closest approach** and **areas**: as the semantic record defines them
//!   (the first step of least distance between the centres; the crosswalks,
//!   interaction areas and declared `areas` its centre was in with the ego in
//!   the scene).

use serde::{Deserialize, Serialize};
use sightline_dsl::{Agent, AgentKind, ObjectProperty, ObjectSelection};

use crate::math::elapsed;
use crate::semantic::{Closest, Region, contains, keeps};
use crate::trace::WorldStep;

/// One road user around the ego over a run with a system under test.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SystemObject {
    /// Its agent id.
    pub id: String,
    /// Its kind.
    pub class: AgentKind,
    /// When a served sensor first had it in sight, seconds.
    pub first_in_sight: Option<f64>,
    /// When a judged detection of the system first matched it.
    pub first_detected: Option<f64>,
    /// When one of the ego's own sensors first had it in sight.
    pub first_seen_by_ego: Option<f64>,
    /// Its closest approach to the ego.
    pub closest: Closest,
    /// The ids of the regions it was in with the ego in the scene.
    pub areas: Vec<String>,
}

impl SystemObject {
    /// Whether `selection` keeps it (as it keeps a semantic record).
    pub fn selected_by(&self, selection: &ObjectSelection) -> bool {
        keeps(selection, (&self.id, self.class, &self.areas), Some(self.closest))
    }

    /// Whether a check on `property` judges it: `sut_delay` judges only a road
    /// user that came into a served sensor's sight; the others judge all.
    pub fn judged_on(&self, property: ObjectProperty) -> bool {
        property != ObjectProperty::SutDelay || self.first_in_sight.is_some()
    }

    /// Its value of a system property ([`ObjectProperty::of_system`]), seconds;
    /// `None` for one the system never detected, and for another property.
    pub fn property(&self, property: ObjectProperty) -> Option<f64> {
        let detected = self.first_detected?;
        match property {
            ObjectProperty::SutLead => Some(elapsed(self.closest.time, detected)),
            ObjectProperty::SutAnticipation => {
                let ego_knows = self.first_seen_by_ego.unwrap_or(self.closest.time);
                Some(elapsed(ego_knows, detected).max(0.0))
            }
            ObjectProperty::SutDelay => Some(elapsed(detected, self.first_in_sight?).max(0.0)),
            _ => None,
        }
    }
}

/// The agents of a run, by index, and the regions of its world a selection
/// or a record names: what the judge and its record both read.
#[derive(Debug, Clone)]
pub(crate) struct Roster {
    /// Each agent's id and kind.
    pub(crate) agents: Vec<(String, AgentKind)>,
    /// Each region with its id.
    pub(crate) regions: Vec<(String, Region)>,
}

impl Roster {
    /// `regions`, with no agent yet.
    pub(crate) fn new(regions: Vec<(String, Region)>) -> Self {
        Self {
            agents: Vec::new(),
            regions,
        }
    }

    /// Every agent of the run, by index (a sink's `start`).
    pub(crate) fn start(&mut self, agents: &[Agent]) {
        self.agents = agents.iter().map(|a| (a.id.clone(), a.kind)).collect();
    }
}

/// What the steps showed of one agent relative to the ego.
#[derive(Debug, Clone, Default)]
struct Around {
    closest: Option<Closest>,
    first_seen_by_ego: Option<f64>,
}

/// Follows every road user around the ego over a run, for the record, among
/// the agents and regions of a [`Roster`].
#[derive(Debug, Clone)]
pub(crate) struct AroundEgo {
    ego: usize,
    host: usize,
    /// By agent index.
    by_agent: Vec<Around>,
    /// By agent index, then region: whether it was inside.
    inside: Vec<bool>,
}

impl AroundEgo {
    /// Nothing seen yet around agent `ego`, with the system serving agent
    /// `host`.
    pub(crate) fn new(ego: usize, host: usize) -> Self {
        Self {
            ego,
            host,
            by_agent: Vec::new(),
            inside: Vec::new(),
        }
    }

    /// The run's agents are `roster`'s (a sink's `start`).
    pub(crate) fn start(&mut self, roster: &Roster) {
        let agents = roster.agents.len();
        self.by_agent = vec![Around::default(); agents];
        self.inside = vec![false; agents * roster.regions.len()];
    }

    /// What `step` shows around the ego; nothing without the ego in the scene.
    pub(crate) fn step(&mut self, step: &WorldStep<'_>, roster: &Roster) {
        let Some(ego) = step.agents.get(self.ego).copied().flatten() else {
            return;
        };
        let regions = roster.regions.len();
        for (agent, state) in step.agents.iter().enumerate() {
            let Some(state) = state.filter(|_| agent != self.ego) else {
                continue;
            };
            let at = state.position();
            for (inside, (_, area)) in self.inside[agent * regions..][..regions]
                .iter_mut()
                .zip(&roster.regions)
            {
                *inside = *inside || contains(area, at);
            }
            let distance = (at - ego.position()).length();
            let around = &mut self.by_agent[agent];
            around.closest = Closest::nearer(around.closest, step.time, distance, at);
        }
        let Some(cooperator) = step.cooperators.iter().find(|c| c.agent == self.ego) else {
            return;
        };
        for sighting in cooperator.observation.sighted() {
            if sighting.visible_fraction > 0.0 {
                self.by_agent[sighting.target]
                    .first_seen_by_ego
                    .get_or_insert(step.time);
            }
        }
    }

    /// The record of every listed road user, with when each first came into
    /// the served sensors' sight (`first_in_sight`) and was first detected
    /// (`first_detected`), both by agent index.
    pub(crate) fn records(
        &self,
        roster: &Roster,
        (first_in_sight, first_detected): (&[Option<f64>], &[Option<f64>]),
    ) -> Vec<SystemObject> {
        let regions = roster.regions.len();
        (self.by_agent.iter().enumerate())
            .filter(|&(agent, _)| agent != self.ego && agent != self.host && roster.agents[agent].1 != AgentKind::Rsu)
            .filter_map(|(agent, around)| {
                let inside = &self.inside[agent * regions..][..regions];
                let (id, class) = &roster.agents[agent];
                Some(SystemObject {
                    id: id.clone(),
                    class: *class,
                    first_in_sight: first_in_sight[agent],
                    first_detected: first_detected[agent],
                    first_seen_by_ego: around.first_seen_by_ego,
                    closest: around.closest?,
                    areas: (roster.regions.iter().zip(inside))
                        .filter(|&(_, &inside)| inside)
                        .map(|((id, _), _)| id.clone())
                        .collect(),
                })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;
    use sightline_dsl::Area;
    use sightline_dsl::ObjectProperty::{SutAnticipation, SutDelay, SutLead};

    use super::*;
    use crate::math::{Pose, Vector};
    use crate::system::tests::agent;
    use crate::trace::CooperatorStep;
    use crate::world::{AgentState, Observation, Sighting, Visibility};

    fn at(x: f64, y: f64) -> Option<AgentState> {
        Some(AgentState {
            pose: Pose::new(Vector::new(x, y), 0.0),
            speed: 0.0,
            offset: 0.0,
            limit: f64::INFINITY,
        })
    }

    /// Step `step` (0.1 s each) with the agents at `agents` and the ego, when
    /// in the scene, sighting `(target, visible fraction)`.
    fn step(
        (around, roster): (&mut AroundEgo, &Roster),
        step: usize,
        agents: &[Option<AgentState>],
        sighted: &[(usize, f64)],
    ) {
        let sighted = sighted
            .iter()
            .map(|&(target, visible_fraction)| Sighting {
                sensor: 0,
                target,
                visibility: Visibility::Los,
                visible_fraction,
                detected: None,
            })
            .collect();
        let observation = Observation::with_sighted(sighted);
        let cooperators: Vec<CooperatorStep<'_>> = (agents[0].iter())
            .map(|ego| CooperatorStep {
                agent: 0,
                estimate: ego.pose,
                observation: &observation,
            })
            .collect();
        around.step(
            &WorldStep {
                step,
                time: step as f64 * 0.1,
                agents,
                cooperators: &cooperators,
                measured: None,
            },
            roster,
        );
    }

    /// Four steps by hand. The ego (0) at the origin, the host (1), a
    /// pedestrian `a` (2) walking towards the ego through `zone` (a disc of
    /// 3 m about (0, 10)), a roadside unit (3), a car `b` (4) never in the
    /// scene and a car `c` (5) driving in. At step 2 the ego is out of the
    /// scene: `a`, 1 m from where the ego was, does not count. At step 3 the
    /// ego is at (0, 2): `a` 6 m off, `c` 22 m off, both closest then. The
    /// ego sights `c` at step 0, and `a` at step 1 (at step 0 `a` is in range
    /// but wholly hidden).
    #[test]
    fn the_record_by_hand() {
        let zone = Region::new(Area::Circle {
            center: [0.0, 10.0],
            radius: 3.0,
        });
        let mut roster = Roster::new(vec![("zone".into(), zone)]);
        roster.start(&[
            agent("ego", AgentKind::Car),
            agent("host", AgentKind::Car),
            agent("a", AgentKind::Pedestrian),
            agent("rsu", AgentKind::Rsu),
            agent("b", AgentKind::Car),
            agent("c", AgentKind::Car),
        ]);
        let mut around = AroundEgo::new(0, 1);
        around.start(&roster);
        let rsu = at(5.0, 5.0);
        let host = at(10.0, 0.0);
        step(
            (&mut around, &roster),
            0,
            &[at(0.0, 0.0), host, at(0.0, 20.0), rsu, None, at(30.0, 0.0)],
            &[(5, 0.5), (2, 0.0)],
        );
        step(
            (&mut around, &roster),
            1,
            &[at(0.0, 0.0), host, at(0.0, 12.0), rsu, None, at(25.0, 0.0)],
            &[(2, 0.3)],
        );
        step(
            (&mut around, &roster),
            2,
            &[None, host, at(0.0, 1.0), rsu, None, at(24.0, 0.0)],
            &[],
        );
        step(
            (&mut around, &roster),
            3,
            &[at(0.0, 2.0), host, at(0.0, 8.0), rsu, None, at(22.0, 2.0)],
            &[(2, 1.0)],
        );
        // The system's judge had `a` in sight at 0 s and detected it at
        // 0.1 s, had `c` in sight at 0.1 s and never detected it.
        let in_sight = [None, Some(0.0), Some(0.0), None, None, Some(0.1)];
        let detected = [None, None, Some(0.1), None, None, None];
        let records = around.records(&roster, (&in_sight, &detected));
        let ids: Vec<&str> = records.iter().map(|r| r.id.as_str()).collect();
        assert_eq!(ids, ["a", "c"]);
        let (a, c) = (&records[0], &records[1]);
        assert_eq!(
            (a.first_in_sight, a.first_detected, a.first_seen_by_ego),
            (Some(0.0), Some(0.1), Some(0.1))
        );
        assert_relative_eq!(a.closest.time, 0.3, epsilon = 1e-12);
        assert_relative_eq!(a.closest.distance, 6.0);
        assert_eq!(
            (a.closest.position, a.areas.as_slice()),
            ([0.0, 8.0], ["zone".to_string()].as_slice())
        );
        assert_relative_eq!(a.property(SutLead).unwrap(), 0.2, epsilon = 1e-12);
        assert_eq!(a.property(SutAnticipation), Some(0.0));
        assert_relative_eq!(a.property(SutDelay).unwrap(), 0.1);
        assert_eq!(
            (c.first_seen_by_ego, c.first_detected, c.closest.distance),
            (Some(0.0), None, 22.0)
        );
        assert!(c.areas.is_empty() && c.judged_on(SutDelay) && c.property(SutLead).is_none());
    }

    fn object(in_sight: Option<f64>, detected: Option<f64>, seen_by_ego: Option<f64>) -> SystemObject {
        SystemObject {
            id: "a".into(),
            class: AgentKind::Car,
            first_in_sight: in_sight,
            first_detected: detected,
            first_seen_by_ego: seen_by_ego,
            closest: Closest {
                time: 6.0,
                distance: 3.0,
                position: [0.0, 0.0],
            },
            areas: Vec::new(),
        }
    }

    /// Each property by hand, for a road user detected at 2 s, closest at 6 s.
    #[test]
    fn properties_by_hand() {
        // In the served sight at 1.5 s, in the ego's at 4 s.
        let told = object(Some(1.5), Some(2.0), Some(4.0));
        assert_eq!(told.property(SutLead), Some(4.0));
        assert_eq!(told.property(SutAnticipation), Some(2.0));
        assert_eq!(told.property(SutDelay), Some(0.5));
        // The ego never sees it: anticipation runs to the closest approach.
        assert_eq!(object(Some(1.5), Some(2.0), None).property(SutAnticipation), Some(4.0));
        // The ego saw it first: nothing anticipated. Detected after its
        // closest approach: a negative lead, and none anticipated.
        assert_eq!(
            object(Some(1.5), Some(2.0), Some(1.0)).property(SutAnticipation),
            Some(0.0)
        );
        let late = object(Some(1.5), Some(7.0), None);
        assert_eq!(late.property(SutLead), Some(-1.0));
        assert_eq!(late.property(SutAnticipation), Some(0.0));
        // Never detected: none of the three; in sight, it is judged on delay.
        let missed = object(Some(1.5), None, Some(4.0));
        for property in [SutLead, SutAnticipation, SutDelay] {
            assert_eq!(missed.property(property), None, "{property:?}");
        }
        assert!(missed.judged_on(SutDelay));
        // Never in the served sight (detected by a coasting track, say): no
        // delay and not judged on it; judged on the others.
        let unseen = object(None, Some(2.0), None);
        assert_eq!(unseen.property(SutDelay), None);
        assert!(!unseen.judged_on(SutDelay) && unseen.judged_on(SutLead));
        assert_eq!(ObjectProperty::ALL.iter().filter(|p| p.of_system()).count(), 3);
        assert_eq!(told.property(ObjectProperty::WarningLead), None);
    }
}
