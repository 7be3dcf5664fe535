//! The paper's full grid (199 x 199 = 39,601 points) with the exact engine, on
//! all cores. Throughput is in points.
//!
//! cargo bench -p impact-study --bench sweep

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use impact_study::{BilayerViscosity, Engine, Grid, sweep};
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
    group.finish();
}

criterion_group!(benches, paper_grid);
criterion_main!(benches);
