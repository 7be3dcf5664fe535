//! Cost of the chain kernels, one core, at N = 10^3, 10^4 (the paper's) and
//! 10^5: at 10^5 the state no longer fits in the L2 (1 to 2 MiB a core), so the three sizes
//! show where the cache ends. Throughput is in mass-steps, so
//! 1 / (criterion's elem/s) is the time per mass-step.
//!
//! Every iteration steps a clone of the same prepared engine (16 steps into
//! the contact), so old and new kernels time the same steps whatever
//! criterion's iteration count; the clone is set-up, not timed.
//!
//! cargo bench -p impact-chain --bench chain

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use impact_chain::{ChainConfig, ChainEngine, VerletChain, ViscousKernel};
use impact_model::Bilayer;
use std::time::Duration;

/// Mass-steps per iteration (about 10 ms), whatever `N`.
const MASS_STEPS: u64 = 2_000_000;

fn kernels(c: &mut Criterion) {
    for masses in [1_000usize, 10_000, 100_000] {
        let steps = MASS_STEPS / masses as u64;
        let mut group = c.benchmark_group(format!("chain_kernel_n{masses}"));
        group
            .throughput(Throughput::Elements(steps * masses as u64))
            .sample_size(20)
            .warm_up_time(Duration::from_secs(1))
            .measurement_time(Duration::from_secs(3));
        // the viscous bottom keeps the wall dashpot on for every timed step
        // (the contact lasts far longer); both viscous kernels, the default
        // (implicit) and the split one by name
        use ViscousKernel::{Implicit, Split};
        let cases = [
            ("elastic", None, None, Implicit),
            ("viscous_e2_0.72", None, Some(0.72), Implicit),
            ("viscous_e2_0.72_split", None, Some(0.72), Split),
            ("viscous_bottom_e1_0.72", Some(0.72), None, Implicit),
            ("viscous_bottom_e1_0.72_split", Some(0.72), None, Split),
        ];
        for (label, e1, e2, viscous_kernel) in cases {
            let mut scene = Bilayer::new(0.4, 0.05).unwrap().scene();
            scene.layers[0].restitution = e1;
            scene.layers[1].restitution = e2;
            let rod = scene.validate().unwrap();
            group.bench_function(label, |b| {
                // prepared here, so that a filtered run prepares only what it
                // times (instruction counts under callgrind stay clean)
                let mut engine = ChainEngine::new(
                    &rod,
                    ChainConfig {
                        masses,
                        viscous_kernel,
                        ..ChainConfig::default()
                    },
                )
                .unwrap();
                for _ in 0..16 {
                    engine.step().unwrap();
                }
                b.iter_batched(
                    || engine.clone(),
                    |mut e| {
                        for _ in 0..steps {
                            e.step().unwrap();
                        }
                        e
                    },
                    BatchSize::LargeInput,
                )
            });
        }
        // the elastic kernel alone: Beeman's positions as Verlet's, one sweep a step
        let rod = Bilayer::new(0.4, 0.05).unwrap().scene().validate().unwrap();
        let layout = impact_chain::ChainLayout::new(&rod, masses).unwrap();
        group.bench_function("elastic_verlet_kernel", |b| {
            let mut verlet = VerletChain::new(&layout, layout.paper_time_step(), 1.0);
            b.iter(|| {
                for _ in 0..steps {
                    verlet.step();
                }
            })
        });
        group.finish();
    }
}

criterion_group!(benches, kernels);
criterion_main!(benches);
