//! `sightline export` (issue 19, part 3): every bundled world and a falsify
//! counterexample written as OpenSCENARIO and OpenDRIVE, both files passing
//! the ASAM Quality Checker with no error and no warning when `SIGHTLINE_QC_PYTHON` names a
//! Python that has it (`.ci/run` sets it; with `CI` set the test fails rather
//! than skip without it); the sweep point chosen by label; the same bytes from
//! the same scenario; and scenarios it cannot export refused with nothing written.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::support::{arg, read, root, sightline, temp_dir, tool};

/// Names a Python with asam-qc-opendrive and asam-qc-openscenarioxml.
const QC_VAR: &str = "SIGHTLINE_QC_PYTHON";

const SCENARIO: &str = "scenario.xosc";
const MAP: &str = "scenario.xodr";

/// The Python with the ASAM Quality Checker, `None` (after saying why) when
/// none is named outside CI.
fn checker() -> Option<PathBuf> {
    tool(QC_VAR, "a Python with asam-qc-opendrive and asam-qc-openscenarioxml")
}

/// Runs the checker on an export's folder and panics on any error or warning
/// it reports.
#[track_caller]
fn assert_checked(python: &Path, dir: &Path) {
    let output = Command::new(python)
        .arg(root().join("tests/python/check_export.py"))
        .arg(dir)
        .output()
        .unwrap_or_else(|e| panic!("failed to start {}: {e}", python.display()));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "the ASAM Quality Checker found errors in {}:\n{stdout}{}",
        dir.display(),
        String::from_utf8_lossy(&output.stderr)
    );
    assert_eq!(stdout.matches(" 0 errors, 0 warnings,").count(), 2, "{stdout}");
}

/// Both files parse as XML 1.0, and no two entities share a name.
#[track_caller]
fn assert_well_formed(scenario: &str, map: &str) {
    roxmltree::Document::parse(map).unwrap_or_else(|e| panic!("the map is no XML: {e}"));
    let scenario = roxmltree::Document::parse(scenario).unwrap_or_else(|e| panic!("the scenario is no XML: {e}"));
    let mut names = std::collections::HashSet::new();
    for object in scenario.descendants().filter(|n| n.has_tag_name("ScenarioObject")) {
        let name = object.attribute("name").expect("a ScenarioObject has a name");
        assert!(names.insert(name), "two ScenarioObjects named {name:?}");
    }
}

/// Every bundled scenario file.
fn bundled() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(root().join("scenarios"))
        .expect("scenarios/ is readable")
        .map(|entry| entry.expect("an entry of scenarios/").path())
        .filter(|path| path.extension().is_some_and(|e| e == "yaml"))
        .collect();
    files.sort();
    files
}

#[test]
fn every_bundled_world_exports_and_passes_the_asam_checker() {
    let tmp = temp_dir();
    let python = checker();
    let mut exported = 0;
    for file in bundled() {
        let relative = file.strip_prefix(root()).expect("under the root");
        let out = tmp.path().join(file.file_stem().expect("a file name"));
        let outcome = sightline(["export", arg(relative), "--out", arg(&out)]);
        if read(&file).contains("\nfield:") {
            outcome.assert_exit(2);
            assert!(outcome.stderr.contains("error: nothing to export"), "{outcome}");
            assert!(!out.exists(), "nothing is written for a field experiment");
            continue;
        }
        outcome.assert_exit(0);
        assert!(outcome.stdout.starts_with("EXPORTED "), "{outcome}");
        let scenario = read(&out.join(SCENARIO));
        let map = read(&out.join(MAP));
        assert_well_formed(&scenario, &map);
        assert!(
            scenario.contains(r#"<FileHeader revMajor="1" revMinor="2""#),
            "{relative:?}"
        );
        assert!(scenario.contains(r#"<LogicFile filepath="scenario.xodr"/>"#));
        assert!(map.contains(r#"<header revMajor="1" revMinor="7""#), "{relative:?}");
        if let Some(python) = &python {
            assert_checked(python, &out);
        }
        exported += 1;
    }
    assert!(exported >= 4, "the bundled worlds: {exported}");
}

#[test]
fn a_counterexample_exports_and_passes_the_asam_checker() {
    let tmp = temp_dir();
    let search = tmp.path().join("search");
    sightline([
        "falsify",
        "scenarios/urban-falsify.yaml",
        "--cases",
        "8",
        "--out",
        arg(&search),
    ])
    .assert_exit(1);
    let counterexample = search.join("counterexample.yaml");
    let out = tmp.path().join("export");
    let outcome = sightline(["export", arg(&counterexample), "--out", arg(&out)]);
    outcome.assert_exit(0);
    // The counterexample's generated traffic is there, drawn from its seed.
    assert!(outcome.stdout.contains("generated)"), "{outcome}");
    let scenario = read(&out.join(SCENARIO));
    assert_well_formed(&scenario, &read(&out.join(MAP)));
    assert!(scenario.contains(r#"<ScenarioObject name="ego">"#));
    assert!(scenario.contains(r#"<MiscObject name="rsu" mass="100" miscObjectCategory="pole">"#));
    if let Some(python) = checker() {
        assert_checked(&python, &out);
    }
}

#[test]
fn the_same_scenario_exports_the_same_bytes_and_a_point_is_chosen_by_label() {
    let tmp = temp_dir();
    let file = "scenarios/roundabout-six-agents.yaml";
    let [a, b, c] = ["a", "b", "c"].map(|name| tmp.path().join(name));
    sightline(["export", file, "--out", arg(&a)]).assert_exit(0);
    sightline(["export", file, "--out", arg(&b)]).assert_exit(0);
    for name in [SCENARIO, MAP] {
        assert_eq!(
            read(&a.join(name)),
            read(&b.join(name)),
            "{name} differs between two exports"
        );
    }
    assert!(
        read(&a.join(SCENARIO)).contains("at v2x.penetration=0 (seed 7)"),
        "the first point by default"
    );
    let outcome = sightline([
        "export",
        file,
        "--point",
        "localization.position_sigma=0.5",
        "--out",
        arg(&c),
    ]);
    outcome.assert_exit(0);
    assert!(read(&c.join(SCENARIO)).contains("at localization.position_sigma=0.5 (seed 7)"));
    // The map is the same at every point; the agents' trajectories are not.
    assert_eq!(read(&a.join(MAP)), read(&c.join(MAP)));
    assert_ne!(read(&a.join(SCENARIO)), read(&c.join(SCENARIO)));
}

#[test]
fn an_unknown_point_a_world_without_roads_and_a_field_are_refused_with_nothing_written() {
    let tmp = temp_dir();
    let out = tmp.path().join("out");
    let unknown = sightline([
        "export",
        "scenarios/roundabout-six-agents.yaml",
        "--point",
        "nope",
        "--out",
        arg(&out),
    ]);
    unknown.assert_exit(2);
    assert!(
        unknown
            .stderr
            .contains("--point: no sweep point is labelled `nope` (the points: `v2x.penetration=0`"),
        "{unknown}"
    );
    let roads = sightline(["export", "tests/fixtures/export/no-roads.yaml", "--out", arg(&out)]);
    roads.assert_exit(2);
    assert_eq!(
        roads.stderr,
        "tests/fixtures/export/no-roads.yaml: error: nothing to export as a map: the scenario declares no \
         roads (OpenDRIVE needs at least one)\n"
    );
    let field = sightline(["export", "tests/fixtures/valid/small-field.yaml", "--out", arg(&out)]);
    field.assert_exit(2);
    assert!(!out.exists(), "nothing is written for a refused export");
}

/// `scenarios/urban-falsify.yaml` with `from` replaced by `to`, exported:
/// refused with nothing written, the error one line naming `shown`.
#[track_caller]
fn assert_refused(from: &str, to: &str, shown: &str) {
    let tmp = temp_dir();
    let file = tmp.path().join("scenario.yaml");
    let text = read(&root().join("scenarios/urban-falsify.yaml"));
    assert!(text.contains(from), "{from}");
    std::fs::write(&file, text.replacen(from, to, 1)).unwrap();
    let out = tmp.path().join("out");
    let outcome = sightline(["export", arg(&file), "--out", arg(&out)]);
    outcome.assert_exit(2);
    assert!(
        outcome.stderr.contains("error: ") && outcome.stderr.contains(shown),
        "{outcome}"
    );
    assert!(
        !outcome.stderr.chars().any(|c| c.is_control() && c != '\n'),
        "a control character reached standard error\n{outcome}"
    );
    assert!(!out.exists(), "nothing is written for a refused export");
}

/// A name or id holding a character XML 1.0 does not allow is refused,
/// never written into a malformed file: the language refuses it first (the
/// exporter's own refusal is tested in `reports::export::xml`).
#[test]
fn a_value_xml_cannot_hold_is_refused_with_nothing_written() {
    assert_refused(
        r#"name: "Urban junction, 10 s, falsify the RSU-to-ego link""#,
        r#"name: "Urban \x1b[1m junction""#,
        "U+001B",
    );
    assert_refused("- { id: rsu,", r#"- { id: "r\x01su","#, "U+0001");
    assert_refused("- { id: block_ne,", r#"- { id: "block\uFFFEne","#, "U+FFFE");
}

/// A declared agent named as generated traffic is (`route1-1`, the first
/// vehicle of the first route) makes no two entities of one name.
#[test]
fn an_agent_named_as_generated_traffic_is_refused() {
    assert_refused(
        "agents:\n",
        "agents:\n  - { id: route1-1, kind: pedestrian, path: [[100, 100], [101, 100]], speed: { target: 1 } }\n",
        "route1-1",
    );
}

/// The notes name what the files leave out of this scenario: the junctions'
/// connections of the network it imports, by its kind, an OpenDRIVE map's
/// sidewalks (a walker of the crossroads walks `road 4 lane -2`, one), and a
/// system under test.
#[test]
fn the_notes_say_what_is_left_out_by_the_map_s_kind() {
    let tmp = temp_dir();
    let export = |file: &str| {
        let outcome = sightline(["export", file, "--out", arg(&tmp.path().join(file.replace('/', "-")))]);
        outcome.assert_exit(0);
        outcome.stderr
    };
    let crossroads = export("scenarios/opendrive-crossroads-semantic.yaml");
    assert!(
        crossroads.contains("note: the connections across the OpenDRIVE map's junctions are not linked"),
        "{crossroads}"
    );
    assert!(
        crossroads.contains("note: the OpenDRIVE map's sidewalks and other walking lanes are not in the map"),
        "{crossroads}"
    );
    assert!(!crossroads.contains("SUMO"), "{crossroads}");
    let town = export("scenarios/sumo-town-semantic.yaml");
    assert!(
        town.contains("note: the connections across the SUMO network's junctions are not linked"),
        "{town}"
    );
    assert!(
        !town.contains("OpenDRIVE") && !town.contains("system under test"),
        "{town}"
    );
    let tracker = export("examples/osi-sut/tracker.yaml");
    assert!(
        tracker.contains("note: the system under test (`python3 examples/osi-sut/tracker.py`) is not exported"),
        "{tracker}"
    );
}

#[test]
fn an_export_that_cannot_be_put_in_place_leaves_neither_file() {
    let tmp = temp_dir();
    let out = tmp.path().join("out");
    // A directory where the map would go stops the commit before anything moves.
    std::fs::create_dir_all(out.join(MAP)).expect("a directory in the way");
    let outcome = sightline(["export", "scenarios/urban-falsify.yaml", "--out", arg(&out)]);
    outcome.assert_exit(3);
    assert!(!out.join(SCENARIO).exists(), "no half-written export:\n{outcome}");
    let left: Vec<String> = std::fs::read_dir(&out)
        .expect("the folder")
        .map(|e| e.expect("an entry").file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(left, vec![MAP.to_string()], "only the directory in the way");
}
