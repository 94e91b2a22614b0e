//! Partial visibility (issue 16, part 4) through the CLI: a requirement on
//! `mean_visible_fraction` is judged with its n over a scene counted by hand,
//! and results.json carries the sightings by class.
// See: issue 16, "Partial visibility".

use crate::support::{arg, read_json, requirement, sightline, temp_dir};

/// The hand-counted scene of the calibration tests (`cav` at (0, 20) facing
/// east, its 25 m lidar at its centre; the ego 30 m south, out of range of
/// everything below).
const SCENE: &str = include_str!("../fixtures/templates/wall-and-cooperator.yaml.in");

/// A car 5 m east of `cav` (x from 2.75 to 7.25, y from 19.1 to 20.9), wholly
/// seen; a car 10 m east, in its shadow (the near car spans ±18.1° from `cav`,
/// atan(0.9 / 2.75), the far one ±6.6°), wholly hidden by it; a pedestrian
/// (a circle of radius 0.3 m) whose centre, (11, 23.6), lies on the shadow's
/// edge, the line from `cav` through the near car's corner (2.75, 20.9): half
/// seen. Mean visible fraction (1 + 0 + 0.5) / 3 = 0.5 over n = 3 pairs.
const OTHERS: &str = "  - { id: near, kind: car, route: [we], start: { offset: 35 }, speed: { target: 0 } }
  - { id: far, kind: car, route: [we], start: { offset: 40 }, speed: { target: 0 } }
  - { id: walker, kind: pedestrian, path: [[11, 23.6], [12, 23.6]], speed: { target: 0 } }";

const REQUIREMENTS: &str = "requirements:
  - { id: VIS-HALF, text: Half of what is in view shows., check: { metric: mean_visible_fraction, at_least: 0.45 } }
  - { id: VIS-MORE, text: More shows., check: { metric: mean_visible_fraction, at_least: 0.55 } }
";

#[test]
fn a_mean_visible_fraction_requirement_is_judged_with_its_n() {
    let tmp = temp_dir();
    let (file, out) = (tmp.path().join("visibility.yaml"), tmp.path().join("evidence"));
    std::fs::write(&file, SCENE.replace("{others}", OTHERS).replace("{rest}", REQUIREMENTS)).unwrap();
    sightline(["run", arg(&file), "--out", arg(&out)]).assert_exit(1);

    let results = read_json(&out.join("results.json"));
    let sightings = &results["sweep"][0]["counts"]["sightings"];
    assert_eq!(
        (&sightings["los"], &sightings["nlos_static"], &sightings["nlos_dynamic"]),
        (&2.into(), &0.into(), &1.into()),
        "the near car and the half-hidden pedestrian in line of sight, the far car behind the near one"
    );
    for (id, verdict) in [("VIS-HALF", "pass"), ("VIS-MORE", "fail")] {
        let r = requirement(&results, id);
        assert_eq!(
            (&r["verdict"], &r["value"], &r["n"]),
            (&verdict.into(), &0.5.into(), &3.into()),
            "{id}"
        );
    }
}
