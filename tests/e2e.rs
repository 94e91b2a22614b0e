//! End-to-end tests of the `sightline` command line: the real binary on real
//! scenario files, checked against the CLI and evidence contracts of DESIGN.md.
//!
//! One test binary (like ripgrep's `tests/tests.rs`), its modules in `tests/e2e/`.
//! Expected files (invalid-input messages, golden evidence, generated docs) are
//! refreshed with `SIGHTLINE_BLESS=1 cargo test --test e2e`, never by hand.

// Helpers: running the binary, blessing expected files, redacting evidence.
#[path = "e2e/support.rs"]
mod support;

// `run` on valid scenarios: exit codes, the three evidence files, several files.
#[path = "e2e/run.rs"]
mod run;

// Invalid inputs and usage errors: exit 2, exact `file:line:col` messages, nothing written.
#[path = "e2e/invalid.rs"]
mod invalid;

// Not-exercised verdicts, sample sizes, and failures named in the summary, junit.xml and report.
#[path = "e2e/verdicts.rs"]
mod verdicts;

// Calibration of the fused grid: a brier_score requirement, the reliability table and diagram.
#[path = "e2e/calibration.rs"]
mod calibration;

// Collective perception over the radio: a dead radio, a perfect one a step late, selection.
#[path = "e2e/radio.rs"]
mod radio;
// Partial visibility: a mean_visible_fraction requirement judged with its n on a hand-counted scene.
#[path = "e2e/visibility.rs"]
mod visibility;

// The user's own system under test driven over ASAM OSI: failures are errors, examples judged.
#[path = "e2e/system.rs"]
mod system;

// Every key of the language changes the result or is refused, per kind of scenario.
#[path = "e2e/keys.rs"]
mod keys;

// Same file and seed give byte-identical evidence whatever the thread count; `--seed`.
#[path = "e2e/determinism.rs"]
mod determinism;

// junit.xml validated against Jenkins' junit-10.xsd and read with junitparser.
#[path = "e2e/junit.rs"]
mod junit;

// Redacted evidence of the fixtures against `tests/golden/<scenario>/`.
#[path = "e2e/golden.rs"]
mod golden;

// docs/ generated from the schema, and the bundled scenarios valid and linked to it.
#[path = "e2e/docs.rs"]
mod docs;

// results.json's published schema: generated from the wire types, every bundled
// and golden results.json valid against it, renamed keys refused.
#[path = "e2e/results_schema.rs"]
mod results_schema;

// `sightline export`: OpenSCENARIO and OpenDRIVE checked by the ASAM Quality Checker.
#[path = "e2e/export.rs"]
mod export;

// The bundled scenarios run end to end (the slow tests), each once.
#[path = "e2e/bundled.rs"]
mod bundled;

// run.mcap and `replay`: channels, counts, size, bytes whatever the thread
// count, the Python reader, replay on every bundled scenario, damaged recordings.
#[path = "e2e/record.rs"]
mod record;

// `run --osi`: osi.mcap as ASAM's OSI trace convention asks, read by ASAM's tools.
#[path = "e2e/osi.rs"]
mod osi;

// The recordings against the viewers' own artefacts: Foxglove's published
// schemas, their parsers' subset, every message valid (node, ci/viewers/).
#[path = "e2e/viewers.rs"]
mod viewers;
// The per-object record of a semantic run: one road user per category by hand,
// the bundled junction's road users counted by category.
#[path = "e2e/objects.rs"]
mod objects;
// The semantic pipeline's shares and close approaches, worked out by hand.
#[path = "e2e/semantic.rs"]
mod semantic;

// TTC, PET and DRAC: a scene judged by hand through the CLI, and
// commonroad-crime on two-road-user scenes where the definitions match.
#[path = "e2e/criticality.rs"]
mod criticality;
// One world: collective perception and the semantic pipeline together, judged
// road user by road user; the bundled joint junction; its shards.
#[path = "e2e/joint.rs"]
mod joint;

// The findings pages quote the bundled runs.
#[path = "e2e/findings.rs"]
mod findings;

// The bundled field experiment within sampling error of an independent numpy implementation.
#[path = "e2e/field_reference.rs"]
mod field_reference;

// `falsify`: the bundled counterexample found and shrunk, determinism, exit codes.
#[path = "e2e/falsify.rs"]
mod falsify;

// `run --shard K/N` and `merge`: merged evidence equals the unsharded run's; bad campaigns refused.
#[path = "e2e/shard.rs"]
mod shard;

// Evidence written as a set: a failed, killed or interrupted run never leaves a
// mix or a temporary; a commit cut short is finished by the next run.
#[path = "e2e/evidence_set.rs"]
mod evidence_set;

// `-`: the scenario on standard input, and what is refused.
#[path = "e2e/stdin.rs"]
mod stdin;

// `--template DIR`: custom report templates checked before anything runs, escaped, rendered.
#[path = "e2e/template.rs"]
mod template;

// report.html as a controlled document: its id by content, its scope per kind of world.
#[path = "e2e/report.rs"]
mod report;

// report.html in headless Chromium: every bundled report offline, banner and
// traceability as results.json says, markup in the scenario's text shown as text.
#[path = "e2e/browser.rs"]
mod browser;

// Mutated scenarios, damaged recordings and shard files under a memory and a
// time cap: refused with a location or run to a whole evidence set (issue 15).
#[path = "e2e/fuzz.rs"]
mod fuzz;

// Each class of hostile input of issue 15, made from a bundled scenario by a
// named edit, under the same caps; interrupted and failed writes of evidence.
#[path = "e2e/hostile.rs"]
mod hostile;

// The house rules on the source tree: file sizes, no mutual imports, the engine's closed interface.
#[path = "e2e/architecture.rs"]
mod architecture;
