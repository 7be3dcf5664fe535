//! Figs. 8, 9: `e(x)` and the reduced contact time of viscoelastic
//! bilayers, one layer's restitution varied at a time, and where the
//! transition between the two contact-time regimes moves.

use super::{ALPHA, ends, point};
use crate::claim::{Claim, Item, csv, figure};
use crate::{PaperError, Settings, try_par_map};
use impact_model::{Bilayer, Outcome};
use impact_plot::{Axis, Colour, LinePlot, Series};
use std::path::Path;

/// The curves' colours, red (most viscous) to blue, then black.
fn palette(i: usize) -> Colour {
    [
        Colour::RED,
        Colour(214, 96, 77),
        Colour(244, 165, 130),
        Colour(146, 197, 222),
        Colour(67, 147, 195),
        Colour::BLUE,
        Colour::INK,
    ][i % 7]
}

/// `x` at which the reduced contact time first passes midway between the
/// `2 t1` and `2 t1 + 2 t2` regimes.
fn transition(curve: &[(f64, Outcome)]) -> f64 {
    curve
        .iter()
        .find(|(x, o)| {
            let low = Bilayer {
                x: *x,
                alpha: ALPHA,
            }
            .first_echo_reduced_time();
            o.reduced_contact_time > 0.5 * (low + 1.0)
        })
        .map_or(f64::NAN, |(x, _)| *x)
}

pub fn run_8_9(dir: &Path, s: &Settings) -> Result<Item, PaperError> {
    let xs = Settings::unit_steps(s.visco_x_step);
    // (panel, varied layer): (a) e1 varied with e2 = 1; (b) e2 varied with e1 = 1
    let mut figures = Vec::new();
    let mut rows = Vec::new();
    let mut transitions = Vec::new();
    let mut regimes_ok = 0;
    let mut curves_total = 0;
    for (panel, varied_bottom) in [("a", true), ("b", false)] {
        let curves: Vec<(f64, Vec<(f64, Outcome)>)> = try_par_map(&s.visco_values, |&v| {
            let (e1, e2) = if varied_bottom { (v, 1.0) } else { (1.0, v) };
            let curve = xs
                .iter()
                .map(|&x| point(x, e1, e2, s.visco_masses).map(|o| (x, o)))
                .collect::<Result<Vec<_>, _>>()?;
            Ok((v, curve))
        })?;
        figures.extend(draw_panel(dir, panel, varied_bottom, &xs, &curves)?);
        for (v, curve) in &curves {
            for (x, o) in curve {
                rows.push(vec![
                    if varied_bottom { 1.0 } else { 2.0 },
                    *v,
                    *x,
                    o.restitution,
                    o.reduced_contact_time,
                    f64::from(o.bounces),
                ]);
            }
            transitions.push((varied_bottom, *v, transition(curve)));
            // Fig. 9: 2 t1 at the smallest x, 2 t1 + 2 t2 at the largest
            let (first, last) = (&curve[0], &curve[curve.len() - 1]);
            let low = |x: f64| Bilayer { x, alpha: ALPHA }.first_echo_reduced_time();
            curves_total += 1;
            if (first.1.reduced_contact_time - low(first.0)).abs() < 0.05 * low(first.0)
                && (last.1.reduced_contact_time - 1.0).abs() < 0.05
            {
                regimes_ok += 1;
            }
        }
    }
    let data = csv(
        dir,
        "fig8-9",
        "varied_layer,layer_restitution,x,restitution,reduced_contact_time,bounces",
        rows,
    )?;
    // transition moves to larger x as e2 drops, to smaller x as e1 drops
    let trend = |bottom: bool| {
        let mut t: Vec<(f64, f64)> = transitions
            .iter()
            .filter(|t| t.0 == bottom)
            .map(|t| (t.1, t.2))
            .collect();
        t.sort_by(|a, b| a.0.total_cmp(&b.0));
        t
    };
    let (t_e1, t_e2) = (trend(true), trend(false));
    let fmt = |t: &[(f64, f64)]| {
        t.iter()
            .map(|(v, x)| format!("{v}: x = {x:.3}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    // monotone, and actually moving between the extreme values
    let moves = |t: &[(f64, f64)]| t.len() >= 2 && t[0].1 != t[t.len() - 1].1;
    let e2_ok = t_e2.windows(2).all(|w| w[0].1 >= w[1].1) && moves(&t_e2);
    let e1_ok = t_e1.windows(2).all(|w| w[0].1 <= w[1].1) && moves(&t_e1);
    let claims = vec![
        ends::claim(s)?,
        Claim::new(
            "Fig. 9: t_c = 2 t1 for small x and t_c = 2 t1 + 2 t2 for large x, in all cases",
            "both regimes on every curve",
            format!("paper's wall law: {regimes_ok} of {curves_total} curves (within 5%)"),
            regimes_ok == curves_total,
            "with a strongly viscous top (e2 = 0.4) the reduced contact time stays near 0.85 up to x = 0.99, at N = 400 and 2000 alike: a viscous rod's contact is shorter than its wave's round trip, as the paper's own Fig. 2(b) inset shows for homogeneous rods (t_c c/L = 1.75 at tau c/L = 0.3)",
        ),
        Claim::new(
            "Figs. 8-9: the transition shifts to larger x when e2 decreases",
            "x* grows as e2 drops",
            format!("paper's wall law: x* by e2: {}", fmt(&t_e2)),
            e2_ok,
            "",
        ),
        Claim::new(
            "Figs. 8-9: the transition shifts to smaller x when e1 decreases",
            "x* falls as e1 drops",
            format!("paper's wall law: x* by e1: {}", fmt(&t_e1)),
            e1_ok,
            "",
        ),
    ];
    Ok(Item {
        id: "fig8-9".into(),
        title: "Figs. 8, 9: viscoelastic bilayers, alpha = 0.005".into(),
        figures,
        data: vec![data],
        claims,
        notes: vec![format!(
            "Chain of {} masses; layer restitutions calibrated (data/calibration); x* is where the reduced contact time passes midway between the two regimes.",
            s.visco_masses
        )],
    })
}

/// Figs. 8 and 9, panel `panel`: `e(x)` and the reduced contact time of
/// each curve (one layer's restitution varied), with the regimes' guides.
fn draw_panel(
    dir: &Path,
    panel: &str,
    varied_bottom: bool,
    xs: &[f64],
    curves: &[(f64, Vec<(f64, Outcome)>)],
) -> Result<Vec<String>, PaperError> {
    let name = if varied_bottom { "e1" } else { "e2" };
    let mut e_series = Vec::new();
    let mut t_series = Vec::new();
    for (i, (v, curve)) in curves.iter().enumerate() {
        e_series.push(Series::line(
            &format!("{name} = {v}"),
            curve.iter().map(|(x, o)| (*x, o.restitution)).collect(),
            palette(i),
        ));
        t_series.push(Series::line(
            &format!("{name} = {v}"),
            curve
                .iter()
                .map(|(x, o)| (*x, o.reduced_contact_time))
                .collect(),
            palette(i),
        ));
    }
    let mut figures = Vec::new();
    let dashed = Series::line(
        "t_c = 2 t1",
        xs.iter()
            .map(|&x| (x, Bilayer { x, alpha: ALPHA }.first_echo_reduced_time()))
            .collect(),
        Colour(0, 0, 0),
    )
    .dashed();
    t_series.push(dashed);
    e_series.push(
        Series::line(
            "1 - 2x",
            xs.iter().map(|&x| (x, 1.0 - 2.0 * x)).collect(),
            Colour(120, 120, 120),
        )
        .dashed(),
    );
    e_series.push(
        Series::line(
            "x",
            xs.iter().map(|&x| (x, x)).collect(),
            Colour(160, 160, 160),
        )
        .dashed(),
    );
    let varied = if varied_bottom {
        "e1 varied, e2 = 1"
    } else {
        "e2 varied, e1 = 1"
    };
    figures.push(figure(
        dir,
        &format!("fig8{panel}"),
        &LinePlot {
            title: format!("Fig. 8({panel}): e vs x, alpha = 0.005, {varied}"),
            x: Axis::linear(0.0, 1.0, "x"),
            y: Axis::linear(0.0, 1.0, "e"),
            series: e_series,
        }
        .to_svg(),
    )?);
    figures.push(figure(
        dir,
        &format!("fig9{panel}"),
        &LinePlot {
            title: format!("Fig. 9({panel}): t_c / (2 t1 + 2 t2), {varied}"),
            x: Axis::linear(0.0, 1.0, "x"),
            y: Axis::linear(0.0, 1.1, "reduced contact time"),
            series: t_series,
        }
        .to_svg(),
    )?);
    Ok(figures)
}
