fn main() {
    let path = std::env::args().nth(1).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let s = sightline_dsl::compile(&path, &text, &Default::default()).unwrap_or_else(|e| panic!("{e}"));
    let t = std::time::Instant::now();
    let run = sightline_engine::simulate(&s);
    eprintln!("simulate: {:?}", t.elapsed());
    for (p, o) in s.points.iter().zip(&run.points) {
        let m = &o.metrics;
        println!(
            "{:60} acc {:.4} below {:7} fa {:6} md {:6} unk {:6} conflict {:?} cov {:?}",
            p.label(),
            m.value(sightline_dsl::Metric::Accuracy).unwrap(),
            m.below_threshold,
            m.false_alarms,
            m.missed_detections,
            m.decided_unknown,
            m.conflict.as_ref().map(|c| (c.mean, c.weighted_cells)),
            (o.coverage.min_sources, o.coverage.max_sources, o.coverage.mean_sources)
        );
    }
}
