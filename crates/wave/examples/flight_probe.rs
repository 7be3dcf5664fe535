//! How near the bottom comes to the wall in the flight after the last
//! separation, against the escape bound's reach: `flight_probe SCENE.json P`
//! (one merged run, lattice `P` of each transit, `P / 50` of the longest;
//! `P` 0: exact).
//! The bottom lies `offset = rise - height` below where the centre of mass
//! puts it; the escape bound stops the run when the rise reaches `D`, the
//! largest offset the internal energy allows. The largest offset seen is
//! the least any escape proof must allow, so the escape time it would give
//! is the earliest any proof could stop the run. (A leap is seen at its
//! end only, so the offset seen may be low and that time early: the time
//! a sharper proof could save is at most what this says.)
use impact_model::Scene;
use impact_model::escape::{EscapeBound, Margin};
use impact_wave::{ContactState, Resolution, WaveConfig, WaveEngine};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let Some(path) = args.get(1) else {
        return Err("usage: flight_probe SCENE.json [P]".into());
    };
    let scene: Scene = serde_json::from_str(&std::fs::read_to_string(path)?)?;
    let p: f64 = args.get(2).map_or(Ok(0.1), |s| s.parse())?;
    let rod = scene.validate()?;
    let config = WaveConfig {
        resolution: if p > 0.0 {
            Resolution::Merged {
                per_transit: p,
                per_longest: p / 50.0,
            }
        } else {
            Resolution::Exact
        },
        max_events: u64::MAX / 4,
        ..WaveConfig::default()
    };
    let mut engine = WaveEngine::new(&rod, config)?;
    // (time, height) in flight, from the last separation on
    let mut flight: Vec<(f64, f64)> = Vec::new();
    while engine.stopped().is_none() {
        engine.step()?;
        match engine.contact_state() {
            ContactState::Free {
                height,
                velocity,
                at,
            } => {
                let t = engine.time();
                flight.push((t, height + velocity * (t - at)));
            }
            ContactState::InContact { .. } => flight.clear(),
        }
    }
    let e = engine.restitution();
    let v = e * rod.impact_speed();
    let mass = rod.mass();
    let internal = 0.5 * mass * (rod.impact_speed().powi(2) - v * v);
    // the model's compliance moment `integral m(s)^2 / E ds`, in the
    // scene's units (it scales as mass^2 * length / modulus)
    let u = rod.units();
    let moment = rod.scaled_compliance_moment() * u.density.powi(2) * u.length.powi(3) / u.modulus;
    let bound = EscapeBound::new(moment, mass);
    let reach = bound.reach(internal, Margin::relative(0.0));
    let Some(&(start, _)) = flight.first() else {
        return Err("the run did not end in flight".into());
    };
    let end = engine.time();
    // the centre of mass rises at v: at the end it stands `reach` up
    let offset = |&(t, h): &(f64, f64)| reach - v * (end - t) - h;
    let worst = flight.iter().map(offset).fold(f64::NEG_INFINITY, f64::max);
    // a bound no larger than the offset seen would have stopped the run
    // when the rise reached it: no valid bound can stop it earlier
    let earliest = end - (reach - worst) / v;
    println!(
        "e {e:.6}, last separation {start:.4}, escape {end:.4} (the flight {:.0} % of the run), D {reach:.3e}, largest offset seen {worst:.3e} ({:.0} % of D): a bound of that stops at {earliest:.4} at the earliest ({:.0} % of the run)",
        100.0 * (end - start) / end,
        100.0 * worst / reach,
        100.0 * earliest / end,
    );
    Ok(())
}
