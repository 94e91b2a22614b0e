//! Sensor positions.

use rand::RngExt;
use sightline_dsl::{Grid, Layout};

use crate::idealisation::Idealisation;
use crate::math::Point;
use crate::rng::{Purpose, stream};

/// Sensors are where the layout says.
pub(crate) const EXACT_POSITIONS: Idealisation = Idealisation {
    id: "field.exact-positions",
    text: "Sensor positions are known exactly.",
};

/// The sensor positions of `layout` on `grid`; random layouts draw from `seed`.
pub fn positions(layout: &Layout, grid: &Grid, seed: u64) -> Vec<Point> {
    match layout {
        Layout::Positions(positions) => positions.iter().map(|&[x, y]| Point::new(x, y)).collect(),
        Layout::Random { count } => {
            let mut rng = stream(seed, Purpose::Layout, 0);
            let width = grid.cols as f64 * grid.cell;
            let height = grid.rows as f64 * grid.cell;
            (0..*count)
                .map(|_| {
                    Point::new(
                        grid.origin[0] + rng.random::<f64>() * width,
                        grid.origin[1] + rng.random::<f64>() * height,
                    )
                })
                .collect()
        }
    }
}
