//! The ground truth of a step: which counted cells road users occupy, which
//! of them a cooperating agent's own body covers (self-report), and whose
//! footprint each occupied cell is, against which the fused grids are tallied
//! and the snapshot is drawn.

use sightline_dsl::Grid;

use super::raster::{Raster, box_cells};
use super::sight::{Bodies, Body};

/// A free cell (or one outside the region of interest).
pub(super) const FREE: u8 = 0;
/// A cell occupied by a road user that does not cooperate.
pub(super) const OCCUPIED: u8 = 1;
/// A cell excluded from the metrics: the ego's own footprint.
pub(super) const EXCLUDED: u8 = 2;
/// A cell occupied by a cooperating agent other than the ego, which reports
/// its own footprint: counted apart from [`OCCUPIED`].
pub(super) const SELF_REPORT: u8 = 3;

/// The ground truth of the current step, per cell ([`FREE`], [`OCCUPIED`],
/// [`EXCLUDED`] or [`SELF_REPORT`]), kept from step to step so that only the
/// cells marked are reset.
#[derive(Debug, Clone)]
pub(super) struct Truth {
    cells: Vec<u8>,
    /// Per cell, the agent whose footprint marked it (meaningful where marked).
    owners: Vec<u32>,
    /// The cells not free, in marking order.
    marked: Vec<usize>,
}

impl Truth {
    /// Every one of `cells` cells free.
    pub(super) fn new(cells: usize) -> Self {
        Self {
            cells: vec![FREE; cells],
            owners: vec![0; cells],
            marked: Vec::new(),
        }
    }

    /// Marks the footprints of `bodies` on the counted cells of `grid` (in the
    /// region of interest, not an occluder of `raster`): the ego's own as
    /// excluded, first, so that no other body claims its cells; then those of
    /// the agents that report themselves (`reporting`: the cooperating agents
    /// in the scene) as self-report, then every other body's as occupied. A
    /// cell two footprints cover is the first one's.
    pub(super) fn mark(
        &mut self,
        grid: &Grid,
        raster: &Raster,
        in_region: &[bool],
        bodies: &Bodies,
        ego: usize,
        reporting: &[usize],
    ) {
        for &cell in &self.marked {
            self.cells[cell] = FREE;
        }
        self.marked.clear();
        let truth = |agent: usize| match agent {
            _ if agent == ego => EXCLUDED,
            _ if reporting.contains(&agent) => SELF_REPORT,
            _ => OCCUPIED,
        };
        let mut footprints: Vec<(u8, &Body)> = bodies.all().iter().map(|b| (truth(b.agent), b)).collect();
        // Stable: the ego first, then self-report, then the others, each in scene order.
        footprints.sort_by_key(|&(truth, _)| match truth {
            EXCLUDED => 0,
            SELF_REPORT => 1,
            _ => 2,
        });
        for (truth, body) in footprints {
            for cell in box_cells(grid, body) {
                if in_region[cell] && !raster.is_occluder(cell) && self.cells[cell] == FREE {
                    self.cells[cell] = truth;
                    // Agent indices are bounded far below 2³² (dsl budget: 10 000 agents).
                    self.owners[cell] = body.agent as u32;
                    self.marked.push(cell);
                }
            }
        }
    }

    /// The truth of every cell.
    pub(super) fn cells(&self) -> &[u8] {
        &self.cells
    }

    /// Per cell, the agent whose footprint marked it; meaningful only for
    /// the cells not free.
    pub(super) fn owners(&self) -> &[u32] {
        &self.owners
    }

    /// The cells not free, in marking order.
    pub(super) fn marked(&self) -> &[usize] {
        &self.marked
    }
}
