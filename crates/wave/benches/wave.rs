//! Per-point cost of the exact engine. Throughput is in events, so criterion
//! reports events per second beside the time per point.
//!
//! cargo bench -p impact-wave --bench wave

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use impact_model::Bilayer;
use impact_wave::{WaveConfig, simulate};
use std::hint::black_box;

fn points(c: &mut Criterion) {
    let mut group = c.benchmark_group("wave_point");
    for (label, x, alpha) in [
        ("fig3a", 0.2, 0.05),
        ("fig3c", 0.4, 0.05),
        ("fig3d", 0.6, 0.8),
        ("hard_corner_x0.995_a0.005", 0.995, 0.005),
    ] {
        let rod = Bilayer::new(x, alpha).unwrap().scene().validate().unwrap();
        let config = WaveConfig::default();
        let events = simulate(&rod, &config).unwrap().events.unwrap();
        group.throughput(Throughput::Elements(events));
        group.bench_function(label, |b| {
            b.iter(|| simulate(black_box(&rod), &config).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, points);
criterion_main!(benches);
