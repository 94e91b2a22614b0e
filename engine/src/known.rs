//! Known answers, computed by hand, that the engine's models must reproduce:
//! `sightline selftest` runs them on the user's machine (the "validation of the
//! software tool" evidence of a tool qualification; docs/qualification.md).

use sightline_dsl::{Channel, Occluder, PathLossModel, Rule};

use crate::fusion::{Mass, Source, combine, fuse};
use crate::math::{Pose, Vector};
use crate::semantic::{Criticality, OrientedBox, post_encroachment};
use crate::v2x::{Link, path_loss_db};
use crate::world::{Bodies, Body, Occluders, Visibility, visibility};

/// One known answer: what it checks, the value expected (and where it comes
/// from, in `what`), the value computed, and the tolerance between them.
#[derive(Debug, Clone, PartialEq)]
pub struct KnownAnswer {
    /// A stable identifier (`FUSE-01`).
    pub id: &'static str,
    /// What it checks.
    pub what: &'static str,
    /// The value computed by hand.
    pub expected: f64,
    /// The value the code computed.
    pub got: f64,
    /// The largest accepted difference.
    pub tolerance: f64,
}

impl KnownAnswer {
    /// A floating-point answer to within 1e-9.
    pub fn close(id: &'static str, what: &'static str, expected: f64, got: f64) -> Self {
        KnownAnswer {
            id,
            what,
            expected,
            got,
            tolerance: 1e-9,
        }
    }

    /// An exact answer (a class code).
    pub fn exact(id: &'static str, what: &'static str, expected: f64, got: f64) -> Self {
        KnownAnswer {
            id,
            what,
            expected,
            got,
            tolerance: 0.0,
        }
    }

    /// Whether the computed value is within the tolerance of the expected one.
    pub fn holds(&self) -> bool {
        (self.got - self.expected).abs() <= self.tolerance
    }
}

/// The engine's known answers: fusion, line of sight, the radio channel and
/// criticality.
pub fn known_answers() -> Vec<KnownAnswer> {
    [fusion(), visibility_cases(), channel(), criticality()]
        .into_iter()
        .flatten()
        .collect()
}

/// Dempster's rule (seed 001, eq. 1) and Bayesian log-odds fusion, by hand.
fn fusion() -> Vec<KnownAnswer> {
    // (e, o, u) = (0.6, 0.3, 0.1) ⊕ (0.5, 0.2, 0.3): k = 0.6·0.2 + 0.3·0.5 = 0.27;
    // m(E) = (0.30 + 0.18 + 0.05) / 0.73, m(O) = (0.06 + 0.09 + 0.02) / 0.73.
    let c = combine(Mass::new(0.6, 0.3, 0.1), Mass::new(0.5, 0.2, 0.3));
    // Two sources at p(occupied) = 0.8: log-odds ln 4 + ln 4, p = 16/17.
    let source = Source {
        mass: Mass::new(0.2, 0.8, 0.0),
        distance: 10.0,
    };
    let p = fuse(&Rule::Bayes, &[source, source]).decision_mass().occupied;
    let total = combine(Mass::new(1.0, 0.0, 0.0), Mass::new(0.0, 1.0, 0.0));
    vec![
        KnownAnswer::close(
            "FUSE-01",
            "Dempster conflict k of (0.6,0.3,0.1)⊕(0.5,0.2,0.3)",
            0.27,
            c.conflict,
        ),
        KnownAnswer::close("FUSE-02", "Dempster m(empty) of the same", 0.53 / 0.73, c.mass.empty),
        KnownAnswer::close(
            "FUSE-03",
            "Dempster m(occupied) of the same",
            0.17 / 0.73,
            c.mass.occupied,
        ),
        KnownAnswer::close(
            "FUSE-04",
            "Dempster total conflict of certain empty ⊕ certain occupied",
            1.0,
            total.conflict,
        ),
        KnownAnswer::close("FUSE-05", "Bayesian fusion of two sources at p = 0.8", 16.0 / 17.0, p),
    ]
}

/// Line of sight (issue 3's hand-built cases): a 2 × 2 m target 20 m east of the
/// viewer, with a building or a truck between them, or beside the line.
fn visibility_cases() -> Vec<KnownAnswer> {
    let building = Occluder {
        id: "building".into(),
        polygon: vec![[8.0, -5.0], [12.0, -5.0], [12.0, 5.0], [8.0, 5.0]],
    };
    let body = |agent: usize, x: f64, y: f64, half: [f64; 2]| {
        Body::rectangle(agent, Pose::new(Vector::new(x, y), 0.0), Vector::new(half[0], half[1]))
    };
    let target = body(1, 20.0, 0.0, [1.0, 1.0]);
    let truck = body(2, 10.0, 0.0, [6.0, 1.25]);
    let class = |occluders: &[Occluder], bodies: Vec<Body>| match visibility(
        &Occluders::new(occluders),
        &Bodies::new(bodies),
        Vector::ZERO,
        0,
        &target,
    ) {
        Visibility::Los => 0.0,
        Visibility::NlosStatic => 1.0,
        Visibility::NlosDynamic => 2.0,
    };
    let beside = body(2, 10.0, 8.0, [6.0, 1.25]);
    vec![
        KnownAnswer::exact(
            "VIS-01",
            "behind a building: NLoS-static (1)",
            1.0,
            class(&[building], vec![target]),
        ),
        KnownAnswer::exact(
            "VIS-02",
            "behind a truck: NLoS-dynamic (2)",
            2.0,
            class(&[], vec![target, truck]),
        ),
        KnownAnswer::exact(
            "VIS-03",
            "a truck beside the line: LoS (0)",
            0.0,
            class(&[], vec![target, beside]),
        ),
    ]
}

/// 3GPP TR 36.885 path loss at 5.9 GHz, vehicle antennas 1.5 m (table A.1.4-1).
fn channel() -> Vec<KnownAnswer> {
    let at = |model: PathLossModel, distance_m: f64, los: bool| {
        let channel = Channel {
            model,
            ..Channel::default()
        };
        let height = channel.vehicle_antenna_m;
        path_loss_db(
            &channel,
            &Link {
                distance_m,
                los,
                tx_antenna_m: height,
                rx_antenna_m: height,
            },
        )
    };
    let db = |id, what, expected, got| KnownAnswer {
        id,
        what,
        expected,
        got,
        tolerance: 1e-5,
    };
    vec![
        // 40 log10(50) + 20.056938 (the breakpoint form, WINNER+ B1).
        db(
            "CHAN-01",
            "urban LOS path loss at 50 m, dB",
            88.015738,
            at(PathLossModel::Tr36885Urban, 50.0, true),
        ),
        db(
            "CHAN-02",
            "urban NLOS path loss at 50 m, dB",
            109.711187,
            at(PathLossModel::Tr36885Urban, 50.0, false),
        ),
        db(
            "CHAN-03",
            "freeway path loss at 200 m, dB",
            93.837640,
            at(PathLossModel::Tr36885Highway, 200.0, true),
        ),
    ]
}

/// TTC, DRAC and PET on oriented boxes 4 m × 2 m (the unit tests of
/// `semantic::criticality` derive each).
fn criticality() -> Vec<KnownAnswer> {
    let along = |deg: f64| Vector::new(deg.to_radians().cos(), deg.to_radians().sin());
    let car = |x: f64, y: f64, deg: f64| OrientedBox::new(Vector::new(x, y), along(deg), 4.0, 2.0);
    let moving = |x, y, deg, speed: f64| (car(x, y, deg), along(deg) * speed);
    let of = |(ego, v_ego): (OrientedBox, Vector), (other, v_other): (OrientedBox, Vector)| {
        Criticality::of((&ego, v_ego), (&other, v_other))
    };
    let nan = f64::NAN;
    let head_on = of(moving(0.0, 0.0, 0.0, 10.0), moving(30.0, 0.0, 180.0, 5.0));
    let crossing = of(moving(0.0, 0.0, 0.0, 10.0), moving(20.0, -10.0, 90.0, 5.0));
    let rear = of(moving(0.0, 0.0, 0.0, 12.0), moving(20.0, 0.0, 0.0, 8.0));
    let corner = of(moving(0.0, 0.0, 0.0, 0.0), (car(10.0, 0.0, 45.0), along(180.0) * 2.0));
    let track = |from: Vector, deg: f64, speed: f64| -> Vec<(f64, OrientedBox)> {
        (0..120)
            .map(|k| {
                let t = f64::from(k) * 0.1;
                (t, OrientedBox::new(from + along(deg) * speed * t, along(deg), 4.0, 2.0))
            })
            .collect()
    };
    let pet = post_encroachment(
        &track(Vector::new(-0.25, 0.0), 0.0, 10.0),
        &track(Vector::new(20.0, -25.25), 90.0, 5.0),
    );
    vec![
        KnownAnswer::close(
            "CRIT-01",
            "TTC head on, 26 m closing at 15 m/s, s",
            26.0 / 15.0,
            head_on.ttc.unwrap_or(nan),
        ),
        KnownAnswer::close(
            "CRIT-02",
            "TTC crossing at right angles, s",
            1.7,
            crossing.ttc.unwrap_or(nan),
        ),
        KnownAnswer::close(
            "CRIT-03",
            "TTC of a box turned 45° touching corner first, s",
            (8.0 - 3.0 / 2f64.sqrt()) / 2.0,
            corner.ttc.unwrap_or(nan),
        ),
        KnownAnswer::close(
            "CRIT-04",
            "DRAC behind a slower car, 4² / (2 · 16) m/s²",
            0.5,
            rear.drac.unwrap_or(nan),
        ),
        KnownAnswer::close(
            "CRIT-05",
            "PET of a right-angle crossing sampled every 0.1 s, s",
            2.2,
            pet.unwrap_or(nan),
        ),
    ]
}
