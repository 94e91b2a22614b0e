//! Criticality of a road user against the ego, on oriented boxes (issue 17):
//! time to collision (TTC), deceleration rate to avoid a crash (DRAC) and
//! post-encroachment time (PET), the measures assessors know from the traffic
//! conflict literature. `docs/qualification.md` ("Metric definitions") states
//! each with its sources and where CommonRoad's criticality package differs.
//!
//! Every road user's footprint is here the rectangle of its length and width
//! about its centre, its length along its heading: a pedestrian's too, whose
//! line of sight takes a circle ([`BOXES`]).
//! - **TTC** at a step: the first time t ≥ 0 at which the two rectangles,
//!   each moving on at its current velocity (its speed along its heading,
//!   neither turning), touch; 0 when they overlap or touch at the step, none
//!   when they never will. Exact, by the separating axis theorem on the four
//!   edge normals: two convex polygons that translate are apart exactly while
//!   one of those axes separates their projections.
//! - **DRAC** at a step with a TTC t > 0: the deceleration the ego needs to
//!   avoid the contact by braking, so only where braking can: when the road
//!   user, moving on, would miss the ego standing where it is. It is then
//!   c / (2 t), with c the closing speed along the ego's heading,
//!   (v_ego − v_other) · heading_ego, when c > 0: the constant deceleration
//!   of the closing motion that sheds c over the c · t metres it has before
//!   the contact, the literature's v_rel² / (2 gap) along the ego's path
//!   (Archer 2005; the review of Westhofen et al. 2023 calls it a_long,req).
//!   Behind a slower road user it is Archer's (v_F − v_L)² / (2 gap), the
//!   ego's own deceleration; across the ego's way (c = the ego's speed), the
//!   deceleration that stops the ego where the contact would be. None without
//!   a predicted contact, at contact (t = 0), or when braking would not avoid
//!   it: a road user coming head on or catching up from behind, and any road
//!   user heading for an ego that stands.
//! - **PET** over a run: the conflict area is the set of points both
//!   footprints covered at the steps given (the intersection of the two swept
//!   footprints); PET is the least, over its points, of the time between the
//!   first of the two last covering the point and the second first covering
//!   it. On the sampled footprints: the least |t_i − t_j| over the pairs of
//!   steps i (the ego) and j (the road user) whose footprints overlap or touch;
//!   0 when they overlap at one step (they touched); none without a conflict
//!   area. Footprints are sampled at the steps: the PET of the continuous motion
//!   can be up to two steps shorter.

use crate::idealisation::Idealisation;
use crate::math::{Point, Vector, elapsed, to_ns};
use crate::world::AgentState;

/// What criticality takes as given.
pub(crate) const BOXES: Idealisation = Idealisation {
    id: "criticality.boxes",
    text: "TTC and DRAC extrapolate both road users at constant velocity, along their heading, without turning; \
           TTC, DRAC and PET take every footprint as the rectangle of its length and width (a pedestrian's too); \
           PET compares the footprints sampled at the steps, so the continuous motion's can be up to two steps \
           shorter.",
};

/// Relative speeds along an axis below this, m/s, count as none: a road user
/// drifting a billionth of a metre per second toward a parallel course is
/// on that course.
const STILL: f64 = 1e-9;

/// A footprint: a rectangle about a centre, its length along a heading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct OrientedBox {
    /// Its centre, world frame, metres.
    pub centre: Point,
    /// Unit vector along its length.
    pub heading: Vector,
    /// Half its length and half its width, metres.
    pub half: Vector,
}

impl OrientedBox {
    /// The rectangle `length` × `width` about `centre`, its length along the
    /// unit vector `heading`.
    pub fn new(centre: Point, heading: Vector, length: f64, width: f64) -> Self {
        Self {
            centre,
            heading,
            half: Vector::new(length, width) / 2.0,
        }
    }

    /// The footprint of a road user `length` × `width` in `state`.
    pub fn of(state: &AgentState, length: f64, width: f64) -> Self {
        Self::new(state.position(), direction(state), length, width)
    }

    /// Its two edge normals (its heading and the heading's left).
    fn axes(&self) -> [Vector; 2] {
        [self.heading, self.heading.perp()]
    }

    /// Half the length of its projection on the unit vector `axis`.
    fn reach_along(&self, axis: Vector) -> f64 {
        self.half.x * self.heading.dot(axis).abs() + self.half.y * self.heading.perp().dot(axis).abs()
    }

    /// The radius of its circumscribed circle.
    fn circumradius(&self) -> f64 {
        self.half.length()
    }
}

/// The first time t ≥ 0 at which `other`, moving at `relative` velocity with
/// respect to `ego`, touches it (0: they overlap or touch now); `None` when it
/// never does.
pub(crate) fn time_to_contact(ego: &OrientedBox, other: &OrientedBox, relative: Vector) -> Option<f64> {
    let offset = other.centre - ego.centre;
    let (mut enter, mut leave) = (0.0_f64, f64::INFINITY);
    for axis in ego.axes().into_iter().chain(other.axes()) {
        // On this axis the projections overlap while |gap + speed · t| ≤ reach.
        let gap = offset.dot(axis);
        let reach = ego.reach_along(axis) + other.reach_along(axis);
        let speed = relative.dot(axis);
        if speed.abs() < STILL {
            if gap.abs() > reach {
                return None;
            }
            continue;
        }
        let (a, b) = ((-reach - gap) / speed, (reach - gap) / speed);
        enter = enter.max(a.min(b));
        leave = leave.min(a.max(b));
        if enter > leave {
            return None;
        }
    }
    Some(enter)
}

/// Whether two footprints overlap or touch.
pub(crate) fn overlap(a: &OrientedBox, b: &OrientedBox) -> bool {
    let offset = b.centre - a.centre;
    a.axes()
        .into_iter()
        .chain(b.axes())
        .all(|axis| offset.dot(axis).abs() <= a.reach_along(axis) + b.reach_along(axis))
}

/// A road user's velocity: its speed along its heading.
pub(crate) fn velocity(state: &AgentState) -> Vector {
    direction(state) * state.speed
}

/// The unit vector along a road user's heading.
fn direction(state: &AgentState) -> Vector {
    let rotation = state.pose.rotation;
    Vector::new(rotation.cos(), rotation.sin())
}

/// The TTC and DRAC of a road user against the ego at one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Criticality {
    /// Time to collision, seconds, to the nanosecond.
    pub ttc: Option<f64>,
    /// Deceleration rate to avoid the crash, m/s².
    pub drac: Option<f64>,
}

impl Criticality {
    /// The road user `other` (its footprint and velocity) against the `ego` at
    /// one step.
    pub fn of((ego, ego_velocity): (&OrientedBox, Vector), (other, other_velocity): (&OrientedBox, Vector)) -> Self {
        let ttc = time_to_contact(ego, other, other_velocity - ego_velocity).map(to_ns);
        let closing = (ego_velocity - other_velocity).dot(ego.heading);
        // Braking avoids the contact only if the road user would miss the ego
        // standing where it is (never so for an ego that stands already).
        let avoidable = || time_to_contact(ego, other, other_velocity).is_none();
        let drac = ttc
            .filter(|&t| t > 0.0 && closing > 0.0 && avoidable())
            .map(|t| closing / (2.0 * t));
        Self { ttc, drac }
    }
}

/// The PET of two footprints sampled at the same steps: `ego` and `other`
/// hold (time, footprint) pairs, the ego's and the road user's at the steps
/// the conflict area is taken over. `None` when no footprint of the one
/// overlaps or touches a footprint of the other.
pub(crate) fn post_encroachment(ego: &[(f64, OrientedBox)], other: &[(f64, OrientedBox)]) -> Option<f64> {
    // Sweep along x: only footprints whose centres are within the sum of the
    // circumradii can overlap, so each of the road user's footprints is tried
    // against the ego's within that distance in x, not against all of them.
    let (ego, other) = (by_x(ego), by_x(other));
    let ego_reach = ego.iter().map(|(_, b)| b.circumradius()).fold(0.0, f64::max);
    let mut best: Option<f64> = None;
    let mut first = 0;
    for &&(t_other, ref b) in &other {
        let reach = ego_reach + b.circumradius();
        while first < ego.len() && ego[first].1.centre.x < b.centre.x - reach {
            first += 1;
        }
        for &&(t_ego, ref a) in ego[first..]
            .iter()
            .take_while(|(_, a)| a.centre.x <= b.centre.x + reach)
        {
            let apart = elapsed(t_ego, t_other).abs();
            if best.is_some_and(|best| apart >= best) || (a.centre - b.centre).length() > reach {
                continue;
            }
            if overlap(a, b) {
                best = Some(apart);
            }
        }
    }
    best
}

/// The samples in order of their footprints' centres along x.
fn by_x(samples: &[(f64, OrientedBox)]) -> Vec<&(f64, OrientedBox)> {
    let mut sorted: Vec<&(f64, OrientedBox)> = samples.iter().collect();
    sorted.sort_by(|a, b| a.1.centre.x.total_cmp(&b.1.centre.x));
    sorted
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    use super::*;

    /// A car 4 × 2 at (x, y) heading `deg` degrees.
    fn car(x: f64, y: f64, deg: f64) -> OrientedBox {
        OrientedBox::new(Vector::new(x, y), at(1.0, deg), 4.0, 2.0)
    }

    fn at(speed: f64, deg: f64) -> Vector {
        let rad = deg.to_radians();
        Vector::new(rad.cos(), rad.sin()) * speed
    }

    /// Head on: centres 30 m apart on one line, 10 and 5 m/s toward each other;
    /// the fronts are 30 − 4 = 26 m apart and close at 15 m/s: 26 / 15 s. The
    /// other reaches the ego even if it stops: no braking avoids it, no DRAC.
    #[test]
    fn head_on() {
        let c = Criticality::of(
            (&car(0.0, 0.0, 0.0), at(10.0, 0.0)),
            (&car(30.0, 0.0, 180.0), at(5.0, 180.0)),
        );
        assert_relative_eq!(c.ttc.unwrap(), 26.0 / 15.0, epsilon = 5e-10); // to the nanosecond
        assert_eq!(c.drac, None);
        // An ego that stands, a car coming at 10 m/s from 60 m (the fronts 56 m
        // apart): TTC 5.6 s, and nothing the ego could shed.
        let c = Criticality::of(
            (&car(0.0, 0.0, 0.0), Vector::ZERO),
            (&car(60.0, 0.0, 180.0), at(10.0, 180.0)),
        );
        assert_eq!(c.ttc, Some(5.6));
        assert_eq!(c.drac, None);
    }

    /// Behind a slower car in the same lane: gap 20 − 4 = 16 m, closing at
    /// 12 − 8 = 4 m/s: TTC 4 s, DRAC Δv² / (2 gap) = 16 / 32 = 0.5 m/s².
    #[test]
    fn rear_end_is_archers_drac() {
        let c = Criticality::of(
            (&car(0.0, 0.0, 0.0), at(12.0, 0.0)),
            (&car(20.0, 0.0, 0.0), at(8.0, 0.0)),
        );
        assert_eq!(c.ttc, Some(4.0));
        assert_relative_eq!(c.drac.unwrap(), 0.5, epsilon = 1e-12);
        // Behind a car that stands, gap 16 m at 8 m/s: 8² / (2 · 16) = 2 m/s².
        let c = Criticality::of(
            (&car(0.0, 0.0, 0.0), at(8.0, 0.0)),
            (&car(20.0, 0.0, 0.0), Vector::ZERO),
        );
        assert_relative_eq!(c.drac.unwrap(), 2.0, epsilon = 1e-12);
        // Caught up from behind: braking only brings the contact sooner.
        let c = Criticality::of(
            (&car(0.0, 0.0, 0.0), at(8.0, 0.0)),
            (&car(-20.0, 0.0, 0.0), at(12.0, 0.0)),
        );
        assert_eq!((c.ttc, c.drac), (Some(4.0), None));
        // Pulling away: no collision course.
        let c = Criticality::of(
            (&car(0.0, 0.0, 0.0), at(8.0, 0.0)),
            (&car(20.0, 0.0, 0.0), at(12.0, 0.0)),
        );
        assert_eq!(c, Criticality { ttc: None, drac: None });
    }

    /// Crossing at right angles: the ego heads +x at 10 m/s from (0, 0), the
    /// other heads +y at 5 m/s from (20, −15). They touch when the ego's front
    /// (x = 2 + 10 t) reaches the other's left side (x = 19) and the other's
    /// front (y = −13 + 5 t) reaches the ego's right side (y = −1): the ego is
    /// there from t = 1.7 until its rear passes x = 21 (t = 2.3), the other
    /// from t = 2.4: they never overlap in both at once. With the other 5 m
    /// nearer, (20, −10), it arrives at t = 1.4 and stays until its rear passes
    /// y = 1 (t = 2.6): the contact is at max(1.7, 1.4) = 1.7 s.
    #[test]
    fn crossing_at_right_angles() {
        let ego = (&car(0.0, 0.0, 0.0), at(10.0, 0.0));
        assert_eq!(Criticality::of(ego, (&car(20.0, -15.0, 90.0), at(5.0, 90.0))).ttc, None);
        let c = Criticality::of(ego, (&car(20.0, -10.0, 90.0), at(5.0, 90.0)));
        assert_eq!(c.ttc, Some(1.7));
        // The other crosses the ego's way: the ego closes at its own speed,
        // 10 / (2 · 1.7) m/s², stopping in the 17 m to where it would touch.
        assert_relative_eq!(c.drac.unwrap(), 10.0 / 3.4, epsilon = 1e-12);
    }

    /// A box turned 45° approaches corner first: the ego, axis-aligned at
    /// the origin, stands; the other, 4 × 2 turned 45°, reaches 2 cos 45° +
    /// 1 sin 45° = 3/√2 along x, with its corner (−3/√2, −1/√2) from its
    /// centre. Moving −x at 2 m/s from (10, 0), that corner meets the ego's
    /// face x = 2 (it is at y = −0.71, within the face) when
    /// 10 − 2 t − 3/√2 = 2: t = (8 − 3/√2) / 2.
    #[test]
    fn rotated_box_touches_corner_first() {
        let ego = (&car(0.0, 0.0, 0.0), Vector::ZERO);
        let c = Criticality::of(ego, (&car(10.0, 0.0, 45.0), at(2.0, 180.0)));
        assert_relative_eq!(c.ttc.unwrap(), (8.0 - 3.0 / 2f64.sqrt()) / 2.0, epsilon = 5e-10); // to the nanosecond
        // The ego stands: braking sheds nothing.
        assert_eq!(c.drac, None);
        // Crossing the way of an ego that stands (its front from y = −8 to the
        // ego's side at −1, 7 m at 2 m/s): likewise.
        let c = Criticality::of(ego, (&car(0.0, -10.0, 90.0), at(2.0, 90.0)));
        assert_eq!((c.ttc, c.drac), (Some(3.5), None));
        // 2.5 m up, that corner passes above the face (y = 1.79) and the
        // other's lower edge meets the ego's corner (2, 1) instead: along the
        // other's length axis (cos 45°, sin 45°) the centres are
        // (12.5 − 2 t)/√2 apart and touch at 2 + 3/√2 (its half length, the
        // ego's reach there): t = (9.5 − 2√2) / 2.
        let c = Criticality::of(ego, (&car(10.0, 2.5, 45.0), at(2.0, 180.0)));
        assert_relative_eq!(c.ttc.unwrap(), (9.5 - 2.0 * 2f64.sqrt()) / 2.0, epsilon = 5e-10); // to the nanosecond
        // 3.2 m up it passes above: 3.2 > 1 + 3/√2 = 3.12.
        assert_eq!(Criticality::of(ego, (&car(10.0, 3.2, 45.0), at(2.0, 180.0))).ttc, None);
    }

    /// Side by side in adjacent lanes, 3.5 m apart, at any speeds: the
    /// lateral axis separates them forever.
    #[test]
    fn parallel_courses_never_touch() {
        for (mine, theirs) in [(10.0, 10.0), (14.0, 9.0), (0.0, 13.0)] {
            let c = Criticality::of(
                (&car(0.0, 0.0, 0.0), at(mine, 0.0)),
                (&car(30.0, 3.5, 0.0), at(theirs, 0.0)),
            );
            assert_eq!(c.ttc, None, "{mine} {theirs}");
        }
        // Just touching sides (2 m apart centre to centre, 1 + 1 half widths) is contact.
        let c = Criticality::of(
            (&car(0.0, 0.0, 0.0), at(10.0, 0.0)),
            (&car(30.0, 2.0, 0.0), at(10.0, 0.0)),
        );
        assert_eq!(c.ttc, None, "touching only when they are level");
        assert_eq!(
            time_to_contact(&car(0.0, 0.0, 0.0), &car(3.0, 2.0, 0.0), Vector::ZERO),
            Some(0.0)
        );
    }

    /// Already overlapping: TTC 0, and no DRAC (no deceleration undoes a contact).
    #[test]
    fn already_overlapping() {
        let c = Criticality::of(
            (&car(0.0, 0.0, 0.0), at(10.0, 0.0)),
            (&car(3.0, 1.0, 30.0), at(4.0, 30.0)),
        );
        assert_eq!(
            c,
            Criticality {
                ttc: Some(0.0),
                drac: None
            }
        );
        assert!(overlap(&car(0.0, 0.0, 0.0), &car(3.0, 1.0, 30.0)));
        // A car across the ego's way, 2.5 m and 3.5 m abeam: it reaches 2 m
        // toward the ego, the ego 1 m toward it.
        assert!(overlap(&car(0.0, 0.0, 0.0), &car(0.0, 2.5, 90.0)));
        assert!(!overlap(&car(0.0, 0.0, 0.0), &car(0.0, 3.5, 90.0)));
    }

    /// The footprints of one road user moving at `speed` along `heading`
    /// from `from`, sampled every `dt` for `steps` steps.
    fn track(from: (f64, f64), heading: f64, speed: f64, (dt, steps): (f64, usize)) -> Vec<(f64, OrientedBox)> {
        (0..steps)
            .map(|k| {
                let t = k as f64 * dt;
                let centre = Vector::new(from.0, from.1) + at(speed * t, heading);
                (t, OrientedBox::new(centre, at(1.0, heading), 4.0, 2.0))
            })
            .collect()
    }

    /// The ego heads +x at 10 m/s from (−0.25, 0); the other +y at 5 m/s
    /// from (20, −25.25). The conflict area is the square x ∈ [19, 21],
    /// y ∈ [−1, 1]. The ego covers it from its front at x = 19 (t = 1.725)
    /// until its rear passes x = 21 (t = 2.325); the other's front reaches
    /// y = −1 at (−1 + 23.25) / 5 = 4.45 s: the continuous PET is 2.125 s.
    /// On steps of 0.1 s the last ego step covering it is 2.3, the first of
    /// the other 4.5: 2.2 s (no event falls on a step).
    #[test]
    fn pet_of_a_right_angle_crossing() {
        let steps = (0.1, 120);
        let ego = track((-0.25, 0.0), 0.0, 10.0, steps);
        let other = track((20.0, -25.25), 90.0, 5.0, steps);
        assert_relative_eq!(post_encroachment(&ego, &other).unwrap(), 2.2, epsilon = 1e-9);
        // Either way round.
        assert_relative_eq!(post_encroachment(&other, &ego).unwrap(), 2.2, epsilon = 1e-9);
        // From (20, −10) it covers the square from 1.4 s to 2.6 s, the ego from
        // 1.725 s: they touch at a step (TTC 1.7 s from the start), PET 0.
        let other = track((20.0, -10.0), 90.0, 5.0, steps);
        assert_eq!(post_encroachment(&ego, &other), Some(0.0));
        // Behind the ego in its lane, 15.2 m back at the same speed: its front
        // reaches each spot 11.2 m, 1.12 s, after the ego's rear left it; on
        // the steps (1 m apart) the footprints overlap only 12 steps apart.
        let follower = track((-15.45, 0.0), 0.0, 10.0, steps);
        assert_relative_eq!(post_encroachment(&ego, &follower).unwrap(), 1.2, epsilon = 1e-9);
        // Three lanes over: no common spot.
        let apart = track((-15.45, 7.0), 0.0, 10.0, steps);
        assert_eq!(post_encroachment(&ego, &apart), None);
    }

    /// A footprint on an integer grid: centre within 20 m, heading in whole
    /// degrees, sides of 1 to 6 m in half metres.
    fn footprint() -> impl Strategy<Value = OrientedBox> {
        (-20..=20i32, -20..=20i32, 0..360i32, 2..=12i32, 2..=12i32).prop_map(|(x, y, deg, l, w)| {
            OrientedBox::new(
                Vector::new(x.into(), y.into()),
                at(1.0, deg.into()),
                f64::from(l) / 2.0,
                f64::from(w) / 2.0,
            )
        })
    }

    /// The footprint moved by `by`, each side grown by `grow` on both ends.
    fn moved(b: &OrientedBox, by: Vector, grow: f64) -> OrientedBox {
        OrientedBox {
            centre: b.centre + by,
            half: b.half + Vector::splat(grow),
            ..*b
        }
    }

    proptest! {
        /// The TTC is the first contact: the footprints touch then (up to
        /// rounding), and at any time they overlap the TTC is no later; it does
        /// not depend on which is the ego.
        #[test]
        fn proptest_ttc_is_the_first_contact(
            a in footprint(),
            b in footprint(),
            (vx, vy) in (-15..=15i32, -15..=15i32),
            steps in proptest::collection::vec(0..=400u32, 8),
        ) {
            let relative = Vector::new(vx.into(), vy.into());
            let ttc = time_to_contact(&a, &b, relative);
            prop_assert_eq!(ttc, time_to_contact(&b, &a, -relative));
            if let Some(t) = ttc {
                prop_assert!(t >= 0.0);
                prop_assert!(overlap(&a, &moved(&b, relative * t, 1e-9)), "apart at the TTC {t}");
            }
            for s in steps.into_iter().map(|k| f64::from(k) * 0.05) {
                if overlap(&a, &moved(&b, relative * s, 0.0)) {
                    prop_assert!(ttc.is_some_and(|t| t <= s + 1e-9), "overlap at {s} but TTC {ttc:?}");
                }
            }
        }
    }
}
