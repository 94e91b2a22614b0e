//! Invariants over every fused cell.

use sightline_dsl::Invariant;
use sightline_engine::MassAudit;

use super::short;
use crate::Status;

/// Checks the mass-function invariant from the run's audit: no NaN or infinite
/// mass, every mass in [−tol, 1 + tol], every cell's masses summing to 1 within
/// tol. The value is the largest |Σ m − 1|; the margin is the smallest slack of
/// the three conditions.
pub(crate) fn evaluate(
    invariant: Invariant,
    tolerance: f64,
    audit: Option<&MassAudit>,
) -> (Status, Option<f64>, Option<f64>, String) {
    let Some(audit) = audit else {
        return (Status::Error, None, None, "this run fuses no cells".into());
    };
    match invariant {
        Invariant::MassFunction => mass_function(tolerance, audit),
    }
}

fn mass_function(tolerance: f64, audit: &MassAudit) -> (Status, Option<f64>, Option<f64>, String) {
    let (Some(min), Some(max)) = (audit.min_mass, audit.max_mass) else {
        return (Status::Error, None, None, "no fused cell to check".into());
    };
    if audit.non_finite > 0 {
        return (
            Status::Fail,
            None,
            None,
            format!(
                "{} of {} fused cells hold a NaN or infinite mass",
                audit.non_finite, audit.cells
            ),
        );
    }
    let margin = (tolerance - audit.max_sum_error)
        .min(min + tolerance)
        .min(1.0 + tolerance - max);
    let status = if margin >= 0.0 { Status::Pass } else { Status::Fail };
    let message = format!(
        "over {} fused cells: masses in [{}, {}], largest |Σm − 1| = {} (tolerance {})",
        audit.cells,
        short(min),
        short(max),
        short(audit.max_sum_error),
        short(tolerance)
    );
    (status, Some(audit.max_sum_error), Some(margin), message)
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let (status, value, margin, _) = mass_function(1e-9, &audit(0.0, 1.0, 2e-16, 0));
        assert_eq!(status, Status::Pass);
        assert_eq!(value, Some(2e-16));
        assert!(margin.unwrap() > 0.0);
    }

    #[test]
    fn fails_on_sum_range_or_nan() {
        assert_eq!(mass_function(1e-9, &audit(0.0, 1.0, 1e-6, 0)).0, Status::Fail);
        assert_eq!(mass_function(1e-9, &audit(-1e-3, 1.0, 0.0, 0)).0, Status::Fail);
        assert_eq!(mass_function(1e-9, &audit(0.0, 1.1, 0.0, 0)).0, Status::Fail);
        assert_eq!(mass_function(1e-9, &audit(0.0, 1.0, 0.0, 1)).0, Status::Fail);
    }

    #[test]
    fn nothing_fused_is_an_error() {
        let empty = MassAudit {
            cells: 0,
            non_finite: 0,
            min_mass: None,
            max_mass: None,
            max_sum_error: 0.0,
        };
        assert_eq!(mass_function(1e-9, &empty).0, Status::Error);
    }
}
