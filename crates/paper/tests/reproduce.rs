//! The reproduction at a toy resolution: every file is written, the data
//! agree with direct runs of the engines, and the verdicts follow the numbers.

use impact_paper::{Settings, Verdict, reproduce};
use std::path::PathBuf;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("impact-paper-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn rows(path: &std::path::Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .map(|c| c.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect()
}

#[test]
fn a_tiny_reproduction_writes_every_file_and_its_numbers_are_the_engines() {
    let d = dir("tiny");
    let items = reproduce(&d, &Settings::tiny(), &|_| {}).unwrap();
    assert_eq!(items.len(), 9);
    for item in &items {
        for stem in &item.figures {
            for ext in ["svg", "png"] {
                let p = d.join(format!("{stem}.{ext}"));
                assert!(
                    p.metadata().is_ok_and(|m| m.len() > 1000),
                    "{}",
                    p.display()
                );
            }
        }
        for data in &item.data {
            assert!(d.join(data).exists(), "{data}");
        }
        assert!(!item.claims.is_empty(), "{}", item.id);
    }
    let page = std::fs::read_to_string(d.join("index.html")).unwrap();
    assert!(page.contains("tiny (tests)") && page.contains("Fig. 3(d) caption"));

    // maps: the exact engine at sample points
    for r in rows(&d.join("maps.csv")).iter().step_by(37) {
        let rod = impact_model::Bilayer::new(r[0], r[1])
            .unwrap()
            .scene()
            .validate()
            .unwrap();
        let o = impact_wave::simulate(&rod, &impact_wave::WaveConfig::default()).unwrap();
        assert_eq!(r[6], o.restitution);
        assert_eq!(r[2], o.reduced_contact_time);
        assert_eq!(r[4], f64::from(o.bounces));
    }
    // Figs. 8-9: the chain with calibrated layers
    for r in rows(&d.join("fig8-9.csv")).iter().step_by(3) {
        let (e1, e2) = if r[0] == 1.0 {
            (r[1], 1.0)
        } else {
            (1.0, r[1])
        };
        let mut scene = impact_model::Bilayer::new(r[2], 0.005).unwrap().scene();
        scene.layers[0].restitution = (e1 < 1.0).then_some(e1);
        scene.layers[1].restitution = (e2 < 1.0).then_some(e2);
        let o = impact_chain::simulate(
            &scene.validate().unwrap(),
            &impact_chain::ChainConfig {
                masses: 150,
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(r[3], o.restitution);
    }
    // Fig. 11: the homogeneous elastic chain
    for r in rows(&d.join("fig11.csv")) {
        let rod = impact_model::Scene {
            impact_speed: 1.0,
            layers: vec![impact_model::Layer::elastic(1.0, 1.0, 1.0)],
            wall_contact: None,
        }
        .validate()
        .unwrap();
        let o = impact_chain::simulate(
            &rod,
            &impact_chain::ChainConfig {
                masses: r[0] as usize,
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(r[1], 1.0 - o.restitution);
    }
    // Appendix C: the model column is the model
    for r in rows(&d.join("appendix-c.csv")) {
        assert_eq!(
            r[1],
            impact_model::rigid_bottom::rigid_bottom(r[0]).restitution
        );
    }
}

#[test]
fn verdicts_follow_the_numbers() {
    let d = dir("verdicts");
    let items = reproduce(&d, &Settings::tiny(), &|_| {}).unwrap();
    let claim = |part: &str| {
        items
            .iter()
            .flat_map(|i| &i.claims)
            .find(|c| c.statement.contains(part))
            .unwrap_or_else(|| panic!("{part}"))
    };
    // computed from the engine: the caption of 3(d) is wrong, the others right
    assert_eq!(claim("Fig. 3(d) caption").verdict, Verdict::Disagrees);
    assert!(claim("Fig. 3(d) caption").ours.contains("3.5000 t1"));
    assert_eq!(claim("Fig. 3(a) caption").verdict, Verdict::Agrees);
    assert_eq!(claim("Fig. 3(c): several").verdict, Verdict::Agrees);
    // every disagreement says which side the evidence supports
    for c in items
        .iter()
        .flat_map(|i| &i.claims)
        .filter(|c| c.verdict == Verdict::Disagrees)
    {
        assert!(!c.ours.is_empty());
    }
    // viscous verdicts name the wall law they ran under, and none calls a
    // sentence of the paper wrong: Sec. VII's ends are checked directly,
    // against the paper's e1 at x -> 0 and the model's own limit at x -> 1
    for item in items
        .iter()
        .filter(|i| ["fig2", "fig8-9", "fig10"].contains(&i.id.as_str()))
    {
        for c in &item.claims {
            assert!(
                c.ours.contains("paper's wall law"),
                "{}: {}",
                c.statement,
                c.ours
            );
        }
    }
    for c in items.iter().flat_map(|i| &i.claims) {
        let text = format!("{} {} {}", c.statement, c.ours, c.comment).to_lowercase();
        assert!(!text.contains("paper is wrong"), "{text}");
    }
    let ends = claim("Sec. VII: the layer restitutions");
    assert_eq!(ends.verdict, Verdict::Agrees, "{}", ends.ours);
    assert!(ends.ours.contains("unilateral e(tau2)"), "{}", ends.ours);
    // the Fig. 11 verdict is the number it shows
    let f11 = claim("about 1% for N = 50");
    let pct: f64 = f11
        .ours
        .trim_start_matches("1 - e = ")
        .split('%')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(f11.verdict == Verdict::Agrees, (0.5..2.0).contains(&pct));
}
