//! Fused cells looked up instead of computed, where that gives the same bits.
//!
//! Under a rule that reads only its sources' masses (Bayes, Dempster), a cell
//! whose evidence is all fresh (weight 1) fuses to a value that depends on
//! nothing but the sequence of its sources' states, free or occupied, in
//! source order: the inverse sensor model gives each state one mass. A
//! [`Memo`] holds the judged cell of every such sequence up to
//! [`MEMO_SOURCES`] long, computed once a run by the very code that fuses an
//! uncached cell (the same sources, [`fuse`], then [`judge`]), so that a
//! lookup returns the same bits; the roundabout's 56 000 fused cells a step then need
//! no logarithm or exponential each.

use sightline_dsl::{Decision, Rule};

use super::evidence::Evidence;
use super::observe::Observed;
use crate::fusion::{Estimate, Source, State, decide, fuse, pignistic};

/// The longest sequence of sources a memo holds: 2¹¹ − 2 judged cells.
pub(super) const MEMO_SOURCES: u32 = 10;

/// A fused cell, judged: its estimate, P(occupied) and decision.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Judged {
    /// The fused estimate.
    pub(super) estimate: Estimate,
    /// Its pignistic (or Bayesian) probability of occupancy.
    pub(super) probability: f64,
    /// Its decision by the job's rule.
    pub(super) decision: Option<State>,
}

/// Judges a fused estimate by the decision rule `decision`.
pub(super) fn judge(estimate: Estimate, decision: Decision) -> Judged {
    let probability = match estimate {
        Estimate::Occupancy(o) => o.probability,
        Estimate::Evidential { combination, .. } => pignistic(combination.mass),
    };
    Judged {
        estimate,
        probability,
        decision: decide(estimate.decision_mass(), decision),
    }
}

/// The judged cell of every sequence of fresh sources up to [`MEMO_SOURCES`]
/// long, for one rule, inverse sensor model and decision rule.
#[derive(Debug, Clone)]
pub(super) struct Memo {
    /// By key − 2: a sequence of n states is the key 2ⁿ + its bits, occupied
    /// 1, the first source highest.
    table: Vec<Judged>,
}

impl Memo {
    /// The memo of `rule` judged by `decision`, where a fresh observation of a
    /// cell free makes the source `free` and one of it occupied `occupied`;
    /// `None` when the rule reads more than the masses (distances).
    pub(super) fn new(rule: &Rule, [free, occupied]: [Source; 2], decision: Decision) -> Option<Self> {
        if !matches!(rule, Rule::Bayes | Rule::Dempster) {
            return None;
        }
        let mut sources = Vec::with_capacity(MEMO_SOURCES as usize);
        let table = (2..1usize << (MEMO_SOURCES + 1))
            .map(|key| {
                let length = usize::BITS - 1 - key.leading_zeros();
                sources.clear();
                sources.extend(
                    (0..length)
                        .rev()
                        .map(|bit| if key >> bit & 1 == 1 { occupied } else { free }),
                );
                judge(fuse(rule, &sources), decision)
            })
            .collect();
        Some(Self { table })
    }

    /// The judged cell `cell` of `observations`, all fresh; `None` when more
    /// than [`MEMO_SOURCES`] of them observed it.
    #[inline]
    pub(super) fn get(&self, observations: &[&dyn Evidence], cell: usize) -> Option<&Judged> {
        let mut key = 1usize;
        for observation in observations {
            let bit = match observation.get(cell) {
                Observed::Unknown => continue,
                Observed::Free => 0,
                Observed::Occupied | Observed::Own => 1,
            };
            if key >> MEMO_SOURCES != 0 {
                return None;
            }
            key = key << 1 | bit;
        }
        self.table.get(key.checked_sub(2)?)
    }
}

#[cfg(test)]
mod tests {
    use sightline_dsl::{DecisionRule, Grid, SourceCombination, WeightScaling, Weighting};

    use super::super::fuse::CellFusion;
    use super::*;
    use crate::math::Point;

    /// Evidence that says `states[cell]` of each cell, fresh.
    struct Fixed(Vec<Observed>);

    impl Evidence for Fixed {
        fn get(&self, cell: usize) -> Observed {
            self.0[cell]
        }
        fn touched(&self) -> &[usize] {
            &[]
        }
        fn weight(&self, _cell: usize) -> f64 {
            1.0
        }
        fn sensors(&self, _cell: usize) -> &[Point] {
            &[]
        }
        fn fresh(&self) -> bool {
            true
        }
    }

    const GRID: Grid = Grid {
        origin: [0.0, 0.0],
        cell: 0.5,
        cols: 256,
        rows: 1,
    };

    /// Every combination of four sources' states (unknown, free, occupied,
    /// own) is one cell: the memo's cell equals the one fused and judged cell
    /// by cell, to the bit, for Bayes and Dempster by both rules at two thresholds.
    #[test]
    fn a_looked_up_cell_is_the_computed_one() {
        use Observed::{Free, Occupied, Own, Unknown};
        let states = [Unknown, Free, Occupied, Own];
        let observations: Vec<Fixed> = (0..4)
            .map(|source| Fixed((0..256).map(|cell| states[cell >> (2 * source) & 3]).collect()))
            .collect();
        let present: Vec<&dyn Evidence> = observations.iter().map(|o| o as &dyn Evidence).collect();
        for rule in [Rule::Bayes, Rule::Dempster] {
            for decision in [0.0, 0.8].into_iter().flat_map(|threshold| {
                [DecisionRule::Margin, DecisionRule::Exceeds].map(|rule| Decision { rule, threshold })
            }) {
                let fusion = CellFusion {
                    grid: &GRID,
                    rule: &rule,
                    observations: &present,
                    occupied: 0.7,
                    free: 0.3,
                };
                let memo = fusion.memo(decision).expect("the rule reads masses only");
                let mut sources = Vec::new();
                for cell in 1..256 {
                    let computed = judge(fusion.estimate(cell, &mut sources), decision);
                    assert_eq!(
                        memo.get(&present, cell),
                        Some(&computed),
                        "{rule:?} {decision:?} cell {cell}"
                    );
                }
                assert_eq!(memo.get(&present, 0), None, "no source: nothing to fuse");
            }
        }
    }

    /// More sources than the memo holds, or a rule that reads distances: no memo.
    #[test]
    fn long_sequences_and_distance_rules_are_computed() {
        const ANY: Decision = Decision {
            rule: DecisionRule::Margin,
            threshold: 0.0,
        };
        let rule = Rule::Bayes;
        let many: Vec<Fixed> = (0..=MEMO_SOURCES).map(|_| Fixed(vec![Observed::Free])).collect();
        let present: Vec<&dyn Evidence> = many.iter().map(|o| o as &dyn Evidence).collect();
        let fusion = CellFusion {
            grid: &GRID,
            rule: &rule,
            observations: &present,
            occupied: 0.7,
            free: 0.3,
        };
        let memo = fusion.memo(ANY).expect("Bayes reads masses only");
        assert_eq!(memo.get(&present, 0), None);
        assert!(memo.get(&present[1..], 0).is_some());
        let weighted = Rule::DistanceWeighted(Weighting {
            scaling: WeightScaling::default(),
            sources: SourceCombination::default(),
        });
        let free = fusion.source(Observed::Free, 1.0, 0.0);
        assert!(Memo::new(&weighted, [free, free], ANY).is_none());
    }
}
