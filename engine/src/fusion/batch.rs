//! Fusion of many cells at once: what [`fuse`] gives cell by cell, bit for
//! bit, with the weighted rule's power transforms of all the cells computed
//! first, in one branch-free pass ([`pow_many`]).
//!
//! Cell by cell, each source's two powers wait on the source before them
//! through the combination; in one pass over a row's sources they do not wait
//! on anything, and the processor overlaps them. The seed 001 experiment
//! fuses a row of 1000 cells (about 5 700 sources) at a time.
//!
//! What the weighted rule reads of the distances alone, which cells it weighs
//! and with what weights, is planned apart ([`Weights`]), so that batches of
//! sources at the same distances share it.

use sightline_dsl::{Rule, SourceCombination, Switch, SwitchMeasure, Weighting};

use super::dempster::Combiner;
use super::rule::{Estimate, Source, fuse};
use super::weighted::{Distances, Ratios};
use crate::elementary::pow_many;

/// Buffers reused from batch to batch.
#[derive(Debug, Default)]
pub struct BatchScratch {
    /// Per source of a weighted cell, in order: its largest state, whose two
    /// ratios are the next pair in `ratios` (`None`: its weight is 1, it is
    /// used as it is).
    transforms: Vec<Option<Ratios>>,
    ratios: Vec<f64>,
    weights: Vec<f64>,
    powers: Vec<f64>,
}

/// What the weighted rule decides from a batch's distances alone: which
/// cells it weighs and the weight of each of their sources. Batches whose
/// sources stand at the same distances (the samplings of one field pass)
/// share it.
#[derive(Debug, Default)]
pub struct Weights {
    /// Whether the rule transforms all of a cell's sources at once; if not,
    /// [`fuse_cells`] fuses cell by cell and reads nothing else.
    at_once: bool,
    /// Per cell: whether the weighted rule fuses it.
    weighted: Vec<bool>,
    /// Per source of a weighted cell, in order: its weight.
    weights: Vec<f64>,
}

/// The weighting and the switch of a rule that transforms all of a cell's
/// sources at once; `None` for a rule without a power transform, or one that
/// depends on the order of the fold.
fn at_once(rule: &Rule) -> Option<(&Weighting, Option<&Switch>)> {
    match rule {
        Rule::DistanceWeighted(weighting) if weighting.sources == SourceCombination::AllAtOnce => {
            Some((weighting, None))
        }
        Rule::Hybrid { weighting, switch } if weighting.sources == SourceCombination::AllAtOnce => {
            Some((weighting, Some(switch)))
        }
        _ => None,
    }
}

/// The cells of a batch: cell `i`'s sources are `sources[ends[i - 1]..ends[i]]`
/// (from 0 for the first).
fn cells<'a>(sources: &'a [Source], ends: &'a [usize]) -> impl Iterator<Item = &'a [Source]> {
    ends.iter()
        .scan(0, |start, &end| Some(&sources[std::mem::replace(start, end)..end]))
}

impl Weights {
    /// Plans `rule` for the batch of `sources` (only their distances are
    /// read) cut by `ends` (see [`fuse_cells`]), reusing this plan's buffers.
    pub fn plan(&mut self, rule: &Rule, sources: &[Source], ends: &[usize]) {
        self.weighted.clear();
        self.weights.clear();
        let Some((weighting, switch)) = at_once(rule) else {
            self.at_once = false;
            return;
        };
        self.at_once = true;
        for sources in cells(sources, ends) {
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
            self.weighted.push(is_weighted);
            if is_weighted {
                self.weights.extend(
                    sources
                        .iter()
                        .map(|source| distances.weight(source.distance, weighting.scaling)),
                );
            }
        }
    }
}

/// Fuses every cell of a batch with `rule` and hands each estimate to
/// `each(cell, estimate)` in cell order (`None` for a cell without sources).
/// Cell `i`'s sources are `sources[ends[i - 1]..ends[i]]` (from 0 for the
/// first); `weights` is [`Weights::plan`]'s for the same rule and the same
/// distances and ends. The estimates are [`fuse`]'s, bit for bit.
pub fn fuse_cells(
    rule: &Rule,
    weights: &Weights,
    sources: &[Source],
    ends: &[usize],
    scratch: &mut BatchScratch,
    mut each: impl FnMut(usize, Option<Estimate>),
) {
    if !weights.at_once {
        for (cell, sources) in cells(sources, ends).enumerate() {
            each(cell, (!sources.is_empty()).then(|| fuse(rule, sources)));
        }
        return;
    }
    debug_assert_eq!(weights.weighted.len(), ends.len(), "a plan of this batch");

    // The ratios to raise, and their weights, for every source of a weighted cell.
    let BatchScratch {
        transforms,
        ratios,
        weights: pair_weights,
        powers,
    } = scratch;
    transforms.clear();
    ratios.clear();
    pair_weights.clear();
    let mut planned = weights.weights.iter();
    for (sources, _) in cells(sources, ends).zip(&weights.weighted).filter(|(_, w)| **w) {
        for (source, &weight) in sources.iter().zip(planned.by_ref()) {
            if weight == 1.0 {
                transforms.push(None);
                continue;
            }
            let (largest, pair) = Ratios::of(source.mass);
            transforms.push(Some(largest));
            ratios.extend(pair);
            pair_weights.extend([weight; 2]);
        }
    }
    powers.clear();
    powers.resize(ratios.len(), 0.0);
    pow_many(ratios, pair_weights, powers);

    // Each cell combined in order, as `fuse` does.
    let switched = matches!(rule, Rule::Hybrid { .. });
    let mut transforms = transforms.iter();
    let mut powers = powers.chunks_exact(2);
    for ((cell, sources), &is_weighted) in cells(sources, ends).enumerate().zip(&weights.weighted) {
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
        let weighted = if switched { is_weighted } else { sources.len() > 1 };
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
    use sightline_dsl::WeightScaling;

    use super::*;
    use crate::fusion::Mass;

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
        let scratch = std::cell::RefCell::new((Weights::default(), BatchScratch::default()));
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
                    let (weights, scratch) = &mut *scratch.borrow_mut();
                    weights.plan(&rule, &sources, &ends);
                    fuse_cells(&rule, weights, &sources, &ends, scratch, |cell, estimate| {
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
