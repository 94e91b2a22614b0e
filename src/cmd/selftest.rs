//! `sightline selftest`: known answers, computed by hand, that sightline's own
//! code must reproduce on this machine. It is the "validation of the software
//! tool" evidence of a tool qualification (ISO 26262-8, 11.4.9; see
//! docs/qualification.md): each case names what it checks, the expected value
//! and where that value comes from.

use sightline_dsl::{Channel, Occluder, PathLossModel, Rule};
use sightline_engine::fusion::{Mass, Source, combine, fuse};
use sightline_engine::math::{Pose, Vector};
use sightline_engine::v2x::{Link, path_loss_db};
use sightline_engine::world::{Bodies, Body, Occluders, Visibility, visibility};
use sightline_oracles::{clopper_pearson_lower, mean_bound, wilson_lower};

use crate::exit::Exit;
use crate::output::say;

/// One known answer.
struct Case {
    id: &'static str,
    what: &'static str,
    expected: f64,
    got: f64,
    tolerance: f64,
}

impl Case {
    fn holds(&self) -> bool {
        (self.got - self.expected).abs() <= self.tolerance
    }
}

/// Runs every case, prints one line each and a summary; exit 0 when all hold.
pub fn selftest() -> Exit {
    let cases: Vec<Case> = [fusion(), visibility_cases(), channel(), statistics()]
        .into_iter()
        .flatten()
        .collect();
    for case in &cases {
        say(format_args!(
            "{} {:<8} {} (expected {}, got {}, tolerance {})",
            if case.holds() { "PASS" } else { "FAIL" },
            case.id,
            case.what,
            case.expected,
            case.got,
            case.tolerance
        ));
    }
    let held = cases.iter().filter(|c| c.holds()).count();
    say(format_args!(
        "sightline {} (git {}) selftest: {held} of {} known answers hold",
        env!("CARGO_PKG_VERSION"),
        env!("SIGHTLINE_GIT"),
        cases.len()
    ));
    if held == cases.len() { Exit::Pass } else { Exit::Fail }
}

/// Dempster's rule (seed 001, eq. 1) and Bayesian log-odds fusion, by hand.
fn fusion() -> Vec<Case> {
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
        case(
            "FUSE-01",
            "Dempster conflict k of (0.6,0.3,0.1)⊕(0.5,0.2,0.3)",
            0.27,
            c.conflict,
        ),
        case("FUSE-02", "Dempster m(empty) of the same", 0.53 / 0.73, c.mass.empty),
        case(
            "FUSE-03",
            "Dempster m(occupied) of the same",
            0.17 / 0.73,
            c.mass.occupied,
        ),
        case(
            "FUSE-04",
            "Dempster total conflict of certain empty ⊕ certain occupied",
            1.0,
            total.conflict,
        ),
        case("FUSE-05", "Bayesian fusion of two sources at p = 0.8", 16.0 / 17.0, p),
    ]
}

/// Line of sight (issue 3's hand-built cases): a 2 × 2 m target 20 m east of the
/// viewer, with a building or a truck between them, or beside the line.
fn visibility_cases() -> Vec<Case> {
    let building = Occluder {
        id: "building".into(),
        polygon: vec![[8.0, -5.0], [12.0, -5.0], [12.0, 5.0], [8.0, 5.0]],
    };
    let body = |agent: usize, x: f64, y: f64, half: [f64; 2]| Body {
        agent,
        pose: Pose::new(Vector::new(x, y), 0.0),
        half_extents: Vector::new(half[0], half[1]),
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
        exact(
            "VIS-01",
            "behind a building: NLoS-static (1)",
            1.0,
            class(&[building], vec![target]),
        ),
        exact(
            "VIS-02",
            "behind a truck: NLoS-dynamic (2)",
            2.0,
            class(&[], vec![target, truck]),
        ),
        exact(
            "VIS-03",
            "a truck beside the line: LoS (0)",
            0.0,
            class(&[], vec![target, beside]),
        ),
    ]
}

/// 3GPP TR 36.885 path loss at 5.9 GHz, vehicle antennas 1.5 m (table A.1.4-1).
fn channel() -> Vec<Case> {
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
    let db = |id, what, expected, got| Case {
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

/// Confidence bounds of checks over seeds.
fn statistics() -> Vec<Case> {
    let ten: Vec<f64> = (1..=10).map(f64::from).collect();
    vec![
        case(
            "STAT-01",
            "Clopper–Pearson lower 95 % bound, 30 of 30: 0.05^(1/30)",
            0.05f64.powf(1.0 / 30.0),
            clopper_pearson_lower(30, 30, 0.95),
        ),
        case(
            "STAT-02",
            "Wilson lower 95 % bound, 8 of 10",
            0.540792805687488,
            wilson_lower(8, 10, 0.95),
        ),
        Case {
            id: "STAT-03",
            what: "Student-t lower 95 % bound of the mean of 1…10: 5.5 − 1.833113·√(55/60)",
            expected: 5.5 - 1.833113 * (55.0f64 / 60.0).sqrt(),
            got: mean_bound(&ten, 0.95, false).1,
            tolerance: 1e-5,
        },
    ]
}

/// A floating-point answer to within 1e-9.
fn case(id: &'static str, what: &'static str, expected: f64, got: f64) -> Case {
    Case {
        id,
        what,
        expected,
        got,
        tolerance: 1e-9,
    }
}

/// An exact answer (a class code).
fn exact(id: &'static str, what: &'static str, expected: f64, got: f64) -> Case {
    Case {
        id,
        what,
        expected,
        got,
        tolerance: 0.0,
    }
}
