//! Comparisons of a metric with another on the same run (`check.relative_to`,
//! `check.by`): the other metric resolved (`baseline` to the metric's twin over
//! the ETSI baseline's messages), and the keys refused where they mean nothing.

use super::context::Context;
use crate::de::closest;
use crate::error::ErrorKind;
use crate::model::{Bound, Check, Comparison, Metric, OverSeeds};
use crate::path::Path;
use crate::raw::RawCheck;

/// What `relative_to` names for the ETSI baseline.
const BASELINE: &str = "baseline";

/// The check on `metric`: a comparison when `relative_to` is given, else a
/// plain metric check (over seeds, if given); `None` after recording why.
pub(super) fn metric_check(
    ctx: &mut Context<'_>,
    raw: &RawCheck,
    (metric, bound, over_seeds): (Metric, Bound, Option<OverSeeds>),
    path: &Path,
) -> Option<Check> {
    let Some(name) = &raw.relative_to else {
        if raw.by.is_some() {
            ctx.error(
                &path.key("by"),
                ErrorKind::Invalid("`by` says how `relative_to` compares; give `relative_to` too".into()),
            );
            return None;
        }
        return Some(Check::Metric {
            metric,
            bound,
            over_seeds,
        });
    };
    let at = path.key("relative_to");
    if over_seeds.is_some() {
        ctx.error(
            &at,
            ErrorKind::Invalid("a comparison is checked on the point's own run; remove `seeds`".into()),
        );
        return None;
    }
    let other = if name == BASELINE {
        let Some(twin) = metric.baseline() else {
            let twins: Vec<&str> = Metric::ALL
                .iter()
                .filter(|m| m.baseline().is_some())
                .map(|m| m.name())
                .collect();
            ctx.error(
                &at,
                ErrorKind::Invalid(format!(
                    "`{}` has no measurement over the ETSI baseline; these do: {}",
                    metric.name(),
                    twins.join(", ")
                )),
            );
            return None;
        };
        twin
    } else {
        let Some(&other) = Metric::ALL.iter().find(|m| m.name() == name) else {
            let hint = closest(name, Metric::ALL.iter().map(|m| m.name()).chain([BASELINE]))
                .map(|close| format!("; did you mean `{close}`?"))
                .unwrap_or_default();
            ctx.error(
                &at,
                ErrorKind::DanglingReference(format!(
                    "no metric `{name}` to compare with (give `{BASELINE}` or a metric's name{hint})"
                )),
            );
            return None;
        };
        other
    };
    if other == metric {
        ctx.error(
            &at,
            ErrorKind::Invalid(format!("`{name}` is the metric itself: compare with another")),
        );
        return None;
    }
    Some(Check::Compare {
        metric,
        other,
        by: raw.by.unwrap_or(Comparison::Ratio),
        bound,
    })
}

/// Records an error for `relative_to` or `by` in a check on no metric.
pub(super) fn refuse_without_metric(ctx: &mut Context<'_>, raw: &RawCheck, path: &Path) -> bool {
    let stray = [("relative_to", raw.relative_to.is_some()), ("by", raw.by.is_some())];
    match stray.iter().find(|(_, given)| *given) {
        Some((key, _)) => {
            ctx.error(
                &path.key(key),
                ErrorKind::Invalid(format!("`{key}` compares a `metric` with another")),
            );
            false
        }
        None => true,
    }
}
