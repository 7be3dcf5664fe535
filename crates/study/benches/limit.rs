//! The chain's continuum answer on Fig. 10's materials (e1 = 0.94,
//! e2 = 0.72, alpha = 0.005, x = 0.5): chains of 250, 500 and 1000 masses
//! on two threads, extrapolated (target: under 2 s, within 1e-4 of the
//! limit; the accuracy is tested in `tests/limit.rs`).
//!
//! cargo bench -p impact-study --bench limit

use criterion::{Criterion, criterion_group, criterion_main};
use impact_chain::ChainConfig;
use impact_model::Bilayer;
use impact_study::{LimitSettings, chain_limit};

fn fig10(c: &mut Criterion) {
    let mut scene = Bilayer::new(0.5, 0.005).unwrap().scene();
    scene.layers[0].restitution = Some(0.94);
    scene.layers[1].restitution = Some(0.72);
    let rod = scene.validate().unwrap();
    let mut group = c.benchmark_group("chain_limit");
    group.sample_size(10);
    group.bench_function("fig10_materials_x0.5", |b| {
        b.iter(|| chain_limit(&rod, &ChainConfig::default(), &LimitSettings::default()).unwrap())
    });
    group.finish();
}

criterion_group!(benches, fig10);
criterion_main!(benches);
