//! The world on the grid: which cell holds what, and the cells a ray crosses.
//!
//! A cell belongs to a shape (a footprint's rectangle or circle, an occluder's
//! polygon) when its centre lies inside it; a footprint also
//! always owns the cell under its own centre, so that a pedestrian smaller than a
//! cell is never lost. Rays are walked cell by cell (Amanatides and Woo, "A fast
//! voxel traversal algorithm", 1987): this is the hot path of free-space carving.

use sightline_dsl::{Grid, Occluder, geometry::Xy};

use super::sight::Body;
use crate::math::{Point, Vector};

/// What a cell of the obstacle raster holds.
const EMPTY: u32 = 0;
const OCCLUDER: u32 = 1;

/// The owner code of agent `agent`.
fn agent_code(agent: usize) -> u32 {
    agent as u32 + 2
}

/// The obstacles of a step on the grid: occluders (rasterised once) and footprints.
pub struct Raster {
    grid: Grid,
    owners: Vec<u32>,
    /// Cells currently owned by footprints, to clear them at the next step.
    body_cells: Vec<usize>,
    /// The bounds of each occluder's cells, then of each footprint's.
    bounds: Vec<Bounds>,
    /// How many of `bounds` are the occluders'.
    occluders: usize,
}

/// The box around the cells one owner holds, grown by half a cell on every
/// side: a ray that misses it crosses none of them (the walk's rounding is
/// some 10⁻¹² m).
#[derive(Debug, Clone, Copy)]
struct Bounds {
    owner: u32,
    low: Point,
    high: Point,
}

impl Bounds {
    /// The bounds of `cells` (at least one), held by `owner`.
    fn of(grid: &Grid, owner: u32, cells: &[usize]) -> Self {
        let (mut low, mut high) = ((usize::MAX, usize::MAX), (0, 0));
        for &cell in cells {
            let (col, row) = (cell % grid.cols, cell / grid.cols);
            low = (low.0.min(col), low.1.min(row));
            high = (high.0.max(col), high.1.max(row));
        }
        let corner = |(col, row): (usize, usize)| {
            Vector::new(
                grid.origin[0] + col as f64 * grid.cell,
                grid.origin[1] + row as f64 * grid.cell,
            )
        };
        let margin = Vector::splat(grid.cell / 2.0);
        Self {
            owner,
            low: corner(low) - margin,
            high: corner((high.0 + 1, high.1 + 1)) + margin,
        }
    }

    /// Whether the segment from `from` along the unit `direction` for
    /// `length` meets the box (slab method).
    fn crossed(&self, from: Point, direction: Vector, length: f64) -> bool {
        let (mut t_in, mut t_out) = (0.0_f64, length);
        for axis in 0..2 {
            let (o, d, lo, hi) = (from[axis], direction[axis], self.low[axis], self.high[axis]);
            if d == 0.0 {
                if o < lo || o > hi {
                    return false;
                }
            } else {
                let (t0, t1) = ((lo - o) / d, (hi - o) / d);
                t_in = t_in.max(t0.min(t1));
                t_out = t_out.min(t0.max(t1));
            }
        }
        t_in <= t_out
    }
}

impl Raster {
    /// The occluders of a world on `grid`.
    pub fn new(grid: Grid, occluders: &[Occluder]) -> Self {
        let mut owners = vec![EMPTY; grid.cells()];
        let mut bounds = Vec::new();
        for occluder in occluders {
            let cells = polygon_cells(&grid, &occluder.polygon);
            for &cell in &cells {
                owners[cell] = OCCLUDER;
            }
            if !cells.is_empty() {
                bounds.push(Bounds::of(&grid, OCCLUDER, &cells));
            }
        }
        Self {
            grid,
            owners,
            body_cells: Vec::new(),
            occluders: bounds.len(),
            bounds,
        }
    }

    /// Whether a cell is covered by an occluder.
    pub fn is_occluder(&self, cell: usize) -> bool {
        self.owners[cell] == OCCLUDER
    }

    /// Replaces the footprints of the previous step by `bodies`.
    pub fn set_bodies(&mut self, bodies: &[Body]) {
        for &cell in &self.body_cells {
            if self.owners[cell] != OCCLUDER {
                self.owners[cell] = EMPTY;
            }
        }
        self.body_cells.clear();
        self.bounds.truncate(self.occluders);
        for body in bodies {
            let first = self.body_cells.len();
            for cell in box_cells(&self.grid, body) {
                if self.owners[cell] == EMPTY {
                    self.owners[cell] = agent_code(body.agent);
                    self.body_cells.push(cell);
                }
            }
            if self.body_cells.len() > first {
                let owned = &self.body_cells[first..];
                self.bounds.push(Bounds::of(&self.grid, agent_code(body.agent), owned));
            }
        }
    }

    /// How far a ray from `from` at `angle` runs before it enters a cell of an
    /// occluder or of a footprint other than `observer`'s, up to `range`.
    pub fn free_length(&self, from: Point, angle: f64, range: f64, observer: usize) -> f64 {
        let own = agent_code(observer);
        let direction = Vector::new(angle.cos(), angle.sin());
        // Most rays cross no one's cells but the observer's: no walk.
        let blocked = self
            .bounds
            .iter()
            .any(|b| b.owner != own && b.crossed(from, direction, range));
        if blocked {
            self.walk(from, direction, range, own)
        } else {
            range
        }
    }

    /// [`Self::free_length`] along the unit `direction`, cell by cell, for
    /// the owner code `own`.
    fn walk(&self, from: Point, direction: Vector, range: f64, own: u32) -> f64 {
        let mut free = range;
        traverse(&self.grid, from, direction, range, |cell, enter| {
            let owner = self.owners[cell];
            if owner == EMPTY || owner == own {
                true
            } else {
                free = enter;
                false
            }
        });
        free
    }
}

/// The index of the cell holding `point`, if it lies on the grid.
pub fn cell_at(grid: &Grid, point: Point) -> Option<usize> {
    let col = ((point.x - grid.origin[0]) / grid.cell).floor();
    let row = ((point.y - grid.origin[1]) / grid.cell).floor();
    (col >= 0.0 && row >= 0.0 && col < grid.cols as f64 && row < grid.rows as f64)
        .then(|| row as usize * grid.cols + col as usize)
}

/// The centre of cell `cell`.
pub fn cell_center(grid: &Grid, cell: usize) -> Point {
    let [x, y] = grid.cell_center(cell % grid.cols, cell / grid.cols);
    Vector::new(x, y)
}

/// The columns and rows a box spanning `min`..`max` touches, clipped to the grid.
fn cell_range(
    grid: &Grid,
    min: Point,
    max: Point,
) -> Option<(std::ops::RangeInclusive<usize>, std::ops::RangeInclusive<usize>)> {
    let to_index =
        |v: f64, origin: f64, count: usize| ((v - origin) / grid.cell).floor().clamp(0.0, count as f64 - 1.0) as usize;
    let beyond = max.x < grid.origin[0]
        || max.y < grid.origin[1]
        || min.x >= grid.origin[0] + grid.cols as f64 * grid.cell
        || min.y >= grid.origin[1] + grid.rows as f64 * grid.cell;
    (!beyond).then(|| {
        (
            to_index(min.x, grid.origin[0], grid.cols)..=to_index(max.x, grid.origin[0], grid.cols),
            to_index(min.y, grid.origin[1], grid.rows)..=to_index(max.y, grid.origin[1], grid.rows),
        )
    })
}

/// The cells whose centre lies in the footprint (its rectangle or circle,
/// half-open: [`Body::contains`]), and the cell under its centre.
pub fn box_cells(grid: &Grid, body: &Body) -> Vec<usize> {
    let corners = body.corners();
    let min = corners.iter().fold(Vector::splat(f64::INFINITY), |m, c| m.min(*c));
    let max = corners.iter().fold(Vector::splat(f64::NEG_INFINITY), |m, c| m.max(*c));
    let mut cells = Vec::new();
    if let Some((cols, rows)) = cell_range(grid, min, max) {
        for row in rows {
            for col in cols.clone() {
                let cell = row * grid.cols + col;
                if body.contains(cell_center(grid, cell)) {
                    cells.push(cell);
                }
            }
        }
    }
    if let Some(center) = cell_at(grid, body.pose.translation)
        && !cells.contains(&center)
    {
        cells.push(center);
    }
    cells
}

/// The cells whose centre lies inside a polygon (even-odd rule).
pub fn polygon_cells(grid: &Grid, polygon: &[Xy]) -> Vec<usize> {
    let points: Vec<Point> = polygon.iter().map(|&[x, y]| Vector::new(x, y)).collect();
    let min = points.iter().fold(Vector::splat(f64::INFINITY), |m, p| m.min(*p));
    let max = points.iter().fold(Vector::splat(f64::NEG_INFINITY), |m, p| m.max(*p));
    let Some((cols, rows)) = cell_range(grid, min, max) else {
        return Vec::new();
    };
    let mut cells = Vec::new();
    for row in rows {
        for col in cols.clone() {
            let cell = row * grid.cols + col;
            if contains(&points, cell_center(grid, cell)) {
                cells.push(cell);
            }
        }
    }
    cells
}

fn contains(polygon: &[Point], p: Point) -> bool {
    let mut inside = false;
    let mut j = polygon.len() - 1;
    for i in 0..polygon.len() {
        let (a, b) = (polygon[i], polygon[j]);
        if (a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x {
            inside = !inside;
        }
        j = i;
    }
    inside
}

/// Where a ray enters a grid, and what Amanatides and Woo's walk steps by.
struct Entry {
    /// The first cell's column.
    col: usize,
    /// The first cell's row.
    row: usize,
    /// The walk's step in columns, ±1.
    step_col: isize,
    /// The walk's step in rows, ±1.
    step_row: isize,
    /// Distance along the ray to the next vertical and horizontal cell boundary.
    t_max: [f64; 2],
    /// Distance along the ray between two vertical, and two horizontal, boundaries.
    t_delta: [f64; 2],
    /// Distance along the ray at which it enters the grid.
    t_in: f64,
    /// Distance along the ray at which it leaves the grid, or ends.
    t_out: f64,
}

/// Where a ray from `from` along the unit `direction`, `length` long, enters
/// `grid`; `None` when none of it lies inside.
#[inline]
fn entry(grid: &Grid, from: Point, direction: Vector, length: f64) -> Option<Entry> {
    let low = Vector::new(grid.origin[0], grid.origin[1]);
    let high = low + Vector::new(grid.cols as f64, grid.rows as f64) * grid.cell;
    // Clip the ray to the grid (slab method).
    let (mut t_in, mut t_out) = (0.0_f64, length);
    for axis in 0..2 {
        let (o, d, lo, hi) = (from[axis], direction[axis], low[axis], high[axis]);
        if d.abs() < 1e-12 {
            if o < lo || o >= hi {
                return None;
            }
        } else {
            let (t0, t1) = ((lo - o) / d, (hi - o) / d);
            t_in = t_in.max(t0.min(t1));
            t_out = t_out.min(t0.max(t1));
        }
    }
    if t_in >= t_out {
        return None;
    }
    let start = from + direction * t_in;
    let clamp_index = |v: f64, lo: f64, count: usize| (((v - lo) / grid.cell).floor().max(0.0) as usize).min(count - 1);
    let col = clamp_index(start.x, low.x, grid.cols);
    let row = clamp_index(start.y, low.y, grid.rows);
    let step_col: isize = if direction.x >= 0.0 { 1 } else { -1 };
    let step_row: isize = if direction.y >= 0.0 { 1 } else { -1 };
    let boundary =
        |index: usize, lo: f64, step: isize| lo + (index as f64 + if step > 0 { 1.0 } else { 0.0 }) * grid.cell;
    let next = |o: f64, d: f64, b: f64| if d.abs() < 1e-12 { f64::INFINITY } else { (b - o) / d };
    let delta = |d: f64| {
        if d.abs() < 1e-12 {
            f64::INFINITY
        } else {
            grid.cell / d.abs()
        }
    };
    Some(Entry {
        col,
        row,
        step_col,
        step_row,
        t_max: [
            next(from.x, direction.x, boundary(col, low.x, step_col)),
            next(from.y, direction.y, boundary(row, low.y, step_row)),
        ],
        t_delta: [delta(direction.x), delta(direction.y)],
        t_in,
        t_out,
    })
}

/// Walks the cells a ray from `from` along the unit `direction` crosses within
/// `length`, in order, calling `visit(cell, distance at which the ray enters
/// it)` until it returns `false`. The part of the ray outside the grid is
/// skipped.
pub fn traverse(grid: &Grid, from: Point, direction: Vector, length: f64, mut visit: impl FnMut(usize, f64) -> bool) {
    let Some(Entry {
        col,
        row,
        step_col,
        step_row,
        t_max: [mut t_max_x, mut t_max_y],
        t_delta: [t_delta_x, t_delta_y],
        t_in,
        t_out,
    }) = entry(grid, from, direction, length)
    else {
        return;
    };
    // The walk keeps the cell's index and, per axis, how many more cells lie
    // ahead on the grid: the same cells as stepping the column and row and
    // checking them against the grid's edges.
    let (cols, rows) = (grid.cols, grid.rows);
    let (cell_step_x, mut x_left) = if step_col > 0 { (1, cols - 1 - col) } else { (-1, col) };
    let (cell_step_y, mut y_left) = if step_row > 0 {
        (cols as isize, rows - 1 - row)
    } else {
        (-(cols as isize), row)
    };
    let mut cell = row * cols + col;
    let mut enter = t_in;
    loop {
        if !visit(cell, enter) {
            return;
        }
        if t_max_x < t_max_y {
            enter = t_max_x;
            t_max_x += t_delta_x;
            if x_left == 0 {
                return;
            }
            x_left -= 1;
            cell = cell.wrapping_add_signed(cell_step_x);
        } else {
            enter = t_max_y;
            t_max_y += t_delta_y;
            if y_left == 0 {
                return;
            }
            y_left -= 1;
            cell = cell.wrapping_add_signed(cell_step_y);
        }
        if enter >= t_out {
            return;
        }
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;
    use proptest::strategy::Strategy;

    use super::*;
    use crate::math::Pose;

    /// 10 × 10 cells of 1 m from the origin.
    fn grid() -> Grid {
        Grid {
            origin: [0.0, 0.0],
            cell: 1.0,
            cols: 10,
            rows: 10,
        }
    }

    fn walk(from: Point, angle: f64, length: f64) -> Vec<(usize, f64)> {
        let mut cells = Vec::new();
        traverse(
            &grid(),
            from,
            Vector::new(angle.cos(), angle.sin()),
            length,
            |cell, enter| {
                cells.push((cell, enter));
                true
            },
        );
        cells
    }

    #[test]
    fn a_ray_along_a_row_visits_each_cell_once() {
        let cells = walk(Vector::new(0.5, 2.5), 0.0, 4.0);
        assert_eq!(cells.iter().map(|c| c.0).collect::<Vec<_>>(), vec![20, 21, 22, 23, 24]);
        assert_relative_eq!(cells[1].1, 0.5);
        assert_relative_eq!(cells[4].1, 3.5);
    }

    #[test]
    fn a_diagonal_ray_steps_through_neighbours() {
        let cells = walk(Vector::new(0.5, 0.5), std::f64::consts::FRAC_PI_4, 2.0_f64.sqrt() * 2.0);
        for pair in cells.windows(2) {
            let (a, b) = (pair[0].0 as isize, pair[1].0 as isize);
            assert!(b - a == 1 || b - a == 10 || b - a == 11, "{cells:?}");
        }
        assert_eq!(cells.last().unwrap().0, 22);
    }

    #[test]
    fn a_ray_from_outside_enters_the_grid() {
        let cells = walk(Vector::new(-5.0, 3.5), 0.0, 7.0);
        assert_eq!(cells.first().unwrap(), &(30, 5.0));
        assert_eq!(cells.last().unwrap().0, 31);
    }

    #[test]
    fn a_ray_that_misses_the_grid_visits_nothing() {
        assert!(walk(Vector::new(-5.0, 3.5), std::f64::consts::PI, 7.0).is_empty());
        assert!(walk(Vector::new(-5.0, 30.0), 0.0, 100.0).is_empty());
    }

    #[test]
    fn an_obstacle_stops_the_free_length() {
        let wall = Occluder {
            id: "w".into(),
            polygon: vec![[6.0, 0.0], [7.0, 0.0], [7.0, 10.0], [6.0, 10.0]],
        };
        let raster = Raster::new(grid(), &[wall]);
        assert_relative_eq!(raster.free_length(Vector::new(0.5, 5.5), 0.0, 20.0, 0), 5.5);
        assert_relative_eq!(
            raster.free_length(Vector::new(0.5, 5.5), std::f64::consts::PI, 20.0, 0),
            20.0
        );
    }

    #[test]
    fn an_agent_does_not_block_its_own_sensor() {
        let mut raster = Raster::new(grid(), &[]);
        let own = Body::rectangle(3, Pose::new(Vector::new(2.0, 5.0), 0.0), Vector::new(1.5, 0.5));
        let other = Body::rectangle(4, Pose::new(Vector::new(7.5, 5.5), 0.0), Vector::new(0.5, 0.5));
        raster.set_bodies(&[own, other]);
        assert_relative_eq!(raster.free_length(Vector::new(2.0, 5.5), 0.0, 20.0, 3), 5.0);
        raster.set_bodies(&[own]);
        assert_relative_eq!(raster.free_length(Vector::new(2.0, 5.5), 0.0, 20.0, 3), 20.0);
    }

    proptest::proptest! {
        /// A ray whose bounds test finds no one's cells on its way runs its
        /// whole range: the walk from any point at any angle, among a
        /// building, the observer and two other footprints, gives the same
        /// length to the bit as the bounds test and the walk together.
        #[test]
        fn proptest_skipping_a_walk_never_changes_the_free_length(
            x in -2.0..12.0_f64, y in -2.0..12.0_f64, angle in -4.0..4.0_f64, range in 0.0..20.0_f64,
            bodies in proptest::collection::vec((0.0..10.0_f64, 0.0..10.0_f64, 0.0..3.2_f64, 0.05..1.5_f64), 3),
        ) {
            let wall = Occluder {
                id: "w".into(),
                polygon: vec![[6.2, 0.3], [7.1, 0.3], [7.1, 4.4], [6.2, 4.4]],
            };
            let mut raster = Raster::new(grid(), &[wall]);
            let bodies: Vec<Body> = bodies
                .iter()
                .enumerate()
                .map(|(agent, &(x, y, heading, half))| {
                    Body::rectangle(agent, Pose::new(Vector::new(x, y), heading), Vector::new(half, half / 2.0))
                })
                .collect();
            raster.set_bodies(&bodies);
            let from = Vector::new(x, y);
            let walked = raster.walk(from, Vector::new(angle.cos(), angle.sin()), range, agent_code(0));
            proptest::prop_assert_eq!(raster.free_length(from, angle, range, 0).to_bits(), walked.to_bits());
        }
    }

    /// The walk as first written (Amanatides and Woo's column and row,
    /// checked against the grid's edges at every step) from the same
    /// [`entry`], the reference of the one kept.
    fn stepped(grid: &Grid, from: Point, direction: Vector, length: f64) -> Vec<(usize, u64)> {
        let mut visited = Vec::new();
        let Some(Entry {
            mut col,
            mut row,
            step_col,
            step_row,
            t_max: [mut t_max_x, mut t_max_y],
            t_delta: [t_delta_x, t_delta_y],
            t_in,
            t_out,
        }) = entry(grid, from, direction, length)
        else {
            return visited;
        };
        let mut enter = t_in;
        loop {
            visited.push((row * grid.cols + col, enter.to_bits()));
            if t_max_x < t_max_y {
                enter = t_max_x;
                t_max_x += t_delta_x;
                col = match col.checked_add_signed(step_col) {
                    Some(c) if c < grid.cols => c,
                    _ => return visited,
                };
            } else {
                enter = t_max_y;
                t_max_y += t_delta_y;
                row = match row.checked_add_signed(step_row) {
                    Some(r) if r < grid.rows => r,
                    _ => return visited,
                };
            }
            if enter >= t_out {
                return visited;
            }
        }
    }

    proptest::proptest! {
        /// The walk visits the same cells, entered at the same distances to
        /// the bit, as the column-and-row walk it replaced: rays from inside
        /// and outside a grid, along its axes, its diagonals and any angle,
        /// ending inside it or beyond its edges.
        #[test]
        fn proptest_the_walk_visits_the_cells_of_the_column_and_row_walk(
            cols in 1..40_usize, rows in 1..40_usize, cell in 0.1..2.0_f64,
            x in -0.3..1.3_f64, y in -0.3..1.3_f64,
            angle in proptest::prop_oneof![
                (0..16_i32).prop_map(|eighth| f64::from(eighth) * std::f64::consts::FRAC_PI_8),
                -4.0..4.0_f64,
            ],
            length in 0.0..1.5_f64,
        ) {
            let grid = Grid { origin: [-3.0, 2.0], cell, cols, rows };
            let size = Vector::new(cols as f64, rows as f64) * cell;
            let from = Vector::new(-3.0 + x * size.x, 2.0 + y * size.y);
            let direction = Vector::new(angle.cos(), angle.sin());
            let length = length * size.length();
            let mut visited = Vec::new();
            traverse(&grid, from, direction, length, |cell, enter| {
                visited.push((cell, enter.to_bits()));
                true
            });
            proptest::prop_assert_eq!(visited, stepped(&grid, from, direction, length));
        }
    }

    /// A 4.5 × 1.8 m car whose ends lie on cell centres (0.5 m cells): half-open,
    /// it holds 9 columns × 4 rows wherever it is, placed exactly or driven
    /// there by fifty-five steps of 0.1 m (x = 5.499999999999996). Closed, it
    /// held 10 columns placed exactly and 9 driven there: rounding decided.
    #[test]
    fn a_footprint_s_edges_on_cell_centres_hold_as_many_cells_however_it_got_there() {
        let grid = Grid {
            origin: [0.0, 0.0],
            cell: 0.5,
            cols: 40,
            rows: 10,
        };
        let driven = (0..55).fold(0.0, |x, _| x + 0.1);
        assert_ne!(driven, 5.5);
        for x in [5.5, driven] {
            let car = Body::rectangle(0, Pose::new(Vector::new(x, 2.0), 0.0), Vector::new(2.25, 0.9));
            assert_eq!(box_cells(&grid, &car).len(), 36, "x = {x}");
        }
    }

    #[test]
    fn a_small_footprint_still_owns_its_centre_cell() {
        let pedestrian = Body::circle(0, Pose::new(Vector::new(3.0, 3.0), 0.0), 0.1);
        assert_eq!(box_cells(&grid(), &pedestrian), vec![33]);
    }

    /// A circle of radius 0.8 about the corner (5, 5) of four cells: their
    /// centres lie 0.71 m away, inside; the next ring's, 1.58 m and more, do not.
    /// The square of the same half size would hold the same four; at radius
    /// 1.6 the square holds the 4 × 4 block around the corner, the circle only
    /// the 12 centres within 1.6 m (the block's corners lie 2.12 m away).
    #[test]
    fn a_circle_covers_the_cells_whose_centre_lies_within_its_radius() {
        let at = Pose::new(Vector::new(5.0, 5.0), 0.3);
        assert_eq!(box_cells(&grid(), &Body::circle(0, at, 0.8)).len(), 4);
        let circle = box_cells(&grid(), &Body::circle(0, at, 1.6));
        assert_eq!(circle.len(), 12);
        for corner in [33, 36, 63, 66] {
            assert!(!circle.contains(&corner), "{corner}");
        }
    }

    /// A 4 × 0.6 m box along the diagonal through (5, 5): the centres (4.5, 4.5) and
    /// (5.5, 5.5) lie 0.71 m along it, inside; (3.5, 3.5) and (6.5, 6.5) lie 2.12 m
    /// along, beyond its 2 m half length; (5.5, 4.5) lies 0.71 m across, beyond 0.3.
    #[test]
    fn a_rotated_box_covers_the_cells_under_it() {
        let diagonal = Body::rectangle(
            0,
            Pose::new(Vector::new(5.0, 5.0), std::f64::consts::FRAC_PI_4),
            Vector::new(2.0, 0.3),
        );
        assert_eq!(box_cells(&grid(), &diagonal), vec![44, 55]);
    }
}
