//! Appendix C and Fig. 13: the rigid-bottom model (`alpha -> 0`), its
//! bounce sequence, and its `e(x)` against the exact engine at small `alpha`.

use crate::claim::{Claim, Item, csv, curve_csv, figure};
use crate::{PaperError, Settings, exact_bilayer, try_par_map};
use impact_model::Bilayer;
use impact_model::numerics::exponential_fit;
use impact_model::rigid_bottom::{height, rigid_bottom};
use impact_plot::{Axis, Colour, LinePlot, Series};
use std::path::Path;

/// The composition whose bounce sequence Fig. 13 shows (many bounces).
const X_TRAJECTORY: f64 = 0.9;

pub fn run(dir: &Path, s: &Settings) -> Result<Item, PaperError> {
    let model = rigid_bottom(X_TRAJECTORY);
    // Fig. 13(a): the rigid part's height, units v_b tau, time units tau
    let mut path = Vec::new();
    let bounces = &model.bounces;
    for (i, b) in bounces.iter().enumerate() {
        let end = bounces.get(i + 1).map_or(
            model
                .rests_from
                .unwrap_or(model.takeoff_time)
                .min(model.takeoff_time),
            |n| n.time,
        );
        for k in 0..=40 {
            let t = b.time + (end - b.time) * f64::from(k) / 40.0;
            path.push((t, height(b.speed, t - b.time)));
        }
    }
    // Fig. 13(b): bounce speeds, and the fit v = exp(-t / (k tau))
    let pts: Vec<(f64, f64)> = bounces
        .iter()
        .filter(|b| b.speed > 1e-6)
        .map(|b| (b.time, b.speed))
        .collect();
    let k = -1.0 / exponential_fit(&pts).slope;
    // e(x): model against the exact engine at small alpha
    let xs: Vec<f64> = (1..20).map(|i| f64::from(i) * 0.05).collect();
    let compared: Vec<(f64, f64, f64)> = try_par_map(&xs, |&x| {
        let exact = exact_bilayer(Bilayer {
            x,
            alpha: s.appendix_alpha,
        })?;
        Ok((x, rigid_bottom(x).restitution, exact.restitution))
    })?;
    let data = csv(
        dir,
        "appendix-c",
        "x,e_rigid_bottom,e_exact",
        compared.iter().map(|&(x, m, e)| vec![x, m, e]),
    )?;
    let bounce_csv = curve_csv(dir, "fig13b", "t_over_tau,v_over_vb", &pts)?;
    let figures = vec![
        figure(
            dir,
            "fig13a",
            &LinePlot {
                title: format!("Fig. 13(a): rigid part's height, x = {X_TRAJECTORY}"),
                x: Axis::linear(
                    0.0,
                    model
                        .takeoff_time
                        .min(path.last().map_or(1.0, |p| p.0) * 1.05),
                    "t / tau_relax",
                ),
                y: Axis::fit(
                    path.iter().map(|p| p.1),
                    impact_plot::Scale::Linear,
                    "(y1 - L1/2) / (v_b tau_relax)",
                    0.05,
                ),
                series: vec![Series::line("Eq. C2", path.clone(), Colour::BLUE)],
            }
            .to_svg(),
        )?,
        figure(
            dir,
            "fig13b",
            &LinePlot {
                title: "Fig. 13(b): bounce speeds".into(),
                x: Axis::linear(
                    0.0,
                    pts.last().map_or(1.0, |p| p.0) * 1.05,
                    "t_1,i / tau_relax",
                ),
                y: Axis::log(pts.last().map_or(1e-3, |p| p.1) * 0.5, 1.5, "v_1,i / v_b"),
                series: vec![
                    Series::markers("recursion", pts.clone(), Colour::INK),
                    Series::line(
                        &format!("fit exp(-t / {k:.2} tau)"),
                        pts.iter().map(|&(t, _)| (t, (-t / k).exp())).collect(),
                        Colour::BLUE,
                    ),
                    Series::line(
                        "paper: exp(-t / 3 tau)",
                        pts.iter().map(|&(t, _)| (t, (-t / 3.0).exp())).collect(),
                        Colour::RED,
                    )
                    .dashed(),
                ],
            }
            .to_svg(),
        )?,
        figure(
            dir,
            "appendix-c",
            &LinePlot {
                title: format!(
                    "Appendix C: e(x), rigid-bottom model vs exact engine at alpha = {}",
                    s.appendix_alpha
                ),
                x: Axis::linear(0.0, 1.0, "x"),
                y: Axis::linear(0.0, 1.0, "e"),
                series: vec![
                    Series::line(
                        "rigid-bottom model",
                        compared.iter().map(|c| (c.0, c.1)).collect(),
                        Colour::RED,
                    ),
                    Series::markers(
                        &format!("exact, alpha = {}", s.appendix_alpha),
                        compared.iter().map(|c| (c.0, c.2)).collect(),
                        Colour::BLUE,
                    ),
                    Series::line("e = x", vec![(0.0, 0.0), (1.0, 1.0)], Colour(120, 120, 120))
                        .dashed(),
                ],
            }
            .to_svg(),
        )?,
    ];
    let big_x: Vec<&(f64, f64, f64)> = compared.iter().filter(|c| c.0 > 0.6 + 1e-9).collect();
    let asym = big_x.iter().map(|c| (c.1 - c.0).abs()).fold(0.0, f64::max);
    let model_vs_exact = compared
        .iter()
        .map(|c| (c.1 - c.2).abs())
        .fold(0.0, f64::max);
    let claims = vec![
        Claim::new(
            "Fig. 13(b): v_1,i / v_b ~ exp(-t_1,i / (3 tau_relax))",
            "decay time 3 tau_relax",
            format!(
                "fitted decay time {k:.2} tau_relax ({} bounces, x = {X_TRAJECTORY})",
                pts.len()
            ),
            (k - 3.0).abs() < 0.6,
            "",
        ),
        Claim::new(
            "Appendix C: e(x) ~ x for x > 0.6 (rigid part damped to rest)",
            "e = x",
            format!("max |e - x| = {asym:.3} for x = 0.65..0.95 (model)"),
            asym < 0.05,
            "",
        ),
        Claim::new(
            "Appendix C: the model describes the limit alpha -> 0",
            "model ~ exact as alpha -> 0",
            format!(
                "max |e_model - e_exact| = {model_vs_exact:.3} at alpha = {}",
                s.appendix_alpha
            ),
            model_vs_exact < 0.1,
            "the model is discontinuous in x (bounce counts jump) where the exact solution at finite alpha is smooth",
        ),
    ];
    Ok(Item {
        id: "appendix-c".into(),
        title: "Appendix C and Fig. 13: the rigid-bottom limit".into(),
        figures,
        data: vec![data, bounce_csv],
        claims,
        notes: vec!["The recursion of Eqs. C1-C3 (crates/model/src/rigid_bottom.rs); time in units of tau_relax = L1/c2; the model ends at t_c = 2 t2.".into()],
    })
}
