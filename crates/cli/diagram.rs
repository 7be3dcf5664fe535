//! `impact diagram`: the space-time picture of one impact.

use crate::args::{DiagramArgs, DiagramEngine};
use crate::input;
use crate::output::write_atomically;
use impact_diagram::{Diagram, DiagramOptions, chain_run, chain_run_within, exact_run, page};
use impact_model::{Outcome, Scene};
use impact_wave::WaveError;
use std::io::Write;

/// Checks the window and scale flags.
fn check_flags(a: &DiagramArgs) -> anyhow::Result<()> {
    // (flag, value, whether 0 is allowed: a window may start at the impact)
    for (flag, v, zero_allowed) in [
        ("t-start", a.t_start, true),
        ("t-end", a.t_end, false),
        ("strain-scale", a.strain_scale, false),
    ] {
        let Some(v) = v else { continue };
        let ok = v.is_finite() && if zero_allowed { v >= 0.0 } else { v > 0.0 };
        if !ok {
            let range = if zero_allowed { ">= 0" } else { "> 0" };
            return Err(input(format!(
                "--{flag} must be a finite number {range} (got {v})"
            )));
        }
    }
    if let (Some(s), Some(e)) = (a.t_start, a.t_end)
        && s >= e
    {
        return Err(input(format!(
            "--t-start must be before --t-end (got {s} and {e})"
        )));
    }
    Ok(())
}

pub fn diagram(a: DiagramArgs) -> anyhow::Result<()> {
    let ext = a.out.extension().and_then(|e| e.to_str()).unwrap_or("");
    let (d, options) = build(&a, None)?;
    match ext {
        "html" => write_atomically(&a.out, |w| w.write_all(page(&d, &options).as_bytes()))?,
        "png" => {
            let png = impact_plot::png(&d.to_svg(&options), 2.0)?;
            write_atomically(&a.out, |w| w.write_all(&png))?;
        }
        _ => write_atomically(&a.out, |w| w.write_all(d.to_svg(&options).as_bytes()))?,
    }
    if a.html && ext != "html" {
        write_atomically(&a.out.with_extension("html"), |w| {
            w.write_all(page(&d, &options).as_bytes())
        })?;
    }
    eprintln!("wrote {}", a.out.display());
    Ok(())
}

/// Where the default window, `[0, 1.12 t_c]`, would hold under a
/// fifteenth of a chain's frames spread over `[0, until]`: the end of the
/// window to sample alone. A stiff base that rebounds alone ends its
/// contact far sooner than the layers' transits: steel under a gel, in
/// reduced units, drew no frame at all.
fn shown_window_alone(a: &DiagramArgs, outcome: &Outcome, until: f64) -> Option<f64> {
    let window = 1.12 * outcome.contact_time;
    (a.t_end.is_none() && window > 0.0 && window < until / 15.0)
        .then_some(1.15 * outcome.contact_time)
}

/// Runs what `a` asks for and lays out the figure, on `given` instead of
/// the scene `a` names when the caller already holds one (the explorer);
/// writes nothing.
pub fn build(a: &DiagramArgs, given: Option<Scene>) -> anyhow::Result<(Diagram, DiagramOptions)> {
    let (scene, _, name) = a.subject.load(given)?;
    let rod = scene.validate().map_err(|e| input(e.to_string()))?;
    let ext = a.out.extension().and_then(|e| e.to_str()).unwrap_or("");
    if !matches!(ext, "svg" | "png" | "html") {
        return Err(input(format!(
            "--out must end in .svg, .png or .html (got '{}')",
            a.out.display()
        )));
    }
    check_flags(a)?;
    if rod.is_viscous() && (a.engine == DiagramEngine::Wave || a.side_by_side) {
        return Err(input(
            "the scene has a viscous layer: only --engine chain can draw it",
        ));
    }
    let chain_label = format!("chain, N = {}", a.masses);
    let (mut pictures, outcome, wall) = if a.engine == DiagramEngine::Wave || a.side_by_side {
        let run = exact_run(&rod).map_err(|e| match e {
            WaveError::EventLimit { .. } => anyhow::anyhow!(
                "the diagram draws every front, and this scene's fronts multiply beyond {} events \
                 (impact run merges them and still answers); draw the chain instead: --engine chain",
                impact_diagram::MAX_DRAWN_EVENTS
            ),
            e => anyhow::Error::new(e).context("the exact engine could not finish"),
        })?;
        (
            vec![("exact (front tracing)".to_string(), run.picture)],
            run.outcome,
            run.wall,
        )
    } else {
        let until = a
            .t_end
            .unwrap_or(3.0 * rod.transit_times().iter().sum::<f64>());
        let mut run = chain_run(&rod, a.masses, until).map_err(crate::flags::chain)?;
        if let Some(within) = shown_window_alone(a, &run.outcome, until) {
            run = chain_run_within(&rod, a.masses, within).map_err(crate::flags::chain)?;
        }
        (
            vec![(chain_label.clone(), run.picture)],
            run.outcome,
            run.wall,
        )
    };
    if a.side_by_side {
        let until = a.t_end.unwrap_or(1.2 * outcome.end_time);
        let chain = match shown_window_alone(a, &outcome, until) {
            Some(within) => chain_run_within(&rod, a.masses, within),
            None => chain_run(&rod, a.masses, until),
        };
        pictures.push((chain_label, chain.map_err(crate::flags::chain)?.picture));
    }
    let d = Diagram {
        title: format!(
            "{name}: e = {:.4}, t_c = {:.4}, N_b = {}",
            outcome.restitution, outcome.contact_time, outcome.bounces
        ),
        rod,
        outcome,
        wall,
        pictures,
    };
    let window = match (a.t_start, a.t_end) {
        (None, None) => None,
        (s, e) => Some((s.unwrap_or(0.0), e.unwrap_or(1.12 * d.outcome.contact_time))),
    };
    let options = DiagramOptions {
        window,
        strain_scale: a.strain_scale,
        draw_fronts: !a.no_fronts,
        ..DiagramOptions::default()
    };
    Ok((d, options))
}
