//! Cost of drawing the hard corner (x = 0.995, alpha = 0.005): run with
//! fronts recorded, build the exact field, and write SVG and PNG.
//!
//! cargo bench -p impact-diagram --bench diagram

use criterion::{Criterion, criterion_group, criterion_main};
use impact_diagram::{Diagram, DiagramOptions, exact_run};
use impact_model::Bilayer;

fn corner(c: &mut Criterion) {
    let rod = Bilayer::new(0.995, 0.005)
        .unwrap()
        .scene()
        .validate()
        .unwrap();
    let build = || {
        let run = exact_run(&rod).unwrap();
        Diagram {
            title: "corner".into(),
            rod: rod.clone(),
            wall: run.wall,
            outcome: run.outcome,
            pictures: vec![("exact".into(), run.picture)],
        }
    };
    let mut group = c.benchmark_group("diagram_hard_corner");
    group.sample_size(10);
    group.bench_function("run_and_svg", |b| {
        b.iter(|| build().to_svg(&DiagramOptions::default()).len())
    });
    let svg = build().to_svg(&DiagramOptions::default());
    group.bench_function("png", |b| {
        b.iter(|| impact_plot::png(&svg, 2.0).unwrap().len())
    });
    group.finish();
}

criterion_group!(benches, corner);
criterion_main!(benches);
