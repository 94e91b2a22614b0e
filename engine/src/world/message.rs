//! The messages that carry a cooperating agent's grid to the ego over the
//! radio: the grid as runs of cells, their size in bytes, and the messages a
//! grid goes out in when it does not fit in one.
//!
//! # Encoding (ours)
//!
//! ETSI TS 103 324 V2.1.1 carries perceived objects and perception regions, not
//! occupancy grids, so the encoding of a grid is ours; it is counted in bytes so
//! that the size limit and the channel load are honest:
//! - every message carries a header of [`MESSAGE_HEADER_BYTES`] (ITS PDU header,
//!   management container, station data) and [`SENSOR_INFORMATION_BYTES`] per
//!   sensor (sensor information container), as ETSI TR 103 562 (Table 3)
//!   measures a CPM's mandatory fields, so that each message is interpretable on
//!   its own (TS 103 324 §6.1.2.1);
//! - the cells are maximal runs of consecutive cells of one grid row in one
//!   state (free, occupied, the sender's own footprint), at most 255 cells:
//!   4 bytes a run (first column 2, length 1, state 1);
//! - each row a message holds runs of adds 3 bytes (its index 2, its number of
//!   runs 1), again for every 255 runs.
//!
//! A grid larger than `max_bytes` is split ([`Oversize::Split`]: rows in order,
//! as many messages as it takes, each on its own over the channel) or reduced
//! to one message ([`Oversize::Select`]: the sender's footprint, then occupied
//! runs, then free runs nearest the sender first, up to the first that does not
//! fit).

use sightline_dsl::{Grid, MESSAGE_HEADER_BYTES, Oversize, SENSOR_INFORMATION_BYTES};

use super::observe::{Observation, Observed};
use super::raster::cell_center;
use crate::math::Point;

/// Bytes of one run of cells.
const RUN_BYTES: u32 = 4;
/// Bytes that announce a row's runs.
const ROW_BYTES: u32 = 3;
/// The most cells in a run, and runs under one row header.
const MAX_RUN: u32 = 255;

/// Consecutive cells of one grid row in one state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Run {
    /// Its first cell.
    pub(crate) start: usize,
    /// Its number of cells (1 to 255).
    pub(crate) len: u32,
    /// What the sender observed of its cells.
    pub(crate) state: Observed,
}

impl Run {
    /// Its cells.
    pub(crate) fn cells(&self) -> impl Iterator<Item = usize> {
        self.start..self.start + self.len as usize
    }
}

/// One message: runs of cells, in row order, and its size.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Message {
    /// The runs it carries.
    pub(crate) runs: Vec<Run>,
    /// Its size, bytes, header included.
    pub(crate) bytes: u32,
}

/// Bytes of a message's header for a sender with `sensors` sensors.
pub(crate) fn header_bytes(sensors: usize) -> u32 {
    MESSAGE_HEADER_BYTES + SENSOR_INFORMATION_BYTES * sensors as u32
}

/// The runs of `observation`'s observed cells on `grid`, in row order: the
/// cells from its first observed to its last (found in one pass), scanned row
/// by row (cheaper than sorting them; stretches of one state, unknown or not,
/// are crossed a block at a time).
pub(crate) fn runs(observation: &Observation, grid: &Grid) -> Vec<Run> {
    let touched = observation.touched();
    if touched.is_empty() {
        return Vec::new();
    }
    let (first, last) = touched.iter().fold((usize::MAX, 0), |(first, last), &cell| {
        (first.min(cell), last.max(cell))
    });
    let mut runs: Vec<Run> = Vec::new();
    for row in first / grid.cols..=last / grid.cols {
        let start = first.max(row * grid.cols);
        let cells = observation.cells(start..last.min(row * grid.cols + grid.cols - 1) + 1);
        let mut i = same_until(cells, 0, Observed::Unknown, cells.len());
        while i < cells.len() {
            let state = cells[i];
            let end = same_until(cells, i + 1, state, cells.len().min(i + MAX_RUN as usize));
            runs.push(Run {
                start: start + i,
                len: (end - i) as u32,
                state,
            });
            i = same_until(cells, end, Observed::Unknown, cells.len());
        }
    }
    runs
}

/// The first of `cells` from `i` to `limit` whose state is not `state`, or
/// `limit`: long stretches (unknown ones, free ones) are crossed 16 cells at a
/// time (a comparison of all 16 without an early exit, which the compiler
/// vectorises).
fn same_until(cells: &[Observed], mut i: usize, state: Observed, limit: usize) -> usize {
    const BLOCK: usize = 16;
    while i + BLOCK <= limit && cells[i..i + BLOCK].iter().fold(true, |same, &c| same & (c == state)) {
        i += BLOCK;
    }
    while i < limit && cells[i] == state {
        i += 1;
    }
    i
}

/// Fills messages of at most `max_bytes` with runs, counting each row's header
/// where a message starts holding the row's runs.
struct Packer {
    cols: usize,
    header: u32,
    max_bytes: u32,
    current: Message,
    /// The row of the current message's last run, and the runs under its header.
    row: Option<(usize, u32)>,
}

impl Packer {
    fn new(grid: &Grid, header: u32, max_bytes: u32) -> Self {
        Self {
            cols: grid.cols,
            header,
            max_bytes,
            current: Message {
                runs: Vec::new(),
                bytes: header,
            },
            row: None,
        }
    }

    /// What adding `run` costs the current message, and the row header state after it.
    fn cost(&self, run: &Run) -> (u32, (usize, u32)) {
        let row = run.start / self.cols;
        match self.row {
            Some((last, count)) if last == row && count < MAX_RUN => (RUN_BYTES, (row, count + 1)),
            _ => (ROW_BYTES + RUN_BYTES, (row, 1)),
        }
    }

    /// Adds `run` when it fits; returns whether it did.
    fn try_add(&mut self, run: Run) -> bool {
        let (cost, row) = self.cost(&run);
        if self.current.bytes + cost > self.max_bytes {
            return false;
        }
        self.current.bytes += cost;
        self.current.runs.push(run);
        self.row = Some(row);
        true
    }

    /// The current message, and a new empty one in its place.
    fn take(&mut self) -> Message {
        self.row = None;
        std::mem::replace(
            &mut self.current,
            Message {
                runs: Vec::new(),
                bytes: self.header,
            },
        )
    }
}

/// The messages `runs` go out in, each at most `max_bytes` with a header of
/// `header` bytes, by `oversize`; the sender's sensors at `sender` rank free
/// runs when it selects. No runs: one message, the header alone (the sender's
/// station data still goes out).
pub(crate) fn pack(
    runs: &[Run],
    grid: &Grid,
    header: u32,
    max_bytes: u32,
    oversize: Oversize,
    sender: Point,
) -> Vec<Message> {
    debug_assert!(
        header + ROW_BYTES + RUN_BYTES <= max_bytes,
        "`check` keeps room for a run"
    );
    let mut packer = Packer::new(grid, header, max_bytes);
    match oversize {
        Oversize::Split => {
            let mut messages = Vec::new();
            for &run in runs {
                if !packer.try_add(run) {
                    messages.push(packer.take());
                    let added = packer.try_add(run);
                    debug_assert!(added, "a run fits in an empty message");
                }
            }
            messages.push(packer.take());
            messages
        }
        Oversize::Select => {
            let rank = |run: &Run| match run.state {
                Observed::Own => 0,
                _ if run.state.is_occupied() => 1,
                _ => 2,
            };
            let distance = |run: &Run| {
                let middle = run.start + run.len as usize / 2;
                (cell_center(grid, middle) - sender).length()
            };
            let mut ranked: Vec<(u8, f64, Run)> = runs.iter().map(|r| (rank(r), distance(r), *r)).collect();
            ranked.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)).then(a.2.start.cmp(&b.2.start)));
            let mut chosen: Vec<Run> = Vec::new();
            let mut bytes = header;
            let mut rows = std::collections::HashMap::<usize, u32>::new();
            for (_, _, run) in ranked {
                let row = run.start / grid.cols;
                let count = rows.get(&row).copied().unwrap_or(0);
                let cost = RUN_BYTES + if count % MAX_RUN == 0 { ROW_BYTES } else { 0 };
                if bytes + cost > max_bytes {
                    break;
                }
                bytes += cost;
                rows.insert(row, count + 1);
                chosen.push(run);
            }
            chosen.sort_unstable_by_key(|run| run.start);
            vec![Message { runs: chosen, bytes }]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 10 × 4 grid of 1 m cells at the origin.
    fn grid() -> Grid {
        Grid {
            origin: [0.0, 0.0],
            cols: 10,
            rows: 4,
            cell: 1.0,
        }
    }

    fn run(start: usize, len: u32, state: Observed) -> Run {
        Run { start, len, state }
    }

    /// Runs break at a change of state, at a row's end and after 255 cells.
    #[test]
    fn runs_follow_rows_and_states() {
        let grid = grid();
        let mut observation = Observation::new(40);
        // Row 0: cells 7..10 free; row 1: 10, 11 free, 12 occupied.
        for cell in [7, 8, 9, 10, 11] {
            observation.mark(cell, Observed::Free);
        }
        observation.mark(12, Observed::Occupied);
        assert_eq!(
            runs(&observation, &grid),
            [
                run(7, 3, Observed::Free),
                run(10, 2, Observed::Free),
                run(12, 1, Observed::Occupied)
            ]
        );
        let wide = Grid {
            origin: [0.0, 0.0],
            cols: 600,
            rows: 1,
            cell: 1.0,
        };
        let mut observation = Observation::new(600);
        for cell in 0..300 {
            observation.mark(cell, Observed::Free);
        }
        assert_eq!(
            runs(&observation, &wide),
            [run(0, 255, Observed::Free), run(255, 45, Observed::Free)]
        );
    }

    /// Bytes by hand: a 156-byte header (one sensor), three runs in two rows:
    /// 156 + 2 × 3 + 3 × 4 = 174. With room for 170 bytes, the third run goes
    /// in a second message that repeats the header and the row's.
    #[test]
    fn split_counts_headers_rows_and_runs() {
        let grid = grid();
        let header = header_bytes(1);
        assert_eq!(header, 156);
        let runs = [
            run(7, 3, Observed::Free),
            run(10, 2, Observed::Free),
            run(12, 1, Observed::Occupied),
        ];
        let whole = pack(&runs, &grid, header, 1100, Oversize::Split, Point::new(0.0, 0.0));
        assert_eq!(whole.len(), 1);
        assert_eq!(whole[0].bytes, 174);
        let split = pack(&runs, &grid, header, 170, Oversize::Split, Point::new(0.0, 0.0));
        assert_eq!(
            split,
            [
                Message {
                    runs: runs[..2].to_vec(),
                    bytes: 156 + 3 + 4 + 3 + 4
                },
                Message {
                    runs: runs[2..].to_vec(),
                    bytes: 156 + 3 + 4
                },
            ]
        );
        // Nothing observed: the header alone.
        assert_eq!(
            pack(&[], &grid, header, 170, Oversize::Split, Point::new(0.0, 0.0)),
            [Message {
                runs: Vec::new(),
                bytes: 156
            }]
        );
    }

    /// Selecting keeps the own footprint, then occupied runs, then the free runs
    /// nearest the sender, and stops at the first that does not fit.
    #[test]
    fn select_ranks_own_then_occupied_then_near_free() {
        let grid = grid();
        let header = header_bytes(1);
        let runs = [
            run(0, 1, Observed::Free),      // (0.5, 0.5), near the sender
            run(8, 2, Observed::Free),      // far
            run(21, 1, Observed::Occupied), // row 2
            run(35, 1, Observed::Own),      // row 3
        ];
        let sender = Point::new(0.0, 0.0);
        // Room for three runs in three rows: own (7), occupied (7), near free (7).
        let selected = pack(&runs, &grid, header, header + 21, Oversize::Select, sender);
        assert_eq!(
            selected,
            [Message {
                runs: vec![runs[0], runs[2], runs[3]],
                bytes: header + 21
            }]
        );
    }
}
