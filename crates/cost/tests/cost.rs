//! The cost study on a cheap point: it runs end to end, errors fall as each
//! setting tightens, and the Pareto front is monotone. No timing is asserted.

use impact_cost::{
    ChainCost, ChainKind, ChainStudy, CostReport, CostSettings, cost_study, write_report,
};
use impact_model::Bilayer;

/// The chain rows of one kind and study, in the report's order.
fn rows(r: &CostReport, kind: ChainKind, study: ChainStudy) -> Vec<&ChainCost> {
    r.chain
        .iter()
        .filter(|c| c.kind == kind && c.study == study)
        .collect()
}

#[test]
fn the_cost_study_runs_and_its_errors_fall_as_settings_tighten() {
    let rod = Bilayer::new(0.2, 0.05).unwrap().scene().validate().unwrap();
    let s = CostSettings::tiny();
    let r = cost_study("x = 0.2, alpha = 0.05", &rod, &s, &|_| {}).unwrap();

    // chain, elastic: error strictly falls as N doubles
    let n: Vec<_> = rows(&r, ChainKind::Elastic, ChainStudy::Masses);
    assert_eq!(n.len(), s.sizes.len());
    for w in n.windows(2) {
        assert!(
            w[1].restitution_error < w[0].restitution_error,
            "{} then {}",
            w[0].restitution_error,
            w[1].restitution_error
        );
        assert!(w[1].mass_steps > w[0].mass_steps, "work grows with N");
    }
    // work grows as ~N^2 (mass-steps are hardware-independent)
    assert!(
        (r.chain_work_exponent - 2.0).abs() < 0.15,
        "{}",
        r.chain_work_exponent
    );
    // chain, viscous: a finite limit, near the finest chain (its convergence
    // here is not monotone: 0.6334, 0.6328, 0.6316, 0.6325 for N = 50..400)
    let v: Vec<_> = rows(&r, ChainKind::Viscous, ChainStudy::Masses);
    assert!(
        r.viscous_limit.is_finite()
            && (v.last().unwrap().restitution - r.viscous_limit).abs() < 0.01
    );
    // chain, time step: a smaller step costs more steps
    let dt: Vec<_> = rows(&r, ChainKind::Elastic, ChainStudy::TimeStep);
    assert_eq!(dt.len(), s.dt_factors.len());
    let mut by_dt: Vec<_> = dt.iter().map(|c| (c.dt_factor, c.steps)).collect();
    by_dt.sort_by(|a, b| a.0.total_cmp(&b.0));
    for w in by_dt.windows(2) {
        assert!(w[0].1 >= w[1].1, "{by_dt:?}");
    }

    // exact engine: looser drop tolerances never need more events, and the
    // error at the default tolerance is below 1e-12 at every point
    for point in [
        "x = 0.2, alpha = 0.05",
        "hard corner x = 0.995, alpha = 0.005",
    ] {
        let rows: Vec<_> = r
            .exact
            .iter()
            .filter(|e| e.point == point && e.merge_window == 0.0)
            .collect();
        assert_eq!(rows[0].drop_tolerance, 0.0);
        assert_eq!(rows[0].restitution_error, 0.0, "the reference is itself");
        for w in rows.windows(2) {
            assert!(
                w[1].events <= w[0].events,
                "{point}: {} then {}",
                w[0].events,
                w[1].events
            );
        }
    }
    let corner: Vec<_> = r
        .exact
        .iter()
        .filter(|e| e.point.starts_with("hard corner") && e.merge_window == 0.0)
        .collect();
    assert!(
        corner
            .iter()
            .find(|e| e.drop_tolerance == 1e-14)
            .unwrap()
            .restitution_error
            < 1e-11
    );
    assert!(
        corner.last().unwrap().restitution_error > corner[1].restitution_error,
        "a loose tolerance costs accuracy"
    );

    // Pareto fronts: time increasing, error strictly decreasing
    for front in [&r.pareto, &r.pareto_exact, &r.pareto_chain] {
        for w in front.windows(2) {
            assert!(
                w[1].0 >= w[0].0 && w[1].1 < w[0].1,
                "{:?} then {:?}",
                w[0],
                w[1]
            );
        }
    }
    // the chain trades time for accuracy along its N study
    assert!(r.pareto_chain.len() >= 3, "{:?}", r.pareto_chain);
    // over both engines the exact engine dominates: fastest and most exact
    assert!(
        r.pareto.iter().all(|p| p.2.starts_with("exact")),
        "{:?}",
        r.pareto
    );

    // the headline, measured in the run: at this point the chain reaches
    // |de| < 5e-3 at a modest N, far slower than the exact engine
    let h = &r.headline;
    assert!(h.masses.is_some() && h.chain_error < s.target_error);
    assert!(h.ratio > 1.0);

    // growth: events grow with t2/t1 along alpha = 0.005
    let g: Vec<_> = r
        .growth
        .iter()
        .filter(|g| g.sweep == impact_cost::GrowthSweep::X)
        .collect();
    assert!(g.last().unwrap().events > 10 * g.first().unwrap().events);

    let dir = std::env::temp_dir().join(format!("impact-cost-{}", std::process::id()));
    write_report(&dir, &r).unwrap();
    for f in [
        "cost.json",
        "exact.csv",
        "chain.csv",
        "growth.csv",
        "index.html",
        "pareto.svg",
        "pareto.png",
        "tolerance.png",
        "chain-growth.png",
        "exact-growth.png",
    ] {
        assert!(dir.join(f).metadata().unwrap().len() > 100, "{f}");
    }
}

#[test]
fn viscous_scenes_are_refused_with_the_reason() {
    let mut scene = Bilayer::new(0.4, 0.05).unwrap().scene();
    scene.layers[1].restitution = Some(0.7);
    let err = cost_study(
        "v",
        &scene.validate().unwrap(),
        &CostSettings::tiny(),
        &|_| {},
    )
    .unwrap_err();
    assert!(err.to_string().contains("needs an elastic scene"));
}
