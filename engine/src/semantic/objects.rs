//! The per-object record of a semantic run (issue 17): for every road user
//! relevant to the ego, when it became relevant, when the ego first saw it,
//! first heard of it through V2X and was first warned of a conflict with it,
//! its closest approach, its least time to collision, and its [`Category`].
//!
//! The definitions, all on the truth and the ego's own clock (seconds from the
//! start of the run):
//! - **relevant**: a road user other than the ego and the RSUs whose centre comes
//!   closer to the ego's than `semantic.proximity` (the pipeline's first layer,
//!   on true positions) at a step with both in the scene, or that an RSU message
//!   the ego received names (its own status message, if it is connected, does
//!   not: relevance is what the RSU selects for the ego, seed 002's RSUs
//!   "selecting and transmitting only those actors that are relevant"). It
//!   becomes relevant at the first of the two.
//! - **first own sight**: the first step at which the ego sees it (its centre in
//!   range, field of view and line of sight of one of the ego's sensors).
//! - **first V2X knowledge**: the arrival of the first message the ego received
//!   that names it: an RSU's semantic message, or its own status message if it
//!   is connected.
//! - **first warning**: the arrival of the first RSU message the ego received
//!   that flags a conflict with it.
//! - **closest approach**: the step, among those with both in the scene, at which
//!   the centres are closest (the first such step on a tie: distances within
//!   1 µm are one), that distance, and
//!   where the road user was then (so that it can be placed in an area).
//! - **areas**: the crosswalks, interaction areas and declared `areas` its centre
//!   was inside at some step with the ego in the scene, in declaration order.
//! - **first in the grid** (a joint world): the first step at which a counted
//!   cell of its footprint (a cell the ground truth marks for it) is decided
//!   occupied in the ego's fused grid, for each fusion job's grid; a
//!   cooperating agent's own footprint, which it reports, counts as its own
//!   V2X message counts for first V2X knowledge.
//! - **criticality** ([`super::criticality`]), over the steps at which it is
//!   within `semantic.proximity` of the ego, on the oriented boxes of both:
//!   its least time to collision (TTC), its greatest deceleration rate to avoid
//!   a crash (DRAC), and its post-encroachment time (PET) over the conflict
//!   area their footprints at those steps share; none where it never had one.

use serde::{Deserialize, Serialize};
use sightline_dsl::{Agent, AgentKind, Semantic, World};

use super::criticality::{Criticality, OrientedBox, post_encroachment, velocity};
use super::ego::Knowledge;
use super::relevance::{Region, contains, regions};
use crate::math::{Point, elapsed};
use crate::world::AgentState;

/// How the ego came to know a road user: by V2X, by its own sight, in which
/// order, or not at all. Exactly one holds for each relevant road user.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Category {
    /// A V2X message named it strictly before the ego first saw it.
    WarnedBeforeSeen,
    /// A V2X message named it, and the ego never saw it.
    WarnedNeverSeen,
    /// The ego saw it no later than the first V2X message naming it, or no
    /// message named it.
    SeenFirst,
    /// Neither: no message named it and the ego never saw it.
    NeverKnown,
}

impl Category {
    /// Every category, in documentation order.
    pub const ALL: [Category; 4] = [
        Self::WarnedBeforeSeen,
        Self::WarnedNeverSeen,
        Self::SeenFirst,
        Self::NeverKnown,
    ];

    /// The name tools read (results.json, the recording).
    pub fn name(self) -> &'static str {
        match self {
            Self::WarnedBeforeSeen => "warned_before_seen",
            Self::WarnedNeverSeen => "warned_never_seen",
            Self::SeenFirst => "seen_first",
            Self::NeverKnown => "never_known",
        }
    }

    /// The category of a road user first named by V2X at `first_v2x` and first
    /// seen at `first_seen`; a tie goes to sight.
    pub fn of(first_v2x: Option<f64>, first_seen: Option<f64>) -> Self {
        match (first_v2x, first_seen) {
            (Some(told), Some(seen)) if told < seen => Self::WarnedBeforeSeen,
            (Some(_), None) => Self::WarnedNeverSeen,
            (_, Some(_)) => Self::SeenFirst,
            (None, None) => Self::NeverKnown,
        }
    }
}

/// Where and when a road user came closest to the ego.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Closest {
    /// The time, seconds.
    pub time: f64,
    /// The distance between the centres, metres.
    pub distance: f64,
    /// The road user's centre then, world frame [x, y], metres.
    pub position: [f64; 2],
}

impl Closest {
    /// How much nearer than the closest approach so far a later step must be
    /// to replace it (1 µm): distances within it are a tie, and the first step
    /// keeps it, not whichever the rounding of the positions favours.
    const TIE: f64 = 1e-6;

    /// `closest` so far, or the step at `time` with the road user at `at`,
    /// `distance` from the ego, where that is nearer by more than `Self::TIE`.
    pub fn nearer(closest: Option<Self>, time: f64, distance: f64, at: Point) -> Option<Self> {
        match closest {
            Some(c) if distance >= c.distance - Self::TIE => Some(c),
            _ => Some(Self {
                time,
                distance,
                position: [at.x, at.y],
            }),
        }
    }
}

/// A road user coming within d_min of the ego (seed 002's close approach).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CloseApproach {
    /// The pooled run it happened in (0: the run with the point's own seed).
    pub run: u32,
    /// The road user's agent id.
    pub id: String,
    /// The step it came within d_min of the ego, seconds.
    pub at: f64,
    /// When the first message flagging a conflict with it reached the ego,
    /// seconds (`None`: none did before `at`).
    pub flagged: Option<f64>,
}

impl CloseApproach {
    /// Seconds from the first flag to the approach (`warning_time`); `None`
    /// when it was never flagged.
    pub fn warning_time(&self) -> Option<f64> {
        Some(elapsed(self.at, self.flagged?))
    }
}

/// One relevant road user over one run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObjectRecord {
    /// The pooled run it belongs to (0: the run with the point's own seed).
    pub run: u32,
    /// Its agent id (generated road users: `routeI-N` on the I-th traffic
    /// route, `CROSSWALK-N` at a crosswalk).
    pub id: String,
    /// Its kind.
    pub class: AgentKind,
    /// Its length, metres.
    pub length: f64,
    /// Its width, metres.
    pub width: f64,
    /// When it became relevant, seconds.
    pub first_relevant: f64,
    /// When the ego first saw it.
    pub first_seen: Option<f64>,
    /// When the first message naming it reached the ego.
    pub first_v2x: Option<f64>,
    /// When the first message flagging a conflict with it reached the ego.
    pub first_warning: Option<f64>,
    /// In a joint world, when a cell of its footprint was first decided
    /// occupied in the ego's fused grid; always `None` in a semantic world.
    pub first_in_grid: Option<f64>,
    /// Its closest approach to the ego (`None` only for a road user never in
    /// the scene together with the ego).
    pub closest: Option<Closest>,
    /// Its least time to collision with the ego while within
    /// `semantic.proximity` of it, seconds (oriented boxes at constant
    /// velocity; 0: they overlapped or touched).
    pub min_ttc: Option<f64>,
    /// Its greatest deceleration rate to avoid a crash while within
    /// `semantic.proximity` of the ego: what the ego needed, m/s².
    pub max_drac: Option<f64>,
    /// Its post-encroachment time with the ego over the steps it was within
    /// `semantic.proximity` of it, seconds (0: their footprints overlapped).
    pub pet: Option<f64>,
    /// How the ego came to know it.
    pub category: Category,
    /// When the first message naming it would have reached the ego had the
    /// RSUs sent the ETSI baseline's messages instead (or its own message, if
    /// it is connected).
    pub baseline_v2x: Option<f64>,
    /// The ids of the regions it was in with the ego in the scene.
    pub areas: Vec<String>,
}

impl ObjectRecord {
    /// Seconds the ego knew of it through V2X before it could know it on its
    /// own, by category:
    /// - `warned_before_seen`: first own sight − first V2X knowledge (> 0);
    /// - `warned_never_seen`: closest approach − first V2X knowledge, or 0 when
    ///   the first message came after the closest approach;
    /// - `seen_first`, `never_known`: none (V2X gave nothing ahead of sight, or
    ///   nothing at all).
    pub fn anticipation(&self) -> Option<f64> {
        self.anticipation_if_told_at(self.first_v2x)
    }

    /// [`Self::anticipation`] over the ETSI baseline's messages.
    pub fn baseline_anticipation(&self) -> Option<f64> {
        self.anticipation_if_told_at(self.baseline_v2x)
    }

    /// Our anticipation had V2X first named it at `told`.
    fn anticipation_if_told_at(&self, told: Option<f64>) -> Option<f64> {
        let told = told?;
        match Category::of(Some(told), self.first_seen) {
            Category::WarnedBeforeSeen => self.first_seen.map(|seen| elapsed(seen, told)),
            Category::WarnedNeverSeen => self.closest.map(|c| elapsed(c.time, told).max(0.0)),
            Category::SeenFirst | Category::NeverKnown => None,
        }
    }
}

/// What the steps showed of one road user relative to the ego.
#[derive(Debug, Clone, Default)]
struct Encounter {
    /// The first step it was within the proximity of the ego.
    proximate: Option<f64>,
    closest: Option<Closest>,
    /// Its state at each step it was within the proximity of the ego, with
    /// the index of the ego's state then (in [`Encounters::ego_states`]).
    near: Vec<(u32, AgentState)>,
}

/// The encounters of every road user with the ego over a run.
pub(super) struct Encounters {
    ego: usize,
    proximity: f64,
    /// By agent index.
    by_agent: Vec<Encounter>,
    /// The ego's time and state at each step with it in the scene.
    ego_states: Vec<(f64, AgentState)>,
    /// The regions a record names, with their ids.
    regions: Vec<(String, Region)>,
    /// By agent index, then region: whether it was inside.
    inside: Vec<bool>,
}

impl Encounters {
    /// Nothing seen yet of the `agents` agents of a scene of `world` run with
    /// `semantic`.
    pub(super) fn new(world: &World, semantic: &Semantic, agents: usize) -> Self {
        let regions = regions(world);
        Self {
            ego: semantic.ego,
            proximity: semantic.proximity,
            by_agent: vec![Encounter::default(); agents],
            ego_states: Vec::new(),
            inside: vec![false; agents * regions.len()],
            regions,
        }
    }

    /// The step at `time` with the ego at `ego` and every agent's state in `states`.
    pub(super) fn step(&mut self, time: f64, ego: AgentState, states: &[Option<AgentState>]) {
        let ego_step = self.ego_states.len() as u32;
        self.ego_states.push((time, ego));
        for (agent, state) in states.iter().enumerate() {
            let Some(state) = state.filter(|_| agent != self.ego) else {
                continue;
            };
            let regions = self.regions.len();
            for (inside, (_, area)) in self.inside[agent * regions..][..regions].iter_mut().zip(&self.regions) {
                *inside = *inside || contains(area, state.position());
            }
            let encounter = &mut self.by_agent[agent];
            let distance = (state.position() - ego.position()).length();
            encounter.closest = Closest::nearer(encounter.closest, time, distance, state.position());
            // Farther, criticality says nothing the nearer steps do not;
            // leaving those steps out keeps the record cheap in dense traffic.
            if distance >= self.proximity {
                continue;
            }
            encounter.proximate.get_or_insert(time);
            encounter.near.push((ego_step, state));
        }
    }

    /// The record of every relevant road user among `agents`, with what the
    /// ego knew of each (`knowledge`, by agent index) and, in a joint world,
    /// when each first came into the ego's fused grid (`in_grid`, by agent
    /// index), in order of becoming relevant (then of agent index), labelled
    /// with pooled run `run`.
    pub(super) fn records(
        &self,
        run: u32,
        agents: &[Agent],
        knowledge: &[Knowledge],
        in_grid: Option<&[Option<f64>]>,
    ) -> Vec<ObjectRecord> {
        let mut records: Vec<(usize, ObjectRecord)> = self
            .by_agent
            .iter()
            .zip(knowledge)
            .enumerate()
            .filter(|&(agent, _)| agent != self.ego && agents[agent].kind != AgentKind::Rsu)
            .filter_map(|(agent, (encounter, known))| {
                let named = known.first_received.map(|(at, _)| at);
                let first_relevant = match (encounter.proximate, named) {
                    (Some(near), Some(named)) => near.min(named),
                    (near, named) => near.or(named)?,
                };
                let first_v2x = least(named, known.first_direct);
                let baseline_v2x = least(known.baseline_received.map(|(at, _)| at), known.first_direct);
                let spec = &agents[agent];
                let critical = self.criticality(encounter, (&agents[self.ego], spec));
                let record = ObjectRecord {
                    run,
                    id: spec.id.clone(),
                    class: spec.kind,
                    length: spec.length,
                    width: spec.width,
                    first_relevant,
                    first_seen: known.first_seen,
                    first_v2x,
                    first_warning: known.flagged,
                    first_in_grid: in_grid.and_then(|grid| grid[agent]),
                    closest: encounter.closest,
                    min_ttc: critical.min_ttc,
                    max_drac: critical.max_drac,
                    pet: critical.pet,
                    category: Category::of(first_v2x, known.first_seen),
                    baseline_v2x,
                    areas: self.areas_of(agent),
                };
                Some((agent, record))
            })
            .collect();
        records.sort_by(|(a, x), (b, y)| x.first_relevant.total_cmp(&y.first_relevant).then(a.cmp(b)));
        records.into_iter().map(|(_, record)| record).collect()
    }

    /// The ids of the regions agent `agent` was inside.
    fn areas_of(&self, agent: usize) -> Vec<String> {
        let regions = self.regions.len();
        self.regions
            .iter()
            .zip(&self.inside[agent * regions..][..regions])
            .filter(|&(_, &inside)| inside)
            .map(|((id, _), _)| id.clone())
            .collect()
    }

    /// The criticality of a road user (`spec`) in its `encounter` with the
    /// ego (`ego`), over the steps it was within the proximity.
    fn criticality(&self, encounter: &Encounter, (ego, spec): (&Agent, &Agent)) -> Critical {
        let mut critical = Critical::default();
        let mut ego_boxes = Vec::with_capacity(encounter.near.len());
        let mut boxes = Vec::with_capacity(encounter.near.len());
        for &(ego_step, ref state) in &encounter.near {
            let (time, ref ego_state) = self.ego_states[ego_step as usize];
            let ego_box = OrientedBox::of(ego_state, ego.length, ego.width);
            let other = OrientedBox::of(state, spec.length, spec.width);
            let step = Criticality::of((&ego_box, velocity(ego_state)), (&other, velocity(state)));
            critical.min_ttc = least(critical.min_ttc, step.ttc);
            critical.max_drac = pick(critical.max_drac, step.drac, f64::max);
            ego_boxes.push((time, ego_box));
            boxes.push((time, other));
        }
        critical.pet = post_encroachment(&ego_boxes, &boxes);
        critical
    }
}

/// A road user's criticality against the ego over a run.
#[derive(Debug, Clone, Copy, Default)]
struct Critical {
    min_ttc: Option<f64>,
    max_drac: Option<f64>,
    pet: Option<f64>,
}

/// The lesser (the earlier) of two values, either absent.
fn least(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    pick(a, b, f64::min)
}

/// `choose` of two values, or the one present.
fn pick(a: Option<f64>, b: Option<f64>, choose: fn(f64, f64) -> f64) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) => Some(choose(a, b)),
        (a, b) => a.or(b),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A road user keeping its distance (25.243811122728676 m, then a hair
    /// less by rounding at 7 s) has its closest approach at its first step; one
    /// that comes 1 mm nearer replaces it.
    #[test]
    fn the_first_step_keeps_a_tied_closest_approach() {
        let at = Point::new(25.0, 3.5);
        let steps = [
            (0.0, 25.243811122728676),
            (3.0, 25.24381112272868),
            (7.0, 25.243811122728662),
        ];
        let closest = steps
            .iter()
            .fold(None, |c, &(t, d)| Closest::nearer(c, t, d, at))
            .unwrap();
        assert_eq!((closest.time, closest.distance), (0.0, 25.243811122728676));
        let nearer = Closest::nearer(Some(closest), 9.0, 25.242, at).unwrap();
        assert_eq!((nearer.time, nearer.distance), (9.0, 25.242));
    }

    #[test]
    fn each_road_user_falls_in_exactly_one_category() {
        use Category::*;
        for (told, seen, category) in [
            (Some(1.0), Some(2.0), WarnedBeforeSeen),
            (Some(1.0), None, WarnedNeverSeen),
            (Some(2.0), Some(2.0), SeenFirst),
            (Some(3.0), Some(2.0), SeenFirst),
            (None, Some(2.0), SeenFirst),
            (None, None, NeverKnown),
        ] {
            assert_eq!(Category::of(told, seen), category, "{told:?} {seen:?}");
        }
    }

    fn record(category: Category, first_v2x: Option<f64>, first_seen: Option<f64>, closest: f64) -> ObjectRecord {
        ObjectRecord {
            run: 0,
            id: "x".into(),
            class: AgentKind::Car,
            length: 4.5,
            width: 1.8,
            first_relevant: 0.0,
            first_seen,
            first_v2x,
            first_warning: None,
            first_in_grid: None,
            closest: Some(Closest {
                time: closest,
                distance: 1.0,
                position: [0.0, 0.0],
            }),
            min_ttc: None,
            max_drac: None,
            pet: None,
            category,
            baseline_v2x: None,
            areas: Vec::new(),
        }
    }

    #[test]
    fn anticipation_by_category() {
        use Category::*;
        assert_eq!(
            record(WarnedBeforeSeen, Some(1.5), Some(4.0), 6.0).anticipation(),
            Some(2.5)
        );
        assert_eq!(record(WarnedNeverSeen, Some(1.5), None, 6.0).anticipation(), Some(4.5));
        // Told only after its closest approach: nothing gained.
        assert_eq!(record(WarnedNeverSeen, Some(7.0), None, 6.0).anticipation(), Some(0.0));
        assert_eq!(record(SeenFirst, Some(4.0), Some(1.0), 6.0).anticipation(), None);
        assert_eq!(record(NeverKnown, None, None, 6.0).anticipation(), None);
    }
}
