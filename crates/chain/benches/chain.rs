//! Cost of the chain kernels at the paper's N = 10^4, one core. Throughput is
//! in mass-steps, so 1 / (criterion's elem/s) is the time per mass-step.
//!
//! cargo bench -p impact-chain --bench chain

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use impact_chain::{ChainConfig, ChainEngine, VerletChain};
use impact_model::Bilayer;

const MASSES: usize = 10_000;
const STEPS: u64 = 200;

fn kernels(c: &mut Criterion) {
    let mut group = c.benchmark_group("chain_kernel_n10000");
    group.throughput(Throughput::Elements(STEPS * MASSES as u64));
    // the viscous bottom keeps the wall dashpot on for all 200 steps (the
    // contact lasts far longer)
    let cases = [
        ("elastic", None, None),
        ("viscous_e2_0.72", None, Some(0.72)),
        ("viscous_bottom_e1_0.72", Some(0.72), None),
    ];
    for (label, e1, e2) in cases {
        let mut scene = Bilayer::new(0.4, 0.05).unwrap().scene();
        scene.layers[0].restitution = e1;
        scene.layers[1].restitution = e2;
        let rod = scene.validate().unwrap();
        let mut engine = ChainEngine::new(
            &rod,
            ChainConfig {
                masses: MASSES,
                ..ChainConfig::default()
            },
        )
        .unwrap();
        group.bench_function(label, |b| {
            b.iter(|| {
                for _ in 0..STEPS {
                    engine.step().unwrap();
                }
            })
        });
    }
    // the elastic kernel alone: Beeman's positions as Verlet's, two arrays
    let rod = Bilayer::new(0.4, 0.05).unwrap().scene().validate().unwrap();
    let layout = impact_chain::ChainLayout::new(&rod, MASSES).unwrap();
    let mut verlet = VerletChain::new(&layout, layout.paper_time_step(), 1.0);
    group.bench_function("elastic_verlet_kernel", |b| {
        b.iter(|| {
            for _ in 0..STEPS {
                verlet.step();
            }
        })
    });
    group.finish();
}

criterion_group!(benches, kernels);
criterion_main!(benches);
