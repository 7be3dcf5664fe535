//! A result beside the wall time its runner measured. Engines return
//! outcomes that depend on the scene and the settings alone; whoever runs
//! them (a sweep, a report, the command line) times the call and keeps the
//! time here, next to the value, never inside it.

use serde::{Deserialize, Serialize};
use std::time::Instant;

/// `value` and the seconds its computation took. Serialised as the value's
/// own fields followed by `elapsed_seconds`, so a timed outcome reads as an
/// outcome with one more key. Dereferences to the value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Timed<T> {
    /// The value computed, its keys written first.
    #[serde(flatten)]
    pub value: T,
    /// Wall-clock seconds (0 when the runner was asked not to time, so
    /// that identical runs write identical files).
    #[serde(rename = "elapsed_seconds")]
    pub seconds: f64,
}

impl<T> Timed<T> {
    /// Runs `f` and times it.
    pub fn measure(f: impl FnOnce() -> T) -> Self {
        let start = Instant::now();
        let value = f();
        Timed {
            value,
            seconds: start.elapsed().as_secs_f64(),
        }
    }

    /// Runs a fallible `f` and times it when it succeeds.
    pub fn try_measure<E>(f: impl FnOnce() -> Result<T, E>) -> Result<Self, E> {
        let Timed { value, seconds } = Timed::measure(f);
        value.map(|value| Timed { value, seconds })
    }

    /// The same value with no time (seconds 0), for deterministic output.
    pub fn untimed(self) -> Self {
        Timed {
            seconds: 0.0,
            ..self
        }
    }
}

impl<T> std::ops::Deref for Timed<T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.value
    }
}
