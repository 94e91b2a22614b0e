//! Falsification: a search over a scenario's `vary` space for a case that breaks
//! a requirement, and the shrinking of that case toward a minimal one.
//!
//! The search works on grid indices (one per varied setting, 0 = the low end of
//! a range or the first choice; see [`sightline_dsl::Vary`]) and knows nothing
//! of simulation: the caller's `evaluate` compiles, simulates and checks a case
//! and returns its [`Score`]. Random cases and shrinking come from proptest's
//! [`TestRunner`], seeded with ChaCha, so a search is deterministic for its seed
//! (unless a wall-clock deadline cuts it short). Integer indices shrink by binary
//! search toward 0, so a counterexample shrinks toward the low end of every
//! range and the first choice, stopping where one step less no longer breaks it.
//!
//! Guided search: after a few random cases, every other case is a step from the
//! case with the smallest worst margin so far (its robustness), drawn within a
//! radius that halves after every three steps that find a larger margin (a
//! step of equal margin is taken, so the search walks across plateaus). It
//! moves toward the boundary where the margin crosses zero, while the random
//! cases in between keep exploring.
//!
//! Cases are chosen in rounds of [`Search::round`] and scored together, so the
//! caller can simulate a round in parallel; a guided step starts from the best
//! case before its round. Shrinking goes one case at a time.

use std::time::Instant;

use proptest::num::u64::BinarySearch;
use proptest::strategy::{NewTree, Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, RngSeed, TestRng, TestRunner};
use serde::Serialize;

use crate::verdict::{Status, Verdict};

/// How long and how a search runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Search {
    /// The most cases to try before shrinking (random and guided together).
    pub cases: u64,
    /// How many cases are chosen and scored together (at least 1). The cases
    /// tried depend on it, not on how the caller runs a round.
    pub round: usize,
    /// The most cases to try while shrinking a counterexample.
    pub shrink_cases: u64,
    /// The seed of the search's random stream.
    pub seed: u64,
    /// Whether guided steps alternate with the random cases.
    pub guided: bool,
    /// Stop trying new cases (and shrinking) after this instant.
    pub deadline: Option<Instant>,
}

/// The outcome of one case as the search sees it: its worst requirement.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Score {
    /// The requirement with the smallest margin (one that could not be checked
    /// first); `None` when the scenario has no requirements.
    pub requirement: Option<String>,
    /// That requirement's status.
    pub status: Status,
    /// That requirement's margin (`None` when it could not be checked).
    pub margin: Option<f64>,
    /// Whether the case fails a `sightline run`: a requirement fails, could
    /// not be checked, or is not exercised without accepting it.
    pub breaks: bool,
    /// Every requirement's outcome in this case, in the scenario's order.
    pub each: Vec<Judged>,
}

/// One requirement's outcome in one case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Judged {
    /// The requirement's id.
    pub id: String,
    /// Its status.
    pub status: Status,
    /// Its margin (`None` when it could not be checked or was not exercised).
    pub margin: Option<f64>,
    /// Whether it fails a `sightline run` of the case.
    pub breaks: bool,
}

impl Score {
    /// The score of a case from its verdicts: the worst is one that could not
    /// be checked, else one that breaks the run, else the smallest margin; an
    /// accepted not-exercised verdict without a margin only when nothing
    /// else is there (it would hide every margin from the guided search).
    pub fn of(verdicts: &[Verdict]) -> Self {
        let rank = |v: &Verdict| match (v.status, v.fails_run(), v.decisive.margin) {
            (Status::Error, ..) => 0,
            (_, true, _) => 1,
            (_, false, Some(_)) => 2,
            (_, false, None) => 3,
        };
        let worst = verdicts.iter().min_by(|a, b| {
            rank(a).cmp(&rank(b)).then(b.status.cmp(&a.status)).then_with(|| {
                match (a.decisive.margin, b.decisive.margin) {
                    (Some(x), Some(y)) => x.total_cmp(&y),
                    (x, y) => x.is_some().cmp(&y.is_some()),
                }
            })
        });
        Self {
            requirement: worst.map(|v| v.id.clone()),
            status: worst.map_or(Status::Pass, |v| v.status),
            margin: worst.and_then(|v| v.decisive.margin),
            breaks: verdicts.iter().any(Verdict::fails_run),
            each: verdicts
                .iter()
                .map(|v| Judged {
                    id: v.id.clone(),
                    status: v.status,
                    margin: v.decisive.margin,
                    breaks: v.fails_run(),
                })
                .collect(),
        }
    }

    /// The robustness the guided search minimises: the margin, −∞ when the
    /// case breaks without one (a requirement could not be checked or is not
    /// exercised), +∞ without requirements or with only an accepted
    /// not-exercised verdict.
    fn robustness(&self) -> f64 {
        match (self.status, self.margin, self.breaks) {
            (Status::Error, _, _) => f64::NEG_INFINITY,
            (_, Some(margin), _) => margin,
            (_, None, true) => f64::NEG_INFINITY,
            (_, None, false) => f64::INFINITY,
        }
    }
}

/// How a case was chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Phase {
    /// Drawn uniformly from the space.
    Random,
    /// A step from the case with the smallest margin so far.
    Guided,
    /// A simpler variant of a counterexample.
    Shrink,
}

/// One case tried.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Case {
    /// How it was chosen.
    pub phase: Phase,
    /// One grid index per varied setting.
    pub indices: Vec<u64>,
    /// What its check found.
    pub score: Score,
}

/// What a search found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Outcome {
    /// Every case tried, in order.
    pub cases: Vec<Case>,
    /// The number of cases tried up to and including the first that broke a
    /// requirement (`None` when none did).
    pub first_counterexample: Option<usize>,
    /// Index in `cases` of the shrunk counterexample (`None` when none was found).
    pub counterexample: Option<usize>,
}

/// A strategy whose value tree starts at a given index and shrinks toward 0:
/// how a counterexample found by any phase is handed to proptest's shrinking.
#[derive(Debug, Clone, Copy)]
struct StartAt(u64);

impl Strategy for StartAt {
    type Tree = BinarySearch;
    type Value = u64;

    fn new_tree(&self, _: &mut TestRunner) -> NewTree<Self> {
        Ok(BinarySearch::new(self.0))
    }
}

/// Searches the space of `counts[i]` values per setting for a case that
/// `evaluate` scores as breaking a requirement, then shrinks it. `evaluate`
/// scores a round of up to [`Search::round`] cases at once (the caller may run
/// them in parallel) and returns their scores in order. An `evaluate` error ends
/// the search and is returned.
pub fn falsify<E>(
    counts: &[u64],
    search: &Search,
    mut evaluate: impl FnMut(&[Vec<u64>]) -> Result<Vec<Score>, E>,
) -> Result<Outcome, E> {
    let mut runner = runner(search.seed);
    let uniform: Vec<_> = counts.iter().map(|&n| 0..=n.saturating_sub(1)).collect();
    let out_of_time = || search.deadline.is_some_and(|d| Instant::now() >= d);
    let mut cases: Vec<Case> = Vec::new();
    let mut best: Option<(Vec<u64>, f64)> = None;
    // Guided steps that found a larger margin since the last that found a smaller.
    let mut stale = 0;
    let mut drawn = 0;
    'search: while drawn < search.cases && !out_of_time() {
        // A round's cases are chosen before any of them is scored, so the
        // search does not depend on how the caller runs them.
        let size = (search.cases - drawn).min(search.round.max(1) as u64);
        let mut round = Vec::new();
        for k in drawn..drawn + size {
            let step = best
                .as_ref()
                .filter(|_| search.guided && k >= GUIDED_AFTER && k % 2 == 1)
                .map(|(from, _)| neighbour(&mut runner, from, counts, stale));
            round.push(match step {
                Some(indices) => (Phase::Guided, indices),
                // Integer ranges always yield a tree; should one not, the search ends.
                None => match uniform.new_tree(&mut runner) {
                    Ok(tree) => (Phase::Random, tree.current()),
                    Err(_) => break 'search,
                },
            });
        }
        drawn += size;
        let indices: Vec<Vec<u64>> = round.iter().map(|(_, indices)| indices.clone()).collect();
        let scores = evaluate(&indices)?;
        let mut first = None;
        for ((phase, indices), score) in round.into_iter().zip(scores) {
            let robustness = score.robustness();
            if score.breaks && first.is_none() {
                first = Some(cases.len());
            }
            cases.push(Case {
                phase,
                indices: indices.clone(),
                score,
            });
            match &best {
                // Take a guided step of equal margin, so the search walks across
                // plateaus (at full radius) instead of sampling one point again.
                Some((_, margin)) if robustness == *margin && phase == Phase::Guided => {
                    best = Some((indices, robustness));
                }
                Some((_, margin)) if robustness >= *margin => {
                    if phase == Phase::Guided {
                        stale += 1;
                    }
                }
                _ => {
                    if phase == Phase::Guided {
                        stale = 0;
                    }
                    best = Some((indices, robustness));
                }
            }
        }
        if let Some(first) = first {
            let start = cases[first].indices.clone();
            let counterexample = shrink(
                &mut runner,
                start,
                first,
                search,
                &mut cases,
                &mut evaluate,
                out_of_time,
            )?;
            return Ok(Outcome {
                cases,
                first_counterexample: Some(first + 1),
                counterexample: Some(counterexample),
            });
        }
    }
    Ok(Outcome {
        cases,
        first_counterexample: None,
        counterexample: None,
    })
}

/// Random cases drawn before the first guided step.
const GUIDED_AFTER: u64 = 4;

/// A runner that never reads `PROPTEST_*` variables' effects (only its random
/// stream is used, seeded here) and never persists failures.
fn runner(seed: u64) -> TestRunner {
    let config = Config {
        failure_persistence: None,
        rng_algorithm: RngAlgorithm::ChaCha,
        rng_seed: RngSeed::Fixed(seed),
        ..Config::default()
    };
    let mut bytes = [0u8; 32];
    bytes[..8].copy_from_slice(&seed.to_le_bytes());
    TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &bytes))
}

/// A guided step from `from`: every index moved uniformly within a radius of a
/// quarter of its range, halved after every three stale steps, at least 1.
fn neighbour(runner: &mut TestRunner, from: &[u64], counts: &[u64], stale: u32) -> Vec<u64> {
    from.iter()
        .zip(counts)
        .map(|(&at, &n)| {
            let last = n.saturating_sub(1);
            let radius = ((last as f64 / 4.0) * 0.5f64.powi((stale / 3) as i32)).max(1.0) as u64;
            let range = at.saturating_sub(radius)..=at.saturating_add(radius).min(last);
            range.new_tree(runner).map_or(at, |tree| tree.current())
        })
        .collect()
}

/// Shrinks the counterexample `start` (at `counterexample` in `cases`) with
/// proptest's value trees, one case at a time: each
/// simplification that still breaks a requirement is kept, one that does not is
/// undone. Returns the index in `cases` of the last case that broke one.
fn shrink<E>(
    runner: &mut TestRunner,
    start: Vec<u64>,
    mut counterexample: usize,
    search: &Search,
    cases: &mut Vec<Case>,
    evaluate: &mut impl FnMut(&[Vec<u64>]) -> Result<Vec<Score>, E>,
    out_of_time: impl Fn() -> bool,
) -> Result<usize, E> {
    let strategy: Vec<StartAt> = start.into_iter().map(StartAt).collect();
    let Ok(mut tree) = strategy.new_tree(runner) else {
        return Ok(counterexample);
    };
    let mut more = tree.simplify();
    let mut tried = 0;
    while more && tried < search.shrink_cases && !out_of_time() {
        let indices = tree.current();
        // Shrinking is a sequence of single cases: each depends on the last.
        let Some(score) = evaluate(std::slice::from_ref(&indices))?.pop() else {
            break;
        };
        tried += 1;
        let breaks = score.breaks;
        cases.push(Case {
            phase: Phase::Shrink,
            indices,
            score,
        });
        if breaks {
            counterexample = cases.len() - 1;
            more = tree.simplify();
        } else {
            more = tree.complicate();
        }
    }
    Ok(counterexample)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A score that breaks when the first index is at least `boundary`, with a
    /// margin that falls linearly toward it.
    fn threshold(boundary: u64) -> impl FnMut(&[Vec<u64>]) -> Result<Vec<Score>, ()> {
        move |round| {
            Ok(round
                .iter()
                .map(|indices| {
                    let margin = boundary as f64 - 0.5 - indices[0] as f64;
                    Score {
                        requirement: Some("R".into()),
                        status: if margin < 0.0 { Status::Fail } else { Status::Pass },
                        margin: Some(margin),
                        breaks: margin < 0.0,
                        each: Vec::new(),
                    }
                })
                .collect())
        }
    }

    fn search(guided: bool, seed: u64) -> Search {
        Search {
            cases: 200,
            round: 2,
            shrink_cases: 200,
            seed,
            guided,
            deadline: None,
        }
    }

    #[test]
    fn a_counterexample_shrinks_to_the_boundary() {
        for guided in [false, true] {
            let outcome = falsify(&[1001, 3], &search(guided, 7), threshold(900)).unwrap();
            let found = &outcome.cases[outcome.counterexample.unwrap()];
            assert_eq!(found.indices, vec![900, 0]);
            assert!(outcome.cases.iter().any(|c| c.indices[0] == 899 && !c.score.breaks));
        }
    }

    #[test]
    fn a_search_is_deterministic_for_its_seed() {
        let a = falsify(&[1001, 5], &search(true, 3), threshold(950)).unwrap();
        let b = falsify(&[1001, 5], &search(true, 3), threshold(950)).unwrap();
        assert_eq!(a, b);
        let c = falsify(&[1001, 5], &search(true, 4), threshold(950)).unwrap();
        assert_ne!(a.cases, c.cases);
    }

    #[test]
    fn an_unbreakable_space_tries_every_case_and_finds_nothing() {
        let outcome = falsify(&[11], &search(true, 1), threshold(100)).unwrap();
        assert_eq!(outcome.cases.len(), 200);
        assert_eq!(outcome.counterexample, None);
        assert_eq!(outcome.first_counterexample, None);
    }

    #[test]
    fn guided_steps_find_a_narrow_failure_sooner_than_random_cases() {
        let first = |guided| -> usize {
            (0..20)
                .map(|seed| {
                    falsify(&[1001], &search(guided, seed), threshold(980))
                        .unwrap()
                        .first_counterexample
                        .unwrap_or(200)
                })
                .sum()
        };
        assert!(
            first(true) < first(false),
            "guided {} random {}",
            first(true),
            first(false)
        );
    }

    #[test]
    fn the_first_breaking_case_of_a_round_is_the_one_shrunk() {
        // Every case breaks: the first of the first round is the counterexample's
        // start, and its partner in the round is still recorded.
        let outcome = falsify(&[1001, 3], &search(false, 9), threshold(0)).unwrap();
        assert_eq!(outcome.first_counterexample, Some(1));
        assert_eq!(outcome.cases[1].phase, Phase::Random);
        assert_eq!(outcome.cases[2].phase, Phase::Shrink);
        assert_eq!(outcome.cases[outcome.counterexample.unwrap()].indices, vec![0, 0]);
    }

    fn verdict(id: &str, status: Status, margin: Option<f64>) -> Verdict {
        let decisive = crate::verdict::Evaluation {
            point: 0,
            status,
            value: margin,
            margin,
            n: Some(1),
            measured: String::new(),
            message: String::new(),
            seeds: None,
            time: None,
        };
        Verdict {
            id: id.into(),
            status,
            threshold: 0.0,
            min_samples: 1,
            accepted: None,
            decisive: decisive.clone(),
            evaluations: vec![decisive],
        }
    }

    #[test]
    fn a_case_scores_its_worst_requirement() {
        let pass = verdict("A", Status::Pass, Some(0.3));
        let close = verdict("B", Status::Pass, Some(0.1));
        let fail = verdict("C", Status::Fail, Some(-0.2));
        let error = verdict("D", Status::Error, None);
        let score = Score::of(&[pass.clone(), close.clone()]);
        assert_eq!((score.requirement.as_deref(), score.margin), (Some("B"), Some(0.1)));
        assert!(!score.breaks);
        let score = Score::of(&[pass.clone(), fail.clone(), close]);
        assert_eq!((score.requirement.as_deref(), score.status), (Some("C"), Status::Fail));
        // Every requirement's own outcome is kept beside the worst.
        let each: Vec<(&str, Status, Option<f64>, bool)> = score
            .each
            .iter()
            .map(|j| (j.id.as_str(), j.status, j.margin, j.breaks))
            .collect();
        assert_eq!(
            each,
            [
                ("A", Status::Pass, Some(0.3), false),
                ("C", Status::Fail, Some(-0.2), true),
                ("B", Status::Pass, Some(0.1), false)
            ]
        );
        let score = Score::of(&[pass, error, fail]);
        assert_eq!((score.requirement.as_deref(), score.status), (Some("D"), Status::Error));
        let none = Score::of(&[]);
        assert!(!none.breaks);
        assert_eq!(none.robustness(), f64::INFINITY);
    }

    #[test]
    fn errors_rank_below_every_margin() {
        let error = Score::of(&[verdict("R", Status::Error, None)]);
        assert!(error.breaks);
        assert_eq!(error.robustness(), f64::NEG_INFINITY);
    }

    #[test]
    fn a_not_exercised_requirement_breaks_unless_accepted() {
        let idle = verdict("R", Status::NotExercised, None);
        let score = Score::of(&[verdict("A", Status::Pass, Some(0.3)), idle.clone()]);
        assert_eq!((score.requirement.as_deref(), score.breaks), (Some("R"), true));
        assert_eq!(score.robustness(), f64::NEG_INFINITY);
        let accepted = Verdict {
            accepted: Some("no pedestrians in this variant".into()),
            ..idle
        };
        let score = Score::of(std::slice::from_ref(&accepted));
        assert!(!score.breaks);
        assert_eq!(score.robustness(), f64::INFINITY);
        // Beside a margin, the accepted one does not hide it from the search.
        let score = Score::of(&[accepted, verdict("A", Status::Pass, Some(0.3))]);
        assert_eq!((score.requirement.as_deref(), score.margin), (Some("A"), Some(0.3)));
        assert_eq!(score.robustness(), 0.3);
    }
}
