//! report.html as a controlled document: its id names what was verified and
//! found, not how the scenario's path was typed, and its scope says what the
//! world simulates.

use std::collections::BTreeSet;
use std::path::Path;

use crate::bundled::every_run;
use crate::support::{FAILING, arg, read, root, sightline, sightline_in, temp_dir, unescape_html};

/// The document id of the report in `out`.
fn document_id(out: &Path) -> String {
    let html = read(&out.join("report.html"));
    let start = "<th scope=\"row\">Document id</th><td class=\"mono\">";
    let begin = html.find(start).expect("the report has a document id") + start.len();
    let id = &html[begin..begin + html[begin..].find("</td>").expect("the cell is closed")];
    assert!(id.starts_with("SL-") && id.len() == 19, "document id {id:?}");
    id.to_string()
}

/// The (aspect, value) rows of a report's scope table.
fn scope(report: &str) -> Vec<(String, String)> {
    let begin = report.find("<h2 id=\"scope\">").expect("the report has a scope");
    let table = &report[begin..begin + report[begin..].find("</table>").expect("the table is closed")];
    table
        .split("<tr><th scope=\"row\">")
        .skip(1)
        .map(|row| {
            let (aspect, rest) = row.split_once("</th><td>").expect("a row holds a cell");
            let value = rest.split_once("</td>").expect("the cell is closed").0;
            (unescape_html(aspect), unescape_html(value))
        })
        .collect()
}

/// The value of `aspect` in `rows`, if the scope has it.
fn row<'a>(rows: &'a [(String, String)], aspect: &str) -> Option<&'a str> {
    rows.iter().find(|(a, _)| a == aspect).map(|(_, v)| v.as_str())
}

/// The same scenario named four ways — as written, with `./`, absolute, and
/// from its own folder — gives one document id (auditor F9, session 20): a
/// scenario that imports SUMO files and warns about them, so the paths of
/// the imports and of the warnings, which results.json writes as reached,
/// differ too.
#[test]
fn the_document_id_does_not_depend_on_how_the_scenario_is_named() {
    let tmp = temp_dir();
    let scenario = "scenarios/sumo-grid-semantic.yaml";
    let absolute = root().join(scenario);
    let runs = [
        (root().to_path_buf(), scenario.to_string()),
        (root().to_path_buf(), format!("./{scenario}")),
        (root().to_path_buf(), arg(&absolute).to_string()),
        (root().join("scenarios"), "sumo-grid-semantic.yaml".to_string()),
    ];
    let mut ids = Vec::new();
    for (k, (dir, name)) in runs.iter().enumerate() {
        let out = tmp.path().join(k.to_string());
        sightline_in(dir, ["run", name.as_str(), "--out", arg(&out)]).assert_exit(0);
        let results = read(&out.join("results.json"));
        assert!(
            results.contains("\"warnings\": [\n    {"),
            "the scenario warns: {results}"
        );
        ids.push(document_id(&out));
    }
    assert!(ids.iter().all(|id| *id == ids[0]), "{ids:?}");
}

/// The falsification report's id does not depend on the spelling either: its
/// falsify.json names the scenario and the command as typed.
#[test]
fn the_falsify_document_id_does_not_depend_on_how_the_scenario_is_named() {
    let tmp = temp_dir();
    let scenario = "scenarios/urban-falsify.yaml";
    let ids: Vec<String> = [scenario.to_string(), format!("./{scenario}")]
        .iter()
        .enumerate()
        .map(|(k, name)| {
            let out = tmp.path().join(k.to_string());
            let search = sightline(["falsify", name.as_str(), "--cases", "2", "--out", arg(&out)]);
            assert!(matches!(search.code, Some(0 | 1)), "{search}");
            assert!(read(&out.join("falsify.json")).contains(name.as_str()));
            document_id(&out)
        })
        .collect();
    assert_eq!(ids[0], ids[1]);
}

/// One byte changed in the scenario (in a comment, which changes no result)
/// or in a file it imports gives another id; the same bytes under another
/// name give the same id.
#[test]
fn one_changed_byte_of_any_input_changes_the_document_id() {
    let tmp = temp_dir();
    let copy = |name: &str, scenario: &str, route: &str| {
        let dir = tmp.path().join(name);
        std::fs::create_dir_all(dir.join("sumo")).unwrap();
        std::fs::write(dir.join("s.yaml"), scenario).unwrap();
        for file in ["grid3x3.fcd.xml", "grid3x3.net.xml"] {
            std::fs::copy(root().join("scenarios/sumo").join(file), dir.join("sumo").join(file)).unwrap();
        }
        std::fs::write(dir.join("sumo/grid3x3.poly.xml"), route).unwrap();
        let out = dir.join("out");
        sightline(["run", arg(&dir.join("s.yaml")), "--out", arg(&out)]).assert_exit(0);
        document_id(&out)
    };
    let scenario = read(&root().join("scenarios/sumo-grid-semantic.yaml"));
    let poly = read(&root().join("scenarios/sumo/grid3x3.poly.xml"));
    assert!(scenario.starts_with("# ") && poly.ends_with('\n'));
    let original = copy("a", &scenario, &poly);
    assert_eq!(copy("b", &scenario, &poly), original, "the same bytes elsewhere");
    assert_ne!(
        copy("c", &scenario.replacen("# ", "#!", 1), &poly),
        original,
        "the scenario's comment"
    );
    assert_ne!(copy("d", &scenario, &format!("{poly}\n")), original, "an imported file");
}

/// The joint world's scope says what it simulates (auditor F13, session 20):
/// both collective perception and the semantic pipeline, for its one ego; the
/// grids the ego fuses (its own, the roadside unit's and the cooperating
/// car's, as `scenarios/junction-joint.yaml` declares them), the unit that
/// runs the pipeline, both radios, no `v2x.penetration`, which a joint world
/// refuses, and both fusion methods it sweeps, not the first (#18).
#[test]
fn the_scope_of_the_joint_world_says_what_it_simulates() {
    let rows = scope(&crate::joint::junction_run().report);
    assert_eq!(
        row(&rows, "Fusion"),
        Some("swept by `fusion.method` (see Sweep): {bayes, dempster}")
    );
    let experiment = row(&rows, "Experiment").expect("an experiment row");
    assert!(
        experiment.starts_with("joint world: collective perception") && experiment.contains("semantic pipeline"),
        "{experiment}"
    );
    assert_eq!(row(&rows, "Ego"), Some("ego"));
    assert_eq!(
        row(&rows, "Road users and units"),
        Some("2 cars, 1 roadside unit, 2 pedestrians")
    );
    assert_eq!(
        row(&rows, "Grids fused"),
        Some("the ego's and 2 cooperating agents': rsu, cav")
    );
    assert_eq!(
        row(&rows, "V2X, grids"),
        Some(
            "over the radio: channel tr36885_urban, latency 0.01 s, 10 Hz messages of at most 1100 bytes, evidence dropped after 1 s"
        )
    );
    assert_eq!(row(&rows, "Semantic pipeline"), Some("run by rsu"));
    assert_eq!(
        row(&rows, "V2X, pipeline"),
        Some("channel tr36885_urban, latency 0.01 s; generated and imported road users are not connected")
    );
    assert!(rows.iter().all(|(_, v)| !v.contains("penetration")), "{rows:?}");
}

/// Every bundled scenario's scope names its kind of experiment, and shows a
/// row only where its kind has it: grids in perception and joint worlds, the
/// pipeline in semantic and joint worlds, `v2x.penetration` (but as a swept
/// key) only in a semantic world with generated or imported vehicles to
/// connect. A row a sweep changes names swept keys only (#18).
#[test]
fn every_bundled_scope_describes_its_kind_of_world() {
    for run in every_run() {
        let rows = scope(&run.report);
        let experiment = row(&rows, "Experiment").expect("an experiment row");
        let text = read(&root().join(run.scenario));
        let file: serde_yaml::Mapping = serde_yaml::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", run.scenario));
        let has = |section: &str| file.contains_key(section);
        let (perception, semantic) = (has("perception"), has("semantic"));
        let kind = match (has("field"), perception, semantic) {
            (true, _, _) => "static evidential field",
            (_, true, true) => "joint world",
            (_, true, false) => "collective perception",
            _ => "roadside units' semantic pipeline",
        };
        assert!(experiment.starts_with(kind), "{}: {experiment}", run.scenario);
        assert_eq!(row(&rows, "Grids fused").is_some(), perception, "{}", run.scenario);
        assert_eq!(row(&rows, "Semantic pipeline").is_some(), semantic, "{}", run.scenario);
        let penetration = semantic && !perception && (has("traffic") || has("traces"));
        // A swept row's value, after the keys that sweep it.
        let shown = |v: &str| v.split_once("(see Sweep): ").map_or(v, |(_, shown)| shown).to_string();
        assert_eq!(
            rows.iter()
                .any(|(a, v)| a != "Sweep" && shown(v).contains("penetration")),
            penetration,
            "{}: {rows:?}",
            run.scenario
        );
        let sweep = row(&rows, "Sweep").expect("a sweep row");
        for (aspect, value) in &rows {
            let Some(keys) = value.strip_prefix("swept by ") else {
                continue;
            };
            let keys = keys.split_once(" (see Sweep): ").expect("the keys end").0;
            for key in keys.split(", ") {
                let key = key.trim_matches('`');
                assert!(sweep.contains(key), "{}: {aspect} names {key}, not swept", run.scenario);
            }
        }
    }
}

/// The roundabout's scope gives each radio setting it sweeps as the set of
/// its values, not its first (#18): the channel models, latencies and ages
/// of `scenarios/roundabout-six-agents.yaml`, the message rate it
/// does not sweep as written, and the keys that sweep them named.
#[test]
fn the_roundabout_scope_gives_the_radio_it_sweeps() {
    let rows = scope(&crate::bundled::roundabout_run().report);
    assert_eq!(
        row(&rows, "V2X, grids"),
        Some(
            "swept by `v2x.channel.model`, `v2x.latency`, `v2x.messages.max_age` (see Sweep): over the radio: \
             channel {tr36885_urban, ideal}, latency {0.02, 0.1, 0.3} s, 10 Hz messages of at most 1100 bytes, \
             evidence dropped after {0.1, 0.3, 1} s"
        )
    );
    let grids = row(&rows, "Grids fused").expect("a grids row");
    assert!(
        grids.starts_with("swept by `v2x.penetration` (see Sweep): {the ego's own only: no other agent cooperates; "),
        "{grids}"
    );
    assert_eq!(row(&rows, "Fusion"), Some("bayes"));
}

/// docs/report-templates.md lists every field a template receives in
/// `report` (auditor F12, session 20): a template set that walks `report`
/// (`tests/fixtures/templates/keys`) writes out its key paths on the pages of
/// runs that between them fill every kind of field (a failing requirement, an
/// accepted not-exercised one, published figures, a joint world's pictures,
/// charts and sweep), and the doc's data section names each as `path`. A
/// field added to the view without a line in the doc fails here.
#[test]
fn the_template_data_contract_lists_every_field_of_the_report() {
    let doc = read(&root().join("docs/report-templates.md"));
    let begin = doc
        .find("### `report` of `report.html`")
        .expect("the doc has the run page's data");
    let section = &doc[begin..begin + doc[begin + 4..].find("\n### ").expect("a section follows") + 4];
    let tmp = temp_dir();
    let mut shown = BTreeSet::new();
    for (k, scenario) in [
        FAILING,
        "tests/fixtures/not-exercised/junction-idle.yaml",
        "tests/fixtures/valid/small-field.yaml",
        "scenarios/junction-joint.yaml",
    ]
    .into_iter()
    .enumerate()
    {
        let out = tmp.path().join(k.to_string());
        let template = "tests/fixtures/templates/keys";
        let run = sightline(["run", scenario, "--template", template, "--out", arg(&out)]);
        assert!(matches!(run.code, Some(0 | 1)), "{run}");
        let html = read(&out.join("report.html"));
        let begin = html.find("<pre id=\"keys\">").expect("the page lists its keys");
        let keys = &html[begin..begin + html[begin..].find("</pre>").expect("the list is closed")];
        shown.extend(keys.lines().skip(1).map(|line| {
            let path = line.strip_prefix("report.").unwrap_or_else(|| panic!("{line:?}"));
            path.trim_end_matches("[]").to_string()
        }));
    }
    for path in [
        "name",
        "findings[].accepted",
        "requirements[].points[].label",
        "points[].pictures.images[].legend.swatches[].colour",
        "comparisons[].n",
        "appendix.content[].end",
    ] {
        assert!(shown.contains(path), "the walk missed {path}: {shown:?}");
    }
    let missing: Vec<&String> = shown
        .iter()
        .filter(|path| !section.contains(&format!("`{path}`")))
        .collect();
    assert!(missing.is_empty(), "docs/report-templates.md does not list {missing:?}");
}

/// Beneath each figure of a sweep table, its n (a user audit: the roundabout's
/// recall over penetration rose while its population shrank, and no table
/// said so). Checked on the bundled roundabout's first table: each row's first
/// figure, `occupied_recall`, carries that point's sample size.
#[test]
fn every_figure_of_a_sweep_table_carries_its_n() {
    let run = crate::bundled::roundabout_run();
    let report = &run.report;
    let begin = report.find("<h2>Results over").expect("the report has a sweep table");
    let table = &report[begin..begin + report[begin..].find("</table>").expect("the table is closed")];
    let body = &table[table.find("<tbody>").expect("a body")..];
    let rows: Vec<&str> = body.split("<tr>").skip(1).collect();
    let points = run.results["sweeps"][0]["points"]
        .as_array()
        .expect("the sweep's points");
    assert_eq!(rows.len(), points.len(), "one row per point");
    for (row, point) in rows.iter().zip(points) {
        let index = point.as_u64().expect("a point index") as usize;
        let n = run.results["sweep"][index]["samples"]["occupied_recall"]
            .as_u64()
            .expect("occupied_recall's n");
        let shown = row
            .split("<span class=\"n\">n = ")
            .nth(1)
            .and_then(|rest| rest.split('<').next())
            .unwrap_or_else(|| panic!("a row without n: {row}"));
        assert_eq!(shown.replace(',', ""), n.to_string(), "{row}");
    }
}
