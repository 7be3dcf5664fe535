#![allow(dead_code)]
use impact_model::{Bilayer, Outcome, Rod};
use impact_wave::{WaveConfig, WaveEngine, simulate};

pub fn rod(x: f64, alpha: f64) -> Rod {
    Bilayer::new(x, alpha).unwrap().scene().validate().unwrap()
}

pub fn run(x: f64, alpha: f64) -> Outcome {
    simulate(&rod(x, alpha), &WaveConfig::default()).unwrap()
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
