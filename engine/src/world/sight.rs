//! Line of sight with parry: occluders (built once) and agent footprints (every
//! step), each behind a BVH broad phase, and the one-ray visibility class of a
//! target.
//!
//! A footprint's outline is an oriented rectangle (vehicles, roadside units) or,
//! for a pedestrian, a circle ([`Outline`]). The perception world decides what a
//! sensor sees of an object with a fan of rays over its outline
//! ([`super::fan`]); the semantic world keeps the one-ray rule of
//! [`visibility`]: a target is visible from a sensor when the segment from the
//! sensor to the target's centre crosses no occluder and no other agent's
//! footprint. It is NLoS-static when an occluder is crossed (whatever agents
//! also are), NLoS-dynamic when only agents are.

use parry2d_f64::bounding_volume::Aabb;
use parry2d_f64::partitioning::{Bvh, BvhBuildStrategy, BvhWorkspace};
use parry2d_f64::query::{Ray, RayCast};
use parry2d_f64::shape::{Ball, Cuboid, Polyline};
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

/// Visibility is decided by one ray per object (the semantic world).
pub(crate) const ONE_RAY: Idealisation = Idealisation {
    id: "sight.one-ray",
    text: "An object is visible when the segment from the sensor to the object's centre crosses no building \
           and no other road user (a road user whose footprint contains the object's centre, standing in the \
           same spot, does not hide it): visibility is all or nothing, so a partly hidden object is either \
           seen whole or missed.",
};

/// Footprints are rectangles and circles.
pub(crate) const OUTLINES: Idealisation = Idealisation {
    id: "sight.outlines",
    text: "A vehicle's footprint is a rectangle of its length and width, a pedestrian's a circle of diameter its \
           larger size: mirrors, wheels, limbs and rounded corners are not modelled.",
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
    /// Line of sight is clear (to some part of it, for a fan; to its centre,
    /// for the one-ray rule).
    Los,
    /// Wholly hidden, and a static occluder (building, wall) blocks it (some
    /// of its rays, for a fan).
    NlosStatic,
    /// Wholly hidden by other agents only.
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

/// The shape of a footprint.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outline {
    /// An oriented rectangle of the body's half extents (vehicles, roadside units).
    Rectangle,
    /// A circle about the body's centre, of radius its half extent along x
    /// (pedestrians; both half extents are the radius).
    Circle,
}

/// An agent's footprint at one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    /// Index of the agent.
    pub agent: usize,
    /// Centre and heading.
    pub pose: Pose,
    /// Half length and half width (a circle's radius, twice).
    pub half_extents: Vector,
    /// Its shape.
    pub outline: Outline,
}

impl Body {
    /// The box around the footprint (the box of a circle's square holds the circle).
    fn aabb(&self) -> Aabb {
        Cuboid::new(self.half_extents).aabb(&self.pose)
    }

    /// The footprint of agent `index` (described by `agent`) at `pose`: a
    /// pedestrian's a circle of diameter its larger size, any other's a rectangle.
    pub fn of(index: usize, agent: &Agent, pose: Pose) -> Self {
        if agent.kind == AgentKind::Pedestrian {
            Self::circle(index, pose, agent.length.max(agent.width) / 2.0)
        } else {
            Self::rectangle(index, pose, Vector::new(agent.length, agent.width) / 2.0)
        }
    }

    /// A rectangle of agent `agent` at `pose`, with its half length and half width.
    pub fn rectangle(agent: usize, pose: Pose, half_extents: Vector) -> Self {
        Self {
            agent,
            pose,
            half_extents,
            outline: Outline::Rectangle,
        }
    }

    /// A circle of agent `agent` about `pose`, of radius `radius`.
    pub fn circle(agent: usize, pose: Pose, radius: f64) -> Self {
        Self {
            agent,
            pose,
            half_extents: Vector::splat(radius),
            outline: Outline::Circle,
        }
    }

    /// Whether `point` (world frame) lies in the outline, half-open in its own
    /// frame: a rectangle holds −h ≤ x < h (and y alike), a circle the points
    /// nearer its centre than its radius, each edge moved by `ON_EDGE` (1 nm) toward
    /// −∞. A point on an edge is then in or out by the edge, not by the
    /// rounding of a position accumulated step by step, and a footprint holds
    /// as many cell centres wherever it lies on the grid's lattice.
    pub fn contains(&self, point: Point) -> bool {
        let local = self.pose.inverse() * point;
        let within = |v: f64, h: f64| (-h - ON_EDGE..h - ON_EDGE).contains(&v);
        match self.outline {
            Outline::Rectangle => within(local.x, self.half_extents.x) && within(local.y, self.half_extents.y),
            Outline::Circle => local.length() < self.half_extents.x - ON_EDGE,
        }
    }

    /// The distance along `ray` (world frame) at which it enters the outline, up
    /// to `max_distance`; 0 when it starts inside.
    pub fn cast_ray(&self, ray: &Ray, max_distance: f64) -> Option<f64> {
        match self.outline {
            Outline::Rectangle => Cuboid::new(self.half_extents).cast_ray(&self.pose, ray, max_distance, true),
            Outline::Circle => Ball::new(self.half_extents.x).cast_ray(&self.pose, ray, max_distance, true),
        }
    }

    /// The corners of the rectangle (of the square around a circle),
    /// counter-clockwise.
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
    /// Per leaf of the BVH: its body's position in `bodies` (`NO_BODY`: none).
    leaf_body: Vec<u32>,
    workspace: BvhWorkspace,
}

/// A leaf of [`Bodies`]'s BVH that holds no body.
const NO_BODY: u32 = u32::MAX;

impl Bodies {
    /// The footprints `bodies`, leaf `i` of the BVH for the `i`-th.
    pub fn new(bodies: Vec<Body>) -> Self {
        let aabbs: Vec<Aabb> = bodies.iter().map(Body::aabb).collect();
        Self {
            bvh: Bvh::from_leaves(BvhBuildStrategy::default(), &aabbs),
            leaf_body: (0..bodies.len() as u32).collect(),
            bodies,
            workspace: BvhWorkspace::default(),
        }
    }

    /// No footprints: a scene before its first step, to [`update`](Self::update).
    pub fn empty() -> Self {
        Self::new(Vec::new())
    }

    /// The footprints of every agent in the scene at a step except roadside
    /// units, in agent order (`states[i]` is agent `i`'s state, `None` when
    /// absent), in place of the last step's. The BVH is kept from step to
    /// step, one leaf per agent (its index): the leaves of the agents that left
    /// are removed, the others moved or inserted, and the tree refitted.
    /// Rebuilding it every step was a sixth of the urban junction's time (issue
    /// 20); what a ray hits does not depend on the tree's shape. Only for
    /// footprints made by [`empty`](Self::empty) and `update`.
    pub fn update(&mut self, agents: &[Agent], states: &[Option<AgentState>]) {
        debug_assert!(
            self.bodies.iter().all(|b| self.leaf_body.get(b.agent).is_some()),
            "leaves keyed by agent"
        );
        self.bodies.clear();
        self.bodies.extend(
            agents
                .iter()
                .zip(states)
                .enumerate()
                .filter(|(_, (agent, _))| agent.kind != AgentKind::Rsu)
                .filter_map(|(i, (agent, state))| state.map(|s| Body::of(i, agent, s.pose))),
        );
        self.leaf_body.resize(agents.len().max(self.leaf_body.len()), NO_BODY);
        for (agent, slot) in self.leaf_body.iter_mut().enumerate() {
            if *slot != NO_BODY && states.get(agent).is_none_or(Option::is_none) {
                self.bvh.remove(agent as u32);
                *slot = NO_BODY;
            }
        }
        for (position, body) in self.bodies.iter().enumerate() {
            self.bvh.insert_or_update_partially(body.aabb(), body.agent as u32, 0.0);
            self.leaf_body[body.agent] = position as u32;
        }
        self.bvh.refit(&mut self.workspace);
    }

    /// The footprints, in the order given.
    pub fn all(&self) -> &[Body] {
        &self.bodies
    }

    /// Whether the segment from `from` to `to` crosses a footprint other than
    /// those of agents `skip`. A footprint the segment meets only at `to` (within
    /// [`TOUCHING`]) touches the target there and does not hide it.
    pub fn block(&self, from: Point, to: Point, skip: [usize; 2]) -> bool {
        self.block_unless(from, to, |body| skip.contains(&body.agent))
    }

    /// [`Self::block`], passing over also the footprints that contain `to`: a road
    /// user standing in the same spot as the target's centre does not hide it.
    pub fn block_at_centre(&self, from: Point, to: Point, skip: [usize; 2]) -> bool {
        self.block_unless(from, to, |body| skip.contains(&body.agent) || body.contains(to))
    }

    fn block_unless(&self, from: Point, to: Point, passed_over: impl Fn(&Body) -> bool) -> bool {
        let Some((ray, length)) = segment_ray(from, to) else {
            return false;
        };
        self.bvh
            .cast_ray(&ray, length - TOUCHING, |leaf, best| {
                let body = &self.bodies[self.leaf_body[leaf as usize] as usize];
                if passed_over(body) {
                    return None;
                }
                body.cast_ray(&ray, best)
            })
            .is_some()
    }
}

/// How far a point may be off an outline's edge and count as on it (1 nm): a
/// position accumulated step by step is off by about 1e-15 m.
const ON_EDGE: f64 = 1e-9;

/// How close to a ray's end a footprint may begin and only touch what the ray
/// reaches (1 µm: rounding, not cover).
const TOUCHING: f64 = 1e-6;

/// A unit ray from `from` toward `to` and the distance, or `None` when they coincide.
pub(super) fn segment_ray(from: Point, to: Point) -> Option<(Ray, f64)> {
    let d = to - from;
    let length = d.length();
    (length > 1e-9).then(|| (Ray::new(from, d / length), length))
}

/// The visibility of `target` from a sensor at `from` on agent `observer` by
/// the one-ray rule (the semantic world's; the perception world casts a fan,
/// [`super::fan::view`]).
pub fn visibility(occluders: &Occluders, bodies: &Bodies, from: Point, observer: usize, target: &Body) -> Visibility {
    let to = target.pose.translation;
    if occluders.block(from, to) {
        Visibility::NlosStatic
    } else if bodies.block_at_centre(from, to, [observer, target.agent]) {
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
        Body::rectangle(agent, Pose::new(Vector::new(x, y), 0.0), Vector::new(2.25, 0.9))
    }

    fn truck(agent: usize, x: f64, y: f64) -> Body {
        Body::rectangle(
            agent,
            Pose::new(Vector::new(x, y), std::f64::consts::FRAC_PI_2),
            Vector::new(5.0, 1.25),
        )
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

    /// A car parked on the target's spot, 0.5 m aside (its box holds the
    /// target's centre at (30, 0)), does not hide it; 3 m nearer it does.
    #[test]
    fn a_road_user_in_the_target_s_spot_does_not_hide_it() {
        let none = Occluders::new(&[]);
        assert_eq!(seen(&none, &[car(1, 29.5, 0.0)], [30.0, 0.0]), Visibility::Los);
        assert_eq!(seen(&none, &[car(1, 27.0, 0.0)], [30.0, 0.0]), Visibility::NlosDynamic);
    }

    /// A ray from the origin to (10, 0) and a disc of radius 1 at (10.5, 0)
    /// covering its last 1.5 m: it blocks the ray, unless the centre rule passes
    /// it over for containing (10, 0). (Touching the ray's end only is the
    /// fan's case: `fan::tests::twins_in_one_spot_do_not_hide_each_other`.)
    #[test]
    fn the_centre_rule_passes_over_a_footprint_holding_the_ray_s_end() {
        let covering = Bodies::new(vec![Body::circle(1, Pose::new(Vector::new(10.5, 0.0), 0.0), 1.0)]);
        let to = Vector::new(10.0, 0.0);
        assert!(covering.block(Vector::ZERO, to, [0, 2]));
        assert!(!covering.block_at_centre(Vector::ZERO, to, [0, 2]));
    }
}
