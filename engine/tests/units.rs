//! Units of work (issue 5 §3): simulated one by one, in any order, they make up
//! the run `simulate` gives; a missing, repeated or foreign unit is refused.

use sightline_dsl::{Scenario, compile};
use sightline_engine::{AssembleError, Unit, assemble, simulate, simulate_unit, units};

/// A small field swept over two noise levels and two fusion methods (two groups
/// of two points sharing their data), with a check over 3 seeds on the Bayes
/// points: six units.
fn scenario() -> Scenario {
    let text = "sightline: 1
name: t
seed: 7
grid: { size: [20, 20], cell: 1 }
field:
  truth: { occupied_fraction: 0.2 }
  sensors: { range: 15, layout: { regular: { rows: 1, cols: 2 } } }
  masses: {}
sweep:
  field.masses.gamma: [5, 10]
  fusion: [{ label: DS, method: dempster }, { label: Bayes, method: bayes }]
requirements:
  - id: ACC
    text: accuracy over seeds
    where: { fusion.label: Bayes }
    check: { metric: accuracy, at_least: 0.5, seeds: 3 }
";
    compile("t.yaml", text, &Default::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn unit(group: &[usize], replicate: u32) -> Unit {
    Unit {
        group: group.to_vec(),
        replicate,
    }
}

#[test]
fn the_units_are_the_groups_at_each_seed_in_order() {
    let expected = [0, 1, 2].map(|r| unit(&[0, 1], r)).into_iter();
    let expected: Vec<Unit> = expected.chain([0, 1, 2].map(|r| unit(&[2, 3], r))).collect();
    assert_eq!(units(&scenario()), expected);
}

#[test]
fn units_simulated_in_any_order_make_up_the_run() {
    let scenario = scenario();
    let mut pieces: Vec<_> = units(&scenario)
        .into_iter()
        .map(|u| {
            let outcomes = simulate_unit(&scenario, &u);
            (u, outcomes)
        })
        .collect();
    pieces.reverse();
    pieces.swap(1, 4);
    let run = assemble(&scenario, pieces).expect("every unit once");
    assert_eq!(run, simulate(&scenario));
    assert_eq!(run.replicates.iter().map(Vec::len).collect::<Vec<_>>(), [2, 2, 2, 2]);
}

#[test]
fn a_missing_repeated_or_foreign_unit_is_refused() {
    let scenario = scenario();
    let pieces: Vec<_> = units(&scenario)
        .into_iter()
        .map(|u| {
            let outcomes = simulate_unit(&scenario, &u);
            (u, outcomes)
        })
        .collect();
    let without = |i: usize| {
        pieces
            .iter()
            .enumerate()
            .filter(move |(j, _)| *j != i)
            .map(|(_, p)| p.clone())
    };

    let missing = assemble(&scenario, without(4));
    assert_eq!(missing, Err(AssembleError::Missing(unit(&[2, 3], 1))));

    let repeated = assemble(&scenario, pieces.iter().cloned().chain([pieces[2].clone()]));
    assert_eq!(repeated, Err(AssembleError::Unexpected(unit(&[0, 1], 2))));

    let foreign = assemble(&scenario, without(5).chain([(unit(&[2, 3], 3), pieces[5].1.clone())]));
    assert_eq!(foreign, Err(AssembleError::Unexpected(unit(&[2, 3], 3))));
    // A unit naming a point the scenario does not have (a forged shard).
    let beyond = assemble(
        &scenario,
        without(5).chain([(unit(&[999], 0), pieces[5].1[..1].to_vec())]),
    );
    assert_eq!(beyond, Err(AssembleError::Unexpected(unit(&[999], 0))));

    let short = (unit(&[0, 1], 0), pieces[0].1[..1].to_vec());
    let mismatched = assemble(&scenario, without(0).chain([short]));
    assert_eq!(mismatched, Err(AssembleError::Mismatched(unit(&[0, 1], 0))));
}
