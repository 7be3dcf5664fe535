//! Figs. 8, 9, 10: viscoelastic bilayers at `alpha = 0.005` (the chain, with
//! the layer restitutions calibrated as in Sec. VII).
//!
//! The pieces: the curves and their transition (`fig8_9.rs`), Sec. VII's
//! end values (`ends.rs`), the experiments' materials (`fig10.rs`).

mod ends;
mod fig10;
mod fig8_9;

pub use fig8_9::run_8_9;
pub use fig10::run_10;

use crate::PaperError;
use impact_chain::{ChainConfig, simulate};
use impact_model::{Bilayer, Outcome, Rod};

const ALPHA: f64 = 0.005;

/// The bilayer at `x`, `alpha = 0.005`, with layer restitutions `(e1, e2)`.
fn rod(x: f64, e1: f64, e2: f64) -> Result<Rod, PaperError> {
    let mut scene = Bilayer { x, alpha: ALPHA }.scene();
    scene.layers[0].restitution = (e1 < 1.0).then_some(e1);
    scene.layers[1].restitution = (e2 < 1.0).then_some(e2);
    Ok(scene.validate()?)
}

/// The chain at `x` with layer restitutions `(e1, e2)`.
pub fn point(x: f64, e1: f64, e2: f64, masses: usize) -> Result<Outcome, PaperError> {
    let rod = rod(x, e1, e2)?;
    let config = ChainConfig {
        masses,
        ..ChainConfig::default()
    };
    Ok(simulate(&rod, &config)?)
}
