//! Fusion of the cooperating agents' observations of one cell.

use sightline_dsl::{Grid, Rule};

use super::observe::{Observation, Observed};
use super::raster::cell_center;
use crate::fusion::{Estimate, Mass, Source, fuse};
use crate::idealisation::Idealisation;

/// The inverse sensor model is two constants.
pub(crate) const INVERSE_MODEL: Idealisation = Idealisation {
    id: "fuse.inverse-model",
    text: "An observation conveys fixed probabilities of occupancy (`perception.inverse_model`), whatever the \
           distance, the sensor or the visibility of the cell.",
};

/// Fuses, cell by cell, what a set of agents observed at one step with one rule.
///
/// Each observation becomes the least-committed mass whose pignistic probability
/// is the inverse sensor model's: free → (1 − 2f, 0, 2f), occupied →
/// (0, 2o − 1, 2 − 2o). Bayes fuses their pignistic probabilities (f and o back);
/// the weighted rules weigh each by the distance from the agent's nearest sensor
/// to the cell (floored at half a cell).
pub struct CellFusion<'a> {
    /// The grid.
    pub grid: &'a Grid,
    /// The fusion rule.
    pub rule: &'a Rule,
    /// The observations to fuse, the ego's first.
    pub observations: &'a [&'a Observation],
    /// P(occupied) of a detected cell.
    pub occupied: f64,
    /// P(occupied) of a cell seen free.
    pub free: f64,
}

impl CellFusion<'_> {
    /// The fused estimate of `cell`, which at least one agent observed.
    /// `sources` is scratch space.
    pub fn estimate(&self, cell: usize, sources: &mut Vec<Source>) -> Estimate {
        sources.clear();
        // Only the distance-weighted rules read distances: spare the square roots.
        let distances = matches!(self.rule, Rule::DistanceWeighted(_) | Rule::Hybrid { .. });
        let center = cell_center(self.grid, cell);
        for observation in self.observations {
            let mass = match observation.get(cell) {
                Observed::Unknown => continue,
                Observed::Free => Mass::new(1.0 - 2.0 * self.free, 0.0, 2.0 * self.free),
                Observed::Occupied => Mass::new(0.0, 2.0 * self.occupied - 1.0, 2.0 - 2.0 * self.occupied),
            };
            let distance = if distances {
                observation
                    .sensor_positions
                    .iter()
                    .map(|p| (*p - center).length())
                    .fold(f64::INFINITY, f64::min)
            } else {
                0.0
            };
            sources.push(Source {
                mass,
                distance: distance.max(self.grid.cell / 2.0),
            });
        }
        fuse(self.rule, sources)
    }
}
