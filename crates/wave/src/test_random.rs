//! Seeded pseudo-random numbers for the unit tests (xorshift64): the same
//! draws on every machine, no dependency.

/// Marsaglia's xorshift64 from `seed` (not zero): each call the next draw.
pub(crate) fn xorshift(mut state: u64) -> impl FnMut() -> u64 {
    assert_ne!(state, 0, "xorshift needs a seed other than zero");
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    }
}
