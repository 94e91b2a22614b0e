//! `sightline falsify FILE [--cases N] [--budget SECONDS] [--seed N] [--search MODE] [--out DIR] [--jobs N] [--template DIR]`
//!
//! Each case sets every `vary` setting to a value of its grid, written out as a
//! concrete scenario (`sightline_dsl::instantiate`), compiled, simulated and
//! checked like `run` does; the search itself is `sightline_oracles::falsify`.

use std::collections::HashMap;
use std::path::Path;
use std::time::{Instant, SystemTime};

use anyhow::Context;
use rayon::prelude::*;
use sightline_dsl::{Options, Scenario, Vary, display_value};
use sightline_oracles::{Score, Search};
use sightline_reports::{
    Execution, Falsification, Page, case_values, falsify_html, falsify_json, falsify_junit, junit_xml, sha256_hex,
};

use crate::cli::{FalsifyArgs, SearchMode};
use crate::evidence::{EVIDENCE_SET, evidence_dirs, tool};
use crate::exit::Exit;
use crate::files::{DATA_LIMIT, read_regular};
use crate::input::load_all;
use crate::output::{relative, say, shell_word};
use crate::staging::Staging;
use crate::template::templates;
use crate::terminal::stderr;

/// Cases simulated side by side: one per core of the 2-core machines sightline
/// targets. A constant, not the thread count, so that the cases tried (and the
/// files written) do not depend on `--jobs`.
const CASES_PER_ROUND: usize = 2;

/// The most cases tried while shrinking a counterexample.
const SHRINK_CASES: u64 = 256;

/// Why the search stopped before its end.
enum Stop {
    /// A case's scenario is invalid (its errors, printed).
    Invalid(String),
    /// Anything else (exit 3).
    Internal(anyhow::Error),
}

/// Searches, then writes `falsify.json`, `junit.xml`, `report.html` and, when
/// a case breaks a requirement, `counterexample.yaml`.
pub fn falsify(args: &FalsifyArgs) -> anyhow::Result<Exit> {
    let input = load_all(std::slice::from_ref(&args.file), None, (false, false), Some(1))
        .and_then(|inputs| inputs.into_iter().next());
    let templates = templates(args.template.as_deref(), Page::Falsify);
    let (Some(input), Some(templates)) = (input, templates) else {
        return Ok(Exit::Invalid);
    };
    let path = input.name.clone();
    let scenario = &input.scenario;
    if scenario.vary.is_empty() {
        stderr!("{path}: error: nothing to falsify: the scenario has no `vary` section");
        return Ok(Exit::Invalid);
    }
    if scenario.requirements.is_empty() {
        stderr!("{path}: error: nothing to falsify: the scenario has no requirements");
        return Ok(Exit::Invalid);
    }
    if scenario.record.is_some() {
        stderr!(
            "{path}: note: record: no case of the search is recorded; the section is kept in counterexample.yaml, \
             which `sightline run` records"
        );
    }
    let text =
        sightline_dsl::utf8_text(&input.bytes).map_err(|_| anyhow::anyhow!("{path} was valid UTF-8 when compiled"))?;
    let Some(dir) = evidence_dirs(args.out.as_deref(), [&input], EVIDENCE_SET, args.template.as_deref())
        .and_then(|dirs| dirs.into_iter().next())
    else {
        return Ok(Exit::Invalid);
    };
    let mut staging = Staging::open(&dir, EVIDENCE_SET)?;
    let pool = super::run::worker_pool(args.jobs)?;
    let (started_at, started) = (SystemTime::now(), Instant::now());
    let search = Search {
        cases: args.cases,
        round: CASES_PER_ROUND,
        shrink_cases: SHRINK_CASES,
        seed: args
            .seed
            .or_else(|| scenario.points.first().map(|p| p.setup.seed))
            .unwrap_or_default(),
        guided: args.search == SearchMode::Guided,
        // A budget beyond what the clock can represent is no budget.
        deadline: args.budget.and_then(|budget| started.checked_add(budget)),
    };
    // Shrinking may come back to a case already tried: simulate each once.
    let mut scores: HashMap<Vec<u64>, Score> = HashMap::new();
    let counts: Vec<u64> = scenario.vary.iter().map(Vary::count).collect();
    let outcome = sightline_oracles::falsify(&counts, &search, |round| {
        let mut new: Vec<&Vec<u64>> = round.iter().filter(|indices| !scores.contains_key(*indices)).collect();
        new.dedup();
        let simulated: Vec<Result<Score, Stop>> = pool.install(|| {
            new.par_iter()
                .map(|indices| simulate_case(&path, text, &scenario.vary, indices))
                .collect()
        });
        for (indices, score) in new.into_iter().zip(simulated) {
            scores.insert(indices.clone(), score?);
        }
        Ok(round
            .iter()
            .filter_map(|indices| scores.get(indices).cloned())
            .collect())
    });
    let outcome = match outcome {
        Ok(outcome) => outcome,
        Err(Stop::Invalid(message)) => {
            stderr!("{message}");
            return Ok(Exit::Invalid);
        }
        Err(Stop::Internal(error)) => return Err(error),
    };
    let elapsed = started.elapsed();
    let mut command = format!(
        "sightline falsify {} --cases {} --seed {}",
        shell_word(&input.path),
        args.cases,
        search.seed
    );
    if !search.guided {
        command.push_str(" --search random");
    }
    if let Some(budget) = args.budget {
        command.push_str(&format!(" --budget {}", budget.as_secs_f64()));
    }
    let evaluations = scores.len();
    let rate = evaluations as f64 / elapsed.as_secs_f64().max(1e-9);
    let counterexample_path = dir.join("counterexample.yaml");
    let reproduce = format!("sightline run {}", shell_word(&counterexample_path));
    let tool = tool();
    let execution = Execution::on_this_machine(pool.current_num_threads(), started_at, elapsed);
    let found = outcome.counterexample.map(|i| &outcome.cases[i]);
    let falsification = Falsification {
        scenario,
        scenario_sha256: &sha256_hex(&input.bytes),
        search: &search,
        budget: args.budget.map(|b| b.as_secs_f64()),
        outcome: &outcome,
        simulations: evaluations,
        command: &command,
        reproduce: found.map(|_| reproduce.as_str()),
        tool: &tool,
        execution: &execution,
    };
    let report_json = falsify_json(&falsification)?;
    let junit_xml = junit_xml(&falsify_junit(&falsification))?;
    let report_html = match falsify_html(&falsification, &templates) {
        Ok(html) => html,
        // A custom template that fails on the data is the input's fault.
        Err(sightline_reports::Error::Template(error)) if templates.is_custom() => {
            stderr!("{error}");
            return Ok(Exit::Invalid);
        }
        Err(error) => return Err(error.into()),
    };
    staging.write("falsify.json", report_json.as_bytes())?;
    staging.write("junit.xml", junit_xml.as_bytes())?;
    staging.write("report.html", report_html.as_bytes())?;
    let Some(found) = found else {
        // The commit also removes a counterexample.yaml of an earlier search,
        // which would contradict this one.
        staging.commit()?;
        if outcome.cases.is_empty() {
            say(format_args!(
                "NOT EXERCISED {path}: no case was tried within the budget -> {}",
                dir.display()
            ));
            return Ok(Exit::Fail);
        }
        let closest = outcome
            .cases
            .iter()
            .filter_map(|c| c.score.margin.zip(c.score.requirement.as_ref()))
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(margin, id)| format!("; smallest margin {margin:.6} ({id})"))
            .unwrap_or_default();
        say(format_args!(
            "NONE {path}: no case of {} breaks a requirement{closest} ({evaluations} simulations, {rate:.1}/s) -> {}",
            outcome.cases.len(),
            dir.display()
        ));
        return Ok(Exit::Pass);
    };
    let mut settings = Vary::settings(&scenario.vary, &found.indices);
    settings.extend(imports_from(&dir, scenario)?);
    let case_text = sightline_dsl::instantiate(&path, text, &settings)
        .map_err(|errors| anyhow::anyhow!("failed to write the counterexample of {path}: {errors}"))?;
    let requirement = found.score.requirement.as_deref().unwrap_or("?");
    let margin = found
        .score
        .margin
        .map_or_else(|| "none".to_string(), |m| format!("{m:.6}"));
    let broken: Vec<String> = found
        .score
        .each
        .iter()
        .filter(|judged| judged.breaks)
        .map(|judged| {
            let margin = judged.margin.map_or_else(|| "none".to_string(), |m| format!("{m:.6}"));
            format!("{} ({}, margin {margin})", judged.id, judged.status.name())
        })
        .collect();
    let mut header = format!(
        "# A counterexample to {path}, found by\n#   {command}\n# It breaks {} with\n",
        broken.join(", ")
    );
    for (vary, &index) in scenario.vary.iter().zip(&found.indices) {
        header.push_str(&format!("#   {}: {}\n", vary.path, display_value(&vary.value(index))));
    }
    header.push_str(&format!("# Reproduce: {reproduce}\n"));
    staging.write("counterexample.yaml", (header + &case_text).as_bytes())?;
    staging.commit()?;
    let also = match broken.len() {
        0 | 1 => String::new(),
        n => format!(" and {} more", n - 1),
    };
    say(format_args!(
        "FOUND {path}: {requirement} {} (margin {margin}){also} at {}; first broken by case {}, {} cases in all ({evaluations} simulations, {rate:.1}/s) -> {}",
        found.score.status.name(),
        case_values(&scenario.vary, &found.indices),
        outcome.first_counterexample.unwrap_or_default(),
        outcome.cases.len(),
        dir.display()
    ));
    Ok(Exit::Fail)
}

/// Writes out, compiles, simulates and checks one case.
fn simulate_case(path: &str, text: &str, vary: &[Vary], indices: &[u64]) -> Result<Score, Stop> {
    let case_text = sightline_dsl::instantiate(path, text, &Vary::settings(vary, indices))
        .map_err(|errors| Stop::Internal(anyhow::anyhow!("failed to write a case of {path}: {errors}")))?;
    let disk = |file: &Path| read_regular(file, DATA_LIMIT);
    let options = Options {
        seed: None,
        loader: Some(&disk),
        record: false,
        osi: false,
        processes: Some(1),
    };
    // The errors' lines are in the case as written out, which is not kept:
    // each is named by its key instead.
    let case = sightline_dsl::compile(path, &case_text, &options).map_err(|errors| {
        let case = case_values(vary, indices);
        let lines: Vec<String> = errors
            .0
            .iter()
            .map(|error| match error.path.as_str() {
                "" => format!("{path}: error: vary: the case {case} is invalid: {}", error.kind),
                key => format!("{path}: error: vary: the case {case} is invalid: {key}: {}", error.kind),
            })
            .collect();
        Stop::Invalid(lines.join("\n"))
    })?;
    let run = sightline_engine::simulate(&case);
    Ok(Score::of(&sightline_oracles::check(&case, &run)))
}

/// The `traces` and `map` settings of `scenario` with each imported file's path relative
/// to `dir`, where its counterexample goes, so that it reads the same files.
fn imports_from(dir: &Path, scenario: &Scenario) -> anyhow::Result<Vec<(String, serde_json::Value)>> {
    if scenario.imports.is_empty() {
        return Ok(Vec::new());
    }
    std::fs::create_dir_all(dir).with_context(|| format!("failed to create {}", dir.display()))?;
    let dir = dir
        .canonicalize()
        .with_context(|| format!("failed to resolve {}", dir.display()))?;
    let mut settings: Vec<(String, serde_json::Value)> = Vec::new();
    // Only the files the scenario names: those a `sumocfg` names are relative
    // to the configuration, which stays where it is.
    for import in scenario.imports.iter().filter(|import| import.named) {
        let file = Path::new(&import.path)
            .canonicalize()
            .with_context(|| format!("failed to resolve {}", import.path))?;
        let relative = relative(&dir, &file);
        let text: serde_json::Value = relative
            .to_str()
            .with_context(|| format!("{} is not a UTF-8 path", relative.display()))?
            .into();
        let key = format!("{}.{}", import.kind.section(), import.kind.key());
        // `traces.routes` is a list of files, in order.
        match settings.iter_mut().find(|(k, _)| *k == key) {
            Some((_, serde_json::Value::Array(files))) => files.push(text),
            _ if import.kind == sightline_dsl::ImportKind::SumoRoutes => {
                settings.push((key, serde_json::Value::Array(vec![text])));
            }
            _ => settings.push((key, text)),
        }
    }
    Ok(settings)
}
