//! The `record` section: which point `run.mcap` records, and how often it
//! records grids.

use super::context::Context;
use super::requirements::select;
use crate::error::ErrorKind;
use crate::model::{Experiment, Point, Record};
use crate::path::Path;
use crate::raw::RawRecord;
use crate::raw::range;

/// Fused grids recorded per simulated second when the file does not say.
const DEFAULT_GRID_RATE: f64 = 1.0;

/// Compiles the `record` section (its defaults when `requested` and the file
/// has none). Without points (the setup is invalid) only what does not depend on
/// them is checked.
pub(super) fn record(
    ctx: &mut Context<'_>,
    raw: Option<&RawRecord>,
    requested: bool,
    points: Option<&[Point]>,
) -> Option<Record> {
    if raw.is_none() && !requested {
        return None;
    }
    let defaults = RawRecord::default();
    let raw = raw.unwrap_or(&defaults);
    let path = Path::root().key("record");
    let rate_ok = raw
        .grid_rate
        .is_none_or(|rate| ctx.within(&path.key("grid_rate"), rate, range::RATE_OR_ZERO));
    if raw.point.is_some() && !raw.filter.is_empty() {
        ctx.error(
            &path.key("where"),
            ErrorKind::Invalid("give `point` (an index) or `where` (settings), not both".into()),
        );
        return None;
    }
    let points = points?;
    let point = match raw.point {
        Some(index) => match usize::try_from(index).ok().filter(|&i| i < points.len()) {
            Some(index) => index,
            None => {
                ctx.error(
                    &path.key("point"),
                    ErrorKind::OutOfRange {
                        expected: format!(
                            "a point index below {} (the scenario has {} sweep point{})",
                            points.len(),
                            points.len(),
                            if points.len() == 1 { "" } else { "s" }
                        ),
                        found: index.to_string(),
                    },
                );
                return None;
            }
        },
        None if raw.filter.is_empty() => 0,
        None => *select(ctx, &raw.filter, points, &path.key("where"))?.first()?,
    };
    if !rate_ok {
        return None;
    }
    let grid_rate = raw.grid_rate.unwrap_or(DEFAULT_GRID_RATE);
    let grid_every = match &points[point].setup.experiment {
        Experiment::World(world) if grid_rate > 0.0 => {
            let step_rate = 1.0 / world.step;
            // A rate written in the file must be one the steps can give; the
            // default is clamped to every step instead.
            if raw.grid_rate.is_some() && grid_rate > step_rate * (1.0 + 1e-9) {
                ctx.error(
                    &path.key("grid_rate"),
                    ErrorKind::OutOfRange {
                        expected: format!("at most the step rate, {step_rate} Hz (one grid per step)"),
                        found: grid_rate.to_string(),
                    },
                );
                return None;
            }
            Some(((step_rate / grid_rate).round() as usize).max(1))
        }
        Experiment::World(_) | Experiment::Field(_) => None,
    };
    Some(Record {
        point,
        grid_rate,
        grid_every,
        agent_grids: raw.agent_grids,
    })
}
