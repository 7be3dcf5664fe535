//! The paper's full grid (199 x 199 = 39,601 points) with the exact engine, on
//! all cores, and the explorer's 99 x 99 map. Throughput is in points.
//!
//! cargo bench -p impact-study --bench sweep

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use impact_study::{Axis, BilayerViscosity, Engine, Grid, sweep};
use impact_wave::WaveConfig;

fn paper_grid(c: &mut Criterion) {
    let points = Grid::paper().points();
    let engine = Engine::Wave(WaveConfig::default());
    let mut group = c.benchmark_group("sweep");
    group.sample_size(10);
    group.throughput(Throughput::Elements(points.len() as u64));
    group.bench_function("paper_grid_wave", |b| {
        b.iter(|| sweep(&points, &engine, &BilayerViscosity::default(), false, &()))
    });
    // the explorer's map as it refines: 99 x 99 (step 0.01) is the redraw
    // its issue times (target: under 300 ms of server time)
    let explorer = Grid {
        x: Axis::parse("x", "0.01:0.99:0.01").unwrap(),
        alpha: Axis::parse("alpha", "0.01:0.99:0.01").unwrap(),
    }
    .points();
    group.throughput(Throughput::Elements(explorer.len() as u64));
    group.bench_function("explorer_map_99x99_wave", |b| {
        b.iter(|| sweep(&explorer, &engine, &BilayerViscosity::default(), false, &()))
    });
    group.finish();
}

criterion_group!(benches, paper_grid);
criterion_main!(benches);
