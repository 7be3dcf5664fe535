//! The unilateral wall: contact, separation and reconnection as pure rules.
//!
//! The wall can push, never pull. In contact the bottom is at rest; free, the
//! bottom's strain is zero and it moves with velocity `v0` at height `z0`.
//! All rules take strain jumps of fronts in the bottom layer, wave speed `c0`
//! (DESIGN.md §2).

use crate::real::Real;

/// State of the rod's bottom.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactState<R = f64> {
    /// Touching the wall with wall strain `strain` (<= 0: compression).
    InContact {
        /// Wall strain `eps0` (<= 0: compression).
        strain: R,
    },
    /// Free: the bottom is at `height` above the wall at time `at`, moving with
    /// `velocity` (positive upward).
    Free {
        /// Height of the bottom above the wall at time `at`.
        height: R,
        /// Velocity of the bottom (positive upward), constant while no front reaches it.
        velocity: R,
        /// Time at which `height` holds.
        at: R,
    },
}

impl<R: Real> ContactState<R> {
    /// The same state in double precision (and scaled by `strain`,
    /// `displacement`, `speed` and `time` units).
    pub fn to_f64(
        self,
        strain_unit: f64,
        displacement: f64,
        speed: f64,
        time: f64,
    ) -> ContactState {
        match self {
            ContactState::InContact { strain } => ContactState::InContact {
                strain: strain.to_f64() * strain_unit,
            },
            ContactState::Free {
                height,
                velocity,
                at,
            } => ContactState::Free {
                height: height.to_f64() * displacement,
                velocity: velocity.to_f64() * speed,
                at: at.to_f64() * time,
            },
        }
    }
}

/// Result of a front group of total jump `d` reaching the wall.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallReflection<R = f64> {
    /// Jump of the reflected (up-going) front.
    pub reflected: R,
    /// New state of the bottom.
    pub state: ContactState<R>,
    /// True when the rod left the wall at this event.
    pub separated: bool,
}

/// A down-going group of total strain jump `d` reaches the bottom at time `t`.
///
/// In contact the rigid reflection `d -> d` would give the wall strain
/// `strain + 2d`; if that is tensile (beyond `grazing`, a strain), the rod
/// separates instead: the reflected front restores zero strain at the bottom,
/// `-strain - d`, and the bottom leaves at `c0 (strain + 2d) > 0`. Within
/// `grazing` of zero the rod stays at the wall with zero force. Free, the
/// bottom reflects `d -> -d` and its velocity changes by `2 c0 d`.
pub fn reflect<R: Real>(
    state: ContactState<R>,
    d: R,
    c0: R,
    t: R,
    grazing: R,
) -> WallReflection<R> {
    let zero = R::zero();
    let two = R::of(2.0);
    match state {
        ContactState::InContact { strain } => {
            let rigid = strain + two * d;
            if rigid > grazing {
                WallReflection {
                    reflected: -strain - d,
                    state: ContactState::Free {
                        height: zero,
                        velocity: c0 * rigid,
                        at: t,
                    },
                    separated: true,
                }
            } else if rigid >= -grazing {
                WallReflection {
                    reflected: -strain - d,
                    state: ContactState::InContact { strain: zero },
                    separated: false,
                }
            } else {
                WallReflection {
                    reflected: d,
                    state: ContactState::InContact { strain: rigid },
                    separated: false,
                }
            }
        }
        ContactState::Free {
            height, velocity, ..
        } => WallReflection {
            reflected: -d,
            state: ContactState::Free {
                height,
                velocity: velocity + two * c0 * d,
                at: t,
            },
            separated: false,
        },
    }
}

/// The free bottom reaches the wall moving down at `velocity < 0`: the wall
/// stops it, launching an up-going compression front `velocity / c0`, which is
/// also the new wall strain.
pub fn reconnect<R: Real>(velocity: R, c0: R) -> (R, ContactState<R>) {
    let jump = velocity / c0;
    (jump, ContactState::InContact { strain: jump })
}

/// When a free bottom at `height`, moving at `velocity`, reaches the wall.
pub fn landing_time<R: Real>(height: R, velocity: R, at: R) -> Option<R> {
    (velocity < R::zero()).then(|| at + height.max(R::zero()) / -velocity)
}

#[cfg(test)]
mod tests {
    use super::*;

    const C: f64 = 2.0;

    #[test]
    fn compression_is_reflected_rigidly() {
        let r = reflect(
            ContactState::InContact { strain: -1.0 },
            -0.5,
            C,
            1.0,
            1e-12,
        );
        assert_eq!(r.reflected, -0.5);
        assert_eq!(r.state, ContactState::InContact { strain: -2.0 });
        assert!(!r.separated);
    }

    #[test]
    fn tension_separates_with_zero_bottom_strain() {
        // homogeneous rod: -v_b/c unloaded by +v_b/c leaves at v_b
        let r = reflect(ContactState::InContact { strain: -0.5 }, 0.5, C, 3.0, 1e-12);
        assert!(r.separated);
        assert_eq!(r.reflected, 0.0);
        assert_eq!(
            r.state,
            ContactState::Free {
                height: 0.0,
                velocity: 1.0,
                at: 3.0
            }
        );
        // bottom strain after: before + incoming + reflected = 0
        assert_eq!(-0.5 + 0.5 + r.reflected, 0.0);
    }

    #[test]
    fn grazing_keeps_contact_at_zero_force() {
        let r = reflect(
            ContactState::InContact { strain: -1.0 },
            0.5 + 1e-15,
            C,
            1.0,
            1e-12,
        );
        assert!(!r.separated);
        assert_eq!(r.state, ContactState::InContact { strain: 0.0 });
    }

    #[test]
    fn free_end_flips_and_accelerates() {
        let free = ContactState::Free {
            height: 0.1,
            velocity: 0.3,
            at: 0.0,
        };
        let r = reflect(free, -0.25, C, 1.0, 1e-12);
        assert_eq!(r.reflected, 0.25);
        assert_eq!(
            r.state,
            ContactState::Free {
                height: 0.1,
                velocity: -0.7,
                at: 1.0
            }
        );
    }

    /// Two fronts arriving together give the same final state whether combined
    /// or taken one after the other with an instant reconnection: the wall rule
    /// is associative, so only the separation count depends on combining.
    #[test]
    fn combined_and_sequential_agree_on_the_state() {
        let start = ContactState::InContact { strain: -1.0 };
        let (d1, d2) = (0.8, -0.7);
        let combined = reflect(start, d1 + d2, C, 1.0, 1e-12);
        let first = reflect(start, d1, C, 1.0, 1e-12);
        assert!(first.separated);
        let second = reflect(first.state, d2, C, 1.0, 1e-12);
        let ContactState::Free { velocity, .. } = second.state else {
            panic!("free")
        };
        let (jump, state) = reconnect(velocity, C);
        assert!((first.reflected + second.reflected + jump - combined.reflected).abs() < 1e-15);
        let (ContactState::InContact { strain: a }, ContactState::InContact { strain: b }) =
            (state, combined.state)
        else {
            panic!("contact")
        };
        assert!((a - b).abs() < 1e-15);
    }

    #[test]
    fn landing() {
        assert_eq!(landing_time(0.5, -0.25, 1.0), Some(3.0));
        assert_eq!(landing_time(0.5, 0.25, 1.0), None);
        assert_eq!(landing_time(-1e-18, -1.0, 2.0), Some(2.0));
    }
}
