//! A road's reference line (`<planView>`): its records (line, arc, spiral,
//! poly3, paramPoly3) read and checked to chain, and evaluated at any s.
//!
//! Coordinates are metres in the map's inertial frame (x east, y north),
//! headings radians counter-clockwise from +x; elevation is not read.

use roxmltree::Node;

use super::fresnel::fresnel;
use super::xml::{self, Locator, OpenDriveError};
use crate::Location;
use crate::geometry::Xy;
use crate::import::xml::Number;

/// Consecutive records must chain within this, metres: a record's `s` equal to
/// the previous one's `s + length`, and its start point the previous one's end.
pub const CHAIN_TOLERANCE: f64 = 0.01;

/// A point of the reference line and its direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Position, metres.
    pub position: Xy,
    /// Heading, radians counter-clockwise from +x.
    pub heading: f64,
}

impl Pose {
    /// The point `t` metres to the left of this one (right when negative).
    pub fn left(&self, t: f64) -> Xy {
        let (sin, cos) = self.heading.sin_cos();
        [self.position[0] - t * sin, self.position[1] + t * cos]
    }
}

/// One record of a reference line (`<geometry>`).
#[derive(Debug, Clone, PartialEq)]
pub struct Geometry {
    /// Where it starts along the road, metres.
    pub s: f64,
    /// Its start point.
    pub start: Pose,
    /// Its length, metres (> 0).
    pub length: f64,
    /// Its shape.
    pub shape: Shape,
    /// Where it is written.
    pub at: Location,
}

/// The shape of a record.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A straight line.
    Line,
    /// A circular arc of constant curvature (1/m, positive to the left).
    Arc {
        /// Curvature, 1/m.
        curvature: f64,
    },
    /// An Euler spiral (clothoid): curvature changing linearly with s.
    Spiral {
        /// Curvature at the start, 1/m.
        start: f64,
        /// Curvature at the end, 1/m.
        end: f64,
    },
    /// A cubic v(u) = a + b·u + c·u² + d·u³ in the record's frame (deprecated
    /// since OpenDRIVE 1.6, still read), u along the start heading.
    Poly3([f64; 4]),
    /// A parametric cubic (u(p), v(p)) in the record's frame.
    ParamPoly3 {
        /// Coefficients a, b, c, d of u(p).
        u: [f64; 4],
        /// Coefficients a, b, c, d of v(p).
        v: [f64; 4],
        /// Whether p runs over [0, 1] (`pRange="normalized"`) rather than
        /// [0, length] (`arcLength`).
        normalized: bool,
    },
}

/// Reads the records of `<planView>` and checks that they chain.
pub(crate) fn plan_view(node: Node, locator: &Locator) -> Result<Vec<Geometry>, OpenDriveError> {
    xml::allowed_children(node, &["geometry"], &[])?;
    let mut records: Vec<Geometry> = Vec::new();
    for child in xml::children(node, "geometry") {
        let record = geometry(child, locator)?;
        if let Some(previous) = records.last() {
            let end = previous.s + previous.length;
            if (record.s - end).abs() > CHAIN_TOLERANCE {
                return Err(xml::element_error(
                    child,
                    format!(
                        "the reference line does not chain: this record starts at s = {} but the previous one \
                         ends at s = {} (s + length)",
                        Number(record.s),
                        Number(end)
                    ),
                ));
            }
            let reached = Evaluator::new(previous).pose(previous.length).position;
            let gap = crate::geometry::distance(reached, record.start.position);
            if gap > CHAIN_TOLERANCE {
                return Err(xml::element_error(
                    child,
                    format!(
                        "the reference line does not close: this record starts at ({}, {}), {:.3} m from where \
                         the previous one ends ({:.3}, {:.3})",
                        Number(record.start.position[0]),
                        Number(record.start.position[1]),
                        Number(gap),
                        Number(reached[0]),
                        Number(reached[1])
                    ),
                ));
            }
        }
        records.push(record);
    }
    if records.is_empty() {
        return Err(xml::element_error(
            node,
            "<planView> holds no <geometry>: a road needs a reference line".into(),
        ));
    }
    Ok(records)
}

/// One `<geometry>`.
fn geometry(node: Node, locator: &Locator) -> Result<Geometry, OpenDriveError> {
    const SHAPES: [&str; 5] = ["line", "arc", "spiral", "poly3", "paramPoly3"];
    xml::allowed_children(node, &SHAPES, &[])?;
    let s = xml::non_negative(node, "s")?;
    let start = Pose {
        position: [xml::number(node, "x")?, xml::number(node, "y")?],
        heading: xml::number(node, "hdg")?,
    };
    let length = xml::non_negative(node, "length")?;
    let mut shapes = node.children().filter(roxmltree::Node::is_element);
    let (Some(kind), None) = (shapes.next(), shapes.next()) else {
        return Err(xml::element_error(
            node,
            "a <geometry> holds exactly one of <line>, <arc>, <spiral>, <poly3>, <paramPoly3>".into(),
        ));
    };
    let coefficients = |names: [&str; 4]| -> Result<[f64; 4], OpenDriveError> {
        Ok([
            xml::number(kind, names[0])?,
            xml::number(kind, names[1])?,
            xml::number(kind, names[2])?,
            xml::number(kind, names[3])?,
        ])
    };
    let shape = match kind.tag_name().name() {
        "line" => Shape::Line,
        "arc" => Shape::Arc {
            curvature: xml::number(kind, "curvature")?,
        },
        "spiral" => Shape::Spiral {
            start: xml::number(kind, "curvStart")?,
            end: xml::number(kind, "curvEnd")?,
        },
        "poly3" => Shape::Poly3(coefficients(["a", "b", "c", "d"])?),
        _ => Shape::ParamPoly3 {
            u: coefficients(["aU", "bU", "cU", "dU"])?,
            v: coefficients(["aV", "bV", "cV", "dV"])?,
            normalized: xml::choice(kind, "pRange", &["arcLength", "normalized"])? == Some("normalized"),
        },
    };
    Ok(Geometry {
        s,
        start,
        length,
        shape,
        at: locator.at(node),
    })
}

impl Geometry {
    /// The largest curvature along the record, 1/m; `None` for the cubics,
    /// whose curvature is not bounded from their coefficients alone.
    pub fn max_curvature(&self) -> Option<f64> {
        match self.shape {
            Shape::Line => Some(0.0),
            Shape::Arc { curvature } => Some(curvature.abs()),
            Shape::Spiral { start, end } => Some(start.abs().max(end.abs())),
            Shape::Poly3(_) | Shape::ParamPoly3 { .. } => None,
        }
    }
}

/// Evaluates a whole reference line at any s, each record's evaluator made once.
#[derive(Debug, Clone)]
pub(crate) struct ReferenceLine<'g> {
    records: Vec<Evaluator<'g>>,
}

impl<'g> ReferenceLine<'g> {
    /// An evaluator of the records of one road, in order of s.
    pub(crate) fn new(records: &'g [Geometry]) -> Self {
        Self {
            records: records.iter().map(Evaluator::new).collect(),
        }
    }

    /// The pose at `s`, in the record that holds it (the first before it, or
    /// the first one).
    pub(crate) fn pose(&self, s: f64) -> Pose {
        let i = self.records.partition_point(|e| e.geometry.s <= s).max(1) - 1;
        let record = &self.records[i];
        record.pose((s - record.geometry.s).clamp(0.0, record.geometry.length))
    }
}

/// Evaluates one record at any distance along it, with what the cubics need
/// precomputed: their arc length as a function of their parameter.
#[derive(Debug, Clone)]
pub(crate) struct Evaluator<'g> {
    geometry: &'g Geometry,
    /// For the cubics: (arc length, parameter) at increasing parameters, from
    /// (0, 0) to (the cubic's arc length, the parameter's end).
    table: Vec<(f64, f64)>,
}

/// The parameter of a cubic is tabulated every this many metres of arc.
const TABLE_STEP: f64 = 0.25;

/// 3-point Gauss–Legendre nodes and weights on [−1, 1].
const GAUSS: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];

impl<'g> Evaluator<'g> {
    /// An evaluator of `geometry`.
    pub(crate) fn new(geometry: &'g Geometry) -> Self {
        let mut evaluator = Self {
            geometry,
            table: Vec::new(),
        };
        evaluator.table = match geometry.shape {
            Shape::Poly3(_) => evaluator.arc_table(None),
            Shape::ParamPoly3 { normalized, .. } => {
                evaluator.arc_table(Some(if normalized { 1.0 } else { geometry.length }))
            }
            _ => Vec::new(),
        };
        evaluator
    }

    /// The pose at distance `ds` (0 ≤ ds ≤ length) along the record.
    pub(crate) fn pose(&self, ds: f64) -> Pose {
        let g = self.geometry;
        let (local, turn) = match g.shape {
            Shape::Line => ([ds, 0.0], 0.0),
            Shape::Arc { curvature } => arc(curvature, ds),
            Shape::Spiral { start, end } => spiral(start, (end - start) / g.length, ds),
            Shape::Poly3(v) => {
                let p = self.parameter(ds);
                ([p, cubic(&v, p)], derivative(&v, p).atan())
            }
            Shape::ParamPoly3 { u, v, .. } => {
                let p = self.parameter(ds);
                let (du, dv) = (derivative(&u, p), derivative(&v, p));
                ([cubic(&u, p), cubic(&v, p)], dv.atan2(du))
            }
        };
        let (sin, cos) = g.start.heading.sin_cos();
        Pose {
            position: [
                g.start.position[0] + local[0] * cos - local[1] * sin,
                g.start.position[1] + local[0] * sin + local[1] * cos,
            ],
            heading: g.start.heading + turn,
        }
    }

    /// A cubic's speed |d(u, v)/dp| at parameter `p`.
    fn speed(&self, p: f64) -> f64 {
        match self.geometry.shape {
            Shape::Poly3(v) => derivative(&v, p).hypot(1.0),
            Shape::ParamPoly3 { u, v, .. } => derivative(&u, p).hypot(derivative(&v, p)),
            _ => 1.0,
        }
    }

    /// A cubic's arc length from parameter `a` to `b`, by 3-point Gauss–Legendre.
    fn arc_between(&self, a: f64, b: f64) -> f64 {
        let (mid, half) = ((a + b) / 2.0, (b - a) / 2.0);
        GAUSS.iter().map(|&(x, w)| w * self.speed(mid + x * half)).sum::<f64>() * half
    }

    /// (arc length, parameter) pairs every [`TABLE_STEP`] of the record's
    /// length or finer: from p = 0 to p = `end`, or (without `end`, for
    /// poly3, whose speed is at least 1, so that length / step steps suffice)
    /// until the arc length reaches the record's length, the last step cut
    /// there.
    fn arc_table(&self, end: Option<f64>) -> Vec<(f64, f64)> {
        let length = self.geometry.length;
        let steps = (length / TABLE_STEP).ceil().max(16.0) as usize;
        let dp = end.map_or(length / steps as f64, |end| end / steps as f64);
        let mut table = Vec::with_capacity(steps + 1);
        table.push((0.0, 0.0));
        let mut arc = 0.0;
        for k in 0..steps {
            if end.is_none() && arc >= length {
                break;
            }
            arc += self.arc_between(k as f64 * dp, (k + 1) as f64 * dp);
            table.push((arc, (k + 1) as f64 * dp));
        }
        if end.is_none() {
            let n = table.len();
            if n >= 2 && table[n - 1].0 > length {
                let (a0, p0) = table[n - 2];
                table[n - 1] = (length, self.invert(p0, length - a0));
            }
        }
        table
    }

    /// The parameter `arc` metres of arc past parameter `p0`: a linear guess
    /// from the speed, refined by Newton steps on the arc length.
    fn invert(&self, p0: f64, arc: f64) -> f64 {
        let mut p = p0 + arc / self.speed(p0);
        for _ in 0..4 {
            p -= (self.arc_between(p0, p) - arc) / self.speed(p);
        }
        p
    }

    /// The cubic's parameter at arc length `ds` × (its arc length / the
    /// record's length), so that the record's end is the cubic's end even when
    /// the file's `length` is not exactly the cubic's arc length.
    fn parameter(&self, ds: f64) -> f64 {
        let (total, _) = *self.table.last().expect("a cubic's table has two entries or more");
        let target = ds / self.geometry.length * total;
        let i = self
            .table
            .partition_point(|&(arc, _)| arc <= target)
            .clamp(1, self.table.len() - 1);
        let (a0, p0) = self.table[i - 1];
        if target <= a0 { p0 } else { self.invert(p0, target - a0) }
    }
}

/// The point and the change of heading at `ds` along an arc of `curvature`
/// starting at the origin heading +x.
fn arc(curvature: f64, ds: f64) -> (Xy, f64) {
    let turn = curvature * ds;
    if curvature.abs() * ds < 1e-9 {
        // The chord formula loses precision as the turn vanishes.
        return ([ds, curvature * ds * ds / 2.0], turn);
    }
    ([turn.sin() / curvature, (1.0 - turn.cos()) / curvature], turn)
}

/// The point and the change of heading at `ds` along a clothoid starting at
/// the origin heading +x with curvature `start`, changing by `rate` per metre.
///
/// The clothoid is part of the standard one through the origin, whose
/// curvature is `rate · u` at arc length u and whose points are
/// √(π/|rate|) · (C(τ), ±S(τ)) with τ = u·√(|rate|/π); this one starts at
/// u₀ = start / rate on it, so its points are the standard one's from u₀,
/// moved to the origin and turned by the standard one's heading at u₀.
fn spiral(start: f64, rate: f64, ds: f64) -> (Xy, f64) {
    let turn = start * ds + rate * ds * ds / 2.0;
    // A rate this small bends the curve less than a nanometre from the arc over
    // any length a road has (the deviation is rate · ds³ / 6).
    if rate.abs() < 1e-12 {
        return (arc(start, ds).0, turn);
    }
    let scale = (std::f64::consts::PI / rate.abs()).sqrt();
    let sign = rate.signum();
    let standard = |u: f64| {
        let (c, s) = fresnel(u / scale);
        [scale * c, sign * scale * s]
    };
    let u0 = start / rate;
    let (a, b) = (standard(u0), standard(u0 + ds));
    let (sin, cos) = (-(rate * u0 * u0 / 2.0)).sin_cos();
    let [dx, dy] = [b[0] - a[0], b[1] - a[1]];
    ([dx * cos - dy * sin, dx * sin + dy * cos], turn)
}

/// a + b·p + c·p² + d·p³.
fn cubic(k: &[f64; 4], p: f64) -> f64 {
    k[0] + p * (k[1] + p * (k[2] + p * k[3]))
}

/// b + 2c·p + 3d·p².
fn derivative(k: &[f64; 4], p: f64) -> f64 {
    k[1] + p * (2.0 * k[2] + 3.0 * p * k[3])
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{FRAC_PI_2, PI};

    use approx::assert_relative_eq;

    use super::*;

    fn record(length: f64, shape: Shape) -> Geometry {
        Geometry {
            s: 0.0,
            start: Pose {
                position: [10.0, 20.0],
                heading: FRAC_PI_2,
            },
            length,
            shape,
            at: Location::new(1, 1),
        }
    }

    fn end(geometry: &Geometry) -> Pose {
        Evaluator::new(geometry).pose(geometry.length)
    }

    #[test]
    fn a_line_heading_north_ends_length_further_north() {
        let pose = end(&record(50.0, Shape::Line));
        assert_relative_eq!(pose.position[0], 10.0, epsilon = 1e-12);
        assert_relative_eq!(pose.position[1], 70.0, epsilon = 1e-12);
        assert_eq!(pose.heading, FRAC_PI_2);
    }

    #[test]
    fn a_quarter_circle_to_the_left_ends_one_radius_over() {
        // Radius 25 m, a quarter turn: from (10, 20) heading north to (−15, 45) heading west.
        let pose = end(&record(25.0 * FRAC_PI_2, Shape::Arc { curvature: 1.0 / 25.0 }));
        assert_relative_eq!(pose.position[0], -15.0, epsilon = 1e-9);
        assert_relative_eq!(pose.position[1], 45.0, epsilon = 1e-9);
        assert_relative_eq!(pose.heading, PI, epsilon = 1e-12);
        // To the right: negative curvature.
        let pose = end(&record(25.0 * FRAC_PI_2, Shape::Arc { curvature: -1.0 / 25.0 }));
        assert_relative_eq!(pose.position[0], 35.0, epsilon = 1e-9);
        assert_relative_eq!(pose.position[1], 45.0, epsilon = 1e-9);
    }

    #[test]
    fn a_spiral_from_straight_ends_at_the_published_fresnel_values() {
        // A clothoid from curvature 0 to π/L² · L over L = 100 m has rate π/L², so
        // its end is L · (C(1), S(1)) in its own frame: C(1) = 0.779893400376823,
        // S(1) = 0.438259147390355 (Abramowitz & Stegun, Table 7.7).
        let length = 100.0;
        let mut spiral = record(
            length,
            Shape::Spiral {
                start: 0.0,
                end: PI / length,
            },
        );
        spiral.start.heading = 0.0;
        spiral.start.position = [0.0, 0.0];
        let pose = end(&spiral);
        assert_relative_eq!(pose.position[0], 77.989_340_037_682_28, epsilon = 1e-9);
        assert_relative_eq!(pose.position[1], 43.825_914_739_035_48, epsilon = 1e-9);
        // Heading: the integral of the curvature, π/L · L / 2 = π/2.
        assert_relative_eq!(pose.heading, FRAC_PI_2, epsilon = 1e-12);
    }

    /// Integrates a heading function numerically (Simpson, fine steps).
    fn integrate(heading: impl Fn(f64) -> f64, length: f64) -> Xy {
        let n = 20_000;
        let h = length / n as f64;
        let mut point = [0.0, 0.0];
        for i in 0..=n {
            let weight = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            let theta = heading(i as f64 * h);
            point[0] += weight * theta.cos() * h / 3.0;
            point[1] += weight * theta.sin() * h / 3.0;
        }
        point
    }

    #[test]
    fn a_spiral_between_any_curvatures_follows_its_heading() {
        // Curvature from 0.05 down through zero to −0.02 over 80 m, from a
        // heading of 0.3 rad: compare with the integral of its heading.
        let (k0, k1, length) = (0.05, -0.02, 80.0);
        let mut spiral = record(length, Shape::Spiral { start: k0, end: k1 });
        spiral.start = Pose {
            position: [0.0, 0.0],
            heading: 0.3,
        };
        let evaluator = Evaluator::new(&spiral);
        let rate = (k1 - k0) / length;
        for ds in [10.0, 45.0, 80.0] {
            let expected = integrate(|u| 0.3 + k0 * u + rate * u * u / 2.0, ds);
            let pose = evaluator.pose(ds);
            assert_relative_eq!(pose.position[0], expected[0], epsilon = 1e-8);
            assert_relative_eq!(pose.position[1], expected[1], epsilon = 1e-8);
        }
        // Constant curvature: the arc.
        let same = record(30.0, Shape::Spiral { start: 0.04, end: 0.04 });
        let arc = record(30.0, Shape::Arc { curvature: 0.04 });
        assert_eq!(end(&same), end(&arc));
    }

    #[test]
    fn a_param_poly3_ends_at_its_polynomials_end() {
        // u(p) = 20p, v(p) = 3p² − 2p³ over p ∈ [0, 1]: from (0, 0) to (20, 1),
        // level at both ends; in the record's frame turned north and moved.
        let shape = Shape::ParamPoly3 {
            u: [0.0, 20.0, 0.0, 0.0],
            v: [0.0, 0.0, 3.0, -2.0],
            normalized: true,
        };
        let geometry = record(20.05, shape);
        let pose = end(&geometry);
        assert_relative_eq!(pose.position[0], 10.0 - 1.0, epsilon = 1e-9);
        assert_relative_eq!(pose.position[1], 20.0 + 20.0, epsilon = 1e-9);
        assert_relative_eq!(pose.heading, FRAC_PI_2, epsilon = 1e-12);
        // Half-way along the arc is half-way along p by symmetry: (10, 0.5) locally.
        let middle = Evaluator::new(&geometry).pose(geometry.length / 2.0);
        assert_relative_eq!(middle.position[0], 10.0 - 0.5, epsilon = 1e-4);
        assert_relative_eq!(middle.position[1], 20.0 + 10.0, epsilon = 1e-4);
        // The same curve with p in metres of arc (`arcLength`): p ends at the length.
        let shape = Shape::ParamPoly3 {
            u: [0.0, 1.0, 0.0, 0.0],
            v: [0.0, 0.0, 0.0, 0.0],
            normalized: false,
        };
        let pose = end(&record(12.0, shape));
        assert_relative_eq!(pose.position[1], 32.0, epsilon = 1e-9);
    }

    #[test]
    fn a_poly3_is_measured_along_its_arc() {
        // v(u) = 0.75u (a line at atan 0.75 = 36.87°): 25 m of arc end at u = 20, v = 15.
        let mut geometry = record(25.0, Shape::Poly3([0.0, 0.75, 0.0, 0.0]));
        geometry.start.heading = 0.0;
        let pose = end(&geometry);
        assert_relative_eq!(pose.position[0], 10.0 + 20.0, epsilon = 1e-9);
        assert_relative_eq!(pose.position[1], 20.0 + 15.0, epsilon = 1e-9);
        assert_relative_eq!(pose.heading, 0.75_f64.atan(), epsilon = 1e-12);
    }

    fn plan(text: &str) -> Result<Vec<Geometry>, String> {
        let doc = xml::parse(text).unwrap();
        plan_view(doc.root_element(), &Locator::new(text)).map_err(|e| e.to_string())
    }

    #[test]
    fn records_must_chain_in_s_and_in_space() {
        let ok = r#"<planView>
  <geometry s="0" x="0" y="0" hdg="0" length="10"><line/></geometry>
  <geometry s="10" x="10" y="0" hdg="0" length="5"><arc curvature="0.1"/></geometry>
</planView>"#;
        assert_eq!(plan(ok).unwrap().len(), 2);
        assert_eq!(
            plan(&ok.replace(r#"s="10" x="10""#, r#"s="12" x="10""#)).unwrap_err(),
            "3:3: the reference line does not chain: this record starts at s = 12 but the previous one ends at \
             s = 10 (s + length)"
        );
        assert_eq!(
            plan(&ok.replace(r#"x="10""#, r#"x="13""#)).unwrap_err(),
            "3:3: the reference line does not close: this record starts at (13, 0), 3.000 m from where the \
             previous one ends (10.000, 0.000)"
        );
        assert_eq!(
            plan(&ok.replace("<line/>", "<line/><arc curvature=\"1\"/>")).unwrap_err(),
            "2:3: a <geometry> holds exactly one of <line>, <arc>, <spiral>, <poly3>, <paramPoly3>"
        );
        assert_eq!(
            plan("<planView/>").unwrap_err(),
            "1:1: <planView> holds no <geometry>: a road needs a reference line"
        );
    }
}
