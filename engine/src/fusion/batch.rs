//! Fusion of many cells at once: what [`fuse`] gives cell by cell, bit for
//! bit, with the weighted rule's power transforms of all the cells computed
//! first, in one branch-free pass ([`pow_many`]).
//!
//! Cell by cell, each source's two powers wait on the source before them
//! through the combination; in one pass over a row's sources they do not wait
//! on anything, and the processor overlaps them. The seed 001 experiment
//! fuses a row of 1000 cells (about 5 700 sources) at a time.

use sightline_dsl::{Rule, SourceCombination, SwitchMeasure};

use super::dempster::Combiner;
use super::rule::{Estimate, Source, fuse};
use super::weighted::{Distances, Ratios};
use crate::elementary::pow_many;

/// Buffers reused from batch to batch.
#[derive(Debug, Default)]
pub struct BatchScratch {
    /// Per cell: whether the weighted rule fuses it.
    weighted: Vec<bool>,
    /// Per source of a weighted cell, in order: its largest state, whose two
    /// ratios are the next pair in `ratios` (`None`: its weight is 1, it is
    /// used as it is).
    transforms: Vec<Option<Ratios>>,
    ratios: Vec<f64>,
    weights: Vec<f64>,
    powers: Vec<f64>,
}

/// Fuses every cell of a batch with `rule` and hands each estimate to
/// `each(cell, estimate)` in cell order (`None` for a cell without sources).
/// Cell `i`'s sources are `sources[ends[i - 1]..ends[i]]` (from 0 for the
/// first). The estimates are [`fuse`]'s, bit for bit.
pub fn fuse_cells(
    rule: &Rule,
    sources: &[Source],
    ends: &[usize],
    scratch: &mut BatchScratch,
    mut each: impl FnMut(usize, Option<Estimate>),
) {
    let cells = || {
        ends.iter()
            .scan(0, |start, &end| Some(&sources[std::mem::replace(start, end)..end]))
    };
    let (weighting, switch) = match rule {
        Rule::DistanceWeighted(weighting) if weighting.sources == SourceCombination::AllAtOnce => (weighting, None),
        Rule::Hybrid { weighting, switch } if weighting.sources == SourceCombination::AllAtOnce => {
            (weighting, Some(switch))
        }
        // No power transform, or one that depends on the order of the fold.
        _ => {
            for (cell, sources) in cells().enumerate() {
                each(cell, (!sources.is_empty()).then(|| fuse(rule, sources)));
            }
            return;
        }
    };

    // The weights and the ratios to raise, for every source of a weighted cell.
    let BatchScratch {
        weighted,
        transforms,
        ratios,
        weights,
        powers,
    } = scratch;
    weighted.clear();
    transforms.clear();
    ratios.clear();
    weights.clear();
    for sources in cells() {
        let distances = Distances::of(sources.iter().map(|s| s.distance));
        let is_weighted = match switch {
            None => true,
            Some(switch) => {
                let spread = match switch.measure {
                    SwitchMeasure::Difference => distances.max - distances.min,
                    SwitchMeasure::Ratio => distances.max / distances.min,
                };
                sources.len() > 1 && spread > switch.threshold
            }
        };
        weighted.push(is_weighted);
        if !is_weighted {
            continue;
        }
        for source in sources {
            let weight = distances.weight(source.distance, weighting.scaling);
            if weight == 1.0 {
                transforms.push(None);
                continue;
            }
            let (largest, pair) = Ratios::of(source.mass);
            transforms.push(Some(largest));
            ratios.extend(pair);
            weights.extend([weight; 2]);
        }
    }
    powers.clear();
    powers.resize(ratios.len(), 0.0);
    pow_many(ratios, weights, powers);

    // Each cell combined in order, as `fuse` does.
    let mut transforms = transforms.iter();
    let mut powers = powers.chunks_exact(2);
    for ((cell, sources), &is_weighted) in cells().enumerate().zip(weighted.iter()) {
        if sources.is_empty() {
            each(cell, None);
            continue;
        }
        let mut combiner = Combiner::new();
        if is_weighted {
            for (source, transform) in sources.iter().zip(transforms.by_ref()) {
                combiner.add(match transform {
                    Some(largest) => {
                        let pair = powers.next().expect("two powers per transformed source");
                        largest.terms([pair[0], pair[1]])
                    }
                    None => source.mass,
                });
            }
        } else {
            sources.iter().for_each(|source| combiner.add(source.mass));
        }
        let weighted = match switch {
            None => sources.len() > 1,
            Some(_) => is_weighted,
        };
        each(
            cell,
            Some(Estimate::Evidential {
                combination: combiner.finish(),
                weighted,
            }),
        );
    }
}

#[cfg(test)]
mod tests {
    use proptest::collection::vec;
    use proptest::prelude::*;
    use sightline_dsl::{Switch, WeightScaling};

    use super::*;
    use crate::fusion::Mass;
    use sightline_dsl::Weighting;

    /// A mass function from three non-negative parts (not all zero).
    fn mass() -> impl Strategy<Value = Mass> {
        (0u32..=1000, 0u32..=1000, 1u32..=1000).prop_map(|(e, o, u)| {
            let total = f64::from(e + o + u);
            Mass::new(f64::from(e) / total, f64::from(o) / total, f64::from(u) / total)
        })
    }

    /// Cells of zero to eight sources at 0.25 to 250 m.
    fn cells() -> impl Strategy<Value = Vec<Vec<Source>>> {
        vec(
            vec(
                (mass(), 1u32..=1000).prop_map(|(mass, d)| Source {
                    mass,
                    distance: f64::from(d) / 4.0,
                }),
                0..8,
            ),
            1..12,
        )
    }

    fn rules() -> Vec<Rule> {
        let mut rules = vec![Rule::Bayes, Rule::Dempster];
        for scaling in [
            WeightScaling::SumToOne,
            WeightScaling::MeanOne,
            WeightScaling::NearestOne,
        ] {
            for sources in [SourceCombination::AllAtOnce, SourceCombination::Pairwise] {
                let weighting = Weighting { scaling, sources };
                rules.push(Rule::DistanceWeighted(weighting));
                for (measure, threshold) in [(SwitchMeasure::Difference, 50.0), (SwitchMeasure::Ratio, 2.0)] {
                    rules.push(Rule::Hybrid {
                        weighting,
                        switch: Switch { measure, threshold },
                    });
                }
            }
        }
        rules
    }

    /// Every rule fuses a batch as `fuse` fuses each of its cells, to the bit.
    #[test]
    fn a_batch_is_fused_as_each_cell_alone() {
        let mut runner = crate::pinned::runner(256, 0x5167_4711_0021);
        let scratch = std::cell::RefCell::new(BatchScratch::default());
        runner
            .run(&cells(), |cells| {
                let sources: Vec<Source> = cells.iter().flatten().copied().collect();
                let ends: Vec<usize> = cells
                    .iter()
                    .scan(0, |end, cell| {
                        *end += cell.len();
                        Some(*end)
                    })
                    .collect();
                for rule in rules() {
                    let mut batch = Vec::new();
                    fuse_cells(&rule, &sources, &ends, &mut scratch.borrow_mut(), |cell, estimate| {
                        batch.push((cell, estimate));
                    });
                    let alone: Vec<_> = cells
                        .iter()
                        .enumerate()
                        .map(|(cell, sources)| (cell, (!sources.is_empty()).then(|| fuse(&rule, sources))))
                        .collect();
                    prop_assert_eq!(format!("{batch:?}"), format!("{alone:?}"), "{:?}", rule);
                }
                Ok(())
            })
            .unwrap();
    }
}
