//! Fig. 10: the experiments' materials (`e1 = 0.94`, `e2 = 0.72`), and
//! the staircase of `N_b(x)`.

use super::point;
use crate::claim::{Claim, Item, csv, figure};
use crate::{PaperError, Settings, try_par_map};
use impact_model::Outcome;
use impact_model::numerics::spearman;
use impact_plot::{Axis, Colour, LinePlot, Series};
use std::path::Path;

pub fn run_10(dir: &Path, s: &Settings) -> Result<Item, PaperError> {
    let xs = Settings::unit_steps(s.visco_x_step);
    let curve: Vec<(f64, Outcome)> = try_par_map(&xs, |&x| {
        point(x, 0.94, 0.72, s.visco_masses).map(|o| (x, o))
    })?;
    let data = csv(
        dir,
        "fig10",
        "x,restitution,bounces,separations,reduced_contact_time",
        curve.iter().map(|(x, o)| {
            vec![
                *x,
                o.restitution,
                f64::from(o.bounces),
                f64::from(o.separations),
                o.reduced_contact_time,
            ]
        }),
    )?;
    let figures = vec![
        figure(
            dir,
            "fig10a",
            &LinePlot {
                title: "Fig. 10(a): e vs x, e1 = 0.94, e2 = 0.72, alpha = 0.005".into(),
                x: Axis::linear(0.0, 1.0, "x"),
                y: Axis::linear(0.0, 1.0, "e"),
                series: vec![Series::line(
                    "chain",
                    curve.iter().map(|(x, o)| (*x, o.restitution)).collect(),
                    Colour::BLUE,
                )],
            }
            .to_svg(),
        )?,
        figure(
            dir,
            "fig10b",
            &LinePlot {
                title: "Fig. 10(b): N_b vs x".into(),
                x: Axis::linear(0.0, 1.0, "x"),
                y: Axis::linear(
                    0.0,
                    curve
                        .iter()
                        .map(|(_, o)| f64::from(o.bounces))
                        .fold(1.0, f64::max)
                        + 1.0,
                    "N_b",
                ),
                series: vec![Series::line(
                    "chain",
                    curve
                        .iter()
                        .map(|(x, o)| (*x, f64::from(o.bounces)))
                        .collect(),
                    Colour::RED,
                )],
            }
            .to_svg(),
        )?,
    ];
    // staircase: N_b rises with x overall (rank correlation), single-step dips
    // are chain noise
    let rho = spearman(
        &curve.iter().map(|c| c.0).collect::<Vec<_>>(),
        &curve
            .iter()
            .map(|c| f64::from(c.1.bounces))
            .collect::<Vec<_>>(),
    );
    let dips = curve
        .windows(2)
        .filter(|w| w[1].1.bounces < w[0].1.bounces)
        .count();
    let claims = vec![Claim::new(
        "Fig. 10(b): N_b rises as a staircase with x",
        "N_b increases with x",
        format!(
            "paper's wall law: rank correlation of N_b with x: {rho:.2}; N_b from {} to {}, {dips} single-step dips",
            curve[0].1.bounces,
            curve[curve.len() - 1].1.bounces
        ),
        rho > 0.6 && curve[curve.len() - 1].1.bounces > curve[0].1.bounces,
        "",
    )];
    Ok(Item {
        id: "fig10".into(),
        title: "Fig. 10: e1 = 0.94, e2 = 0.72 (the experiments' materials)".into(),
        figures,
        data: vec![data],
        claims,
        notes: vec!["The paper's experimental points (D'Angelo et al.) are not reproduced here: their data are not part of the paper's text.".into()],
    })
}
