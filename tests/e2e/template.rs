//! `--template DIR`: an organisation's report templates, checked before anything
//! runs (exit 2, nothing written, the file and what is wrong named), rendered
//! with auto-escaping on; the example set in docs/ for both pages.

use std::path::Path;

use crate::support::{
    SMALL_FIELD, arg, assert_evidence_files, files_under, normalise_execution, normalise_junit_times, read, sightline,
    temp_dir, unescape_html,
};

/// The example template set in the docs.
const EXAMPLE: &str = "docs/report-templates/example";

/// Writes a template set of `files` (name, text) into `dir`.
fn template_set(dir: &Path, files: &[(&str, &str)]) {
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
}

/// Runs the small field with the template set in `set` into `out`.
fn run_with(set: &Path, out: &Path) -> crate::support::Outcome {
    sightline(["run", SMALL_FIELD, "--out", arg(out), "--template", arg(set)])
}

/// A page that extends the bundled report shows its own blocks and everything
/// else of the report; only the report differs from a run without it.
#[test]
fn a_custom_template_overrides_a_block_of_the_report() {
    let tmp = temp_dir();
    let set = tmp.path().join("org");
    template_set(
        &set,
        &[
            (
                "report.html",
                "{% extends \"sightline/report.html\" %}\n\
                 {% block banner %}<p class=\"org\">ACME review of {{ report.name }}</p>{{ super() }}{% endblock %}\n\
                 {% block footer %}{% include \"parts/footer.txt\" %}{% endblock %}\n",
            ),
            (
                "parts/footer.txt",
                "Seed {{ results.seed }} <b>{{ report.verdict }}</b>",
            ),
        ],
    );
    let (custom, plain) = (tmp.path().join("custom"), tmp.path().join("plain"));
    run_with(&set, &custom).assert_exit(0);
    sightline(["run", SMALL_FIELD, "--out", arg(&plain)]).assert_exit(0);
    assert_evidence_files(&custom);

    let html = read(&custom.join("report.html"));
    assert!(
        html.contains("<p class=\"org\">ACME review of Small field"),
        "the override is shown"
    );
    assert!(
        html.contains("class=\"banner pass\""),
        "super() shows the bundled banner"
    );
    // A template's own markup is kept; the data it shows is escaped, even in a `.txt` include.
    assert!(html.contains("Seed 42 <b>pass</b>"), "the include is shown");
    let text = unescape_html(&html);
    for section in [
        "<h2>Provenance</h2>",
        "<h2>Requirements</h2>",
        "<h2>Evidence by requirement</h2>",
    ] {
        assert!(text.contains(section), "the inherited {section} is shown");
    }
    for name in ["results.json", "junit.xml"] {
        let evidence = |dir: &Path| match read(&dir.join(name)) {
            text if name == "junit.xml" => normalise_junit_times(&text),
            text => normalise_execution(&text),
        };
        assert_eq!(
            evidence(&custom),
            evidence(&plain),
            "{name} does not depend on the template"
        );
    }
}

/// A page that does not show a required block is refused before anything
/// runs: exit 2, the file and the block named, nothing written.
#[test]
fn a_missing_block_is_refused_and_nothing_is_written() {
    let tmp = temp_dir();
    let set = tmp.path().join("org");
    template_set(
        &set,
        &[(
            "report.html",
            "<h1>{{ report.name }}</h1>{% block banner %}{% endblock %}{% block traceability %}{% endblock %}",
        )],
    );
    let out = tmp.path().join("out");
    let refused = run_with(&set, &out);
    refused.assert_exit(2);
    assert_eq!(
        refused.stderr,
        format!(
            "{}/report.html: error: the page does not show required block `document_control`: a page of \
             `sightline run` must show the blocks document_control, banner, scope, assumptions, provenance, \
             traceability, evidence, selftest, appendix (extend `sightline/report.html` to inherit them)\n",
            set.display()
        )
    );
    assert!(refused.stdout.is_empty(), "{refused}");
    assert!(!out.exists(), "nothing is written");

    // A misspelt override would silently vanish: refused where it is written.
    template_set(
        &set,
        &[(
            "report.html",
            "{% extends \"sightline/report.html\" %}\n{% block provenence %}x{% endblock %}\n",
        )],
    );
    let refused = run_with(&set, &out);
    refused.assert_exit(2);
    assert!(
        refused.stderr.starts_with(&format!(
            "{}/report.html:2:4: error: block `provenence` is never shown",
            set.display()
        )),
        "{refused}"
    );
    assert!(!out.exists(), "nothing is written");
}

/// A run, a falsification or a merge whose `--out` is the template set's own
/// folder (or a folder in it) would replace the set's `report.html` with the
/// rendered page: refused with exit 2 before anything runs, the set as it
/// was.
// See: session 19's hostile-input check.
#[test]
fn a_set_written_over_its_own_templates_is_refused() {
    let tmp = temp_dir();
    let set = tmp.path().join("org");
    let page = "{% extends \"sightline/report.html\" %}\n";
    let search_page = "{% extends \"sightline/falsify.html\" %}\n";
    template_set(
        &set,
        &[
            ("report.html", page),
            ("falsify.html", search_page),
            ("nested/report.html", page),
            ("nested/falsify.html", search_page),
        ],
    );
    let search = ["falsify", "scenarios/urban-falsify.yaml", "--cases", "2"];
    let nested = set.join("nested");
    for (out, template) in [(&set, &set), (&nested, &set), (&nested, &nested)] {
        let run = run_with(template, out);
        let falsify = sightline(
            search
                .iter()
                .copied()
                .chain(["--out", arg(out), "--template", arg(template)]),
        );
        for outcome in [run, falsify] {
            outcome.assert_exit(2);
            assert_eq!(
                outcome.stderr,
                format!(
                    "{}: error: the evidence written into {} would replace this file, which the command reads; \
                     give another --out\n",
                    out.join("report.html").display(),
                    out.display()
                )
            );
        }
    }
    assert_eq!(read(&set.join("report.html")), page);
    assert_eq!(read(&set.join("nested/report.html")), page);
    assert_eq!(files_under(&set).len(), 4, "nothing is written into the set");
}

#[test]
fn a_syntax_error_names_the_file_line_and_column() {
    let tmp = temp_dir();
    let set = tmp.path().join("org");
    template_set(
        &set,
        &[
            (
                "report.html",
                "{% extends \"sightline/report.html\" %}\n{% block footer %}{% include \"footer.html\" %}{% endblock %}\n",
            ),
            (
                "footer.html",
                "<p>\n  {% for x in report.points %}{{ x.label }}\n</p>\n",
            ),
        ],
    );
    let out = tmp.path().join("out");
    let refused = run_with(&set, &out);
    refused.assert_exit(2);
    let prefix = format!("{}/footer.html:", set.display());
    assert!(refused.stderr.starts_with(&prefix), "{refused}");
    assert!(
        refused
            .stderr
            .contains(": error: syntax error: unexpected end of input"),
        "{refused}"
    );
    assert_eq!(refused.stderr.lines().count(), 1, "{refused}");
    assert!(!out.exists(), "nothing is written");
}

#[test]
fn a_missing_directory_or_page_is_refused() {
    let tmp = temp_dir();
    let out = tmp.path().join("out");
    let missing = tmp.path().join("no-such-set");
    let refused = run_with(&missing, &out);
    refused.assert_exit(2);
    assert_eq!(
        refused.stderr,
        format!(
            "{}: error: failed to read the template set: no such directory\n",
            missing.display()
        )
    );
    // A set for the other command only.
    let set = tmp.path().join("org");
    template_set(&set, &[("falsify.html", "{% extends \"sightline/falsify.html\" %}")]);
    let refused = run_with(&set, &out);
    refused.assert_exit(2);
    assert_eq!(
        refused.stderr,
        format!(
            "{}/report.html: error: no such file: a template set for `sightline run` holds `report.html`, which may \
             extend `sightline/report.html`\n",
            set.display()
        )
    );
    assert!(
        files_under(tmp.path()).iter().all(|f| f.starts_with("org")),
        "nothing is written"
    );

    // An invalid scenario and an invalid set: both are reported.
    let invalid = "tests/fixtures/invalid/vary-errors.yaml";
    let refused = sightline(["run", invalid, "--out", arg(&out), "--template", arg(&missing)]);
    refused.assert_exit(2);
    assert!(refused.stderr.contains("vary-errors.yaml:11:3: error:"), "{refused}");
    assert!(
        refused
            .stderr
            .contains("failed to read the template set: no such directory"),
        "{refused}"
    );
}

/// What only the data can tell (a misspelt field) fails when the page is
/// rendered: exit 2 with the place, and still nothing written.
#[test]
fn a_misspelt_field_is_refused_when_rendered() {
    let tmp = temp_dir();
    let set = tmp.path().join("org");
    template_set(
        &set,
        &[(
            "report.html",
            "{% extends \"sightline/report.html\" %}\n{% block footer %}\n{{ report.nmae }}{% endblock %}\n",
        )],
    );
    let out = tmp.path().join("out");
    let refused = run_with(&set, &out);
    refused.assert_exit(2);
    assert!(
        refused.stderr.starts_with(&format!("{}/report.html:3:", set.display())),
        "{refused}"
    );
    assert!(refused.stderr.contains("undefined value"), "{refused}");
    assert!(!out.exists(), "nothing is written");
}

/// A page whose loops would run for hours, or whose output would fill the
/// memory, runs out of its budget instead: exit 2 at the loop's line within
/// the caps, and nothing written. So does a filter asked for gigabytes of
/// text at once (`format`, `indent`), which aborted under the cap.
// See: session 17's outside check; session 20's report-area audit (F3).
#[test]
fn a_template_that_would_run_for_hours_is_refused_within_the_caps() {
    if !crate::support::caps_available() {
        return;
    }
    let tmp = temp_dir();
    let out_of_fuel = "failed to render the page: engine ran out of fuel";
    let too_large = "failed to render the page: invalid operation: the text would be";
    for (name, body, message) in [
        // 10^10 iterations: a quarter of an hour at about 10^7 a second.
        (
            "loops",
            "{% for i in range(100000) %}{% for j in range(100000) %}x{% endfor %}{% endfor %}",
            out_of_fuel,
        ),
        // 10^5 copies of the results: gigabytes.
        (
            "copies",
            "{% for i in range(100000) %}{{ results }}{% endfor %}",
            out_of_fuel,
        ),
        // 1.27 GB of text in one value, then a copy of it in the page.
        ("format", "{{ \"%1270000000s\"|format(\"a\") }}", too_large),
        ("indent", "{{ \"a\"|indent(1270000000, true) }}", too_large),
        (
            "replace",
            "{{ (\"a\" * 100000)|replace(\"a\", \"b\" * 100000) }}",
            too_large,
        ),
    ] {
        let set = tmp.path().join(name);
        template_set(
            &set,
            &[(
                "report.html",
                &format!("{{% extends \"sightline/report.html\" %}}\n{{% block footer %}}{body}{{% endblock %}}\n"),
            )],
        );
        let out = tmp.path().join(format!("out-{name}"));
        let refused = crate::support::sightline_capped(
            crate::support::root(),
            ["run", SMALL_FIELD, "--out", arg(&out), "--template", arg(&set)],
        );
        refused.assert_exit(2);
        assert!(
            refused.stderr.starts_with(&format!("{}/report.html:2", set.display())) && refused.stderr.contains(message),
            "{name}: {refused}"
        );
        assert!(!out.exists(), "{name}: nothing is written");
        assert!(
            files_under(tmp.path())
                .iter()
                .all(|f| !f.to_string_lossy().contains(".sightline-staging")),
            "{name}: no staging folder is left"
        );
    }
}

/// A template set's files are read where they are: a symbolic link in the
/// set (to a file, or a folder on the way) is refused before anything runs,
/// so a page cannot show `/etc/hostname` or `/proc/self/environ`.
// See: session 20's report-area audit (F4).
#[test]
fn a_template_read_through_a_symbolic_link_is_refused() {
    let tmp = temp_dir();
    let outside = tmp.path().join("outside");
    template_set(&outside, &[("secret.html", "SECRET")]);
    for (name, link, target) in [
        ("parts/x.html", "parts/x.html", outside.join("secret.html")),
        ("parts/secret.html", "parts", outside.clone()),
    ] {
        let set = tmp.path().join("org");
        let _ = std::fs::remove_dir_all(&set);
        template_set(
            &set,
            &[(
                "report.html",
                &format!(
                    "{{% extends \"sightline/report.html\" %}}\n{{% block footer %}}{{% include \"{name}\" %}}{{% endblock %}}\n"
                ),
            )],
        );
        std::fs::create_dir_all(set.join(link).parent().unwrap()).unwrap();
        std::os::unix::fs::symlink(&target, set.join(link)).unwrap();
        let out = tmp.path().join("out");
        let refused = run_with(&set, &out);
        refused.assert_exit(2);
        assert!(
            refused.stderr.starts_with(&format!("{}/{name}", set.display()))
                && refused.stderr.contains(&format!("`{link}` is a symbolic link")),
            "{refused}"
        );
        assert!(!out.exists(), "nothing is written");
    }
}

/// A filter this build does not have is refused when the set is checked,
/// before anything is simulated: exit 2 at its line and column.
// See: session 20's report-area audit (F5).
#[test]
fn an_unknown_filter_is_refused_before_anything_runs() {
    let tmp = temp_dir();
    let set = tmp.path().join("org");
    template_set(
        &set,
        &[(
            "report.html",
            "{% extends \"sightline/report.html\" %}\n{% block footer %}{{ results|tojson }}{% endblock %}\n",
        )],
    );
    let out = tmp.path().join("out");
    let refused = run_with(&set, &out);
    refused.assert_exit(2);
    assert_eq!(
        refused.stderr,
        format!(
            "{}/report.html:2:30: error: unknown filter: `tojson` is none of this build's (see docs/report-templates.md)\n",
            set.display()
        )
    );
    assert!(refused.stdout.is_empty(), "{refused}");
    assert!(!out.exists(), "nothing is written");
}

/// A value's text stays text whatever filters a page passes it through: the
/// audit's page, which spliced a captured `<` into a hostile scenario name's
/// escaped text, shows the name escaped.
// See: session 20's report-area audit (F2).
#[test]
fn a_hostile_name_stays_escaped_through_the_filters() {
    let tmp = temp_dir();
    let scenario = tmp.path().join("hostile.yaml");
    let text = read(&crate::support::root().join(SMALL_FIELD)).replace(
        "name: Small field, three fusion methods",
        "name: \"N <script>window.pwned=1</script>\"",
    );
    std::fs::write(&scenario, text).unwrap();
    let set = tmp.path().join("org");
    template_set(
        &set,
        &[(
            "report.html",
            "{% extends \"sightline/report.html\" %}\n{% set lt %}<{% endset %}{% set gt %}>{% endset %}\n\
             {% block footer %}{{ report.name|replace(\"&lt;\", lt)|replace(\"&gt;\", gt) }}{% endblock %}\n",
        )],
    );
    let out = tmp.path().join("out");
    sightline(["run", arg(&scenario), "--out", arg(&out), "--template", arg(&set)]).assert_exit(0);
    let html = read(&out.join("report.html"));
    assert!(!html.contains("<script>window"), "the name is shown as markup");
    assert!(
        html.contains("&lt;script&gt;window.pwned=1"),
        "the name is shown as text"
    );
}

/// The example set in the docs renders both pages.
#[test]
fn the_example_template_set_renders_both_pages() {
    let tmp = temp_dir();
    let run = tmp.path().join("run");
    sightline(["run", SMALL_FIELD, "--out", arg(&run), "--template", EXAMPLE]).assert_exit(0);
    let html = read(&run.join("report.html"));
    assert!(
        html.contains("ACME SAFETY") && html.contains("Verification record"),
        "masthead"
    );
    assert!(
        html.contains("Georgia") && html.contains(":root { --pass:"),
        "house style over sightline's"
    );
    let sha = crate::support::read_json(&run.join("results.json"))["scenario"]["sha256"]
        .as_str()
        .unwrap()
        .to_string();
    assert!(
        html.contains(&format!("Document ACME-VR-{}", &sha[..8])),
        "document control"
    );

    let falsify = tmp.path().join("falsify");
    let found = sightline([
        "falsify",
        "scenarios/urban-falsify.yaml",
        "--out",
        arg(&falsify),
        "--cases",
        "1",
        "--template",
        EXAMPLE,
    ]);
    found.assert_exit(1);
    let html = read(&falsify.join("report.html"));
    assert!(
        html.contains("Falsification record") && html.contains("Search seed 11"),
        "{html}"
    );
    assert!(
        html.contains("<h2>Cases tried</h2>"),
        "the bundled page's blocks are kept"
    );
}
