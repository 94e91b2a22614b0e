//! Plane geometry the language needs to resolve roads and routes: polylines with
//! arc length, projections, lane offsets, sampled arcs, polygon orientation and
//! convex hulls. Coordinates are metres in
//! the world frame; angles are radians, counter-clockwise from +x.

use serde::Serialize;

/// A point or vector [x, y], metres.
pub type Xy = [f64; 2];

/// Arcs and rings are sampled so that no chord strays further than this from the
/// true curve, metres.
pub const MAX_CHORD_ERROR: f64 = 0.01;

/// A polyline with its cumulative arc length.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Polyline {
    points: Vec<Xy>,
    #[serde(skip)]
    lengths: Vec<f64>,
}

/// Where a point projects onto a polyline.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// Arc length of the closest point, metres from the start.
    pub offset: f64,
    /// Distance from the point to the polyline, metres.
    pub distance: f64,
}

impl Polyline {
    /// A polyline through `points`, dropping consecutive duplicates; `None` when
    /// fewer than two distinct points remain.
    pub fn new(points: impl IntoIterator<Item = Xy>) -> Option<Self> {
        let mut kept: Vec<Xy> = Vec::new();
        for point in points {
            if kept.last().is_none_or(|&last| distance(last, point) > 1e-9) {
                kept.push(point);
            }
        }
        if kept.len() < 2 {
            return None;
        }
        let mut lengths = Vec::with_capacity(kept.len());
        let mut total = 0.0;
        lengths.push(0.0);
        for pair in kept.windows(2) {
            total += distance(pair[0], pair[1]);
            lengths.push(total);
        }
        Some(Self { points: kept, lengths })
    }

    /// The vertices.
    pub fn points(&self) -> &[Xy] {
        &self.points
    }

    /// Total length, metres.
    pub fn length(&self) -> f64 {
        *self.lengths.last().expect("a polyline has at least two points")
    }

    /// The first point.
    pub fn start(&self) -> Xy {
        self.points[0]
    }

    /// The last point.
    pub fn end(&self) -> Xy {
        *self.points.last().expect("a polyline has at least two points")
    }

    /// Whether the last point equals the first (a ring).
    pub fn is_closed(&self) -> bool {
        distance(self.start(), self.end()) <= 1e-9
    }

    /// The segment holding arc length `offset` (clamped to the polyline), and the
    /// fraction along it.
    fn locate(&self, offset: f64) -> (usize, f64) {
        let offset = offset.clamp(0.0, self.length());
        let segment = self
            .lengths
            .partition_point(|&l| l <= offset)
            .clamp(1, self.points.len() - 1)
            - 1;
        let length = self.lengths[segment + 1] - self.lengths[segment];
        (segment, (offset - self.lengths[segment]) / length)
    }

    /// The point at arc length `offset` (clamped to the ends).
    pub fn point_at(&self, offset: f64) -> Xy {
        let (segment, t) = self.locate(offset);
        lerp(self.points[segment], self.points[segment + 1], t)
    }

    /// The heading at arc length `offset`: the direction of its segment, radians.
    pub fn heading_at(&self, offset: f64) -> f64 {
        let (segment, _) = self.locate(offset);
        let [a, b] = [self.points[segment], self.points[segment + 1]];
        (b[1] - a[1]).atan2(b[0] - a[0])
    }

    /// The closest point of the polyline to `point`.
    pub fn project(&self, point: Xy) -> Projection {
        let mut best = Projection {
            offset: 0.0,
            distance: f64::INFINITY,
        };
        for (i, pair) in self.points.windows(2).enumerate() {
            let [a, b] = [pair[0], pair[1]];
            let length = self.lengths[i + 1] - self.lengths[i];
            let along = ((point[0] - a[0]) * (b[0] - a[0]) + (point[1] - a[1]) * (b[1] - a[1])) / (length * length);
            let t = along.clamp(0.0, 1.0);
            let d = distance(point, lerp(a, b, t));
            if d < best.distance {
                best = Projection {
                    offset: self.lengths[i] + t * length,
                    distance: d,
                };
            }
        }
        best
    }

    /// The points between arc lengths `from` and `to` (`from` < `to`), as a list
    /// starting and ending exactly there.
    pub fn slice(&self, from: f64, to: f64) -> Vec<Xy> {
        let mut points = vec![self.point_at(from)];
        points.extend(
            self.points
                .iter()
                .zip(&self.lengths)
                .filter(|&(_, &l)| l > from && l < to)
                .map(|(&p, _)| p),
        );
        points.push(self.point_at(to));
        points
    }

    /// The polyline shifted `left` metres to the left of its direction of travel,
    /// with mitred corners (lane centrelines).
    pub fn offset_left(&self, left: f64) -> Polyline {
        if left == 0.0 {
            return self.clone();
        }
        let n = self.points.len();
        let closed = self.is_closed();
        let normal = |i: usize| {
            let [a, b] = [self.points[i], self.points[i + 1]];
            let length = distance(a, b);
            [-(b[1] - a[1]) / length, (b[0] - a[0]) / length]
        };
        let shifted = (0..n).map(|i| {
            let (before, after) = match (i, closed) {
                (0, false) => (normal(0), normal(0)),
                (0, true) => (normal(n - 2), normal(0)),
                (i, _) if i == n - 1 && !closed => (normal(n - 2), normal(n - 2)),
                (i, _) if i == n - 1 => (normal(n - 2), normal(0)),
                (i, _) => (normal(i - 1), normal(i)),
            };
            let bisector = [before[0] + after[0], before[1] + after[1]];
            // |bisector| = 2 cos(half the turn); the mitre length is left / cos.
            let scale = 2.0 * left / (bisector[0] * bisector[0] + bisector[1] * bisector[1]);
            let p = self.points[i];
            [p[0] + bisector[0] * scale, p[1] + bisector[1] * scale]
        });
        Polyline::new(shifted.collect::<Vec<_>>()).expect("an offset keeps distinct points")
    }
}

/// Euclidean distance.
pub fn distance(a: Xy, b: Xy) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

fn lerp(a: Xy, b: Xy, t: f64) -> Xy {
    [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t]
}

/// A circular arc: `radius` about `center` from angle `start` through `sweep`
/// (radians; counter-clockwise when `sweep` > 0, a whole ring when |`sweep`| = 2π).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Arc {
    /// Centre, metres.
    pub center: Xy,
    /// Radius, metres.
    pub radius: f64,
    /// Angle of the first point, radians counter-clockwise from +x.
    pub start: f64,
    /// Signed angle swept, radians.
    pub sweep: f64,
}

impl Arc {
    /// Its points, as [`arc`] samples them.
    pub fn points(&self) -> Vec<Xy> {
        arc(self.center, self.radius, self.start, self.start + self.sweep)
    }
}

/// Points of the arc of `radius` about `center` from angle `start` to `end`
/// (radians; counter-clockwise when `end` > `start`), both ends included, with
/// chords within [`MAX_CHORD_ERROR`] of the arc.
pub fn arc(center: Xy, radius: f64, start: f64, end: f64) -> Vec<Xy> {
    // A chord spanning Δθ strays r(1 − cos(Δθ/2)) from the arc.
    let max_step = 2.0 * (1.0 - (MAX_CHORD_ERROR / radius).min(1.0)).acos();
    let segments = ((end - start).abs() / max_step).ceil().max(1.0) as usize;
    (0..=segments)
        .map(|i| {
            let angle = start + (end - start) * i as f64 / segments as f64;
            [center[0] + radius * angle.cos(), center[1] + radius * angle.sin()]
        })
        .collect()
}

/// `polygon` counter-clockwise, or `None` when it has fewer than three corners or
/// encloses no area.
pub(crate) fn counter_clockwise(polygon: &[Xy]) -> Option<Vec<Xy>> {
    let area = signed_area(polygon);
    if polygon.len() < 3 || area.abs() < 1e-9 {
        return None;
    }
    let mut polygon = polygon.to_vec();
    if area < 0.0 {
        polygon.reverse();
    }
    Some(polygon)
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone chain).
pub(crate) fn convex_hull(mut points: Vec<Xy>) -> Vec<Xy> {
    points.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let cross = |o: Xy, a: Xy, b: Xy| (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    let mut hull: Vec<Xy> = Vec::with_capacity(points.len() + 1);
    for pass in [false, true] {
        let start = hull.len();
        let ordered: Box<dyn Iterator<Item = &Xy>> = if pass {
            Box::new(points.iter().rev())
        } else {
            Box::new(points.iter())
        };
        for &p in ordered {
            while hull.len() >= start + 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0 {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// The signed area of a polygon, positive when counter-clockwise (shoelace formula).
fn signed_area(polygon: &[Xy]) -> f64 {
    let n = polygon.len();
    (0..n)
        .map(|i| {
            let [a, b] = [polygon[i], polygon[(i + 1) % n]];
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Polyline {
        Polyline::new([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]]).unwrap()
    }

    #[test]
    fn arc_length_and_points() {
        let p = square();
        assert_eq!(p.length(), 20.0);
        assert_eq!(p.point_at(5.0), [5.0, 0.0]);
        assert_eq!(p.point_at(15.0), [10.0, 5.0]);
        assert_eq!(p.point_at(-3.0), [0.0, 0.0]);
        assert_eq!(p.point_at(99.0), [10.0, 10.0]);
        assert_eq!(p.heading_at(5.0), 0.0);
        assert!((p.heading_at(15.0) - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    }

    #[test]
    fn projection_finds_the_closest_segment() {
        let p = square();
        let at = p.project([12.0, 4.0]);
        assert!((at.offset - 14.0).abs() < 1e-12 && (at.distance - 2.0).abs() < 1e-12);
        let before = p.project([-3.0, 4.0]);
        assert_eq!(before.offset, 0.0);
        assert!((before.distance - 5.0).abs() < 1e-12);
    }

    #[test]
    fn degenerate_polylines_are_refused() {
        assert!(Polyline::new([[1.0, 1.0], [1.0, 1.0]]).is_none());
        assert!(Polyline::new([[1.0, 1.0]]).is_none());
    }

    #[test]
    fn slice_starts_and_ends_where_asked() {
        assert_eq!(square().slice(5.0, 15.0), vec![[5.0, 0.0], [10.0, 0.0], [10.0, 5.0]]);
    }

    #[test]
    fn offset_keeps_lanes_parallel_through_corners() {
        let lane = square().offset_left(1.0);
        assert_eq!(lane.points(), &[[0.0, 1.0], [9.0, 1.0], [9.0, 10.0]]);
    }

    #[test]
    fn the_convex_hull_drops_inner_and_collinear_points() {
        let points = vec![
            [0.0, 0.0],
            [2.0, 0.0],
            [1.0, 0.0],
            [2.0, 2.0],
            [1.0, 1.0],
            [0.0, 2.0],
            [2.0, 2.0],
        ];
        assert_eq!(convex_hull(points), [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]);
        assert_eq!(convex_hull(vec![[1.0, 1.0], [2.0, 2.0]]).len(), 2);
    }

    #[test]
    fn arcs_stay_within_the_chord_error() {
        let points = arc([0.0, 0.0], 25.0, 0.0, std::f64::consts::TAU);
        for pair in points.windows(2) {
            let mid = lerp(pair[0], pair[1], 0.5);
            assert!(25.0 - distance(mid, [0.0, 0.0]) <= MAX_CHORD_ERROR + 1e-12);
        }
        let ring = Polyline::new(points).unwrap();
        assert!(ring.is_closed());
        // Inscribed chords are shorter than the arc: by 2πr·(π/N)²/6, 0.02 m here.
        assert!((ring.length() / (std::f64::consts::TAU * 25.0) - 1.0).abs() < 2e-4);
    }
}
