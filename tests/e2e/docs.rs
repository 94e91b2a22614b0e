//! The generated docs stay in sync with the language, the template guide with the
//! bundled pages' blocks, and the bundled scenarios are valid and point editors
//! at the schema. Regenerate docs/schema.json and
//! docs/reference.md with `SIGHTLINE_BLESS=1 cargo test --test e2e docs::`.

use sightline_reports::{Page, Templates};

use crate::support::{arg, assert_matches_file, blessing, files_under, read, root, sightline};

/// The first line of every bundled scenario: the YAML language server then
/// validates and completes it against the schema.
const MODELINE: &str = "# yaml-language-server: $schema=../docs/schema.json";

#[test]
fn schema_json_is_the_output_of_sightline_schema() {
    let outcome = sightline(["schema"]);
    outcome.assert_exit(0);
    let schema: serde_json::Value = serde_json::from_str(&outcome.stdout).expect("the schema is JSON");
    assert!(
        schema["$schema"]
            .as_str()
            .is_some_and(|s| s.contains("json-schema.org"))
    );
    assert_matches_file("docs/schema.json", &outcome.stdout);
}

#[test]
fn reference_md_is_the_output_of_sightline_schema_markdown() {
    let outcome = sightline(["schema", "--markdown"]);
    outcome.assert_exit(0);
    assert!(outcome.stdout.starts_with("# "), "{outcome}");
    assert_matches_file("docs/reference.md", &outcome.stdout);
}

/// docs/report-templates.md has a row for every block the bundled pages show,
/// and marks the required ones.
#[test]
fn report_templates_md_documents_every_block() {
    let guide = read(&root().join("docs/report-templates.md"));
    for page in [Page::Run, Page::Falsify] {
        for block in Templates::bundled(page).blocks().unwrap() {
            let row = if page.required_blocks().contains(&block.as_str()) {
                format!("| `{block}` | yes |")
            } else {
                format!("| `{block}` |")
            };
            assert!(guide.contains(&row), "docs/report-templates.md lacks the row {row}");
        }
    }
}

#[test]
fn bundled_scenarios_are_valid_and_carry_the_schema_modeline() {
    let dir = root().join("scenarios");
    let scenarios: Vec<_> = files_under(&dir)
        .into_iter()
        .filter(|p| p.extension().is_some_and(|e| e == "yaml" || e == "yml"))
        .map(|p| dir.join(p))
        .collect();
    assert!(!scenarios.is_empty(), "no scenarios in {}", dir.display());
    for scenario in &scenarios {
        let first = read(scenario).lines().next().unwrap_or_default().to_string();
        assert_eq!(first, MODELINE, "first line of {}", scenario.display());
        sightline(["check", arg(scenario)]).assert_exit(0);
    }
    // While blessing, another test may be writing docs/schema.json right now.
    if !blessing() {
        assert!(
            dir.join("../docs/schema.json").is_file(),
            "the modeline points at docs/schema.json, which does not exist"
        );
    }
}

/// The fenced block of `language` that follows `marker` in `text`.
fn fenced_after<'a>(text: &'a str, marker: &str, language: &str) -> &'a str {
    let after = &text[text.find(marker).unwrap_or_else(|| panic!("no {marker:?}"))..];
    let fence = format!("```{language}\n");
    let start = after
        .find(&fence)
        .unwrap_or_else(|| panic!("no {language} block after {marker:?}"))
        + fence.len();
    let end = start + after[start..].find("```").expect("the block is closed");
    &after[start..end]
}

/// The README's example scenario passes as it says, and the error message it shows
/// for a negative γ is the one sightline prints.
#[test]
fn readme_example_runs_and_its_error_is_real() {
    let readme = read(&root().join("README.md"));
    let scenario = fenced_after(&readme, "## Writing a scenario", "yaml");
    let quoted_error = fenced_after(&readme, "Errors point at the line", "text");
    let tmp = crate::support::temp_dir();
    std::fs::write(tmp.path().join("small.yaml"), scenario).unwrap();
    crate::support::sightline_in(tmp.path(), ["run", "small.yaml", "--out", "out"]).assert_exit(0);
    let broken = scenario.replace("gamma: 10 }", "gamma: -3 }");
    assert_ne!(broken, scenario, "the example sets gamma: 10");
    std::fs::write(tmp.path().join("small.yaml"), broken).unwrap();
    let outcome = crate::support::sightline_in(tmp.path(), ["check", "small.yaml"]);
    outcome.assert_exit(2);
    assert_eq!(outcome.stderr, quoted_error, "the README quotes another message");
}
