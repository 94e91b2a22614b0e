//! Line of sight with parry: occluders (built once) and agent footprints (every
//! step), each behind a BVH broad phase, and the visibility class of a target.
//!
//! A target is visible from a sensor when the segment from the sensor to the
//! target's centre crosses no occluder and no other agent's footprint. It is
//! NLoS-static when an occluder is crossed (whatever agents also are), NLoS-dynamic
//! when only agents are.

use parry2d_f64::bounding_volume::Aabb;
use parry2d_f64::partitioning::{Bvh, BvhBuildStrategy};
use parry2d_f64::query::{Ray, RayCast};
use parry2d_f64::shape::{Cuboid, Polyline};
use serde::Serialize;
use sightline_dsl::{Agent, AgentKind, Occluder};

use super::state::AgentState;
use crate::idealisation::Idealisation;
use crate::math::{Point, Pose, Vector};

/// The world is flat.
pub(crate) const PLANAR: Idealisation = Idealisation {
    id: "sight.planar",
    text: "The world is flat (2-D): a building or a road user blocks sight whatever its height and the \
           sensor's, and the ground is level.",
};

/// Visibility is decided by one ray per object.
pub(crate) const ONE_RAY: Idealisation = Idealisation {
    id: "sight.one-ray",
    text: "An object is visible when the segment from the sensor to the object's centre crosses no building \
           and no other road user: visibility is all or nothing, so a partly hidden object is either seen \
           whole or missed.",
};

/// Roadside units are not bodies.
pub(crate) const RSU_TRANSPARENT: Idealisation = Idealisation {
    id: "sight.rsu-transparent",
    text: "Roadside units are not part of the ground truth and hide nothing.",
};

/// Whether a target can be seen, and what hides it if not.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Visibility {
    /// Line of sight is clear.
    Los,
    /// A static occluder (building, wall) blocks it.
    NlosStatic,
    /// Only other agents block it.
    NlosDynamic,
}

/// The static occluders as closed outlines behind a BVH.
pub struct Occluders {
    outlines: Vec<Polyline>,
    bvh: Bvh,
}

impl Occluders {
    /// The occluders of a world (polygons counter-clockwise, corners not repeated).
    pub fn new(occluders: &[Occluder]) -> Self {
        let outlines: Vec<Polyline> = occluders
            .iter()
            .map(|o| {
                let vertices = o.polygon.iter().map(|&[x, y]| Vector::new(x, y)).collect();
                let n = o.polygon.len() as u32;
                let edges = (0..n).map(|i| [i, (i + 1) % n]).collect();
                Polyline::new(vertices, Some(edges))
            })
            .collect();
        let aabbs: Vec<Aabb> = outlines.iter().map(|o| o.aabb(&Pose::IDENTITY)).collect();
        Self {
            bvh: Bvh::from_leaves(BvhBuildStrategy::default(), &aabbs),
            outlines,
        }
    }

    /// Whether the segment from `from` to `to` crosses an occluder's outline.
    pub fn block(&self, from: Point, to: Point) -> bool {
        let Some((ray, length)) = segment_ray(from, to) else {
            return false;
        };
        self.bvh
            .cast_ray(&ray, length, |leaf, best| {
                self.outlines[leaf as usize].cast_ray(&Pose::IDENTITY, &ray, best, true)
            })
            .is_some()
    }
}

/// An agent's footprint at one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    /// Index of the agent.
    pub agent: usize,
    /// Centre and heading.
    pub pose: Pose,
    /// Half length and half width.
    pub half_extents: Vector,
}

impl Body {
    /// The footprint of agent `index` (described by `agent`) at `pose`.
    pub fn of(index: usize, agent: &Agent, pose: Pose) -> Self {
        Self {
            agent: index,
            pose,
            half_extents: Vector::new(agent.length, agent.width) / 2.0,
        }
    }

    /// The four corners, counter-clockwise.
    pub fn corners(&self) -> [Point; 4] {
        let Vector { x: l, y: w } = self.half_extents;
        [
            Vector::new(l, w),
            Vector::new(-l, w),
            Vector::new(-l, -w),
            Vector::new(l, -w),
        ]
        .map(|c| self.pose * c)
    }
}

/// The footprints of one step behind a BVH.
pub struct Bodies {
    bodies: Vec<Body>,
    bvh: Bvh,
}

impl Bodies {
    /// The footprints of a step.
    pub fn new(bodies: Vec<Body>) -> Self {
        let aabbs: Vec<Aabb> = bodies
            .iter()
            .map(|b| Cuboid::new(b.half_extents).aabb(&b.pose))
            .collect();
        Self {
            bvh: Bvh::from_leaves(BvhBuildStrategy::default(), &aabbs),
            bodies,
        }
    }

    /// The footprints of every agent in the scene at a step except roadside
    /// units, in agent order: `states[i]` is agent `i`'s state, `None` when absent.
    pub fn of_scene(agents: &[Agent], states: &[Option<AgentState>]) -> Self {
        Self::new(
            agents
                .iter()
                .zip(states)
                .enumerate()
                .filter(|(_, (agent, _))| agent.kind != AgentKind::Rsu)
                .filter_map(|(i, (agent, state))| state.map(|s| Body::of(i, agent, s.pose)))
                .collect(),
        )
    }

    /// The footprints, in the order given.
    pub fn all(&self) -> &[Body] {
        &self.bodies
    }

    /// Whether the segment from `from` to `to` crosses a footprint other than
    /// those of agents `skip`.
    pub fn block(&self, from: Point, to: Point, skip: [usize; 2]) -> bool {
        let Some((ray, length)) = segment_ray(from, to) else {
            return false;
        };
        self.bvh
            .cast_ray(&ray, length, |leaf, best| {
                let body = &self.bodies[leaf as usize];
                if skip.contains(&body.agent) {
                    return None;
                }
                Cuboid::new(body.half_extents).cast_ray(&body.pose, &ray, best, true)
            })
            .is_some()
    }
}

/// A unit ray from `from` toward `to` and the distance, or `None` when they coincide.
fn segment_ray(from: Point, to: Point) -> Option<(Ray, f64)> {
    let d = to - from;
    let length = d.length();
    (length > 1e-9).then(|| (Ray::new(from, d / length), length))
}

/// The visibility of `target` from a sensor at `from` on agent `observer`.
pub fn visibility(occluders: &Occluders, bodies: &Bodies, from: Point, observer: usize, target: &Body) -> Visibility {
    let to = target.pose.translation;
    if occluders.block(from, to) {
        Visibility::NlosStatic
    } else if bodies.block(from, to, [observer, target.agent]) {
        Visibility::NlosDynamic
    } else {
        Visibility::Los
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn building() -> Occluders {
        Occluders::new(&[Occluder {
            id: "b".into(),
            polygon: vec![[10.0, -5.0], [20.0, -5.0], [20.0, 5.0], [10.0, 5.0]],
        }])
    }

    fn car(agent: usize, x: f64, y: f64) -> Body {
        Body {
            agent,
            pose: Pose::new(Vector::new(x, y), 0.0),
            half_extents: Vector::new(2.25, 0.9),
        }
    }

    fn truck(agent: usize, x: f64, y: f64) -> Body {
        Body {
            agent,
            pose: Pose::new(Vector::new(x, y), std::f64::consts::FRAC_PI_2),
            half_extents: Vector::new(5.0, 1.25),
        }
    }

    /// The visibility of a car at `target` from a sensor at the origin on a car
    /// (agent 0), among `occluders` and the bodies `between` (agents 1, 2, …);
    /// the target is the agent after them.
    fn seen(occluders: &Occluders, between: &[Body], target: [f64; 2]) -> Visibility {
        let target = car(between.len() + 1, target[0], target[1]);
        let bodies = std::iter::once(car(0, 0.0, 0.0))
            .chain(between.iter().copied())
            .chain([target])
            .collect();
        visibility(occluders, &Bodies::new(bodies), Vector::ZERO, 0, &target)
    }

    /// The building runs from x = 10 to 20, |y| ≤ 5.
    #[test]
    fn a_box_behind_a_building_is_nlos_static() {
        assert_eq!(seen(&building(), &[], [30.0, 0.0]), Visibility::NlosStatic);
    }

    /// The line to (30, 20) passes the building's near corner at y = 6.7 > 5.
    #[test]
    fn a_box_beside_the_building_is_visible() {
        assert_eq!(seen(&building(), &[], [30.0, 20.0]), Visibility::Los);
    }

    /// A truck across the line of sight at x = 8, in front of the building: the
    /// building still hides the target, so the class is static.
    #[test]
    fn the_building_wins_over_a_truck_in_front_of_it() {
        assert_eq!(
            seen(&building(), &[truck(1, 8.0, 0.0)], [30.0, 0.0]),
            Visibility::NlosStatic
        );
    }

    #[test]
    fn a_box_behind_a_truck_is_nlos_dynamic() {
        assert_eq!(
            seen(&building(), &[truck(1, 15.0, 10.0)], [30.0, 20.0]),
            Visibility::NlosDynamic
        );
    }

    /// Two cars 4 m apart: their own boxes lie on the line between them.
    #[test]
    fn the_observer_and_the_target_do_not_hide_each_other() {
        assert_eq!(seen(&Occluders::new(&[]), &[], [4.0, 0.0]), Visibility::Los);
    }
}
