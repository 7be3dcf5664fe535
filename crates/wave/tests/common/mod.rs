#![allow(dead_code)]
use impact_model::{Bilayer, Layer, Outcome, Rod, Scene};
use impact_wave::{Resolution, WaveConfig, WaveEngine, simulate};

pub fn rod(x: f64, alpha: f64) -> Rod {
    Bilayer::new(x, alpha).unwrap().scene().validate().unwrap()
}

pub fn run(x: f64, alpha: f64) -> Outcome {
    simulate(&rod(x, alpha), &WaveConfig::default()).unwrap()
}

/// A layer of `length` with wave `speed` and `impedance`.
pub fn layer_of(length: f64, speed: f64, impedance: f64) -> Layer {
    let density = impedance / speed;
    Layer::elastic(length, density * speed * speed, density)
}

/// A unit-speed impact of `layers`, bottom first, on the paper's wall.
pub fn scene_of(layers: Vec<Layer>) -> Scene {
    Scene {
        impact_speed: 1.0,
        layers,
        wall_contact: None,
    }
}

/// A merged run (the ladder) even where the exact run would fit: its
/// first lattice from 1,000 events, aiming at `1e-6` within 4 M events,
/// with `config`'s other settings.
pub fn ladder(rod: &Rod, config: WaveConfig) -> Outcome {
    let config = WaveConfig {
        resolution: Resolution::Auto {
            exact_events: 1_000,
            budget_events: 4_000_000,
            target: 1e-6,
            exact_again: false,
        },
        ..config
    };
    simulate(rod, &config).expect("a merged outcome")
}

/// Runs to the end and returns the engine, for field checks.
pub fn engine(rod: &Rod, config: WaveConfig) -> WaveEngine {
    let mut e = WaveEngine::new(rod, config).unwrap();
    e.run().unwrap();
    e
}

/// `(t1, t2)` of the canonical bilayer.
pub fn transits(x: f64, alpha: f64) -> (f64, f64) {
    ((1.0 - x) / (1.0 - alpha).sqrt(), x / alpha.sqrt())
}

/// Checks the physical validity every outcome must have.
pub fn assert_valid(o: &Outcome) {
    assert!(
        o.restitution.is_finite() && (0.0..=1.0 + 1e-12).contains(&o.restitution),
        "{o:?}"
    );
    assert!(o.contact_time.is_finite() && o.contact_time > 0.0, "{o:?}");
    assert!(o.bounces >= 1 && o.bounces <= o.separations.max(1), "{o:?}");
    for w in o.contacts.windows(2) {
        assert!(w[0][1] <= w[1][0], "contacts overlap: {o:?}");
    }
}

/// A tiny xorshift generator: reproducible scenes without a dependency.
pub struct XorShift(pub u64);

impl XorShift {
    /// Uniform in `[0, 1)`.
    pub fn next(&mut self) -> f64 {
        let s = &mut self.0;
        *s ^= *s << 13;
        *s ^= *s >> 7;
        *s ^= *s << 17;
        (*s >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }

    /// Log-uniform in `[lo, hi)`.
    pub fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        10f64.powf(self.uniform(lo.log10(), hi.log10()))
    }
}

/// The exact solution in plain double precision, refusing to run past
/// `max_events` loop steps (then `None`); event by event unless `leap`
/// (a reference for leaping or merged runs shares no closed form with
/// them).
pub fn exact_run(rod: &Rod, max_events: u64, leap: bool) -> Option<Outcome> {
    let config = WaveConfig {
        resolution: Resolution::Exact,
        precision: impact_wave::Precision::Double,
        leap_quiet_layers: leap,
        max_events,
        ..WaveConfig::default()
    };
    match simulate(rod, &config) {
        Ok(o) => Some(o),
        Err(impact_wave::WaveError::EventLimit { .. }) => None,
        Err(e) => panic!("exact run failed otherwise than by its event limit: {e}"),
    }
}

/// A random rod of 2 to `most_layers` layers, unit impact speed: lengths
/// uniform in `[0.2, 1.2)`, densities log-uniform in `[0.1, 10)`, wave
/// speeds log-uniform in `[1, top_speed)`.
pub fn random_scene(rng: &mut XorShift, most_layers: usize, top_speed: f64) -> Scene {
    let n = 2 + (rng.next() * (most_layers - 1) as f64) as usize;
    let layers = (0..n)
        .map(|_| {
            let length = rng.uniform(0.2, 1.2);
            let density = rng.log_uniform(0.1, 10.0);
            let speed = rng.log_uniform(1.0, top_speed);
            Layer::elastic(length, density * speed * speed, density)
        })
        .collect();
    Scene {
        impact_speed: 1.0,
        layers,
        wall_contact: None,
    }
}

/// The layer survey's rod 20 (seed 7; length, modulus, density, bottom
/// first): a slow bottom under four fast layers and a top a hundred
/// times slower than them, whose block's response rings long.
pub const SURVEY_SEED_7_ROD_20: [(f64, f64, f64); 6] = [
    (0.4954541110415926, 188.6900167559795, 8.347365412239864),
    (1.1185481502738823, 9414877211.070044, 0.28648883899932903),
    (0.2840612669703682, 25979164416.074642, 0.3498170036734888),
    (0.38155139141117106, 22329567728.11959, 3.247529431968498),
    (1.0495878272608952, 505785077767.1679, 2.248781579086109),
    (0.6059478279156085, 1780693.6578908376, 1.1835804440683804),
];
