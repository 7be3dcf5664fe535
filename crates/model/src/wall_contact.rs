//! The wall's contact law: a model choice, named in every output.
//!
//! The paper (Sec. III) adds the bottom element's force
//! `-F_{1,0} = -(k (y_1 - l_0) + k' y_1')` to the bottom mass "in case of
//! contact with the wall (`y_1 < l_0`)": while the bottom spring is
//! compressed its spring *and* its dashpot act, so a viscous bottom may be
//! pulled back by the wall as it springs off, and the rod separates when
//! the bottom strain returns to zero (the paper's Eqs. 5-6 assume the
//! same). The alternative, a wall that only pushes, is a defensible
//! contact law too, but a different model: at `tau c / L = 1` a
//! homogeneous rod rebounds with `e = 0.15` under it and `0.01` under the
//! paper's. For elastic rods (no dashpots) the two laws are the same.

use serde::{Deserialize, Serialize};
use std::fmt;

/// How the wall acts on a viscous bottom element: the paper's law or a wall
/// that only pushes. A property of the scene, part of the model.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum WallContact {
    /// The paper's law: spring and dashpot of the bottom element act while
    /// it is compressed; the wall may pull through the dashpot.
    #[default]
    Paper,
    /// The wall only pushes: when spring plus dashpot would pull, the wall
    /// gives no force.
    Unilateral,
}

impl WallContact {
    /// Both laws, the paper's first.
    pub const ALL: [WallContact; 2] = [WallContact::Paper, WallContact::Unilateral];

    /// The name used in scenes, flags and outputs.
    pub fn name(self) -> &'static str {
        match self {
            WallContact::Paper => "paper",
            WallContact::Unilateral => "unilateral",
        }
    }

    /// In words, for reports.
    pub fn describe(self) -> &'static str {
        match self {
            WallContact::Paper => {
                "paper (Sec. III: the bottom element's spring and dashpot act while it is compressed; the wall may pull)"
            }
            WallContact::Unilateral => "unilateral (the wall only pushes)",
        }
    }
}

impl fmt::Display for WallContact {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for WallContact {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "paper" => Ok(WallContact::Paper),
            "unilateral" => Ok(WallContact::Unilateral),
            other => Err(format!(
                "wall contact must be 'paper' or 'unilateral' (got '{other}')"
            )),
        }
    }
}
