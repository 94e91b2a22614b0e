//! Grid pictures for the report: ground truth, the ego's own grid, the fused
//! occupancy probability, its uncertainty and an error map at the snapshot
//! step, as PNG data URIs (the page stays self-contained), each with its legend.
//!
//! One pixel per cell, north up, cropped to the region of interest when there is
//! one; areas wider or taller than [`MAX_SIDE`] cells are sampled every k-th
//! cell. Every picture draws free cells white, occupied black, cells nobody
//! observed light blue-grey, occluders mid grey and the ego sky blue. The fused
//! probability shades from white (0) to black (1); the uncertainty follows
//! viridis from dark purple (certain) to yellow (1); the error map compares the
//! decision with the truth in the Okabe–Ito palette, so that no two classes look
//! alike to colour-blind readers.

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use serde::Serialize;
use sightline_dsl::Grid;
use sightline_engine::outcome::{FusedCell, Snapshot, State};

/// The largest side of a picture, in pixels.
const MAX_SIDE: usize = 1000;

/// An RGB colour.
type Rgb = [u8; 3];

const FREE: Rgb = [255, 255, 255];
const OCCUPIED: Rgb = [20, 20, 20];
const UNKNOWN: Rgb = [205, 213, 225];
const OCCLUDER: Rgb = [140, 140, 140];
const EGO: Rgb = [86, 180, 233];
const FALSE_OCCUPIED: Rgb = [230, 159, 0];
const MISSED_OCCUPIED: Rgb = [0, 114, 178];

/// Viridis at 0, 1/8, …, 1 (matplotlib's), linearly interpolated between.
const VIRIDIS: [Rgb; 9] = [
    [68, 1, 84],
    [72, 40, 120],
    [62, 73, 137],
    [49, 104, 142],
    [38, 130, 142],
    [31, 158, 137],
    [53, 183, 121],
    [110, 206, 88],
    [253, 231, 37],
];

/// The pictures of a snapshot, in reading order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Pictures {
    /// Time of the snapshot, seconds.
    pub time: f64,
    /// Ground truth, the ego's grid, the fused probability, its uncertainty and
    /// the error map.
    pub images: Vec<Picture>,
}

/// One picture and how to read it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Picture {
    /// What it shows, in a few words (also its `alt` text).
    pub title: &'static str,
    /// How to read it.
    pub caption: String,
    /// The PNG as a `data:` URI.
    pub src: String,
    /// Its colours.
    pub legend: Legend,
}

/// The colours of a picture: a continuous scale (for values), then one swatch
/// per class.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Legend {
    /// A value's colour from its low end to its high end, if the picture shades values.
    pub scale: Option<Scale>,
    /// The classes drawn in a colour of their own.
    pub swatches: Vec<Swatch>,
}

/// A colour bar.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Scale {
    /// The bar as a CSS `linear-gradient(…)` from left (low) to right (high).
    pub gradient: String,
    /// What the left end means.
    pub low: &'static str,
    /// What the right end means.
    pub high: &'static str,
}

/// A class and its colour.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Swatch {
    /// The colour, `#rrggbb`.
    pub colour: String,
    /// What it marks.
    pub label: &'static str,
}

/// How the fused decision on a cell compares with the truth.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Judgement {
    /// Free, decided Empty.
    CorrectFree,
    /// Occupied, decided Occupy.
    CorrectOccupied,
    /// Free, decided Occupy (a false alarm).
    FalseOccupied,
    /// Occupied, not decided Occupy (unobserved, undecided or decided otherwise):
    /// what occupied-cell recall counts as missed.
    MissedOccupied,
    /// Free, and unobserved or not decided Empty.
    Unknown,
    /// An occluder (not judged).
    Occluder,
    /// The ego (not judged).
    Ego,
}

impl Judgement {
    const ALL: [Judgement; 7] = [
        Judgement::CorrectFree,
        Judgement::CorrectOccupied,
        Judgement::FalseOccupied,
        Judgement::MissedOccupied,
        Judgement::Unknown,
        Judgement::Occluder,
        Judgement::Ego,
    ];

    /// Judges a cell from its [`Snapshot::truth`] code and its fused cell.
    fn of(truth: u8, fused: Option<&FusedCell>) -> Self {
        let decision = fused.and_then(|c| c.decision);
        match (truth, decision) {
            (2, _) => Self::Occluder,
            (3, _) => Self::Ego,
            (1, Some(State::Occupied)) => Self::CorrectOccupied,
            (1, _) => Self::MissedOccupied,
            (_, Some(State::Occupied)) => Self::FalseOccupied,
            (_, Some(State::Empty)) => Self::CorrectFree,
            _ => Self::Unknown,
        }
    }

    fn colour(self) -> Rgb {
        match self {
            Self::CorrectFree => FREE,
            Self::CorrectOccupied => OCCUPIED,
            Self::FalseOccupied => FALSE_OCCUPIED,
            Self::MissedOccupied => MISSED_OCCUPIED,
            Self::Unknown => UNKNOWN,
            Self::Occluder => OCCLUDER,
            Self::Ego => EGO,
        }
    }

    fn label(self) -> &'static str {
        match self {
            Self::CorrectFree => "free, decided free",
            Self::CorrectOccupied => "occupied, decided occupied",
            Self::FalseOccupied => "free, decided occupied (false alarm)",
            Self::MissedOccupied => "occupied, not decided occupied (missed)",
            Self::Unknown => "free, not decided (unobserved or below the threshold)",
            Self::Occluder => "occluder",
            Self::Ego => "the ego (not counted)",
        }
    }
}

/// The colour of a fused occupancy probability: white (0) to black (1).
fn probability_colour(p: f32) -> Rgb {
    [(255.0 * (1.0 - p.clamp(0.0, 1.0))).round() as u8; 3]
}

/// The colour of an uncertainty in [0, 1] on viridis.
fn uncertainty_colour(u: f32) -> Rgb {
    let position = u.clamp(0.0, 1.0) * (VIRIDIS.len() - 1) as f32;
    let below = (position.floor() as usize).min(VIRIDIS.len() - 2);
    let t = position - below as f32;
    let (a, b) = (VIRIDIS[below], VIRIDIS[below + 1]);
    std::array::from_fn(|i| (f32::from(a[i]) + t * (f32::from(b[i]) - f32::from(a[i]))).round() as u8)
}

/// Draws the snapshot of a world run on `grid` (one step lasting `step` seconds),
/// cropped to the bounding box of `region` (centre, radius) if given; the
/// uncertainty is that of an evidential rule (m(Θ)) if `evidential`, of Bayes
/// (entropy) otherwise.
pub fn pictures(
    grid: &Grid,
    step: f64,
    snapshot: &Snapshot,
    region: Option<([f64; 2], f64)>,
    evidential: bool,
) -> Result<Pictures, png::EncodingError> {
    let area = Area::of(grid, region);
    // Occluders and the ego are drawn alike in every picture.
    let fixed = |cell: usize| match snapshot.truth[cell] {
        2 => Some(OCCLUDER),
        3 => Some(EGO),
        _ => None,
    };
    let fused = |cell: usize, shade: fn(&FusedCell) -> Rgb| {
        fixed(cell).unwrap_or_else(|| snapshot.fused[cell].as_ref().map_or(UNKNOWN, shade))
    };
    let unobserved = [
        swatch(UNKNOWN, "not observed"),
        swatch(OCCLUDER, "occluder"),
        swatch(EGO, "the ego"),
    ];
    let images = vec![
        Picture {
            title: "Ground truth",
            caption: "Where the agents and occluders are.".into(),
            src: draw(&area, |cell| {
                fixed(cell).unwrap_or(if snapshot.truth[cell] == 1 { OCCUPIED } else { FREE })
            })?,
            legend: swatches(&[
                (FREE, "free"),
                (OCCUPIED, "occupied"),
                (OCCLUDER, "occluder"),
                (EGO, "the ego"),
            ]),
        },
        Picture {
            title: "The ego's own grid",
            caption: "What the ego's sensors alone observed.".into(),
            src: draw(&area, |cell| {
                fixed(cell).unwrap_or(match snapshot.ego[cell] {
                    1 => FREE,
                    2 => OCCUPIED,
                    _ => UNKNOWN,
                })
            })?,
            legend: swatches(&[
                (FREE, "free"),
                (OCCUPIED, "occupied"),
                (UNKNOWN, "not observed"),
                (OCCLUDER, "occluder"),
                (EGO, "the ego"),
            ]),
        },
        Picture {
            title: "Fused occupancy",
            caption: "P(occupied) of the fused grid (pignistic for evidential rules).".into(),
            src: draw(&area, |cell| fused(cell, |c| probability_colour(c.probability)))?,
            legend: Legend {
                scale: Some(scale(probability_colour, "0 (free)", "1 (occupied)")),
                swatches: unobserved.to_vec(),
            },
        },
        Picture {
            title: "Fused uncertainty",
            caption: if evidential {
                "The mass left on Unknown, m(Θ): the evidence's ignorance (0 certain, 1 no evidence)."
            } else {
                "The binary entropy of P(occupied), bits: 0 where P is 0 or 1, 1 where P is ½."
            }
            .into(),
            src: draw(&area, |cell| fused(cell, |c| uncertainty_colour(c.uncertainty)))?,
            legend: Legend {
                scale: Some(scale(uncertainty_colour, "0 (certain)", "1 (uncertain)")),
                swatches: unobserved.to_vec(),
            },
        },
        Picture {
            title: "Error map",
            caption: "The fused decision (the decision rule at its threshold) against the ground truth.".into(),
            src: draw(&area, |cell| {
                Judgement::of(snapshot.truth[cell], snapshot.fused[cell].as_ref()).colour()
            })?,
            legend: Legend {
                scale: None,
                swatches: Judgement::ALL.iter().map(|j| swatch(j.colour(), j.label())).collect(),
            },
        },
    ];
    Ok(Pictures {
        time: snapshot.step as f64 * step,
        images,
    })
}

fn hex([r, g, b]: Rgb) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

fn swatch(colour: Rgb, label: &'static str) -> Swatch {
    Swatch {
        colour: hex(colour),
        label,
    }
}

fn swatches(classes: &[(Rgb, &'static str)]) -> Legend {
    Legend {
        scale: None,
        swatches: classes.iter().map(|&(colour, label)| swatch(colour, label)).collect(),
    }
}

/// A colour bar of `colour` over [0, 1], sampled where viridis has its stops
/// (exact for both maps, which are linear between them).
fn scale(colour: fn(f32) -> Rgb, low: &'static str, high: &'static str) -> Scale {
    let stops = VIRIDIS.len() - 1;
    let stops: Vec<String> = (0..=stops)
        .map(|i| {
            let at = i as f32 / stops as f32;
            format!("{} {}%", hex(colour(at)), at * 100.0)
        })
        .collect();
    Scale {
        gradient: format!("linear-gradient(to right, {})", stops.join(", ")),
        low,
        high,
    }
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
fn draw(area: &Area, colour: impl Fn(usize) -> Rgb) -> Result<String, png::EncodingError> {
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

    /// The pixels of a PNG data URI, row by row from the top, and its size.
    fn decode(uri: &str) -> (Vec<u8>, (u32, u32)) {
        let bytes = STANDARD
            .decode(uri.strip_prefix("data:image/png;base64,").unwrap())
            .unwrap();
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let mut reader = decoder.read_info().unwrap();
        let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut pixels).unwrap();
        (pixels, (info.width, info.height))
    }

    fn cell(probability: f32, uncertainty: f32, decision: Option<State>) -> Option<FusedCell> {
        Some(FusedCell {
            probability,
            uncertainty,
            decision,
        })
    }

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
        let (pixels, size) = decode(&uri);
        assert_eq!(size, (3, 2));
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

    /// Every pair of truth and decision lands in its class.
    #[test]
    fn cells_are_judged_against_the_truth() {
        use Judgement::*;
        let decided = |d| cell(0.5, 0.5, d);
        let cases = [
            (0, decided(Some(State::Empty)), CorrectFree),
            (0, decided(Some(State::Occupied)), FalseOccupied),
            (0, decided(Some(State::Unknown)), Unknown),
            (0, decided(None), Unknown),
            (0, None, Unknown),
            (1, decided(Some(State::Occupied)), CorrectOccupied),
            (1, decided(Some(State::Empty)), MissedOccupied),
            (1, decided(None), MissedOccupied),
            (1, None, MissedOccupied),
            (2, decided(Some(State::Occupied)), Occluder),
            (3, decided(Some(State::Occupied)), Ego),
        ];
        for (truth, fused, expected) in cases {
            assert_eq!(Judgement::of(truth, fused.as_ref()), expected, "{truth} {fused:?}");
        }
    }

    #[test]
    fn value_colours_run_from_end_to_end() {
        assert_eq!(probability_colour(0.0), [255; 3]);
        assert_eq!(probability_colour(1.0), [0; 3]);
        assert_eq!(probability_colour(0.5), [128; 3]);
        assert_eq!(probability_colour(7.0), [0; 3], "clamped");
        assert_eq!(uncertainty_colour(0.0), VIRIDIS[0]);
        assert_eq!(uncertainty_colour(1.0), VIRIDIS[8]);
        assert_eq!(uncertainty_colour(0.5), VIRIDIS[4]);
        // Halfway between two stops is their mean.
        let mid = uncertainty_colour(1.0 / 16.0);
        for i in 0..3 {
            let mean = (f32::from(VIRIDIS[0][i]) + f32::from(VIRIDIS[1][i])) / 2.0;
            assert!((f32::from(mid[i]) - mean).abs() <= 0.5, "{mid:?}");
        }
        // Viridis grows lighter throughout, so uncertainty reads as brightness too.
        let light = |c: Rgb| 0.2126 * f32::from(c[0]) + 0.7152 * f32::from(c[1]) + 0.0722 * f32::from(c[2]);
        assert!(VIRIDIS.windows(2).all(|w| light(w[0]) < light(w[1])));
    }

    #[test]
    fn legends_show_the_colours_the_pictures_use() {
        let probability = scale(probability_colour, "0", "1");
        assert!(
            probability
                .gradient
                .starts_with("linear-gradient(to right, #ffffff 0%, ")
        );
        assert!(probability.gradient.ends_with(", #000000 100%)"));
        let uncertainty = scale(uncertainty_colour, "0", "1");
        assert!(uncertainty.gradient.contains("#440154 0%") && uncertainty.gradient.contains("#fde725 100%"));
        assert!(uncertainty.gradient.contains(&format!("{} 50%", hex(VIRIDIS[4]))));
    }

    /// A 4 × 1 grid pictured whole: each picture colours the cells as its
    /// legend says, and the error map has one swatch per class.
    #[test]
    fn a_hand_made_snapshot_is_drawn_as_its_legends_say() {
        let grid = Grid {
            origin: [0.0, 0.0],
            cell: 1.0,
            cols: 4,
            rows: 1,
        };
        // A free cell decided free, an occupied cell missed, an occluder, the ego.
        let snapshot = Snapshot {
            step: 5,
            truth: vec![0, 1, 2, 3],
            ego: vec![1, 0, 0, 2],
            fused: vec![cell(0.0, 0.25, Some(State::Empty)), cell(0.5, 1.0, None), None, None],
        };
        let pictures = pictures(&grid, 0.1, &snapshot, None, true).unwrap();
        assert!((pictures.time - 0.5).abs() < 1e-12);
        let titles: Vec<&str> = pictures.images.iter().map(|p| p.title).collect();
        assert_eq!(
            titles,
            [
                "Ground truth",
                "The ego's own grid",
                "Fused occupancy",
                "Fused uncertainty",
                "Error map"
            ]
        );
        let pixels = |i: usize| -> Vec<Rgb> {
            let (bytes, size) = decode(&pictures.images[i].src);
            assert_eq!(size, (4, 1));
            bytes.chunks(3).map(|c| [c[0], c[1], c[2]]).collect()
        };
        assert_eq!(pixels(0), [FREE, OCCUPIED, OCCLUDER, EGO]);
        assert_eq!(pixels(1), [FREE, UNKNOWN, OCCLUDER, EGO]);
        assert_eq!(pixels(2), [FREE, probability_colour(0.5), OCCLUDER, EGO]);
        assert_eq!(pixels(3), [uncertainty_colour(0.25), VIRIDIS[8], OCCLUDER, EGO]);
        assert_eq!(pixels(4), [FREE, MISSED_OCCUPIED, OCCLUDER, EGO]);
        for (i, picture) in pictures.images.iter().enumerate() {
            let legend: Vec<&str> = picture.legend.swatches.iter().map(|s| s.colour.as_str()).collect();
            for colour in pixels(i).into_iter().filter(|&c| [OCCLUDER, EGO, UNKNOWN].contains(&c)) {
                assert!(legend.contains(&hex(colour).as_str()), "{}: {colour:?}", picture.title);
            }
        }
        assert_eq!(pictures.images[4].legend.swatches.len(), Judgement::ALL.len());
        assert!(pictures.images[3].caption.contains("m(Θ)"));
        let bayes = super::pictures(&grid, 0.1, &snapshot, None, false).unwrap();
        assert!(bayes.images[3].caption.contains("entropy"));
    }

    /// The error map's colours stay apart for readers with each kind of colour
    /// blindness: CIELAB ΔE ≥ 15 between every two classes after simulating
    /// protanopia, deuteranopia and tritanopia (Machado, Oliveira and Fernandes
    /// 2009, severity 1), and unsimulated.
    #[test]
    fn error_map_colours_stay_apart_for_colour_blind_readers() {
        let simulations: [[[f64; 3]; 3]; 4] = [
            [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            [
                [0.152286, 1.052583, -0.204868],
                [0.114503, 0.786281, 0.099216],
                [-0.003882, -0.048116, 1.051998],
            ],
            [
                [0.367322, 0.860646, -0.227968],
                [0.280085, 0.672501, 0.047413],
                [-0.011820, 0.042940, 0.968881],
            ],
            [
                [1.255528, -0.076749, -0.178779],
                [-0.078411, 0.930809, 0.147602],
                [0.004733, 0.691367, 0.303900],
            ],
        ];
        let linear = |c: u8| {
            let c = f64::from(c) / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        };
        let lab = |[r, g, b]: [f64; 3]| {
            let f = |t: f64| {
                if t > 0.008856 {
                    t.cbrt()
                } else {
                    7.787 * t + 16.0 / 116.0
                }
            };
            let x = f((0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047);
            let y = f(0.2126 * r + 0.7152 * g + 0.0722 * b);
            let z = f((0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883);
            [116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)]
        };
        for m in simulations {
            let seen: Vec<[f64; 3]> = Judgement::ALL
                .iter()
                .map(|j| {
                    let c = j.colour().map(linear);
                    lab(std::array::from_fn(|i| {
                        (m[i][0] * c[0] + m[i][1] * c[1] + m[i][2] * c[2]).clamp(0.0, 1.0)
                    }))
                })
                .collect();
            for (i, a) in seen.iter().enumerate() {
                for (j, b) in seen.iter().enumerate().skip(i + 1) {
                    let distance = a.iter().zip(b).map(|(p, q)| (p - q).powi(2)).sum::<f64>().sqrt();
                    let pair = (Judgement::ALL[i], Judgement::ALL[j]);
                    assert!(distance >= 15.0, "{pair:?} are {distance:.1} apart under {m:?}");
                }
            }
        }
    }
}
