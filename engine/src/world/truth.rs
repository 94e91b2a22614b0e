//! The ground truth of a step: which counted cells road users occupy, against
//! which the fused grids are tallied and the snapshot is drawn.

use sightline_dsl::Grid;

use super::raster::{Raster, box_cells};
use super::sight::{Bodies, Body};

/// A free cell (or one outside the region of interest).
pub(super) const FREE: u8 = 0;
/// A cell occupied by a road user other than the ego.
pub(super) const OCCUPIED: u8 = 1;
/// A cell excluded from the metrics: the ego's own footprint.
pub(super) const EXCLUDED: u8 = 2;

/// The ground truth of the current step, per cell ([`FREE`], [`OCCUPIED`] or
/// [`EXCLUDED`]), kept from step to step so that only the cells marked are reset.
#[derive(Debug, Clone)]
pub(super) struct Truth {
    cells: Vec<u8>,
    /// The cells not free, in marking order.
    marked: Vec<usize>,
}

impl Truth {
    /// Every one of `cells` cells free.
    pub(super) fn new(cells: usize) -> Self {
        Self {
            cells: vec![FREE; cells],
            marked: Vec::new(),
        }
    }

    /// Marks the footprints of `bodies` on the counted cells of `grid` (in the
    /// region of interest, not an occluder of `raster`): the ego's own as
    /// excluded, first, so that no other body claims its cells; every other
    /// body's as occupied.
    pub(super) fn mark(&mut self, grid: &Grid, raster: &Raster, in_region: &[bool], bodies: &Bodies, ego: usize) {
        for &cell in &self.marked {
            self.cells[cell] = FREE;
        }
        self.marked.clear();
        let mut footprints: Vec<&Body> = bodies.all().iter().collect();
        footprints.sort_by_key(|b| b.agent != ego);
        for body in footprints {
            for cell in box_cells(grid, body) {
                if in_region[cell] && !raster.is_occluder(cell) && self.cells[cell] == FREE {
                    self.cells[cell] = if body.agent == ego { EXCLUDED } else { OCCUPIED };
                    self.marked.push(cell);
                }
            }
        }
    }

    /// The truth of every cell.
    pub(super) fn cells(&self) -> &[u8] {
        &self.cells
    }

    /// The cells not free, in marking order.
    pub(super) fn marked(&self) -> &[usize] {
        &self.marked
    }
}
