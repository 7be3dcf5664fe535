//! Fig. 11 (Appendix A): the chain's finite-size error for a homogeneous
//! elastic rod, `1 - e` against `N`, with its power-law fit.

use crate::claim::{Claim, Item, curve_csv, figure};
use crate::{PaperError, Settings, try_par_map};
use impact_chain::{ChainConfig, simulate};
use impact_model::numerics::power_fit;
use impact_model::{Layer, Scene};
use impact_plot::{Axis, Colour, LinePlot, Series};
use std::path::Path;

pub fn run(dir: &Path, s: &Settings) -> Result<Item, PaperError> {
    let rod = Scene {
        impact_speed: 1.0,
        layers: vec![Layer::elastic(1.0, 1.0, 1.0)],
        wall_contact: None,
    }
    .validate()?;
    let errors: Vec<(f64, f64)> = try_par_map(&s.fig11_sizes, |&n| {
        simulate(
            &rod,
            &ChainConfig {
                masses: n,
                ..ChainConfig::default()
            },
        )
        .map(|o| (n as f64, 1.0 - o.restitution))
        .map_err(PaperError::from)
    })?;
    let fit = power_fit(&errors);
    let (p, c) = (fit.exponent, fit.prefactor());
    let at50 = errors
        .iter()
        .find(|e| e.0 == 50.0)
        .map_or(f64::NAN, |e| e.1);
    let data = curve_csv(dir, "fig11", "masses,one_minus_e", &errors)?;
    let plot = LinePlot {
        title: "Fig. 11: 1 - e vs N (homogeneous elastic chain)".into(),
        x: Axis::fit(
            errors.iter().map(|e| e.0),
            impact_plot::Scale::Log,
            "N",
            0.1,
        ),
        y: Axis::fit(
            errors.iter().map(|e| e.1),
            impact_plot::Scale::Log,
            "1 - e",
            0.1,
        ),
        series: vec![
            Series::markers("chain", errors.clone(), Colour::BLUE),
            Series::line(
                &format!("fit {c:.3} N^{p:.3}"),
                errors.iter().map(|&(n, _)| (n, c * n.powf(p))).collect(),
                Colour::RED,
            ),
        ],
    };
    Ok(Item {
        id: "fig11".into(),
        title: "Fig. 11: finite-size error of the chain".into(),
        figures: vec![figure(dir, "fig11", &plot.to_svg())?],
        data: vec![data],
        claims: vec![
            Claim::new(
                "Appendix A: the error is about 1% for N = 50",
                "1 - e ~ 1%",
                format!("1 - e = {:.2}% at N = 50", 100.0 * at50),
                (0.005..0.02).contains(&at50),
                "",
            ),
            Claim::new(
                "Appendix A: 1 - e falls with N as a power law",
                "power law",
                format!(
                    "exponent {p:.3} over N = {}..{}",
                    s.fig11_sizes[0],
                    s.fig11_sizes[s.fig11_sizes.len() - 1]
                ),
                p < -0.3,
                "",
            ),
        ],
        notes: vec![],
    })
}
