//! The seed 001 experiment at one γ, both methods: mass sampling, fusion and
//! decision over 1000 × 1000 cells with 16 sensors (DESIGN.md target: ≤ 0.15 s on
//! a 2-core machine). Run with `cargo bench -p sightline-engine --bench field`;
//! measured figures are recorded in docs/performance.md.

use criterion::{Criterion, criterion_group, criterion_main};
use sightline_engine::simulate;

/// The bundled scenario's setup at γ = 10 with Baseline and Proposed only.
const SCENARIO: &str = r#"
sightline: 1
name: bench
seed: 1
grid: { size: [500, 500], cell: 0.5 }
field:
  truth: { occupied_fraction: 0.1 }
  sensors: { range: 200, layout: { regular: { rows: 4, cols: 4 } } }
  masses: { concentration: 32, epsilon0: 0.0625, gamma: 10, error_model: ERROR_MODEL }
decision: { threshold: 0.8 }
sweep:
  fusion:
    - { label: Baseline, method: dempster }
    - { label: Proposed, method: hybrid, switch: { threshold: 50 } }
"#;

fn field(c: &mut Criterion) {
    let mut group = c.benchmark_group("seed001_one_gamma_both_methods");
    group.sample_size(10);
    for error_model in ["dirichlet_mean", "wrong_label", "dirichlet_toward_empty"] {
        let text = SCENARIO.replace("ERROR_MODEL", error_model);
        let scenario =
            sightline_dsl::compile("bench.yaml", &text, &Default::default()).expect("the bench scenario is valid");
        group.bench_function(error_model, |b| b.iter(|| simulate(&scenario)));
    }
    group.finish();
}

criterion_group!(benches, field);
criterion_main!(benches);
