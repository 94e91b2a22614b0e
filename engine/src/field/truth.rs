//! The ground truth: square blobs of cells, each occupied with a fixed probability.

use rand::RngExt;
use sightline_dsl::{Grid, Truth};

use crate::idealisation::Idealisation;
use crate::rng::{Purpose, stream};

/// The truth is drawn once.
pub(crate) const STATIC_TRUTH: Idealisation = Idealisation {
    id: "field.static-truth",
    text: "The ground truth is drawn once and does not change: a static scene, observed once.",
};

/// Which cells are occupied. Stored per blob, so a grid of any size costs one
/// byte per blob.
#[derive(Debug, Clone, PartialEq)]
pub struct GroundTruth {
    blob: usize,
    blobs_per_row: usize,
    occupied: Vec<bool>,
}

impl GroundTruth {
    /// Draws the ground truth of `grid`: blobs in row-major order from one stream
    /// of `seed`, each occupied with probability `truth.occupied_fraction`.
    pub fn generate(grid: &Grid, truth: &Truth, seed: u64) -> Self {
        let blob = truth.blob_cells;
        let blobs_per_row = grid.cols.div_ceil(blob);
        let blob_rows = grid.rows.div_ceil(blob);
        let mut rng = stream(seed, Purpose::Truth, 0);
        let occupied = (0..blobs_per_row * blob_rows)
            .map(|_| rng.random::<f64>() < truth.occupied_fraction)
            .collect();
        Self {
            blob,
            blobs_per_row,
            occupied,
        }
    }

    /// Whether cell (`col`, `row`) is occupied.
    #[inline]
    pub fn is_occupied(&self, col: usize, row: usize) -> bool {
        self.occupied[(row / self.blob) * self.blobs_per_row + col / self.blob]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(cols: usize, rows: usize) -> Grid {
        Grid {
            origin: [0.0, 0.0],
            cell: 1.0,
            cols,
            rows,
        }
    }

    #[test]
    fn blobs_are_uniform_squares() {
        let truth = GroundTruth::generate(
            &grid(10, 10),
            &Truth {
                occupied_fraction: 0.5,
                blob_cells: 5,
            },
            3,
        );
        for row in 0..10 {
            for col in 0..10 {
                assert_eq!(truth.is_occupied(col, row), truth.is_occupied(col / 5 * 5, row / 5 * 5));
            }
        }
    }

    #[test]
    fn occupied_share_matches_the_fraction() {
        let g = grid(200, 200);
        let truth = GroundTruth::generate(
            &g,
            &Truth {
                occupied_fraction: 0.3,
                blob_cells: 1,
            },
            11,
        );
        let occupied = (0..200)
            .flat_map(|r| (0..200).map(move |c| (c, r)))
            .filter(|&(c, r)| truth.is_occupied(c, r))
            .count();
        // 40 000 Bernoulli(0.3) draws: the standard deviation of the share is 0.0023.
        assert!((occupied as f64 / 40_000.0 - 0.3).abs() < 0.01);
    }
}
