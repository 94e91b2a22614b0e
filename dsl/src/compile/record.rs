//! The `record` section: which point `run.mcap` records, and how often it
//! records grids; and the recording's clock, `time.start`.

use super::budget::recording_budget;
use super::context::Context;
use super::requirements::select;
use crate::error::ErrorKind;
use crate::model::{DEFAULT_START, Experiment, Point, Record, RecordedPoints, grid_every};
use crate::path::Path;
use crate::raw::range;
use crate::raw::{RawRecord, RawRecordedPoints, RawTime};

/// Fused grids recorded per simulated second when the file does not say.
const DEFAULT_GRID_RATE: f64 = 1.0;

/// The earliest `time.start`: 1970-01-01T00:00:00Z, the recording's time 0.
const EARLIEST_START: &str = "1970-01-01T00:00:00Z";
/// The latest `time.start`, six years before the recording's Foxglove
/// timestamps, whose seconds are a `uint32`, overflow (2106-02-07T06:28:16Z).
const LATEST_START: &str = "2100-01-01T00:00:00Z";

/// Compiles `time.start`: nanoseconds since 1970-01-01T00:00:00Z, `DEFAULT_START`
/// without it; `None` (after recording why) when it is not a date and time with
/// its offset (within ±23:59, a leap second's :60 refused), or lies outside
/// 1970 to 2100.
pub(super) fn start(ctx: &mut Context<'_>, time: Option<&RawTime>) -> Option<u64> {
    let Some(text) = time.and_then(|t| t.start.as_deref()) else {
        return Some(DEFAULT_START);
    };
    let path = Path::root().key("time").key("start");
    let refused = refused_start(text);
    let Some(start) = text.parse::<jiff::Timestamp>().ok().filter(|_| refused.is_none()) else {
        ctx.error(
            &path,
            ErrorKind::InvalidType {
                expected: "an ISO 8601 date and time with its UTC offset, such as `2026-03-01T08:00:00Z` or \
                           `2026-03-01T09:00:00+01:00`"
                    .into(),
                found: format!("`{text}`{}", refused.unwrap_or_default()),
            },
        );
        return None;
    };
    let bound = |text: &str| text.parse::<jiff::Timestamp>().expect("a valid bound");
    if start < bound(EARLIEST_START) || start >= bound(LATEST_START) {
        ctx.error(
            &path,
            ErrorKind::OutOfRange {
                expected: format!("a time from {EARLIEST_START} to before {LATEST_START}"),
                found: text.into(),
            },
        );
        return None;
    }
    u64::try_from(start.as_nanosecond()).ok()
}

/// Why a start time that parses is refused all the same, as words following
/// it: an offset of a day or more, which no time zone has, or a leap second,
/// which the recording's clock (Foxglove's, seconds since 1970) cannot hold
/// and which would silently become the second before it.
fn refused_start(text: &str) -> Option<&'static str> {
    let (_, time) = text.split_once(['T', 't', ' '])?;
    let digits: String = time
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == ':')
        .filter(char::is_ascii_digit)
        .collect();
    if digits.get(4..6) == Some("60") {
        return Some(" (a leap second: give the second after it, :00 of the next minute)");
    }
    let offset = &time[time.find(['+', '-'])? + 1..];
    let hours: u32 = offset.get(..2)?.parse().ok()?;
    (hours > 23).then_some(" (an offset of a day or more: offsets lie within ±23:59)")
}

/// Compiles the `record` section (its defaults when `requested` and the file
/// has none), the recording's clock starting at `start`. Without points (the
/// setup is invalid) only what does not depend on them is checked.
pub(super) fn record(
    ctx: &mut Context<'_>,
    raw: Option<&RawRecord>,
    requested: bool,
    points: Option<&[Point]>,
    start: Option<u64>,
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
    if raw.agent_grids && raw.grid_rate == Some(0.0) {
        let why = "`grid_rate: 0` records no grid, so no agent's grid either";
        ctx.error_at_key(&path.key("agent_grids"), ErrorKind::NoEffect(why.into()));
        return None;
    }
    if raw.point.is_some() && !raw.filter.is_empty() {
        ctx.error(
            &path.key("where"),
            ErrorKind::Invalid("give `point` (an index) or `where` (settings), not both".into()),
        );
        return None;
    }
    let all = raw.points == Some(RawRecordedPoints::All);
    if all && (raw.point.is_some() || !raw.filter.is_empty()) {
        ctx.error(
            &path.key("points"),
            ErrorKind::Invalid(
                "`points: all` records every point; `point` and `where` choose one: give one or the other".into(),
            ),
        );
        return None;
    }
    let points = points?;
    if all
        && points
            .iter()
            .all(|p| matches!(p.setup.experiment, Experiment::Field(_)))
    {
        ctx.error(
            &path.key("points"),
            ErrorKind::Invalid(
                "the field experiment has no steps to record: a recording holds every point's outcome already; \
                 leave out `points`"
                    .into(),
            ),
        );
        return None;
    }
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
    let recorded: Vec<&Point> = if all {
        points.iter().collect()
    } else {
        vec![&points[point]]
    };
    // A rate written in the file must be one the steps can give; the default is
    // clamped to every step instead.
    if let Some(rate) = raw.grid_rate {
        let fastest = recorded
            .iter()
            .filter_map(|p| match &p.setup.experiment {
                Experiment::World(world) => Some(1.0 / world.step),
                Experiment::Field(_) => None,
            })
            .reduce(f64::min);
        if let Some(step_rate) = fastest.filter(|&step_rate| rate > step_rate * (1.0 + 1e-9)) {
            ctx.error(
                &path.key("grid_rate"),
                ErrorKind::OutOfRange {
                    expected: format!("at most the step rate, {step_rate} Hz (one grid per step)"),
                    found: rate.to_string(),
                },
            );
            return None;
        }
    }
    // Without a named point, any point may turn out to be the one recorded.
    let sized: Vec<&Point> = if all || raw.point.is_some() || !raw.filter.is_empty() {
        recorded
    } else {
        points.iter().collect()
    };
    if !recording_budget(ctx, &path, &sized, all, grid_rate, raw.agent_grids) {
        return None;
    }
    Some(Record {
        point,
        named: raw.point.is_some() || !raw.filter.is_empty(),
        grid_rate,
        grid_every: grid_every(&points[point], grid_rate),
        agent_grids: raw.agent_grids,
        start: start?,
        points: if all { RecordedPoints::All } else { RecordedPoints::One },
        slot: if all { slot(points) } else { 0 },
    })
}

/// The time from one recorded point's step 0 to the next's, nanoseconds: the
/// longest point's duration and a second, rounded up to a whole minute (so
/// each point starts on a whole minute of the recording's clock, with at least
/// a second of nothing between two).
fn slot(points: &[Point]) -> u64 {
    let longest = points
        .iter()
        .map(|p| match &p.setup.experiment {
            Experiment::World(world) => world.step * world.steps as f64,
            Experiment::Field(_) => 0.0,
        })
        .fold(0.0, f64::max);
    let minutes = ((longest + 1.0) / 60.0).ceil().max(1.0);
    // At most a day's run (the duration's range): some 1 441 minutes.
    (minutes as u64).saturating_mul(60_000_000_000)
}
