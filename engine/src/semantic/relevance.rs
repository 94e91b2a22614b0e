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

use sightline_dsl::{Area, Crosswalk, World};

use crate::math::Point;

/// Seconds between the points an approach is tested at.
const APPROACH_STEP: f64 = 0.25;

/// An area with the bounds of its polygon's corners: a point outside them is
/// outside the polygon without a look at its edges, and [`contains`] then
/// answers what the edges would, to the bit (for finite corners, the only
/// ones the dsl and the imports admit).
#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    area: Area,
    /// Least x and y, greatest x and y of a polygon's corners, x widened by
    /// [`Region::margin`]; infinite for a circle, always tested whole.
    bounds: [f64; 4],
}

impl Region {
    /// `area` with its bounds.
    pub fn new(area: Area) -> Self {
        let bounds = match &area {
            Area::Circle { .. } => [f64::NEG_INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::INFINITY],
            Area::Polygon(corners) => {
                let [mut x0, mut y0, mut x1, mut y1] =
                    [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
                for &[x, y] in corners {
                    (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
                }
                let margin = Self::margin(x0, x1);
                [x0 - margin, y0, x1 + margin, y1]
            }
        };
        Self { area, bounds }
    }

    /// How far past its corners' x an edge's crossing may be computed: the
    /// crossing a0 + t·(b0 − a0), t in [0, 1], is exact to a few units in the
    /// last place of the larger |x|, far below this margin. The y bounds need
    /// none: a point above or below every corner lies between no edge's ends.
    fn margin(x0: f64, x1: f64) -> f64 {
        1e-9 * (1.0 + x0.abs().max(x1.abs()))
    }
}

/// Whether `point` lies in `region` (boundary included). Outside a polygon's
/// bounds no edge is crossed left of the point, or an even number of them (a
/// horizontal line meets a closed outline an even number of times): the
/// bounds reject what the edges would.
pub fn contains(region: &Region, point: Point) -> bool {
    let [x0, y0, x1, y1] = region.bounds;
    if !(x0 <= point.x && point.x <= x1 && y0 <= point.y && point.y <= y1) {
        return false;
    }
    match &region.area {
        Area::Circle { center, radius } => (point - Point::new(center[0], center[1])).length() <= *radius,
        Area::Polygon(corners) => {
            // Even-odd ray crossing.
            let mut inside = false;
            let Some(mut a) = corners.last() else {
                return false;
            };
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
pub fn regions(world: &World) -> Vec<(String, Region)> {
    let crosswalks = world.crosswalks.iter().map(|c| (c.id.clone(), crosswalk_area(c)));
    let others = world.interaction_areas.iter().chain(&world.areas);
    crosswalks
        .chain(others.map(|a| (a.id.clone(), a.shape.clone())))
        .map(|(id, area)| (id, Region::new(area)))
        .collect()
}

/// Whether a path, given as its position at a time, enters `area` within `horizon`
/// while starting outside it.
pub fn approaches(area: &Region, horizon: f64, at: impl Fn(f64) -> Point) -> bool {
    if contains(area, at(0.0)) {
        return false;
    }
    let samples = (horizon / APPROACH_STEP).ceil() as usize;
    (1..=samples).any(|k| contains(area, at((k as f64 * APPROACH_STEP).min(horizon))))
}

/// The areas the relevance layer uses.
pub struct Areas {
    /// Interaction areas around conflict zones.
    pub interaction: Vec<Region>,
    /// Crosswalk rectangles, which matter for pedestrians.
    pub crosswalks: Vec<Region>,
}

impl Areas {
    /// The interaction areas and crosswalks `world` declares.
    pub fn of(world: &World) -> Self {
        Self {
            interaction: (world.interaction_areas.iter())
                .map(|area| Region::new(area.shape.clone()))
                .collect(),
            crosswalks: (world.crosswalks.iter())
                .map(|crosswalk| Region::new(crosswalk_area(crosswalk)))
                .collect(),
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
        self.interaction.iter().any(|shape| {
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
    use proptest::prelude::*;

    use super::*;

    fn square() -> Region {
        Region::new(Area::Polygon(vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]]))
    }

    /// The even-odd test over every edge, without the bounds.
    fn crosses_oddly(corners: &[[f64; 2]], point: Point) -> bool {
        let mut inside = false;
        for (i, a) in corners.iter().enumerate() {
            let b = corners[(i + 1) % corners.len()];
            if (a[1] > point.y) != (b[1] > point.y) {
                let x = a[0] + (point.y - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
                inside ^= point.x < x;
            }
        }
        inside
    }

    proptest! {
        /// The bounds change no answer: polygons of 3–8 corners anywhere in a
        /// 10 km square, points near them, on their corners' coordinates and
        /// on the bounds' edges (where a computed crossing could round past a
        /// corner).
        #[test]
        fn the_bounds_answer_what_the_edges_would(
            corners in prop::collection::vec((-5e3..5e3_f64, -5e3..5e3_f64), 3..=8),
            picks in prop::collection::vec((0..8_usize, 0..8_usize, -1e-6..1e-6_f64, 0..3_u8), 64),
        ) {
            let corners: Vec<[f64; 2]> = corners.into_iter().map(|(x, y)| [x, y]).collect();
            let region = Region::new(Area::Polygon(corners.clone()));
            let [x0, y0, x1, y1] = region.bounds;
            for (i, j, nudge, kind) in picks {
                let (a, b) = (corners[i % corners.len()], corners[j % corners.len()]);
                let point = match kind {
                    0 => Point::new(a[0] + nudge, b[1]),
                    1 => Point::new([x0, x1][i % 2] + nudge, (a[1] + b[1]) / 2.0),
                    _ => Point::new((a[0] + b[0]) / 2.0 + nudge * 1e9, [y0, y1][j % 2] + nudge),
                };
                prop_assert_eq!(contains(&region, point), crosses_oddly(&corners, point), "{:?}", point);
            }
        }
    }

    #[test]
    fn polygons_and_circles_contain_their_points() {
        assert!(contains(&square(), Point::new(5.0, 5.0)));
        assert!(!contains(&square(), Point::new(11.0, 5.0)));
        let disc = Region::new(Area::Circle {
            center: [0.0, 0.0],
            radius: 2.0,
        });
        assert!(contains(&disc, Point::new(2.0, 0.0)));
        assert!(!contains(&disc, Point::new(1.5, 1.5)));
    }

    #[test]
    fn a_crosswalk_covers_its_width_around_the_walk() {
        let area = Region::new(crosswalk_area(&Crosswalk {
            id: "c".into(),
            from: [0.0, -5.0],
            to: [0.0, 5.0],
            width: 4.0,
        }));
        assert!(contains(&area, Point::new(1.9, 4.0)));
        assert!(!contains(&area, Point::new(2.1, 0.0)));
    }

    /// A pedestrian 3 m from a crosswalk walking toward it at 1.4 m/s enters it
    /// after about 2.1 s: relevant with a 3 s horizon, not with a 2 s one; walking
    /// away, never.
    #[test]
    fn a_pedestrian_walking_toward_a_crosswalk_is_relevant() {
        let areas = Areas {
            interaction: Vec::new(),
            crosswalks: vec![Region::new(crosswalk_area(&Crosswalk {
                id: "c".into(),
                from: [0.0, -5.0],
                to: [0.0, 5.0],
                width: 4.0,
            }))],
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
        let areas = Areas {
            interaction: vec![square()],
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
