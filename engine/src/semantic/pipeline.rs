//! The four layers an RSU runs each cycle (seed 002, section III): proximity →
//! interaction relevance → obstruction → predictive risk.

use sightline_dsl::geometry::Polyline;
use sightline_dsl::{AgentKind, RiskScope, Semantic};

use super::ldm::{Ldm, Measurement, Track};
use super::message::{Item, Labels};
use super::relevance::Areas;
use super::risk::{Conflict, RouteMap, Trajectory, along, conflict, hypotheses, straight};
use crate::math::{Point, Pose, Vector};
use crate::world::{Bodies, Body, Occluders, Visibility, visibility};

/// Seconds of history a pedestrian's direction is estimated over.
const DIRECTION_SPAN: f64 = 1.0;

/// The ego's state and plan as last received by the RSU: it drives its route at
/// constant speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EgoPlan {
    /// When it was sent, seconds.
    pub time: f64,
    /// Distance along its route then, metres.
    pub offset: f64,
    /// Speed then, m/s.
    pub speed: f64,
}

/// What an RSU's pipeline knows besides its LDM.
pub struct Pipeline<'a> {
    /// The pipeline's settings.
    pub semantic: &'a Semantic,
    /// Interaction areas and crosswalks.
    pub areas: Areas,
    /// The static map's occluders.
    pub occluders: &'a Occluders,
    /// The paths vehicles may follow.
    pub map: &'a RouteMap,
    /// The ego's route.
    pub ego_route: &'a Polyline,
    /// Prediction sampling, seconds.
    pub dt: f64,
}

impl Pipeline<'_> {
    /// The objects to send at `now` with their labels, by agent index; the ego
    /// (agent `semantic.ego`) is never among them.
    pub fn run(&self, ldm: &Ldm, now: f64, plan: &EgoPlan) -> Vec<Item> {
        let s = self.semantic;
        let ego_offset = plan.offset + plan.speed * (now - plan.time);
        let ego_trajectory = along(self.ego_route, ego_offset, plan.speed, s.horizon, self.dt);
        let ego = ego_trajectory[0];
        let ego_path = |t: f64| sample(&ego_trajectory, t / self.dt);
        let current: Vec<(usize, &Track)> = ldm.current(now).filter(|&(agent, _)| agent != s.ego).collect();
        // The tree is built again at every cycle: only of what layer 3 may meet.
        let bodies = Bodies::new(
            current
                .iter()
                .filter(|(_, track)| may_block(ego, s.proximity, track.latest()))
                .map(|&(agent, track)| footprint(agent, track.latest()))
                .collect(),
        );
        let mut items = Vec::new();
        for &(agent, track) in &current {
            let m = track.latest();
            // Layer 1: proximity.
            if (m.position - ego).length() >= s.proximity {
                continue;
            }
            let pedestrian = track.kind == AgentKind::Pedestrian;
            let velocity = if pedestrian {
                track
                    .displacement_velocity(DIRECTION_SPAN)
                    .unwrap_or_else(|| heading_velocity(m.heading, m.speed))
            } else {
                heading_velocity(m.heading, m.speed)
            };
            let path = |t: f64| m.position + velocity * t;
            // Layer 2: interaction relevance.
            let relevant = if pedestrian {
                self.areas.pedestrian_relevant(s.horizon, m.position, &path)
            } else {
                self.areas
                    .vehicle_relevant(s.horizon, (ego, &ego_path), (m.position, &path))
            };
            // Layer 3: obstruction from the ego's viewpoint.
            let nlos = match visibility(self.occluders, &bodies, ego, s.ego, &footprint(agent, m)) {
                Visibility::Los => None,
                hidden => Some(hidden),
            };
            // Layer 4: predictive risk.
            let assessed = s.risk_for == RiskScope::All || relevant;
            let (speeding, conflict) = if pedestrian {
                let crossing = self.areas.crossing(m.position);
                let predicted = (assessed && crossing)
                    .then(|| straight(m.position, velocity, s.horizon, self.dt))
                    .and_then(|trajectory| conflict(&ego_trajectory, &trajectory, self.dt, s.d_min));
                (false, predicted)
            } else {
                let (speeds, dangerous) = hypotheses(track, &s.hypotheses, s.overspeed_window, s.overspeed_threshold);
                let predicted = if assessed {
                    self.predictions(m.position, m.heading, &speeds)
                        .iter()
                        .filter_map(|trajectory| conflict(&ego_trajectory, trajectory, self.dt, s.d_min))
                        .reduce(earliest)
                } else {
                    None
                };
                (dangerous, predicted)
            };
            items.push(Item {
                agent,
                labels: Labels {
                    nlos,
                    relevant,
                    speeding,
                    conflict,
                },
            });
        }
        items
    }

    /// Every speed hypothesis along every branch through `position`, or straight on
    /// along `heading` off the map.
    fn predictions(&self, position: Point, heading: f64, speeds: &[f64]) -> Vec<Trajectory> {
        let s = self.semantic;
        let branches = self.map.branches(position, heading);
        speeds
            .iter()
            .flat_map(|&speed| {
                if branches.is_empty() {
                    vec![straight(position, heading_velocity(heading, speed), s.horizon, self.dt)]
                } else {
                    branches
                        .iter()
                        .map(|&(route, offset)| along(route, offset, speed, s.horizon, self.dt))
                        .collect()
                }
            })
            .collect()
    }
}

fn heading_velocity(heading: f64, speed: f64) -> Point {
    Vector::new(heading.cos(), heading.sin()) * speed
}

/// The trajectory at fractional sample index `index`, linear between samples.
fn sample(trajectory: &[Point], index: f64) -> Point {
    let last = trajectory.len() - 1;
    let i = (index.floor().max(0.0) as usize).min(last);
    let next = (i + 1).min(last);
    let u = (index - i as f64).clamp(0.0, 1.0);
    trajectory[i] + (trajectory[next] - trajectory[i]) * u
}

/// The earlier of two conflicts, with the smaller separation of the two.
fn earliest(a: Conflict, b: Conflict) -> Conflict {
    Conflict {
        time: a.time.min(b.time),
        separation: a.separation.min(b.separation),
    }
}

/// The footprint of agent `agent` measured as `m`.
fn footprint(agent: usize, m: &Measurement) -> Body {
    Body::rectangle(
        agent,
        Pose::new(m.position, m.heading),
        Vector::new(m.length, m.width) / 2.0,
    )
}

/// Whether an object measured as `m` may cross a line of sight of layer 3:
/// one segment from `ego` to an object nearer than `proximity`. A footprint
/// whose centre is farther than `proximity` and its half diagonal (with a
/// metre to spare for rounding) reaches no such segment.
fn may_block(ego: Point, proximity: f64, m: &Measurement) -> bool {
    let reach = Vector::new(m.length, m.width).length() / 2.0;
    (m.position - ego).length() <= proximity + reach + 1.0
}

#[cfg(test)]
mod tests {
    use sightline_dsl::{Baseline, Caution, LabelledBy, RsuSight, ShareCycles};

    use proptest::prelude::*;

    use super::*;

    fn settings() -> Semantic {
        Semantic {
            ego: 0,
            rsus: vec![9],
            proximity: 50.0,
            horizon: 3.0,
            d_min: 2.0,
            overspeed_window: 5.0,
            overspeed_threshold: 2.0,
            hypotheses: vec![0.7, 1.0, 1.1],
            period_steps: 1,
            risk_for: RiskScope::All,
            rsu_sight: RsuSight::Range,
            history: 5.0,
            caution: Caution {
                headway: 2.5,
                speed_factor: 0.8,
                hold: 3.0,
            },
            baseline: Baseline {
                distance: 4.0,
                speed: 0.5,
                heading: 0.07,
                interval: 1.0,
            },
            shares_over: ShareCycles::EgoInRange,
            labelled_by: LabelledBy::Any,
            contribution_over: ShareCycles::EgoInRange,
            runs: 1,
        }
    }

    fn car(time: f64, x: f64, y: f64, heading: f64, speed: f64) -> Measurement {
        Measurement {
            time,
            position: Vector::new(x, y),
            speed,
            heading,
            length: 4.5,
            width: 1.8,
            limit: 13.9,
        }
    }

    /// The ego stands at the origin heading east. An object 49 m away is sent, one
    /// 51 m away is not; a car 30 m north driving south at 10 m/s conflicts with
    /// the standing ego and hides the car behind it (NLoS-dynamic); a car behind a
    /// building is NLoS-static.
    #[test]
    fn the_layers_filter_label_and_predict() {
        let semantic = settings();
        let building = [sightline_dsl::Occluder {
            id: "b".into(),
            polygon: vec![[-40.0, -10.0], [-30.0, -10.0], [-30.0, 10.0], [-40.0, 10.0]],
        }];
        let occluders = Occluders::new(&building);
        let map = RouteMap::new([]);
        let route = Polyline::new([[0.0, 0.0], [100.0, 0.0]]).unwrap();
        let pipeline = Pipeline {
            semantic: &semantic,
            areas: Areas {
                interaction: Vec::new(),
                crosswalks: Vec::new(),
            },
            occluders: &occluders,
            map: &map,
            ego_route: &route,
            dt: 0.1,
        };
        let mut ldm = Ldm::default();
        let south = -std::f64::consts::FRAC_PI_2;
        ldm.record(0, AgentKind::Car, car(0.0, 0.0, 0.0, 0.0, 0.0));
        ldm.record(1, AgentKind::Car, car(0.0, 0.0, 49.0, 0.0, 0.0));
        ldm.record(2, AgentKind::Car, car(0.0, 0.0, -51.0, 0.0, 0.0));
        ldm.record(3, AgentKind::Car, car(0.0, 0.0, 30.0, south, 10.0));
        ldm.record(4, AgentKind::Car, car(0.0, -45.0, 0.0, 0.0, 0.0));
        let plan = EgoPlan {
            time: 0.0,
            offset: 0.0,
            speed: 0.0,
        };
        let items = pipeline.run(&ldm, 0.0, &plan);
        let agents: Vec<usize> = items.iter().map(|i| i.agent).collect();
        assert_eq!(agents, vec![1, 3, 4]);
        let conflict = items[1].labels.conflict.expect("car 3 drives through the ego");
        // Earliest under the 1.1 v hypothesis: within 2 m of the ego's centre when
        // 30 − 11 t ≤ 2, at t = 28 / 11 s.
        assert!((conflict.time - 28.0 / 11.0).abs() < 1e-9, "{conflict:?}");
        assert_eq!(items[0].labels.conflict, None);
        assert_eq!(items[2].labels.nlos, Some(Visibility::NlosStatic));
        // Car 3, between the ego and car 1, hides car 1.
        assert_eq!(items[0].labels.nlos, Some(Visibility::NlosDynamic));
        assert_eq!(items[1].labels.nlos, None);
    }

    proptest! {
        /// Layer 3 gives the same answer with the footprints `may_block`
        /// keeps as with every footprint: objects of up to 20 m anywhere
        /// within 200 m, a target nearer than the proximity.
        #[test]
        fn the_footprints_left_out_block_nothing(
            objects in prop::collection::vec(
                (-200.0..200.0_f64, -200.0..200.0_f64, -3.2..3.2_f64, 0.5..20.0_f64, 0.5..4.0_f64),
                1..40,
            ),
            target in (0.0..49.9_f64, -3.2..3.2_f64),
        ) {
            let proximity = 50.0;
            let ego = Point::new(3.0, -7.0);
            let at = |(x, y, heading, length, width): (f64, f64, f64, f64, f64)| Measurement {
                position: Point::new(x, y),
                heading,
                length,
                width,
                ..car(0.0, 0.0, 0.0, 0.0, 0.0)
            };
            let measured: Vec<Measurement> = objects.into_iter().map(at).collect();
            let (distance, bearing) = target;
            let to = ego + Vector::new(bearing.cos(), bearing.sin()) * distance;
            let every = Bodies::new(measured.iter().enumerate().map(|(i, m)| footprint(i + 2, m)).collect());
            let kept = Bodies::new(
                (measured.iter().enumerate())
                    .filter(|(_, m)| may_block(ego, proximity, m))
                    .map(|(i, m)| footprint(i + 2, m))
                    .collect(),
            );
            prop_assert_eq!(kept.block_at_centre(ego, to, [0, 1]), every.block_at_centre(ego, to, [0, 1]));
        }
    }
}
