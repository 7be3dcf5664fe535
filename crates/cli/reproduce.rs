//! `impact reproduce`: the paper's figures, regenerated and judged.

use crate::args::ReproduceArgs;
use crate::jobs::threads;
use impact_paper::{Settings, Verdict, reproduce as run};
use std::time::Instant;

pub fn reproduce(a: ReproduceArgs) -> anyhow::Result<()> {
    threads(a.threads)?;
    let settings = if a.full {
        Settings::full()
    } else {
        Settings::quick()
    };
    if a.full {
        eprintln!(
            "--full runs chains of 10^4 masses (Figs. 2, 8-10): expect several hours on 2 cores. \
             The exact-engine maps take seconds; for chain grids at N = 10^4 beyond these figures, \
             shard `impact sweep --engine chain` or `impact compare` (--shard I/N, impact merge)."
        );
    }
    let start = Instant::now();
    let items = run(&a.out, &settings, &|label| {
        eprintln!("[{:6.1} s] {label}", start.elapsed().as_secs_f64())
    })?;
    let claims: Vec<_> = items.iter().flat_map(|i| &i.claims).collect();
    let agree = claims
        .iter()
        .filter(|c| c.verdict == Verdict::Agrees)
        .count();
    eprintln!(
        "wrote {}/index.html in {:.1} s ({} resolution): {agree} of {} statements of the paper agree with our numbers",
        a.out.display(),
        start.elapsed().as_secs_f64(),
        settings.resolution,
        claims.len()
    );
    for c in claims.iter().filter(|c| c.verdict == Verdict::Disagrees) {
        eprintln!(
            "  disagrees: {} (paper: {}; ours: {})",
            c.statement, c.paper, c.ours
        );
    }
    Ok(())
}
