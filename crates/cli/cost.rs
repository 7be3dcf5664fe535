//! `impact cost`: what accuracy costs in time.

use crate::args::CostArgs;
use crate::input;
use crate::run::read_scene;
use impact_cost::{CostSettings, cost_study, write_report};
use impact_model::Bilayer;
use std::time::Instant;

pub fn cost(a: CostArgs) -> anyhow::Result<()> {
    let (scene, label) = match &a.scene {
        Some(path) => (read_scene(path)?, path.display().to_string()),
        None => {
            let b = Bilayer::new(a.x, a.alpha).map_err(|e| input(e.to_string()))?;
            (b.scene(), format!("x = {}, alpha = {}", a.x, a.alpha))
        }
    };
    let mut scene = scene;
    if let Some(law) = a.wall_contact {
        scene.wall_contact = Some(law);
    }
    let rod = scene.validate().map_err(|e| input(e.to_string()))?;
    if rod.is_viscous() {
        return Err(input(
            "impact cost needs an elastic scene: its exact solution is the reference (the viscous study is derived from it)",
        ));
    }
    if !(a.target.is_finite() && a.target > 0.0) {
        return Err(input(format!(
            "--target must be a finite number > 0 (got {})",
            a.target
        )));
    }
    let mut settings = if a.quick {
        CostSettings::tiny()
    } else {
        CostSettings::standard()
    };
    settings.target_error = a.target;
    let start = Instant::now();
    let report = cost_study(&label, &rod, &settings, &|step| {
        eprintln!("[{:6.1} s] {step}", start.elapsed().as_secs_f64())
    })?;
    write_report(&a.out, &report)?;
    let h = &report.headline;
    match h.masses {
        Some(n) => eprintln!(
            "headline: the chain needs N = {n} ({:.3} s) to reach |de| < {:e}; the exact engine takes {:.2e} s: {:.0}x faster",
            h.chain_seconds, h.target_error, h.exact_seconds, h.ratio
        ),
        None => eprintln!(
            "headline: the chain does not reach |de| < {:e} by N = {} (|de| = {:.2e}, {:.3} s); the exact engine takes {:.2e} s",
            h.target_error, h.masses_tried, h.chain_error, h.chain_seconds, h.exact_seconds
        ),
    }
    eprintln!(
        "chain time ~ N^{:.2}; wrote {}/index.html in {:.1} s",
        report.chain_time_exponent,
        a.out.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
