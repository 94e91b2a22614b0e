//! The judgement of a system under test (`system_under_test`, issue 21): what
//! it detected at each step, matched against the road users in the scene, and
//! summed into [`SystemMetrics`].
//!
//! The rule, sightline's choice (docs/osi-sut.md): at each step the system
//! answers, its judged detections (existence probability at least the
//! scenario's `min_existence`, given in the host agent's frame and placed in
//! the world with the host's true pose) are matched one to one with the road
//! users in the scene other than the host (roadside units are no road users):
//! every pair within the gate, nearest first (ties by detection, then road
//! user, in order), each detection and road user taken once. A detection
//! left without a road user is a ghost. A road user is *in sight* at a step
//! when a served sensor has it in range and field of view with a visible
//! fraction above 0.
//!
//! Every metric is also summed over what an `objects` selection keeps
//! ([`SelectedMetrics`]). Recall, latency, position error and class accuracy
//! are about road users: a road user's step is kept when its id and class are
//! among the selection's (where it names any) and its centre lies in one of
//! the selection's areas at that step (boundary included). Precision and
//! ghosts are about detections: a detection is kept when the class it reports
//! and its position do (an unknown class is in no class list), and, where the
//! selection names ids, when it matched a road user among them (so a ghost,
//! which has no id, is never kept by ids).

use serde::{Deserialize, Serialize};
use sightline_dsl::{Agent, AgentKind, Metric, ObjectSelection, World};

use crate::math::Point;
use crate::semantic::{Region, contains, regions};
use crate::system_objects::{AroundEgo, Roster, SystemObject};
use crate::trace::WorldStep;

/// One detection of the system, in the host agent's frame: metres forward of
/// its centre (`x`) and to its left (`y`), with the class it reports.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Detection {
    /// Forward of the host's centre, metres.
    pub x: f64,
    /// Left of the host's centre, metres.
    pub y: f64,
    /// The kind of road user it reports; `None`: unknown.
    pub class: Option<AgentKind>,
}

/// What a system under test achieved over a run, each metric with its n.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct SystemMetrics {
    /// Steps the system answered.
    pub steps: u64,
    /// Every metric over every road user and detection.
    pub all: Tally,
    /// Every road user around the ego, with when the system first detected
    /// it ([`SystemObject`]); empty where the judge kept no record.
    pub objects: Vec<SystemObject>,
    /// Every metric over each selection the judge was given.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub selected: Vec<SelectedMetrics>,
}

/// The counts and sums the metrics of a system under test are ratios of,
/// over what a selection keeps (everything, for [`SystemMetrics::all`]).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Tally {
    /// Object-steps in sight of a served sensor (`sut_recall`'s n).
    pub in_sight: u64,
    /// Of those, the ones a detection matched.
    pub in_sight_matched: u64,
    /// Judged detections (`sut_precision`'s and `sut_ghosts`' n).
    pub detections: u64,
    /// Of those, the ones that matched a road user.
    pub detections_matched: u64,
    /// Matched detections, counted by their road user (`sut_position_error`'s
    /// and `sut_class_accuracy`'s n).
    pub matched: u64,
    /// Σ distance from a matched detection to its road user's centre, metres.
    pub position_error_sum: f64,
    /// Matched detections whose reported class is their road user's kind.
    pub class_correct: u64,
    /// Road users matched after first in sight (`sut_latency`'s n).
    pub latencies: u64,
    /// Σ of their latencies, seconds.
    pub latency_sum: f64,
}

impl Tally {
    /// The value and n of `metric`; `None` for another metric. The value is
    /// `None` where the population is empty.
    pub fn sample(&self, metric: Metric) -> Option<(Option<f64>, u64)> {
        let ratio = |num: f64, den: u64| ((den > 0).then(|| num / den as f64), den);
        Some(match metric {
            Metric::SutRecall => ratio(self.in_sight_matched as f64, self.in_sight),
            Metric::SutPrecision => ratio(self.detections_matched as f64, self.detections),
            Metric::SutPositionError => ratio(self.position_error_sum, self.matched),
            Metric::SutClassAccuracy => ratio(self.class_correct as f64, self.matched),
            Metric::SutLatency => ratio(self.latency_sum, self.latencies),
            Metric::SutGhosts => (
                (self.detections > 0).then(|| (self.detections - self.detections_matched) as f64),
                self.detections,
            ),
            _ => return None,
        })
    }
}

/// Every metric over what an `objects` selection keeps.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SelectedMetrics {
    /// The selection.
    pub selection: ObjectSelection,
    /// What it kept.
    pub tally: Tally,
}

impl SystemMetrics {
    /// The value of `metric`; `None` for another metric, or where its
    /// population is empty.
    pub fn value(&self, metric: Metric) -> Option<f64> {
        self.all.sample(metric)?.0
    }

    /// The sample size of `metric`; `None` for another metric.
    pub fn sample_size(&self, metric: Metric) -> Option<u64> {
        Some(self.all.sample(metric)?.1)
    }

    /// The value and n of `metric` over what `selection` keeps; `None` where
    /// the judge was not given the selection or `metric` is no system's.
    pub fn selected_sample(&self, metric: Metric, selection: &ObjectSelection) -> Option<(Option<f64>, u64)> {
        self.selected
            .iter()
            .find(|s| s.selection == *selection)?
            .tally
            .sample(metric)
    }
}

/// A selection being summed: its tally and, by agent, the first kept step in
/// sight and the first kept step matched.
#[derive(Debug, Clone)]
struct Selecting {
    selection: ObjectSelection,
    tally: Tally,
    first_in_sight: Vec<Option<f64>>,
    first_matched: Vec<Option<f64>>,
}

impl Selecting {
    fn new(selection: ObjectSelection) -> Self {
        Self {
            selection,
            tally: Tally::default(),
            first_in_sight: Vec::new(),
            first_matched: Vec::new(),
        }
    }

    /// Its tally, with the latencies of the run.
    fn finish(mut self) -> SelectedMetrics {
        (self.tally.latencies, self.tally.latency_sum) = latencies(&self.first_in_sight, &self.first_matched);
        SelectedMetrics {
            selection: self.selection,
            tally: self.tally,
        }
    }
}

/// One step's matching.
struct Matching {
    /// Each judged detection's place in the world and reported class.
    detections: Vec<(Point, Option<AgentKind>)>,
    /// By detection: the road user it matched and its distance, metres.
    matches: Vec<Option<(usize, f64)>>,
    /// By agent: whether a detection matched it.
    matched: Vec<bool>,
    /// By agent: whether a served sensor has it in sight.
    in_sight: Vec<bool>,
}

/// Matches a system's detections step by step, sums what it achieved and
/// keeps the record of every road user around the ego.
#[derive(Debug, Clone)]
pub struct SystemJudge {
    host: usize,
    sensors: Vec<usize>,
    gate: f64,
    road_user: Vec<bool>,
    roster: Roster,
    around: AroundEgo,
    steps: u64,
    /// Everything first, then each selection the judge was given.
    selecting: Vec<Selecting>,
}

impl SystemJudge {
    /// A judge of a system serving `sensors` (indices on the agent) of agent
    /// `host` in `world`, matching within `gate` metres, summing every metric
    /// also over each of `selections` (only ids, classes and areas select;
    /// the language refuses the rest of a selection on these metrics), and
    /// keeping the record of every road user around `world`'s perception ego
    /// ([`SystemMetrics::objects`]).
    pub fn new(
        world: &World,
        (host, sensors): (usize, Vec<usize>),
        gate: f64,
        selections: Vec<ObjectSelection>,
    ) -> Self {
        let ego = world.perception.as_ref().map_or(host, |p| p.ego);
        Self::with((ego, host, sensors), gate, regions(world), selections)
    }

    /// [`SystemJudge::new`] around agent `ego`, among `regions`.
    fn with(
        (ego, host, sensors): (usize, usize, Vec<usize>),
        gate: f64,
        regions: Vec<(String, Region)>,
        selections: Vec<ObjectSelection>,
    ) -> Self {
        let everything = std::iter::once(ObjectSelection::ALL).chain(selections);
        Self {
            host,
            sensors,
            gate,
            road_user: Vec::new(),
            roster: Roster::new(regions),
            around: AroundEgo::new(ego, host),
            steps: 0,
            selecting: everything.map(Selecting::new).collect(),
        }
    }

    /// Every agent of the run, by index (a sink's `start`).
    pub fn start(&mut self, agents: &[Agent]) {
        self.road_user = agents.iter().map(|a| a.kind != AgentKind::Rsu).collect();
        self.roster.start(agents);
        for selecting in &mut self.selecting {
            selecting.first_in_sight = vec![None; agents.len()];
            selecting.first_matched = vec![None; agents.len()];
        }
        self.around.start(&self.roster);
    }

    /// Follows the road users around the ego at `step`, whether or not the
    /// system is asked then (for the record).
    pub fn observe(&mut self, step: &WorldStep<'_>) {
        self.around.step(step, &self.roster);
    }

    /// Whether `selection`'s areas, where it names any, contain `at`.
    fn in_areas(&self, selection: &ObjectSelection, at: Point) -> bool {
        selection.areas.is_empty()
            || (self.roster.regions.iter()).any(|(region, area)| selection.areas.contains(region) && contains(area, at))
    }

    /// Whether `selection` keeps agent `agent` with its centre at `centre`.
    fn keeps(&self, selection: &ObjectSelection, agent: usize, centre: Point) -> bool {
        let (id, kind) = &self.roster.agents[agent];
        (selection.ids.is_empty() || selection.ids.contains(id))
            && (selection.classes.is_empty() || selection.classes.contains(kind))
            && self.in_areas(selection, centre)
    }

    /// Whether `selection` keeps a detection at `at` reporting `class` that
    /// matched road user `matched`, if any.
    fn keeps_detection(
        &self,
        selection: &ObjectSelection,
        (at, class): (Point, Option<AgentKind>),
        matched: Option<usize>,
    ) -> bool {
        (selection.ids.is_empty() || matched.is_some_and(|agent| selection.ids.contains(&self.roster.agents[agent].0)))
            && (selection.classes.is_empty() || class.is_some_and(|class| selection.classes.contains(&class)))
            && self.in_areas(selection, at)
    }

    /// Judges the system's `detections` at `step`; a step without the host in
    /// the scene or among the cooperating agents has nothing to judge.
    pub fn step(&mut self, step: &WorldStep<'_>, detections: &[Detection]) {
        let Some(host) = step.agents.get(self.host).copied().flatten() else {
            return;
        };
        let Some(cooperator) = step.cooperators.iter().find(|c| c.agent == self.host) else {
            return;
        };
        self.steps += 1;
        let (sin, cos) = host.heading().sin_cos();
        let origin = host.position();
        let placed: Vec<(Point, Option<AgentKind>)> = (detections.iter())
            .map(|d| {
                let at = Point::new(origin.x + cos * d.x - sin * d.y, origin.y + sin * d.x + cos * d.y);
                (at, d.class)
            })
            .collect();
        let mut pairs = Vec::new();
        for (agent, state) in step.agents.iter().enumerate() {
            let Some(state) = state.filter(|_| agent != self.host && self.road_user.get(agent) == Some(&true)) else {
                continue;
            };
            let centre = state.position();
            for (detection, (at, _)) in placed.iter().enumerate() {
                let distance = (*at - centre).length();
                if distance <= self.gate {
                    pairs.push((distance, detection, agent));
                }
            }
        }
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
        let mut matches = vec![None; placed.len()];
        let mut matched = vec![false; step.agents.len()];
        for (distance, detection, agent) in pairs {
            if matches[detection].is_some() || matched[agent] {
                continue;
            }
            matches[detection] = Some((agent, distance));
            matched[agent] = true;
        }
        let mut in_sight = vec![false; step.agents.len()];
        for sighting in cooperator.observation.sighted() {
            if self.sensors.contains(&sighting.sensor) && sighting.visible_fraction > 0.0 {
                in_sight[sighting.target] = true;
            }
        }
        let matching = Matching {
            detections: placed,
            matches,
            matched,
            in_sight,
        };
        let mut selecting = std::mem::take(&mut self.selecting);
        for s in &mut selecting {
            self.count(s, step, &matching);
        }
        self.selecting = selecting;
    }

    /// Sums what `s`'s selection keeps of the step's `matching` into it.
    fn count(&self, s: &mut Selecting, step: &WorldStep<'_>, matching: &Matching) {
        let centre = |agent: usize| step.agents[agent].map(|state| state.position());
        for (agent, at) in (0..step.agents.len()).filter_map(|agent| Some((agent, centre(agent)?))) {
            let (in_sight, matched) = (matching.in_sight[agent], matching.matched[agent]);
            if !(in_sight || matched) || !self.keeps(&s.selection, agent, at) {
                continue;
            }
            if in_sight {
                s.tally.in_sight += 1;
                s.tally.in_sight_matched += u64::from(matched);
                s.first_in_sight[agent].get_or_insert(step.time);
            }
            if matched {
                s.first_matched[agent].get_or_insert(step.time);
            }
        }
        for (&detection, &matched) in matching.detections.iter().zip(&matching.matches) {
            if self.keeps_detection(&s.selection, detection, matched.map(|(agent, _)| agent)) {
                s.tally.detections += 1;
                s.tally.detections_matched += u64::from(matched.is_some());
            }
            let Some((agent, distance)) = matched else {
                continue;
            };
            if centre(agent).is_some_and(|at| self.keeps(&s.selection, agent, at)) {
                s.tally.matched += 1;
                s.tally.position_error_sum += distance;
                s.tally.class_correct += u64::from(detection.1 == Some(self.roster.agents[agent].1));
            }
        }
    }

    /// What the system achieved over the run.
    pub fn finish(self) -> SystemMetrics {
        let mut selecting = self.selecting.into_iter();
        let all = selecting.next().expect("the judge sums everything first");
        let objects = (self.around).records(&self.roster, (&all.first_in_sight, &all.first_matched));
        SystemMetrics {
            steps: self.steps,
            all: all.finish().tally,
            objects,
            selected: selecting.map(Selecting::finish).collect(),
        }
    }
}

/// The number of road users both first in sight and first matched, and the
/// sum of first matched − first in sight over them (at least 0 each).
fn latencies(first_in_sight: &[Option<f64>], first_matched: &[Option<f64>]) -> (u64, f64) {
    let mut n = 0;
    let mut sum = 0.0;
    for (sight, matched) in first_in_sight.iter().zip(first_matched) {
        if let (Some(sight), Some(matched)) = (sight, matched) {
            n += 1;
            sum += (matched - sight).max(0.0);
        }
    }
    (n, sum)
}

#[cfg(test)]
pub(crate) mod tests {
    use approx::assert_relative_eq;
    use sightline_dsl::{Area, Motion};

    use super::*;
    use crate::math::{Pose, Vector};
    use crate::trace::CooperatorStep;
    use crate::world::{AgentState, Observation, Sighting, Visibility};

    /// A fixed agent of `kind`, 4 × 2 m, without sensors.
    pub(crate) fn agent(id: &str, kind: AgentKind) -> Agent {
        Agent {
            id: id.into(),
            kind,
            length: 4.0,
            width: 2.0,
            motion: Motion::Fixed {
                position: [0.0, 0.0],
                heading: 0.0,
            },
            connected: false,
            sensors: Vec::new(),
            antenna_m: None,
        }
    }

    fn at(x: f64, y: f64, heading: f64) -> Option<AgentState> {
        Some(AgentState {
            pose: Pose::new(Vector::new(x, y), heading),
            speed: 0.0,
            offset: 0.0,
            limit: f64::INFINITY,
        })
    }

    fn sighting(sensor: usize, target: usize, visible_fraction: f64) -> Sighting {
        Sighting {
            sensor,
            target,
            visibility: Visibility::Los,
            visible_fraction,
            detected: None,
        }
    }

    /// Judges `detections` (host frame) against `sighted` at step `step`.
    fn judge_step(judge: &mut SystemJudge, step: usize, sighted: Vec<Sighting>, detections: &[(f64, f64, Class)]) {
        // The host `h` at (10, 0) facing north; road users `a` at (10, 10) (10 m
        // ahead) and `b` at (5, 0) (5 m to its left); a roadside unit at (20, 20).
        let agents = [
            at(10.0, 0.0, std::f64::consts::FRAC_PI_2),
            at(10.0, 10.0, 0.0),
            at(5.0, 0.0, 0.0),
            at(20.0, 20.0, 0.0),
        ];
        let observation = Observation::with_sighted(sighted);
        let cooperators = [CooperatorStep {
            agent: 0,
            estimate: agents[0].unwrap().pose,
            observation: &observation,
        }];
        let world = WorldStep {
            step,
            time: step as f64 * 0.1,
            agents: &agents,
            cooperators: &cooperators,
            measured: None,
        };
        let detections: Vec<Detection> = detections
            .iter()
            .map(|&(x, y, class)| Detection { x, y, class })
            .collect();
        judge.step(&world, &detections);
    }

    type Class = Option<AgentKind>;
    const CAR: Class = Some(AgentKind::Car);
    const PEDESTRIAN: Class = Some(AgentKind::Pedestrian);

    /// The two steps the tests below judge, with host `h`, car `a`,
    /// pedestrian `b` and a roadside unit; what `judge` made of them.
    fn two_steps(mut judge: SystemJudge) -> SystemMetrics {
        judge.start(&[
            agent("h", AgentKind::Car),
            agent("a", AgentKind::Car),
            agent("b", AgentKind::Pedestrian),
            agent("rsu", AgentKind::Rsu),
        ]);
        let step0 = vec![sighting(0, 1, 0.5), sighting(1, 2, 1.0), sighting(0, 2, 0.0)];
        let step0_detections = [(0.0, 5.0, PEDESTRIAN), (0.0, -30.0, CAR), (20.0, -10.0, None)];
        judge_step(&mut judge, 0, step0, &step0_detections);
        let step1_detections = [(10.0, 0.5, CAR), (10.0, 0.3, Some(AgentKind::Truck))];
        judge_step(&mut judge, 1, vec![sighting(0, 1, 1.0)], &step1_detections);
        judge.finish()
    }

    /// Two steps counted by hand: at step 0, `a` is in the served sensor's
    /// sight but undetected, `b` is detected exactly but in sight of an
    /// unserved sensor only (and hidden from the served one), and two
    /// detections are ghosts (one beside the roadside unit, no road user); at
    /// step 1, two detections 0.3 m and 0.5 m from `a`: the nearer matches,
    /// the other is a ghost. `b`'s detection reports a pedestrian (right),
    /// `a`'s a truck (wrong).
    #[test]
    fn matching_is_one_to_one_nearest_first_within_the_gate() {
        let metrics = two_steps(SystemJudge::with((0, 0, vec![0]), 2.0, Vec::new(), Vec::new()));
        let all = &metrics.all;
        assert_eq!((metrics.steps, all.in_sight, all.in_sight_matched), (2, 2, 1));
        assert_eq!((all.detections, all.detections_matched, all.matched), (5, 2, 2));
        assert_relative_eq!(metrics.value(Metric::SutRecall).unwrap(), 0.5);
        assert_relative_eq!(metrics.value(Metric::SutPrecision).unwrap(), 0.4);
        assert_relative_eq!(metrics.value(Metric::SutGhosts).unwrap(), 3.0);
        assert_relative_eq!(metrics.value(Metric::SutPositionError).unwrap(), 0.15, epsilon = 1e-12);
        assert_eq!(all.class_correct, 1);
        assert_eq!(metrics.value(Metric::SutClassAccuracy), Some(0.5));
        assert_eq!(metrics.sample_size(Metric::SutClassAccuracy), Some(2));
        // `a`: in sight at 0, matched at 0.1; `b` was never in the served sight.
        assert_eq!(metrics.sample_size(Metric::SutLatency), Some(1));
        assert_relative_eq!(metrics.value(Metric::SutLatency).unwrap(), 0.1, epsilon = 1e-12);
    }

    /// The steps of the test above, judged over selections, counted by hand.
    /// Road users: the cars are `a` (in sight at both steps, matched at step
    /// 1, 0.3 m off, reported a truck); the pedestrians `b` (never in the
    /// served sight, matched at step 0, 0 m off, reported a pedestrian); the
    /// circle `near_a` (radius 1 about `a`) keeps `a`'s two steps; the circle
    /// `away` keeps nothing; `ids: [b]` keeps `b`. Detections: two report a
    /// car, both ghosts; one a pedestrian, `b`'s; two lie in `near_a`, one
    /// matched; one matched `b`.
    #[test]
    fn selections_keep_object_steps_and_detections_by_id_class_and_area() {
        let select = |classes: Vec<AgentKind>, ids: Vec<&str>, areas: Vec<&str>| ObjectSelection {
            classes,
            ids: ids.into_iter().map(String::from).collect(),
            areas: areas.into_iter().map(String::from).collect(),
            ..ObjectSelection::default()
        };
        let circle = |x: f64, y: f64| {
            Region::new(Area::Circle {
                center: [x, y],
                radius: 1.0,
            })
        };
        let selections = vec![
            select(vec![AgentKind::Car], vec![], vec![]),
            select(vec![AgentKind::Pedestrian], vec![], vec![]),
            select(vec![], vec![], vec!["near_a"]),
            select(vec![], vec![], vec!["away"]),
            select(vec![], vec!["b"], vec![]),
        ];
        let regions = vec![
            ("near_a".into(), circle(10.0, 10.0)),
            ("away".into(), circle(50.0, 50.0)),
        ];
        let metrics = two_steps(SystemJudge::with((0, 0, vec![0]), 2.0, regions, selections.clone()));
        let sample = |i: usize, metric| metrics.selected_sample(metric, &selections[i]).unwrap();
        for cars in [0, 2] {
            assert_eq!(sample(cars, Metric::SutRecall), (Some(0.5), 2));
            let (latency, n) = sample(cars, Metric::SutLatency);
            assert_eq!(n, 1);
            assert_relative_eq!(latency.unwrap(), 0.1, epsilon = 1e-12);
        }
        for nothing in [1, 3, 4] {
            assert_eq!(sample(nothing, Metric::SutRecall), (None, 0));
            assert_eq!(sample(nothing, Metric::SutLatency), (None, 0));
        }
        // (precision, ghosts), each with n: judged by the detections' class and place.
        let by_detection = |i| (sample(i, Metric::SutPrecision), sample(i, Metric::SutGhosts));
        assert_eq!(by_detection(0), ((Some(0.0), 2), (Some(2.0), 2)));
        assert_eq!(by_detection(1), ((Some(1.0), 1), (Some(0.0), 1)));
        assert_eq!(by_detection(2), ((Some(0.5), 2), (Some(1.0), 2)));
        assert_eq!(by_detection(3), ((None, 0), (None, 0)));
        assert_eq!(by_detection(4), ((Some(1.0), 1), (Some(0.0), 1)));
        // (position error, class accuracy): judged by the matched road user.
        let by_road_user = |i| (sample(i, Metric::SutPositionError), sample(i, Metric::SutClassAccuracy));
        for a in [0, 2] {
            let ((error, n), class) = by_road_user(a);
            assert_relative_eq!(error.unwrap(), 0.3, epsilon = 1e-12);
            assert_eq!((n, class), (1, (Some(0.0), 1)));
        }
        for b in [1, 4] {
            let ((error, n), class) = by_road_user(b);
            assert_relative_eq!(error.unwrap(), 0.0, epsilon = 1e-12);
            assert_eq!((n, class), (1, (Some(1.0), 1)));
        }
        assert_eq!(by_road_user(3), ((None, 0), (None, 0)));
        assert_eq!(metrics.selected_sample(Metric::Accuracy, &selections[0]), None);
        assert_eq!(
            metrics.selected_sample(Metric::SutRecall, &ObjectSelection::default()),
            None
        );
    }

    #[test]
    fn nothing_judged_is_no_value() {
        let metrics = SystemMetrics::default();
        for metric in [
            Metric::SutRecall,
            Metric::SutPrecision,
            Metric::SutPositionError,
            Metric::SutClassAccuracy,
            Metric::SutLatency,
            Metric::SutGhosts,
        ] {
            assert_eq!((metrics.value(metric), metrics.sample_size(metric)), (None, Some(0)));
        }
        assert_eq!(metrics.value(Metric::Accuracy), None);
    }

    #[test]
    fn a_step_without_the_host_cooperating_judges_nothing() {
        let mut judge = SystemJudge::with((3, 3, vec![0]), 2.0, Vec::new(), Vec::new());
        judge.start(&[
            agent("h", AgentKind::Car),
            agent("a", AgentKind::Car),
            agent("b", AgentKind::Car),
        ]);
        judge_step(&mut judge, 0, vec![sighting(0, 1, 1.0)], &[(0.0, 0.0, CAR)]);
        assert_eq!(judge.finish(), SystemMetrics::default());
    }
}
