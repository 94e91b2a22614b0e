//! Interaction relevance (seed 002, section III-B): which objects may interfere
//! with the ego's right of way, or must be given it.
//!
//! Our readings of the paper's three situations, for each interaction area:
//! - the ego is inside: a vehicle outside that is approaching it is relevant;
//! - the ego is approaching: a vehicle inside it is relevant ("holding priority":
//!   we take a vehicle already in the conflict zone to hold it);
//! - a pedestrian inside an area or a crosswalk, or approaching one, is relevant.
//!
//! "Approaching" means the constant-velocity extrapolation of the object (for the
//! ego, its planned path) enters the area within the prediction horizon.

use sightline_dsl::{Area, Crosswalk, InteractionArea, World};

use crate::math::Point;

/// Seconds between the points an approach is tested at.
const APPROACH_STEP: f64 = 0.25;

/// Whether `point` lies in `area` (boundary included).
pub fn contains(area: &Area, point: Point) -> bool {
    match area {
        Area::Circle { center, radius } => (point - Point::new(center[0], center[1])).length() <= *radius,
        Area::Polygon(corners) => {
            // Even-odd ray crossing.
            let mut inside = false;
            let Some(&last) = corners.last() else {
                return false;
            };
            let mut a = &last;
            for b in corners {
                if (a[1] > point.y) != (b[1] > point.y) {
                    let x = a[0] + (point.y - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
                    if point.x < x {
                        inside = !inside;
                    }
                }
                a = b;
            }
            inside
        }
    }
}

/// The area a crosswalk covers: its rectangle.
pub fn crosswalk_area(crosswalk: &Crosswalk) -> Area {
    let [a, b] = [crosswalk.from, crosswalk.to];
    let along = Point::new(b[0] - a[0], b[1] - a[1]);
    let left = Point::new(-along.y, along.x) / along.length() * (crosswalk.width / 2.0);
    let corner = |p: [f64; 2], sign: f64| [p[0] + sign * left.x, p[1] + sign * left.y];
    Area::Polygon(vec![corner(a, -1.0), corner(b, -1.0), corner(b, 1.0), corner(a, 1.0)])
}

/// Every region of `world` an `objects` selection can name, with its id:
/// crosswalks, interaction areas and declared `areas`, in that order.
pub fn regions(world: &World) -> Vec<(String, Area)> {
    let crosswalks = world.crosswalks.iter().map(|c| (c.id.clone(), crosswalk_area(c)));
    let others = world.interaction_areas.iter().chain(&world.areas);
    crosswalks
        .chain(others.map(|a| (a.id.clone(), a.shape.clone())))
        .collect()
}

/// Whether a path, given as its position at a time, enters `area` within `horizon`
/// while starting outside it.
pub fn approaches(area: &Area, horizon: f64, at: impl Fn(f64) -> Point) -> bool {
    if contains(area, at(0.0)) {
        return false;
    }
    let samples = (horizon / APPROACH_STEP).ceil() as usize;
    (1..=samples).any(|k| contains(area, at((k as f64 * APPROACH_STEP).min(horizon))))
}

/// The areas the relevance layer uses.
pub struct Areas<'a> {
    /// Interaction areas around conflict zones.
    pub interaction: &'a [InteractionArea],
    /// Crosswalk rectangles, which matter for pedestrians.
    pub crosswalks: Vec<Area>,
}

impl<'a> Areas<'a> {
    /// The interaction areas and crosswalks `world` declares.
    pub fn of(world: &'a World) -> Self {
        Self {
            interaction: &world.interaction_areas,
            crosswalks: world.crosswalks.iter().map(crosswalk_area).collect(),
        }
    }

    /// Whether a vehicle at `position` moving as `path` is relevant to an ego at
    /// `ego` moving as `ego_path`.
    pub fn vehicle_relevant(
        &self,
        horizon: f64,
        (ego, ego_path): (Point, &dyn Fn(f64) -> Point),
        (position, path): (Point, &dyn Fn(f64) -> Point),
    ) -> bool {
        self.interaction.iter().any(|area| {
            let shape = &area.shape;
            if contains(shape, ego) {
                approaches(shape, horizon, path)
            } else {
                contains(shape, position) && approaches(shape, horizon, ego_path)
            }
        })
    }

    /// Whether a pedestrian at `position` moving as `path` is relevant.
    pub fn pedestrian_relevant(&self, horizon: f64, position: Point, path: &dyn Fn(f64) -> Point) -> bool {
        self.interaction
            .iter()
            .map(|a| &a.shape)
            .chain(&self.crosswalks)
            .any(|area| contains(area, position) || approaches(area, horizon, path))
    }

    /// Whether a pedestrian at `position` is on a crosswalk (crossing the roadway).
    pub fn crossing(&self, position: Point) -> bool {
        self.crosswalks.iter().any(|area| contains(area, position))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Area {
        Area::Polygon(vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])
    }

    #[test]
    fn polygons_and_circles_contain_their_points() {
        assert!(contains(&square(), Point::new(5.0, 5.0)));
        assert!(!contains(&square(), Point::new(11.0, 5.0)));
        let disc = Area::Circle {
            center: [0.0, 0.0],
            radius: 2.0,
        };
        assert!(contains(&disc, Point::new(2.0, 0.0)));
        assert!(!contains(&disc, Point::new(1.5, 1.5)));
    }

    #[test]
    fn a_crosswalk_covers_its_width_around_the_walk() {
        let area = crosswalk_area(&Crosswalk {
            id: "c".into(),
            from: [0.0, -5.0],
            to: [0.0, 5.0],
            width: 4.0,
        });
        assert!(contains(&area, Point::new(1.9, 4.0)));
        assert!(!contains(&area, Point::new(2.1, 0.0)));
    }

    /// A pedestrian 3 m from a crosswalk walking toward it at 1.4 m/s enters it
    /// after about 2.1 s: relevant with a 3 s horizon, not with a 2 s one; walking
    /// away, never.
    #[test]
    fn a_pedestrian_walking_toward_a_crosswalk_is_relevant() {
        let areas = Areas {
            interaction: &[],
            crosswalks: vec![crosswalk_area(&Crosswalk {
                id: "c".into(),
                from: [0.0, -5.0],
                to: [0.0, 5.0],
                width: 4.0,
            })],
        };
        let start = Point::new(-5.0, 0.0);
        let toward = |t: f64| start + Point::new(1.4 * t, 0.0);
        let away = |t: f64| start - Point::new(1.4 * t, 0.0);
        assert!(areas.pedestrian_relevant(3.0, start, &toward));
        assert!(!areas.pedestrian_relevant(2.0, start, &toward));
        assert!(!areas.pedestrian_relevant(3.0, start, &away));
    }

    #[test]
    fn vehicles_approaching_an_area_the_ego_is_in_are_relevant() {
        let junction = [InteractionArea {
            id: "j".into(),
            shape: square(),
        }];
        let areas = Areas {
            interaction: &junction,
            crosswalks: Vec::new(),
        };
        let ego = Point::new(5.0, 5.0);
        let still = move |_: f64| ego;
        let coming = |t: f64| Point::new(-20.0 + 10.0 * t, 5.0);
        let leaving = |t: f64| Point::new(-20.0 - 10.0 * t, 5.0);
        assert!(areas.vehicle_relevant(3.0, (ego, &still), (coming(0.0), &coming)));
        assert!(!areas.vehicle_relevant(3.0, (ego, &still), (leaving(0.0), &leaving)));
        // The ego approaching: the vehicle inside holds priority.
        let ego_coming = |t: f64| Point::new(5.0, -20.0 + 10.0 * t);
        let inside = Point::new(5.0, 5.0);
        let parked = move |_: f64| inside;
        assert!(areas.vehicle_relevant(3.0, (ego_coming(0.0), &ego_coming), (inside, &parked)));
    }
}
