//! Ranges, units and defaults of the simulation settings: raw → [`Setup`].

use super::budget::within_budget;
use super::checks::{coordinates, whole_multiple};
use super::context::Context;
use super::ignored::ignored_keys;
use super::kind::Kind;
use super::map::Mapped;
use super::traces::Imported;
use super::world::world;
use crate::error::ErrorKind;
use crate::model::{
    Decision, Experiment, Field, Fusion, FusionMethod, Grid, Layout, Masses, Occupancy, Rule, Setup, Switch,
    SwitchMeasure, Truth, Weighting,
};
use crate::path::Path;
use crate::raw::range;
use crate::raw::{RawDecision, RawField, RawFusion, RawGrid, RawLayout, RawMasses, RawScenario, RawTruth};

/// The largest grid sightline accepts, in cells. The field experiment keeps one
/// byte of ground truth per cell and streams everything else by row, so this
/// bounds its memory to about 25 MB plus a few MB of working buffers.
pub const MAX_CELLS: usize = 25_000_000;

/// The most sensors a field may have.
pub const MAX_SENSORS: usize = 1_000;

/// Compiles the simulation settings of one scenario (or one sweep point), and
/// refuses the keys its kind of scenario never reads.
pub(super) fn setup(
    ctx: &mut Context<'_>,
    raw: &RawScenario,
    imported: Option<&Imported>,
    mapped: Option<&Mapped>,
) -> Option<Setup> {
    let root = Path::root();
    let kind = Kind::of(ctx.tree);
    if let Some(kind) = kind {
        for (path, why) in ignored_keys(ctx.tree, kind, ctx.driven) {
            ctx.error_at_key(&path, ErrorKind::NoEffect(why.into()));
        }
    }
    // A semantic world fuses no grid; every other kind needs one.
    let fuses = kind.is_some_and(|kind| kind != Kind::Semantic);
    let grid = match &raw.grid {
        Some(raw_grid) if fuses => grid(ctx, raw_grid, &root.key("grid")),
        None if fuses => {
            ctx.error(&root, ErrorKind::MissingKey("grid".into()));
            None
        }
        _ => None,
    };
    let experiment = match &raw.field {
        Some(field_raw) => grid
            .as_ref()
            .and_then(|g| field(ctx, field_raw, g, &root.key("field")))
            .map(Experiment::Field),
        None => world(ctx, raw, imported, mapped).map(|w| Experiment::World(Box::new(w))),
    };
    let occupancy = if fuses {
        let fusion = fusion(ctx, &raw.fusion, &root.key("fusion"));
        let decision = decision(ctx, &raw.decision, &root.key("decision"));
        Some(Occupancy {
            grid: grid?,
            fusion: fusion?,
            decision: decision?,
        })
    } else {
        None
    };
    let setup = Setup {
        seed: raw.seed,
        experiment: experiment?,
        occupancy,
    };
    within_budget(ctx, &setup).then_some(setup)
}

fn grid(ctx: &mut Context<'_>, raw: &RawGrid, path: &Path) -> Option<Grid> {
    let origin_ok = coordinates(ctx, &path.key("origin"), &[raw.origin]);
    let sizes_ok = raw
        .size
        .iter()
        .enumerate()
        .all(|(i, &v)| ctx.within(&path.key("size").index(i), v, range::EXTENT));
    let cell_ok = ctx.within(&path.key("cell"), raw.cell, range::CELL);
    if !(origin_ok && sizes_ok && cell_ok) {
        return None;
    }
    let mut counts = [0.0; 2];
    for (i, count) in counts.iter_mut().enumerate() {
        match whole_multiple(raw.size[i], raw.cell) {
            Some(n) => *count = n,
            None => {
                ctx.error(
                    &path.key("size").index(i),
                    ErrorKind::OutOfRange {
                        expected: format!("a whole number of {} m cells", raw.cell),
                        found: raw.size[i].to_string(),
                    },
                );
                return None;
            }
        }
    }
    // Compare in f64 so that absurd sizes cannot overflow before the check.
    let cells = counts[0] * counts[1];
    if cells > MAX_CELLS as f64 {
        ctx.error(
            path,
            ErrorKind::TooLarge(format!(
                "a grid of {} × {} cells ({cells:.0} cells) exceeds the limit of {MAX_CELLS} cells; \
                 use larger cells or a smaller area",
                counts[0], counts[1]
            )),
        );
        return None;
    }
    Some(Grid {
        origin: raw.origin,
        cell: raw.cell,
        cols: counts[0] as usize,
        rows: counts[1] as usize,
    })
}

fn field(ctx: &mut Context<'_>, raw: &RawField, grid: &Grid, path: &Path) -> Option<Field> {
    let truth = truth(ctx, &raw.truth, grid, &path.key("truth"));
    let sensors_path = path.key("sensors");
    let range_ok = ctx.within(&sensors_path.key("range"), raw.sensors.range, range::SENSOR_RANGE);
    let layout = layout(ctx, &raw.sensors.layout, &sensors_path.key("layout"), grid);
    let masses = masses(ctx, &raw.masses, &path.key("masses"));
    let bands_path = path.key("distance_bands");
    let mut bands_ok = true;
    for (i, pair) in raw.distance_bands.windows(2).enumerate() {
        bands_ok &= ctx.expect(
            pair[1] > pair[0],
            &bands_path.index(i + 1),
            &format!("a number > {} (edges increase)", pair[0]),
            pair[1],
        );
    }
    for (i, &edge) in raw.distance_bands.iter().enumerate() {
        bands_ok &= ctx.within(&bands_path.index(i), edge, range::EXTENT);
    }
    Some(Field {
        truth: truth?,
        range: range_ok.then_some(raw.sensors.range)?,
        layout: layout?,
        masses: masses?,
        distance_bands: bands_ok.then(|| raw.distance_bands.clone())?,
    })
}

fn truth(ctx: &mut Context<'_>, raw: &RawTruth, grid: &Grid, path: &Path) -> Option<Truth> {
    let fraction_ok = ctx.probability(&path.key("occupied_fraction"), raw.occupied_fraction);
    let blob_cells = match raw.blob {
        None => 1,
        Some(blob) => {
            let blob_path = path.key("blob");
            if !ctx.within(&blob_path, blob, range::EXTENT) {
                return None;
            }
            match whole_multiple(blob, grid.cell) {
                Some(n) if n <= grid.cols.max(grid.rows) as f64 => n as usize,
                _ => {
                    ctx.error(
                        &blob_path,
                        ErrorKind::OutOfRange {
                            expected: format!("a whole number of {} m cells, at most the grid's side", grid.cell),
                            found: blob.to_string(),
                        },
                    );
                    return None;
                }
            }
        }
    };
    fraction_ok.then_some(Truth {
        occupied_fraction: raw.occupied_fraction,
        blob_cells,
    })
}

fn layout(ctx: &mut Context<'_>, raw: &RawLayout, path: &Path, grid: &Grid) -> Option<Layout> {
    let given = [raw.regular.is_some(), raw.positions.is_some(), raw.random.is_some()];
    if given.iter().filter(|&&g| g).count() != 1 {
        ctx.error(
            path,
            ErrorKind::Invalid("give exactly one of `regular`, `positions`, `random`".into()),
        );
        return None;
    }
    let count_ok = |ctx: &mut Context<'_>, path: &Path, count: usize| {
        ctx.expect(
            (1..=MAX_SENSORS).contains(&count),
            path,
            &format!("from 1 to {MAX_SENSORS} sensors"),
            count as f64,
        )
    };
    if let Some(regular) = &raw.regular {
        let rows = regular.rows as usize;
        let cols = regular.cols as usize;
        let ok = ctx.expect(rows >= 1, &path.key("regular").key("rows"), "at least 1", rows as f64)
            & ctx.expect(cols >= 1, &path.key("regular").key("cols"), "at least 1", cols as f64)
            && count_ok(ctx, &path.key("regular"), rows * cols);
        if !ok {
            return None;
        }
        let width = grid.cols as f64 * grid.cell;
        let height = grid.rows as f64 * grid.cell;
        let positions = (0..rows)
            .flat_map(|r| {
                (0..cols).map(move |c| {
                    [
                        grid.origin[0] + (c as f64 + 0.5) * width / cols as f64,
                        grid.origin[1] + (r as f64 + 0.5) * height / rows as f64,
                    ]
                })
            })
            .collect();
        return Some(Layout::Positions(positions));
    }
    if let Some(positions) = &raw.positions {
        let list_path = path.key("positions");
        let ok = count_ok(ctx, &list_path, positions.len()) & coordinates(ctx, &list_path, positions);
        return ok.then(|| Layout::Positions(positions.clone()));
    }
    let random = raw.random.as_ref()?;
    let count = random.count as usize;
    count_ok(ctx, &path.key("random").key("count"), count).then_some(Layout::Random { count })
}

fn masses(ctx: &mut Context<'_>, raw: &RawMasses, path: &Path) -> Option<Masses> {
    let ok = ctx.within(&path.key("concentration"), raw.concentration, range::CONCENTRATION)
        & ctx.expect(
            raw.epsilon0 > 0.0 && raw.epsilon0 < 1.0,
            &path.key("epsilon0"),
            "a number between 0 and 1 (exclusive)",
            raw.epsilon0,
        )
        & ctx.within(&path.key("gamma"), raw.gamma, range::GAMMA);
    if !ok {
        return None;
    }
    let at_range = raw.epsilon0 + raw.gamma / 100.0;
    if at_range >= 1.0 {
        ctx.error(
            &path.key("gamma"),
            ErrorKind::OutOfRange {
                expected: format!(
                    "γ < {} so that the misdetection at the sensing range, ε0 + γ/100, stays below 1",
                    (1.0 - raw.epsilon0) * 100.0
                ),
                found: raw.gamma.to_string(),
            },
        );
        return None;
    }
    Some(Masses {
        concentration: raw.concentration,
        epsilon0: raw.epsilon0,
        gamma: raw.gamma,
        error_model: raw.error_model,
    })
}

fn fusion(ctx: &mut Context<'_>, raw: &RawFusion, path: &Path) -> Option<Fusion> {
    let label = match &raw.label {
        Some(label) if label.trim().is_empty() => {
            ctx.error(&path.key("label"), ErrorKind::Invalid("a label cannot be empty".into()));
            return None;
        }
        Some(label) => label.clone(),
        None => raw.method.name().to_string(),
    };
    let weighting = Weighting {
        scaling: raw.weights,
        sources: raw.sources,
    };
    let rule = match raw.method {
        FusionMethod::Bayes => Rule::Bayes,
        FusionMethod::Dempster => Rule::Dempster,
        FusionMethod::DistanceWeighted => Rule::DistanceWeighted(weighting),
        FusionMethod::Hybrid => {
            let Some(switch) = &raw.switch else {
                ctx.error(
                    path,
                    ErrorKind::Invalid(
                        "the hybrid rule needs `switch: { threshold: … }` (the paper gives no threshold)".into(),
                    ),
                );
                return None;
            };
            let threshold_path = path.key("switch").key("threshold");
            let ok = match switch.measure {
                SwitchMeasure::Difference => ctx.within(&threshold_path, switch.threshold, range::SWITCH),
                SwitchMeasure::Ratio => {
                    ctx.expect(
                        switch.threshold >= 1.0,
                        &threshold_path,
                        "a ratio ≥ 1",
                        switch.threshold,
                    ) && ctx.within(&threshold_path, switch.threshold, range::SWITCH)
                }
            };
            if !ok {
                return None;
            }
            Rule::Hybrid {
                weighting,
                switch: Switch {
                    measure: switch.measure,
                    threshold: switch.threshold,
                },
            }
        }
    };
    Some(Fusion { label, rule })
}

fn decision(ctx: &mut Context<'_>, raw: &RawDecision, path: &Path) -> Option<Decision> {
    ctx.probability(&path.key("threshold"), raw.threshold)
        .then_some(Decision {
            rule: raw.rule,
            threshold: raw.threshold,
        })
}
