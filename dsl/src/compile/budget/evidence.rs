//! What a run's evidence repeats: its verdicts, the rows of results beside
//! them, and the text both carry, each written to results.json, junit.xml and
//! the report (`docs/limits.md`).

use super::limit;
use crate::compile::context::Context;
use crate::model::{Experiment, Point, Reference, Requirement};
use crate::path::Path;

/// The most verdicts a run gives: each requirement at each point it applies
/// to, each kept with its message and written to results.json, junit.xml and
/// the report.
pub const MAX_VERDICTS: f64 = 100_000.0;

/// The most rows of results a run writes beside its verdicts: each reference
/// figure at each point it applies to, and each distance band of a field at
/// each point, written to results.json and the report like a verdict.
pub const MAX_RESULT_ROWS: f64 = 100_000.0;

/// The most bytes of text the evidence repeats: each point's label, each
/// verdict's requirement text, point label and scenario name (junit.xml has a
/// case per requirement and point, each with all three), and each reference
/// row's source and label.
pub const MAX_TEXT_REPEATED: f64 = 5.0e7;

/// What the evidence repeats per verdict and per row of results.
pub(in crate::compile) struct Evidence<'a> {
    /// The scenario's name.
    pub name: &'a str,
    /// The sweep points, when they compiled.
    pub points: Option<&'a [Point]>,
    /// The requirements, compiled.
    pub requirements: &'a [Requirement],
    /// The reference figures, compiled.
    pub references: &'a [Reference],
}

/// Checks the verdicts and rows of results a run writes and the text they
/// repeat; returns whether all are within their limits.
pub(in crate::compile) fn evidence_budget(ctx: &mut Context<'_>, evidence: &Evidence<'_>) -> bool {
    let labels: Vec<f64> = (evidence.points.unwrap_or_default().iter())
        .map(|point| point.label().len() as f64)
        .collect();
    let label = |p: usize| labels.get(p).copied().unwrap_or(0.0);
    let name = evidence.name.len() as f64;
    let verdicts: f64 = evidence.requirements.iter().map(|r| r.points.len() as f64).sum();
    let references: f64 = evidence.references.iter().map(|r| r.points.len() as f64).sum();
    let bands: f64 = (evidence.points.unwrap_or_default().iter())
        .map(|point| match &point.setup.experiment {
            Experiment::Field(field) => field.distance_bands.len() as f64,
            Experiment::World(_) => 0.0,
        })
        .sum();
    let per_verdict =
        (evidence.requirements.iter()).flat_map(|r| r.points.iter().map(|&p| r.text.len() as f64 + label(p) + name));
    let per_reference =
        (evidence.references.iter()).flat_map(|r| r.points.iter().map(|&p| r.source.len() as f64 + label(p)));
    let text: f64 = labels.iter().copied().chain(per_verdict).chain(per_reference).sum();
    let root = Path::root();
    limit(
        ctx,
        &root.key("requirements"),
        verdicts,
        MAX_VERDICTS,
        "verdicts (requirements × the sweep points each applies to)",
        "check fewer requirements, or each at fewer points (`where`)",
    ) && limit(
        ctx,
        &if references > bands {
            root.key("references")
        } else {
            root.key("field").key("distance_bands")
        },
        references + bands,
        MAX_RESULT_ROWS,
        "rows of results beside the verdicts (reference figures × the points each applies to, and a field's \
         distance bands × the points)",
        "compare fewer reference figures, or each at fewer points (`where`), use fewer distance bands, or sweep \
         fewer points",
    ) && limit(
        ctx,
        &root.key("requirements"),
        text,
        MAX_TEXT_REPEATED,
        "bytes of text in the evidence (each point's label; per verdict its requirement's text, its point's label \
         and the scenario's name; per reference row its source and label)",
        "shorten the requirements' text, the scenario's name, the sweep labels or the references' sources, or \
         check each at fewer points",
    )
}
