//! A perception world's steps in a recording: the fused grid and each
//! cooperating agent's own grid, cropped to the cells they hold, and the step's
//! cell signals (`/sightline/signals`), its counts added to the running sums.

use std::collections::BTreeMap;

use sightline_dsl::{Grid as CellGrid, Metric};
use sightline_engine::outcome::{CellTally, WorldMetrics};
use sightline_engine::trace::{CooperatorStep, FusedGrid, Measured, Observed, WorldStep};

use super::Recorder;
use super::channel::{GRID, SIGNALS};
use crate::mcap::foxglove::{Grid, Numeric, Time};
use crate::mcap::topic;
use crate::mcap::wire::{CellSignals, SignalsRecord};

/// A grid topic's fields, in order, and their type.
pub(super) type GridFields = (&'static [&'static str], Numeric);

/// `/fusion/grid`'s fields.
const FUSED_FIELDS: GridFields = (&["probability", "uncertainty"], Numeric::Float32);

/// `/perception/<id>/grid`'s field.
const AGENT_FIELDS: GridFields = (&["state"], Numeric::Uint8);

impl<W> Recorder<'_, W> {
    /// Everything a perception world's step shows: the agents, each
    /// cooperating agent's detections, the fused grid and the agents' own grids
    /// (at the grid rate), and the step's signals (in a joint world, kept to
    /// be published with the pipeline's).
    pub(super) fn publish_world_step(&mut self, step: &WorldStep<'_>) {
        let time = self.at(step.time);
        self.last = time;
        self.publish_agents(time, step.step, step.agents);
        self.publish_detections(time, step.cooperators);
        let grid_step = self.record.grids_at(step.step);
        let earlier = if grid_step {
            std::mem::take(&mut self.grids_shown)
        } else {
            BTreeMap::new()
        };
        let cells = step.measured.and_then(|measured| {
            let fused = measured.fused.first()?;
            if let Some(grid) = &fused.grid {
                self.publish_fused_grid(time, grid);
            }
            Some(self.cell_signals(&measured, &fused.cells))
        });
        if self.record.agent_grids && grid_step {
            self.publish_agent_grids(time, step.cooperators);
        }
        self.clear_grids_of(earlier, time);
        if self.joint() {
            self.pending_cells = cells;
            return;
        }
        let signals = SignalsRecord {
            point: self.record.point,
            step: step.step,
            cells,
            semantic: None,
        };
        self.publish(topic::SIGNALS, SIGNALS, time, &signals);
        self.publish_requirement_signals(step.step, time);
    }

    /// `/fusion/grid`: the fused grid cropped to the cells it holds.
    fn publish_fused_grid(&mut self, time: u64, fused: &FusedGrid<'_>) {
        let Some(grid) = self.grid else { return };
        let Some(crop) = Crop::around(&grid, fused.cells.iter().copied()) else {
            return;
        };
        let mut values = vec![f32::NAN; crop.cells() * 2];
        for ((&cell, &p), &u) in fused.cells.iter().zip(fused.probability).zip(fused.uncertainty) {
            let at = crop.index(&grid, cell) * 2;
            values[at] = p;
            values[at + 1] = u;
        }
        let data: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        self.show_grid(topic::FUSED_GRID.into(), time, FUSED_FIELDS, &crop, data);
    }

    /// `/perception/<id>/grid`: each cooperating agent's own grid, cropped to
    /// the cells it observed.
    fn publish_agent_grids(&mut self, time: u64, cooperators: &[CooperatorStep<'_>]) {
        let Some(grid) = self.grid else { return };
        for c in cooperators {
            let observation = c.observation;
            let Some(crop) = Crop::around(&grid, observation.touched().iter().copied()) else {
                continue;
            };
            let mut data = vec![0u8; crop.cells()];
            for &cell in observation.touched() {
                data[crop.index(&grid, cell)] = match observation.get(cell) {
                    Observed::Unknown => 0,
                    Observed::Free => 1,
                    Observed::Occupied => 2,
                    Observed::Own => 3,
                };
            }
            let topic = topic::agent_grid(&self.agent_id(c.agent));
            self.show_grid(topic, time, AGENT_FIELDS, &crop, data);
        }
    }

    /// Writes the `crop` of the grid holding `data` on `topic`, which the
    /// point's end clears.
    fn show_grid(&mut self, topic: String, time: u64, fields: GridFields, crop: &Crop, data: Vec<u8>) {
        let Some(grid) = self.grid else { return };
        let (names, kind) = fields;
        self.publish_grid(&topic, time, crop.grid(&grid, time, names, kind, data));
        self.grids_shown.insert(topic, fields);
    }

    /// Clears every grid topic the point showed: a grid of no cell on each.
    pub(super) fn clear_grids(&mut self, time: u64) {
        let shown = std::mem::take(&mut self.grids_shown);
        self.clear_grids_of(shown, time);
    }

    /// Clears each of the grid topics `earlier` that no grid was shown on since
    /// (an agent that left the scene, a grid holding no cell), so that nothing
    /// of an earlier step's grid stays on screen.
    fn clear_grids_of(&mut self, earlier: BTreeMap<String, GridFields>, time: u64) {
        for (topic, (names, kind)) in earlier {
            if !self.grids_shown.contains_key(&topic) {
                self.publish_grid(&topic, time, Grid::cleared(Time::from_nanos(time), names, kind));
            }
        }
    }

    /// Writes `grid` on `topic`, encoded by the writer thread.
    fn publish_grid(&mut self, topic: &str, time: u64, grid: Grid) {
        self.out
            .deferred(topic, GRID, time, grid.data_len(), move |out| grid.write_json(out));
    }

    /// The step's cell signals; adds the step to the running counts.
    fn cell_signals(&mut self, measured: &Measured<'_>, cells: &CellTally) -> CellSignals {
        let mut step = WorldMetrics::default();
        step.add_step(measured.ego_observed, measured.joint_observed, cells);
        if let Some(running) = &mut self.running.world {
            running.add_step(measured.ego_observed, measured.joint_observed, cells);
        }
        CellSignals {
            ego_observed: measured.ego_observed,
            joint_observed: measured.joint_observed,
            occupied: cells.occupied,
            detected: cells.detected,
            ego_detected: cells.ego_detected,
            false_positives: cells.false_positives,
            blind_occupied: cells.blind_occupied,
            blind_detected: cells.blind_detected,
            footprint_only: cells.footprint_only,
            self_report: cells.self_report,
            self_report_detected: cells.self_report_detected,
            self_report_only: cells.self_report_only,
            recall: step.value(Metric::OccupiedRecall),
            precision: step.value(Metric::OccupiedPrecision),
            blind_recall: step.value(Metric::BlindRecall),
            self_report_share: step.value(Metric::SelfReportShare),
            fov_gain: step.value(Metric::FovGain),
        }
    }
}

/// The rectangle of grid cells holding every given cell.
struct Crop {
    col: usize,
    row: usize,
    cols: usize,
    rows: usize,
}

impl Crop {
    /// The bounding box of `cells`; `None` when there are none.
    fn around(grid: &CellGrid, cells: impl Iterator<Item = usize>) -> Option<Self> {
        let mut bounds: Option<[usize; 4]> = None;
        for cell in cells {
            let (col, row) = (cell % grid.cols, cell / grid.cols);
            bounds = Some(match bounds {
                None => [col, row, col, row],
                Some([c0, r0, c1, r1]) => [c0.min(col), r0.min(row), c1.max(col), r1.max(row)],
            });
        }
        bounds.map(|[c0, r0, c1, r1]| Self {
            col: c0,
            row: r0,
            cols: c1 - c0 + 1,
            rows: r1 - r0 + 1,
        })
    }

    fn cells(&self) -> usize {
        self.cols * self.rows
    }

    /// The position of grid cell `cell` (inside the crop) in the crop's data.
    fn index(&self, grid: &CellGrid, cell: usize) -> usize {
        (cell / grid.cols - self.row) * self.cols + (cell % grid.cols - self.col)
    }

    fn grid(&self, grid: &CellGrid, time: u64, names: &[&'static str], kind: Numeric, data: Vec<u8>) -> Grid {
        let corner = [
            grid.origin[0] + self.col as f64 * grid.cell,
            grid.origin[1] + self.row as f64 * grid.cell,
        ];
        Grid::new(
            Time::from_nanos(time),
            corner,
            grid.cell,
            u32::try_from(self.cols).unwrap_or(u32::MAX),
            names,
            kind,
            data,
        )
    }
}
