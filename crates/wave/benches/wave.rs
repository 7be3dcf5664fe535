//! Per-point cost of the exact engine. Throughput is in events, so criterion
//! reports events per second beside the time per point.
//!
//! - `wave_point`: a whole point as `impact run` computes it, its error
//!   estimate included (at points where the engine's tolerances were used,
//!   among them the hard corner, that is a second, checking run);
//! - `event_loop`: one exact run of the tracer alone, the event loop's speed.
//!
//! cargo bench -p impact-wave --bench wave

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use impact_model::Bilayer;
use impact_wave::{WaveConfig, WaveEngine, simulate};
use std::hint::black_box;

const POINTS: [(&str, f64, f64); 4] = [
    ("fig3a", 0.2, 0.05),
    ("fig3c", 0.4, 0.05),
    ("fig3d", 0.6, 0.8),
    ("hard_corner_x0.995_a0.005", 0.995, 0.005),
];

fn points(c: &mut Criterion) {
    let mut group = c.benchmark_group("wave_point");
    for (label, x, alpha) in POINTS {
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

fn event_loop(c: &mut Criterion) {
    let mut group = c.benchmark_group("event_loop");
    for (label, x, alpha) in POINTS {
        let rod = Bilayer::new(x, alpha).unwrap().scene().validate().unwrap();
        let config = WaveConfig::default();
        let run = || {
            let mut engine = WaveEngine::new(black_box(&rod), config.clone()).unwrap();
            engine.run().unwrap();
            engine
        };
        group.throughput(Throughput::Elements(run().events()));
        group.bench_function(label, |b| b.iter(run));
    }
    group.finish();
}

criterion_group!(benches, points, event_loop);
criterion_main!(benches);
