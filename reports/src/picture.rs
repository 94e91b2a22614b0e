//! Grid pictures for the report: ground truth, the ego's own grid and the fused
//! grid at the snapshot step, as PNG data URIs (the page stays self-contained).
//!
//! One pixel per cell, north up, cropped to the region of interest when there is
//! one; areas wider or taller than [`MAX_SIDE`] cells are sampled every k-th cell. Colours: free white, occupied black, unknown light
//! blue-grey, occluders mid grey; the fused grid shades P(occupied) from white
//! (0) to black (1).

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use serde::Serialize;
use sightline_dsl::Grid;
use sightline_engine::world::Snapshot;

/// The largest side of a picture, in pixels.
const MAX_SIDE: usize = 1000;

const FREE: [u8; 3] = [255, 255, 255];
const OCCUPIED: [u8; 3] = [20, 20, 20];
const UNKNOWN: [u8; 3] = [205, 213, 225];
const OCCLUDER: [u8; 3] = [140, 140, 140];

/// The three pictures of a snapshot, as `data:` URIs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Pictures {
    /// Time of the snapshot, seconds.
    pub time: f64,
    /// Ground truth.
    pub truth: String,
    /// The ego's own grid.
    pub ego: String,
    /// The fused grid.
    pub fused: String,
}

/// Draws the snapshot of a world run on `grid` (one step lasting `step` seconds),
/// cropped to the bounding box of `region` (centre, radius) if given.
pub fn pictures(
    grid: &Grid,
    step: f64,
    snapshot: &Snapshot,
    region: Option<([f64; 2], f64)>,
) -> Result<Pictures, png::EncodingError> {
    let area = Area::of(grid, region);
    let occluder = |cell: usize| snapshot.truth[cell] == 2;
    let truth = draw(&area, |cell| match snapshot.truth[cell] {
        1 => OCCUPIED,
        2 => OCCLUDER,
        _ => FREE,
    })?;
    let ego = draw(&area, |cell| match (occluder(cell), snapshot.ego[cell]) {
        (true, _) => OCCLUDER,
        (false, 1) => FREE,
        (false, 2) => OCCUPIED,
        _ => UNKNOWN,
    })?;
    let fused = draw(&area, |cell| match (occluder(cell), snapshot.fused[cell]) {
        (true, _) => OCCLUDER,
        (false, None) => UNKNOWN,
        (false, Some(p)) => [(255.0 * (1.0 - p.clamp(0.0, 1.0))).round() as u8; 3],
    })?;
    Ok(Pictures {
        time: snapshot.step as f64 * step,
        truth,
        ego,
        fused,
    })
}

/// The cells a picture shows: columns and rows of the grid.
struct Area {
    cols: usize,
    first_col: usize,
    last_col: usize,
    first_row: usize,
    last_row: usize,
}

impl Area {
    /// The whole grid, or the cells of the bounding box of `region`.
    fn of(grid: &Grid, region: Option<([f64; 2], f64)>) -> Self {
        let whole = Self {
            cols: grid.cols,
            first_col: 0,
            last_col: grid.cols - 1,
            first_row: 0,
            last_row: grid.rows - 1,
        };
        let Some(([x, y], radius)) = region else {
            return whole;
        };
        let index = |v: f64, origin: f64, count: usize| {
            ((v - origin) / grid.cell).floor().clamp(0.0, count as f64 - 1.0) as usize
        };
        Self {
            first_col: index(x - radius, grid.origin[0], grid.cols),
            last_col: index(x + radius, grid.origin[0], grid.cols),
            first_row: index(y - radius, grid.origin[1], grid.rows),
            last_row: index(y + radius, grid.origin[1], grid.rows),
            ..whole
        }
    }
}

/// Draws one picture, colouring each sampled cell.
fn draw(area: &Area, colour: impl Fn(usize) -> [u8; 3]) -> Result<String, png::EncodingError> {
    let (cols, rows) = (area.last_col - area.first_col + 1, area.last_row - area.first_row + 1);
    let every = cols.max(rows).div_ceil(MAX_SIDE);
    let (width, height) = (cols.div_ceil(every), rows.div_ceil(every));
    let mut pixels = Vec::with_capacity(width * height * 3);
    // Image rows run top to bottom; grid rows run south to north.
    for y in (0..height).rev() {
        for x in 0..width {
            let (col, row) = (area.first_col + x * every, area.first_row + y * every);
            pixels.extend(colour(row * area.cols + col));
        }
    }
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, width as u32, height as u32);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&pixels)?;
    writer.finish()?;
    Ok(format!("data:image/png;base64,{}", STANDARD.encode(&bytes)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3 × 2 grid: the picture is 3 × 2 pixels, north up.
    #[test]
    fn one_pixel_per_cell_north_up() {
        let grid = Grid {
            origin: [0.0, 0.0],
            cell: 1.0,
            cols: 3,
            rows: 2,
        };
        let uri = draw(&Area::of(&grid, None), |cell| if cell == 0 { OCCUPIED } else { FREE }).unwrap();
        let bytes = STANDARD
            .decode(uri.strip_prefix("data:image/png;base64,").unwrap())
            .unwrap();
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let mut reader = decoder.read_info().unwrap();
        let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut pixels).unwrap();
        assert_eq!((info.width, info.height), (3, 2));
        // Cell 0 (south-west) is the bottom-left pixel.
        assert_eq!(&pixels[9..12], &OCCUPIED);
        assert_eq!(&pixels[0..3], &FREE);
    }

    #[test]
    fn a_region_crops_the_picture_to_its_bounding_box() {
        let grid = Grid {
            origin: [-10.0, -10.0],
            cell: 1.0,
            cols: 20,
            rows: 20,
        };
        let area = Area::of(&grid, Some(([0.0, 0.0], 2.0)));
        assert_eq!(
            (area.first_col, area.last_col, area.first_row, area.last_row),
            (8, 12, 8, 12)
        );
    }
}
