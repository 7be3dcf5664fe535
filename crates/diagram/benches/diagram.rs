//! Cost of drawing the hard corner (x = 0.995, alpha = 0.005): run with
//! fronts recorded, build the exact field, and write SVG and PNG; and the
//! explorer's figures (with tooltips) of the corner and of Fig. 3(c).
//!
//! cargo bench -p impact-diagram --bench diagram

use criterion::{Criterion, criterion_group, criterion_main};
use impact_diagram::{Diagram, DiagramOptions, exact_run};
use impact_model::Bilayer;

/// The run with fronts recorded and the figure of one point, as `impact
/// diagram` and the explorer draw it.
fn figure(x: f64, alpha: f64) -> impl Fn() -> Diagram {
    let rod = Bilayer::new(x, alpha).unwrap().scene().validate().unwrap();
    move || {
        let run = exact_run(&rod).unwrap();
        Diagram {
            title: "corner".into(),
            rod: rod.clone(),
            wall: run.wall,
            outcome: run.outcome,
            pictures: vec![("exact".into(), run.picture)],
        }
    }
}

fn corner(c: &mut Criterion) {
    let build = figure(0.995, 0.005);
    let mut group = c.benchmark_group("diagram_hard_corner");
    group.sample_size(10);
    group.bench_function("run_and_svg", |b| {
        b.iter(|| build().to_svg(&DiagramOptions::default()).len())
    });
    let svg = build().to_svg(&DiagramOptions::default());
    group.bench_function("png", |b| {
        b.iter(|| impact_plot::png(&svg, 2.0).unwrap().len())
    });
    // the explorer's figures carry tooltips (target: a point under 50 ms,
    // the corner under 200 ms)
    let tooltips = DiagramOptions {
        tooltips: true,
        ..DiagramOptions::default()
    };
    group.bench_function("explorer_run_and_svg", |b| {
        b.iter(|| build().to_svg(&tooltips).len())
    });
    group.finish();
    let fig3c = figure(0.4, 0.05);
    c.bench_function("diagram_fig3c/explorer_run_and_svg", |b| {
        b.iter(|| fig3c().to_svg(&tooltips).len())
    });
}

criterion_group!(benches, corner);
criterion_main!(benches);
