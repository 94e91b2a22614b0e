//! What a sensor sees of an object: a fan of rays over the object's outline,
//! the object's visibility class and its visible fraction.
//!
//! Seen from a sensor outside it, an outline (a vehicle's rectangle, a
//! pedestrian's circle) spans an angular interval about the bearing to its
//! centre. The fan splits that interval into `n` equal sectors and casts one
//! ray through the middle of each to where it enters the outline (parry ray
//! casts against the target's rectangle or circle). A ray is clear when no
//! occluder and no other agent's footprint (the observer's and the target's own
//! aside) lies before that point.
//!
//! - **Rays**: `n` = ⌈extent / `ray_spacing`⌉, the sensor's own angular
//!   resolution, so that the fan is as fine as the rays that carve free space;
//!   but at least [`MIN_RAYS`], so that a distant object narrower than one
//!   carving ray still has its fraction measured in steps of a tenth, and at
//!   most [`MAX_RAYS`], so that a sighting costs a bounded number of casts
//!   (360 rays resolve 0.5° over the widest extent, 180°).
//! - **Visible fraction**: the share of clear rays, that is the share of the
//!   object's angular extent in line of sight. It is an angular share, not a
//!   share of outline length or area.
//! - **Class**: an object with at least one clear ray is in line of sight
//!   ([`Visibility::Los`]), however little of it shows; a wholly hidden one is
//!   NLoS-static when a building stops at least one of its rays, NLoS-dynamic
//!   when only road users stop them all. With one ray this is the one-ray rule
//!   of [`super::sight::visibility`].
//! - A sensor inside the outline sees the whole object.

use super::sight::{Bodies, Body, Occluders, Outline, Visibility, segment_ray};
use crate::idealisation::Idealisation;
use crate::math::{Point, Vector};

/// The fewest rays a fan casts at an object.
pub const MIN_RAYS: usize = 10;

/// The most rays a fan casts at an object.
pub const MAX_RAYS: usize = 360;

/// Partial visibility is sampled by a fan of rays.
pub(crate) const FAN: Idealisation = Idealisation {
    id: "sight.fan",
    text: "What a sensor sees of an object is sampled by a fan of rays over the object's angular extent \
           (one per `ray_spacing_deg`, at least 10 and at most 360): its visible fraction is the share of \
           clear rays, an angular share, in 2-D outlines without height. Any part of an object whose centre \
           is in range and field of view can be seen, even past the edge of the field of view or the range; \
           an object with a clear ray counts in line of sight and is detected with the sensor's full \
           probability, and only the seen part of its measured footprint is marked occupied. A ray ends where \
           it reaches the object's outline: a road user whose outline only touches that point (two in one \
           spot) does not hide it, one that covers it (vehicles driving through one another) does.",
};

/// What a sensor sees of one object.
#[derive(Debug, Clone, PartialEq)]
pub struct View {
    /// The class: in line of sight when any part shows.
    pub visibility: Visibility,
    /// The bearing of the fan's first sector's start, relative to the bearing
    /// of the object's centre, radians.
    start: f64,
    /// The width of a sector, radians.
    sector: f64,
    /// Per ray, from the first: whether it reached the object. Empty when the
    /// sensor lies inside the outline and sees all of it.
    clear: Vec<bool>,
}

impl View {
    /// The share of the object's angular extent in line of sight, in [0, 1].
    pub fn fraction(&self) -> f64 {
        if self.clear.is_empty() {
            return 1.0;
        }
        self.clear.iter().filter(|&&c| c).count() as f64 / self.clear.len() as f64
    }

    /// Whether the whole object is in line of sight.
    pub fn is_whole(&self) -> bool {
        self.clear.iter().all(|&c| c)
    }

    /// Whether the part of the object at `bearing`, relative to the bearing of
    /// its centre, was seen: the ray nearest to it was clear (beyond the fan's
    /// ends, its end ray).
    pub fn sees(&self, bearing: f64) -> bool {
        if self.is_whole() {
            return true;
        }
        let bearing = bearing.sin().atan2(bearing.cos());
        let index = ((bearing - self.start) / self.sector - 0.5).round();
        self.clear[index.clamp(0.0, (self.clear.len() - 1) as f64) as usize]
    }
}

/// The bearing of `offset`, radians.
fn bearing(offset: Vector) -> f64 {
    offset.y.atan2(offset.x)
}

/// The angular extent of `target` seen from `from`, relative to the bearing of
/// its centre: (lowest, highest) bearing, radians. `None` when `from` lies
/// inside the outline.
fn extent(target: &Body, from: Point) -> Option<(f64, f64)> {
    if target.contains(from) {
        return None;
    }
    let to_centre = target.pose.translation - from;
    match target.outline {
        Outline::Circle => {
            let half = (target.half_extents.x / to_centre.length()).asin();
            Some((-half, half))
        }
        Outline::Rectangle => {
            let centre = bearing(to_centre);
            // A convex outline that does not hold `from` spans less than a half
            // turn about its centre's bearing, so the wrapped bearings of its
            // corners hold its extent.
            Some(
                target
                    .corners()
                    .iter()
                    .fold((0.0_f64, 0.0_f64), |(low, high), &corner| {
                        let relative = bearing(corner - from) - centre;
                        let relative = relative.sin().atan2(relative.cos());
                        (low.min(relative), high.max(relative))
                    }),
            )
        }
    }
}

/// What a sensor at `from` on agent `observer` sees of `target` among the
/// occluders and the step's bodies, with a fan whose rays are at most
/// `ray_spacing` radians apart (within [`MIN_RAYS`]..=[`MAX_RAYS`]).
pub fn view(
    occluders: &Occluders,
    bodies: &Bodies,
    from: Point,
    observer: usize,
    target: &Body,
    ray_spacing: f64,
) -> View {
    let Some((low, high)) = extent(target, from) else {
        return View {
            visibility: Visibility::Los,
            start: 0.0,
            sector: 0.0,
            clear: Vec::new(),
        };
    };
    let width = high - low;
    let rays = ((width / ray_spacing).ceil() as usize).clamp(MIN_RAYS, MAX_RAYS);
    let sector = width / rays as f64;
    let centre = bearing(target.pose.translation - from);
    let mut any_static = false;
    let clear = (0..rays)
        .map(|i| {
            let angle = centre + low + (i as f64 + 0.5) * sector;
            let direction = Vector::new(angle.cos(), angle.sin());
            // Where the ray enters the outline; a ray strictly inside the extent
            // of a convex outline always does, but take the centre's distance
            // should rounding let one graze past.
            let reach = segment_ray(from, from + direction)
                .and_then(|(ray, _)| target.cast_ray(&ray, f64::MAX))
                .unwrap_or_else(|| (target.pose.translation - from).length());
            let to = from + direction * reach;
            if occluders.block(from, to) {
                any_static = true;
                false
            } else {
                !bodies.block(from, to, [observer, target.agent])
            }
        })
        .collect::<Vec<bool>>();
    let visibility = if clear.contains(&true) {
        Visibility::Los
    } else if any_static {
        Visibility::NlosStatic
    } else {
        Visibility::NlosDynamic
    };
    View {
        visibility,
        start: low,
        sector,
        clear,
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;
    use proptest::prelude::*;
    use sightline_dsl::Occluder;

    use super::*;
    use crate::math::Pose;

    /// 1°: the fans of the hand-solved cases have an even number of rays, none
    /// of them on a shadow's edge.
    const SPACING: f64 = std::f64::consts::PI / 180.0;

    fn building(polygon: [[f64; 2]; 4]) -> Occluders {
        Occluders::new(&[Occluder {
            id: "b".into(),
            polygon: polygon.to_vec(),
        }])
    }

    fn car(agent: usize, x: f64, y: f64, heading: f64) -> Body {
        Body::rectangle(agent, Pose::new(Vector::new(x, y), heading), Vector::new(2.25, 0.9))
    }

    /// What a sensor at the origin on agent 0 sees of `target` among `occluders` and
    /// the bodies `between`.
    fn seen(occluders: &Occluders, between: &[Body], target: &Body) -> View {
        let bodies = between.iter().copied().chain([*target]).collect();
        view(occluders, &Bodies::new(bodies), Vector::ZERO, 0, target, SPACING)
    }

    /// A car 20 m north, across the line of sight (its 4.5 m side faces the
    /// sensor), and a building whose corner lies on the line to the car's centre:
    /// the building covers x < 0, 5 ≤ y ≤ 15. The car's left half (x < 0) lies in
    /// the corner's shadow, its right half is in view: half its extent, by symmetry
    /// about the line to its centre.
    #[test]
    fn a_car_half_behind_a_building_corner_is_half_seen() {
        let corner = building([[-20.0, 5.0], [0.0, 5.0], [0.0, 15.0], [-20.0, 15.0]]);
        let target = car(1, 0.0, 20.0, 0.0);
        let seen = seen(&corner, &[], &target);
        assert_eq!(seen.visibility, Visibility::Los);
        assert_relative_eq!(seen.fraction(), 0.5, epsilon = 1e-9);
        // The right (east, negative relative bearing) half is seen, the left is not.
        assert!(seen.sees(-0.05) && !seen.sees(0.05));
    }

    /// Two parked vans (6 × 2 m, along x) at y = 10, their near sides 1 m apart
    /// about x = 0: a pedestrian (radius 0.3) 20 m north on the gap's axis is seen
    /// whole through it (the gap spans ±0.5 m at y = 9..11, ±0.91 m at 20 m after
    /// widening by 20/11, wider than the pedestrian's ±0.3 m); moved 3 m east it
    /// lies behind the right van (its bearing, 8.5°, is beyond the gap's right
    /// edge seen from the origin, atan(0.5/11) = 2.6°), hidden by agents only.
    #[test]
    fn a_pedestrian_between_two_parked_vans_is_seen_through_the_gap_or_hidden() {
        let vans = [
            Body::rectangle(1, Pose::new(Vector::new(-3.5, 10.0), 0.0), Vector::new(3.0, 1.0)),
            Body::rectangle(2, Pose::new(Vector::new(3.5, 10.0), 0.0), Vector::new(3.0, 1.0)),
        ];
        let none = Occluders::new(&[]);
        let in_the_gap = Body::circle(3, Pose::new(Vector::new(0.0, 20.0), 0.0), 0.3);
        let through = seen(&none, &vans, &in_the_gap);
        assert_eq!((through.visibility, through.fraction()), (Visibility::Los, 1.0));
        let behind = Body::circle(3, Pose::new(Vector::new(3.0, 20.0), 0.0), 0.3);
        let hidden = seen(&none, &vans, &behind);
        assert_eq!((hidden.visibility, hidden.fraction()), (Visibility::NlosDynamic, 0.0));
    }

    /// Two pedestrians (and two cars) in one spot, 20 m north and 14 m north-east:
    /// each outline is the other's, so every ray meets the twin's outline just
    /// where it reaches the target's. Touching is not covering: each is seen whole.
    #[test]
    fn twins_in_one_spot_do_not_hide_each_other() {
        let none = Occluders::new(&[]);
        let at = Pose::new(Vector::new(0.0, 20.0), 0.0);
        let walker = |agent| Body::circle(agent, at, 0.3);
        let both = seen(&none, &[walker(1)], &walker(2));
        assert_eq!((both.visibility, both.fraction()), (Visibility::Los, 1.0));
        let both = seen(&none, &[car(1, 10.0, 10.0, 0.7)], &car(2, 10.0, 10.0, 0.7));
        assert_eq!((both.visibility, both.fraction()), (Visibility::Los, 1.0));
    }

    /// A pedestrian 20 m north whose centre lies on the gap's right edge seen from
    /// the origin (x = 0.5 · 20/11 = 0.909 m): the edge ray splits the circle
    /// through its centre, so half its extent shows.
    #[test]
    fn a_pedestrian_on_the_edge_of_the_gap_is_half_seen() {
        let vans = [
            Body::rectangle(1, Pose::new(Vector::new(-3.5, 10.0), 0.0), Vector::new(3.0, 1.0)),
            Body::rectangle(2, Pose::new(Vector::new(3.5, 10.0), 0.0), Vector::new(3.0, 1.0)),
        ];
        let edge = Body::circle(3, Pose::new(Vector::new(0.5 * 20.0 / 11.0, 20.0), 0.0), 0.3);
        let seen = seen(&Occluders::new(&[]), &vans, &edge);
        assert_eq!(seen.visibility, Visibility::Los);
        assert_relative_eq!(seen.fraction(), 0.5, epsilon = 1e-9);
    }

    /// A building hides half a car, a truck the other half: wholly hidden, and a
    /// building had a part in it, so the class is static.
    #[test]
    fn a_car_hidden_by_a_building_and_a_truck_is_nlos_static() {
        let corner = building([[-20.0, 5.0], [0.0, 5.0], [0.0, 15.0], [-20.0, 15.0]]);
        let truck = Body::rectangle(2, Pose::new(Vector::new(3.0, 10.0), 0.0), Vector::new(3.0, 1.25));
        let seen = seen(&corner, &[truck], &car(1, 0.0, 20.0, 0.0));
        assert_eq!((seen.visibility, seen.fraction()), (Visibility::NlosStatic, 0.0));
    }

    /// A sensor inside an outline (two bodies overlapping) sees all of it.
    #[test]
    fn a_sensor_inside_the_outline_sees_it_whole() {
        let target = car(1, 1.0, 0.0, 0.3);
        let seen = seen(&Occluders::new(&[]), &[], &target);
        assert_eq!((seen.visibility, seen.fraction()), (Visibility::Los, 1.0));
        assert!(seen.sees(2.0));
    }

    /// The fan's size: a car 20 m away across the line of sight spans 13.4°
    /// (2 · atan(2.25 / 19.1), to its near corners), 14 rays at 1° and 27 at
    /// 0.5°; 400 m away 0.65°, one ray at 1°, so the floor of 10; a coarse
    /// spacing of 10° gives the floor too.
    #[test]
    fn the_fan_has_a_ray_per_spacing_within_its_bounds() {
        let none = Occluders::new(&[]);
        let rays = |target: Body, spacing: f64| {
            view(&none, &Bodies::new(vec![target]), Vector::ZERO, 0, &target, spacing)
                .clear
                .len()
        };
        let across = |y: f64| car(1, 0.0, y, 0.0);
        assert_eq!(rays(across(20.0), SPACING), 14);
        assert_eq!(rays(across(20.0), SPACING / 2.0), 27);
        assert_eq!(rays(across(400.0), SPACING), MIN_RAYS);
        assert_eq!(rays(across(20.0), 10.0_f64.to_radians()), MIN_RAYS);
        // A truck 1 m away spans nearly a half turn: capped.
        let truck = Body::rectangle(1, Pose::new(Vector::new(0.0, 2.0), 0.0), Vector::new(6.0, 1.0));
        assert_eq!(rays(truck, 0.01_f64.to_radians()), MAX_RAYS);
    }

    fn body() -> impl Strategy<Value = Body> {
        (
            -30.0..30.0_f64,
            -30.0..30.0_f64,
            -3.2..3.2_f64,
            0.1..6.0_f64,
            0.1..2.0_f64,
            any::<bool>(),
        )
            .prop_map(|(x, y, heading, length, width, round)| {
                let pose = Pose::new(Vector::new(x, y), heading);
                if round {
                    Body::circle(1, pose, width / 2.0)
                } else {
                    Body::rectangle(1, pose, Vector::new(length, width) / 2.0)
                }
            })
    }

    proptest! {
        /// Nothing between the sensor and an object: it is seen whole.
        #[test]
        fn proptest_an_unobstructed_object_is_wholly_seen(target in body(), spacing in 0.001..0.2_f64) {
            let seen = view(&Occluders::new(&[]), &Bodies::new(vec![target]), Vector::ZERO, 0, &target, spacing);
            prop_assert_eq!(seen.visibility, Visibility::Los);
            prop_assert_eq!(seen.fraction(), 1.0);
        }

        /// Among other bodies and a building, the fraction is a share, never
        /// above what the building alone leaves, and the object is in line of
        /// sight exactly when it is above 0.
        #[test]
        fn proptest_more_obstacles_never_show_more_of_an_object(
            target in body(),
            others in proptest::collection::vec(body(), 0..6),
        ) {
            let others: Vec<Body> = others.into_iter().enumerate().map(|(i, b)| Body { agent: i + 2, ..b }).collect();
            let corner = building([[-20.0, 5.0], [0.0, 5.0], [0.0, 15.0], [-20.0, 15.0]]);
            let alone = view(&corner, &Bodies::new(vec![target]), Vector::ZERO, 0, &target, SPACING);
            let bodies = others.iter().copied().chain([target]).collect();
            let among = view(&corner, &Bodies::new(bodies), Vector::ZERO, 0, &target, SPACING);
            let fraction = among.fraction();
            prop_assert!((0.0..=1.0).contains(&fraction));
            prop_assert!(fraction <= alone.fraction());
            prop_assert_eq!(among.visibility == Visibility::Los, fraction > 0.0);
        }
    }
}
