//! What the ego fuses at a step, source by source: its own observation, and
//! what it holds of each other cooperating agent's grid (handed over whole
//! without a radio, or received over one and ageing).

use super::observe::{Observation, Observed};
use crate::math::Point;

/// One source of evidence on the grid, as fusion reads it.
pub trait Evidence: Sync {
    /// What the source says of `cell`.
    fn get(&self, cell: usize) -> Observed;

    /// The cells it says something of (free or occupied), each once.
    fn touched(&self) -> &[usize];

    /// The weight of what it says of `cell`, in (0, 1]: 1 for fresh evidence,
    /// less as it ages (fusion discounts its mass by the weight).
    fn weight(&self, cell: usize) -> f64;

    /// The estimated positions of the sensors that observed `cell`.
    fn sensors(&self, cell: usize) -> &[Point];

    /// Whether every cell it says something of weighs 1 (none has aged).
    fn fresh(&self) -> bool;
}

impl Evidence for Observation {
    fn get(&self, cell: usize) -> Observed {
        Observation::get(self, cell)
    }

    fn touched(&self) -> &[usize] {
        Observation::touched(self)
    }

    fn weight(&self, _cell: usize) -> f64 {
        1.0
    }

    fn sensors(&self, _cell: usize) -> &[Point] {
        &self.sensor_positions
    }

    fn fresh(&self) -> bool {
        true
    }
}
