//! One pass over the grid: sample every sensor's mass for every cell in range
//! once per sampling, and fuse and decide each sampling with its jobs.
//!
//! Rows are independent: each draws its masses from its own random stream
//! (scenario seed, row), cells left to right, sensors in layout order. Rows run in
//! parallel and their tallies merge in row order, so results are bit-identical
//! whatever the thread count.
//!
//! Samplings of one pass differ only in their mass model (`field.masses`, such
//! as γ): they share the grid, the truth, the sensors and so every row's
//! candidate sensors, distances, distance bands and each rule's weights
//! ([`Weights`]), computed once per row.
//! Each sampling draws from the row's stream from its start, so its draws are
//! the ones it would draw alone.

use rayon::prelude::*;
use sightline_dsl::{Field, Grid, Masses, Rule};

use super::layout::{self, positions};
use super::sensor::{self, Dirichlet, Draw, SensorModel};
use super::truth::{self, GroundTruth};
use crate::fusion::{BatchScratch, Mass, Source, Weights, fuse_cells};
use crate::idealisation::Idealisation;
use crate::math::Point;
use crate::metrics::{Coverage, FieldOutcome, Tally};
use crate::rng::mass_stream;
use crate::run::Job;

/// The idealisations of the field experiment, besides those of its options
/// (error model, fusion method).
pub(crate) const IDEALISATIONS: &[Idealisation] = &[
    truth::STATIC_TRUTH,
    layout::EXACT_POSITIONS,
    sensor::ALL_IN_RANGE,
    sensor::LINEAR_MISDETECTION,
    sensor::INDEPENDENT_SAMPLES,
];

/// One mass model of a pass and the methods that fuse what it draws.
#[derive(Debug, Clone, Copy)]
pub struct Sampling<'a> {
    /// The mass model, in place of the field's own.
    pub masses: Masses,
    /// The methods, each fusing and deciding the same draws.
    pub jobs: &'a [Job<'a>],
}

/// A sensor that may reach cells of the current row.
#[derive(Debug, Clone, Copy)]
struct Candidate {
    x: f64,
    dy_squared: f64,
    first_col: usize,
    last_col: usize,
}

/// Sensors per cell, for one row.
#[derive(Debug, Clone, Copy)]
struct RowCoverage {
    min: usize,
    max: usize,
    sum: u64,
}

/// Runs the field experiment once for `grid` and `field` with each of
/// `samplings`' mass models (the field's own `masses` is not read), and
/// evaluates every job of a sampling on the masses it sampled. Returns, per
/// sampling, one outcome per job, in order: each the outcome the sampling
/// gives alone.
///
/// Distances below half a cell count as half a cell in the fusion weights, so a
/// sensor standing on a cell still gives that cell a finite weight.
pub fn run(seed: u64, grid: &Grid, field: &Field, samplings: &[Sampling<'_>]) -> Vec<Vec<FieldOutcome>> {
    let truth = GroundTruth::generate(grid, &field.truth, seed);
    let sensors = positions(&field.layout, grid, seed);
    let models: Vec<SensorModel> = samplings
        .iter()
        .map(|sampling| SensorModel::new(sampling.masses, field.range))
        .collect();
    let bands = field.distance_bands.len() + 1;
    let mut rules: Vec<Rule> = Vec::new();
    for job in samplings.iter().flat_map(|sampling| sampling.jobs) {
        if !rules.contains(&job.fusion.rule) {
            rules.push(job.fusion.rule);
        }
    }
    let fusions: Vec<Vec<(usize, Vec<usize>)>> = samplings
        .iter()
        .map(|sampling| {
            let mut fusions: Vec<(usize, Vec<usize>)> = Vec::new();
            for (index, job) in sampling.jobs.iter().enumerate() {
                let rule = rules
                    .iter()
                    .position(|rule| *rule == job.fusion.rule)
                    .expect("every job's rule is a rule of the pass");
                match fusions.iter_mut().find(|(r, _)| *r == rule) {
                    Some((_, jobs)) => jobs.push(index),
                    None => fusions.push((rule, vec![index])),
                }
            }
            fusions
        })
        .collect();
    let pass = Pass {
        seed,
        grid,
        field,
        truth: &truth,
        sensors: &sensors,
        models: &models,
        samplings,
        fusions: &fusions,
        rules: &rules,
        // Band membership needs the nearest sensor only up to the last band edge.
        reach: field.distance_bands.last().copied().unwrap_or(0.0).max(field.range),
        min_distance: grid.cell / 2.0,
    };
    let rows: Vec<(Vec<Tally>, RowCoverage)> = (0..grid.rows)
        .into_par_iter()
        .map_init(Scratch::default, |scratch, row| pass.row(row, scratch))
        .collect();

    let jobs = || samplings.iter().flat_map(|sampling| sampling.jobs);
    let mut tallies: Vec<Tally> = jobs().map(|_| Tally::new(bands)).collect();
    let mut coverage = RowCoverage {
        min: usize::MAX,
        max: 0,
        sum: 0,
    };
    for (row_tallies, row_coverage) in &rows {
        for (tally, row_tally) in tallies.iter_mut().zip(row_tallies) {
            tally.merge(row_tally);
        }
        coverage.min = coverage.min.min(row_coverage.min);
        coverage.max = coverage.max.max(row_coverage.max);
        coverage.sum += row_coverage.sum;
    }
    let coverage = Coverage {
        sensors: sensors.len(),
        min_sources: if grid.cells() == 0 { 0 } else { coverage.min },
        max_sources: coverage.max,
        mean_sources: coverage.sum as f64 / grid.cells() as f64,
    };
    let mut outcomes = tallies
        .iter()
        .zip(jobs())
        .map(|(tally, job)| tally.finish(&field.distance_bands, job.fusion.rule.is_evidential(), coverage));
    samplings
        .iter()
        .map(|sampling| outcomes.by_ref().take(sampling.jobs.len()).collect())
        .collect()
}

/// Buffers reused across the rows one thread processes.
#[derive(Default)]
struct Scratch {
    candidates: Vec<Candidate>,
    /// The row's draws, cell by cell, and where each cell's end.
    draws: Vec<Draw>,
    ends: Vec<usize>,
    /// Per cell of the row: its distance band and truth.
    cells: Vec<(usize, bool)>,
    dirichlets: Vec<Dirichlet>,
    masses: Vec<Mass>,
    sources: Vec<Source>,
    /// Per rule of the pass, in [`Pass::rules`] order: its weights for the row.
    weights: Vec<Weights>,
    fusion: BatchScratch,
}

/// Everything a row needs, shared by all rows of a pass.
struct Pass<'a> {
    seed: u64,
    grid: &'a Grid,
    field: &'a Field,
    truth: &'a GroundTruth,
    sensors: &'a [Point],
    models: &'a [SensorModel],
    samplings: &'a [Sampling<'a>],
    /// The distinct rules of the jobs: each weighs a row's sources once.
    rules: &'a [Rule],
    /// Per sampling, each of its rules (an index into `rules`) and the jobs
    /// (indices into the sampling's) that fuse with it: methods that differ
    /// in label or decision only share one fusion of the row.
    fusions: &'a [Vec<(usize, Vec<usize>)>],
    reach: f64,
    min_distance: f64,
}

impl Pass<'_> {
    /// Finds the row's sources and weighs them for each rule, then, sampling
    /// by sampling, samples their masses, fuses the whole row once with each
    /// rule of the sampling's jobs (see [`fuse_cells`]) and tallies it for
    /// every job of that rule: the tallies of every job, samplings in order.
    fn row(&self, row: usize, scratch: &mut Scratch) -> (Vec<Tally>, RowCoverage) {
        let grid = self.grid;
        let bands = &self.field.distance_bands;
        let range_squared = self.field.range * self.field.range;
        let y = grid.cell_center(0, row)[1];
        self.candidates(y, &mut scratch.candidates);

        // Every sampling draws from the row's stream from its start.
        let rng = mass_stream(self.seed, row as u64);
        let mut coverage = RowCoverage {
            min: usize::MAX,
            max: 0,
            sum: 0,
        };
        scratch.draws.clear();
        scratch.ends.clear();
        scratch.cells.clear();
        for col in 0..grid.cols {
            let x = grid.cell_center(col, row)[0];
            let occupied = self.truth.is_occupied(col, row);
            let first = scratch.draws.len();
            let mut nearest_squared = f64::INFINITY;
            for candidate in &scratch.candidates {
                if col < candidate.first_col || col > candidate.last_col {
                    continue;
                }
                let dx = x - candidate.x;
                let distance_squared = dx * dx + candidate.dy_squared;
                nearest_squared = nearest_squared.min(distance_squared);
                if distance_squared <= range_squared {
                    scratch.draws.push(Draw {
                        distance: distance_squared.sqrt(),
                        occupied,
                    });
                }
            }
            let band = bands.partition_point(|&edge| edge <= nearest_squared.sqrt());
            let count = scratch.draws.len() - first;
            coverage.min = coverage.min.min(count);
            coverage.max = coverage.max.max(count);
            coverage.sum += count as u64;
            scratch.ends.push(scratch.draws.len());
            scratch.cells.push((band, occupied));
        }
        // The sources' distances and each rule's weights, for every sampling.
        scratch.sources.clear();
        scratch.sources.extend(scratch.draws.iter().map(|draw| Source {
            mass: Mass::new(0.0, 0.0, 1.0),
            distance: draw.distance.max(self.min_distance),
        }));
        scratch.weights.resize_with(self.rules.len(), Weights::default);
        for (rule, weights) in self.rules.iter().zip(&mut scratch.weights) {
            weights.plan(rule, &scratch.sources, &scratch.ends);
        }
        let mut tallies = Vec::new();
        for ((sampling, model), fusions) in self.samplings.iter().zip(self.models).zip(self.fusions) {
            model.sample_many(
                &scratch.draws,
                &mut rng.clone(),
                &mut scratch.dirichlets,
                &mut scratch.masses,
            );
            for (source, &mass) in scratch.sources.iter_mut().zip(&scratch.masses) {
                source.mass = mass;
            }
            let first = tallies.len();
            tallies.extend(sampling.jobs.iter().map(|_| Tally::new(bands.len() + 1)));
            let sampling_tallies = &mut tallies[first..];
            for (rule, jobs) in fusions {
                let cells = &scratch.cells;
                fuse_cells(
                    &self.rules[*rule],
                    &scratch.weights[*rule],
                    &scratch.sources,
                    &scratch.ends,
                    &mut scratch.fusion,
                    |col, estimate| {
                        let (band, occupied) = cells[col];
                        for &job in jobs {
                            let decision = sampling.jobs[job].decision;
                            sampling_tallies[job].record(band, occupied, estimate.as_ref(), decision);
                        }
                    },
                );
            }
        }
        (tallies, coverage)
    }

    /// The sensors within `reach` of the row at height `y`, with the columns they
    /// may reach (a conservative range; distances are checked per cell).
    fn candidates(&self, y: f64, out: &mut Vec<Candidate>) {
        let grid = self.grid;
        out.clear();
        for sensor in self.sensors {
            let dy = y - sensor.y;
            if dy.abs() > self.reach {
                continue;
            }
            let half_width = (self.reach * self.reach - dy * dy).sqrt();
            let to_col = |x: f64| (x - grid.origin[0]) / grid.cell - 0.5;
            let first = to_col(sensor.x - half_width).floor() - 1.0;
            let last = to_col(sensor.x + half_width).ceil() + 1.0;
            if last < 0.0 || first > (grid.cols - 1) as f64 {
                continue;
            }
            out.push(Candidate {
                x: sensor.x,
                dy_squared: dy * dy,
                first_col: first.max(0.0) as usize,
                last_col: last.min((grid.cols - 1) as f64) as usize,
            });
        }
    }
}
