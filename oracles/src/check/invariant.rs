//! Invariants over every fused cell.

use sightline_dsl::Invariant;
use sightline_engine::outcome::MassAudit;

use super::{seen_among_too_few, short};
use crate::Evaluation;

/// Checks the mass-function invariant from the run's audit: no NaN or infinite
/// mass, every mass in [−tol, 1 + tol], every cell's masses summing to 1 within
/// tol. The value is the largest |Σ m − 1|; the margin is the smallest slack of
/// the three conditions. Fewer fused cells than `min_cells` (none, by default)
/// is not exercised, unless one already breaks the invariant (a failure); a
/// run without an audit is an error.
pub(crate) fn evaluate(invariant: Invariant, tolerance: f64, audit: Option<&MassAudit>, min_cells: u64) -> Evaluation {
    let Some(audit) = audit else {
        return Evaluation::error("this run fuses no cells".into());
    };
    match invariant {
        Invariant::MassFunction => mass_function(tolerance, audit, min_cells),
    }
}

fn mass_function(tolerance: f64, audit: &MassAudit, min_cells: u64) -> Evaluation {
    let n = audit.cells;
    let measured = format!("largest |Σm − 1| over n = {n} fused cells");
    // Too few fused cells leave the check not exercised, unless a cell
    // already breaks it: a violation seen is judged all the same.
    let too_few = n < min_cells;
    let seen = seen_among_too_few(n, min_cells);
    let (Some(min), Some(max)) = (audit.min_mass, audit.max_mass) else {
        if audit.non_finite > 0 {
            return Evaluation::failed(
                n,
                measured,
                format!("all {n} fused cells hold a NaN or infinite mass{seen}"),
            );
        }
        if too_few {
            return not_enough(n, min_cells, measured);
        }
        return Evaluation::error(format!("the audit counts {n} fused cells but no mass"));
    };
    if audit.non_finite > 0 {
        let message = format!(
            "{} of {n} fused cells hold a NaN or infinite mass{seen}",
            audit.non_finite
        );
        return Evaluation::failed(n, measured, message);
    }
    let margin = (tolerance - audit.max_sum_error)
        .min(min + tolerance)
        .min(1.0 + tolerance - max);
    if too_few && margin >= 0.0 {
        return not_enough(n, min_cells, measured);
    }
    let message = format!(
        "over {n} fused cells: masses in [{}, {}], largest |Σm − 1| = {} (tolerance {}){seen}",
        short(min),
        short(max),
        short(audit.max_sum_error),
        short(tolerance)
    );
    Evaluation::judged(audit.max_sum_error, margin, n, measured, message)
}

/// Fewer fused cells than the check needs, none of them breaking it.
fn not_enough(n: u64, min_cells: u64, measured: String) -> Evaluation {
    let message = format!("nothing to judge: {n} fused cells, fewer than the {min_cells} the check needs");
    Evaluation::not_exercised(n, measured, message)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Status;

    fn audit(min: f64, max: f64, sum_error: f64, non_finite: u64) -> MassAudit {
        MassAudit {
            cells: 10,
            non_finite,
            min_mass: Some(min),
            max_mass: Some(max),
            max_sum_error: sum_error,
        }
    }

    #[test]
    fn holds_within_tolerance() {
        let e = mass_function(1e-9, &audit(0.0, 1.0, 2e-16, 0), 1);
        assert_eq!((e.status, e.value, e.n), (Status::Pass, Some(2e-16), Some(10)));
        assert!(e.margin.unwrap() > 0.0);
    }

    #[test]
    fn fails_on_sum_range_or_nan() {
        assert_eq!(mass_function(1e-9, &audit(0.0, 1.0, 1e-6, 0), 1).status, Status::Fail);
        assert_eq!(mass_function(1e-9, &audit(-1e-3, 1.0, 0.0, 0), 1).status, Status::Fail);
        assert_eq!(mass_function(1e-9, &audit(0.0, 1.1, 0.0, 0), 1).status, Status::Fail);
        assert_eq!(mass_function(1e-9, &audit(0.0, 1.0, 0.0, 1), 1).status, Status::Fail);
    }

    #[test]
    fn nothing_fused_is_not_exercised() {
        let empty = MassAudit {
            cells: 0,
            non_finite: 0,
            min_mass: None,
            max_mass: None,
            max_sum_error: 0.0,
        };
        assert_eq!(mass_function(1e-9, &empty, 1).status, Status::NotExercised);
        // Ten cells where twenty are needed: all sound, not exercised.
        assert_eq!(
            mass_function(1e-9, &audit(0.0, 1.0, 2e-16, 0), 20).status,
            Status::NotExercised
        );
    }

    /// A NaN mass, or a sum off by 1e-6, among too few cells is a violation
    /// seen: a failure, however many cells the check needs.
    #[test]
    fn a_violation_among_too_few_cells_fails() {
        let e = mass_function(1e-9, &audit(0.0, 1.0, 0.0, 1), 20);
        assert_eq!((e.status, e.n), (Status::Fail, Some(10)));
        assert_eq!(
            e.message,
            "1 of 10 fused cells hold a NaN or infinite mass; a violation seen, judged though n = 10 is fewer than \
             the 20 the check needs"
        );
        let all_nan = MassAudit {
            cells: 10,
            non_finite: 10,
            min_mass: None,
            max_mass: None,
            max_sum_error: 0.0,
        };
        assert_eq!(mass_function(1e-9, &all_nan, 20).status, Status::Fail);
        let e = mass_function(1e-9, &audit(0.0, 1.0, 1e-6, 0), 20);
        assert_eq!((e.status, e.value), (Status::Fail, Some(1e-6)));
        assert_eq!(evaluate(Invariant::MassFunction, 1e-9, None, 1).status, Status::Error);
    }
}
