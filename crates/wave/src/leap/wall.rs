//! The wall through a leap of the bottom layer: when the next contact
//! decision (a tensile strain, a landing) could come, in closed form, and
//! the wall's strain, impulse and height after the leap.

use super::Phase;
use super::crossing::{count_before, first_crossing, first_nonpositive};
use crate::engine::{NEAR_GRAZING, Tracer};
use crate::lane::{Direction, Lane};
use crate::queue::EventKey;
use crate::real::Real;
use crate::wall::ContactState;

impl<R: Real> Tracer<R> {
    /// How close to tensile a contact strain may come inside a leap: an
    /// exact run's loop takes the near-grazing decisions.
    pub(super) fn leap_threshold(&self) -> R {
        if self.merged {
            self.grazing_strain
        } else {
            let scale = self.impact_speed / self.layers[0].wave_speed;
            self.grazing_strain.max(R::of(NEAR_GRAZING) * scale)
        }
    }

    /// Whether the wall decides something now, or lands the bottom within
    /// `least`, seen without the phases: then a leap of the bottom layer
    /// cannot start, and trying costs a pass over its fronts. In a
    /// chatter (a stiff base under a soft top, contacts of two round
    /// trips) every separation was such a try, and the pause after a
    /// failed try (`leap_retry`) then kept the loop from leaping the next
    /// contact for a round trip. In contact it is true exactly where
    /// [`Tracer::wall_stop`]'s first return would stop the leap at once;
    /// in flight it also answers true for a bottom turned down so near the
    /// wall that it lands within `least`, a bound, not the closed form. A
    /// wrong answer either way costs speed only: a try that fails, or a
    /// leap left to the loop, which takes the same events one by one.
    pub(super) fn wall_decides_now(&mut self, t: R, least: R) -> bool {
        let two = R::of(2.0);
        // the jump reaching the wall now, if a front does
        let down = &self.lanes[Lane::<R>::index(0, Direction::Down)];
        let arriving = match down.head_arrival() {
            Some(at) if at == t => down.fronts().next().map(|f| down.delivered(f.jump)),
            _ => None,
        };
        match self.contact {
            ContactState::InContact { strain } => {
                arriving.is_some_and(|jump| strain + two * jump >= -self.leap_threshold())
            }
            ContactState::Free {
                height,
                velocity,
                at,
            } => {
                if let Some(land) = self.queue.time_of(EventKey::Reconnection)
                    && land - t < least
                {
                    self.leap_after[0] = land;
                    return true;
                }
                // a front turning the bottom down so near the wall that it
                // lands within `least`
                let Some(jump) = arriving else {
                    return false;
                };
                let c0 = self.layers[0].wave_speed;
                let v = velocity + two * c0 * jump;
                height + velocity * (t - at) + v * least <= R::zero()
            }
        }
    }

    /// The earliest time the wall could decide something: in contact, the
    /// first return making the wall strain grazing or tensile; in flight,
    /// the earliest the bottom could come down, from its lowest velocity.
    /// `slack` is what the arrivals the leap takes in could add at most
    /// (`Tracer::arrivals_slack`): to the strain in contact, to the fall of
    /// the height in flight. The phases are the layer's own fronts, sorted,
    /// within a round trip of now (none only when the leap takes arrivals).
    pub(super) fn wall_stop(
        &self,
        phases: &[Phase<R>],
        q: R,
        period: R,
        horizon: R,
        slack: R,
    ) -> R {
        let two = R::of(2.0);
        let one = R::one();
        let total: R = phases.iter().fold(R::zero(), |s, p| s + p.amp);
        match self.contact {
            ContactState::InContact { strain } => {
                // S(p, k) = S0 + 2 (G sum_{j<k} q^j + L_p q^k) = C0 + C_p q^k
                let limit = total / (one - q);
                let c0 = strain + two * limit;
                let mut prefix = R::zero();
                let mut stop = horizon;
                let threshold = self.leap_threshold() + slack;
                if slack > R::zero() && strain >= -threshold {
                    return self.now;
                }
                // The first two returns of every phase by hand, as
                // `first_crossing` evaluates them (`C0 + C_p q^k`): in a
                // chatter the next decision comes within them, and a try
                // that fails there then costs no logarithm (an exact run's
                // ringing layer holds thousands of phases, and a try
                // follows every decision). The phases lie within one
                // period, so an earlier round holds the earlier crossing.
                for (k, qk) in [(0u64, one), (1, q)] {
                    let mut first = None;
                    let mut prefix = R::zero();
                    for p in phases {
                        prefix += p.amp;
                        if c0 + two * (prefix - limit) * qk >= -threshold
                            && count_before(p.tau, period, horizon) > k
                        {
                            let at = p.tau + R::of(k as f64) * period;
                            first = Some(first.map_or(at, |f: R| f.min(at)));
                        }
                    }
                    if let Some(at) = first {
                        return stop.min(at);
                    }
                }
                for p in phases {
                    prefix += p.amp;
                    let kmax = count_before(p.tau, period, horizon);
                    if let Some(k) = first_crossing(c0, two * (prefix - limit), q, kmax, -threshold)
                    {
                        stop = stop.min(p.tau + R::of(k as f64) * period);
                    }
                }
                stop
            }
            ContactState::Free {
                height,
                velocity,
                at,
            } => {
                // the height just before the k-th return of p is
                // f0_p + beta k + gamma_p (q^k - 1): its first zero is where
                // the bottom has landed (DESIGN: the loop then lands it)
                let c0 = self.layers[0].wave_speed;
                let height = height - slack;
                if slack > R::zero() && height <= R::zero() {
                    return self.now;
                }
                if phases.is_empty() {
                    // falling at a constant velocity until the horizon
                    let fall = -velocity * (horizon - at);
                    return match fall >= height {
                        true => at + height / -velocity,
                        false => horizon,
                    };
                }
                let gap = one - q;
                let moment: R = phases.iter().fold(R::zero(), |s, p| s + p.amp * p.tau);
                let beta = period * (velocity + two * c0 * total / gap);
                let mut stop = horizon;
                let mut prefix = R::zero();
                let mut before = R::zero(); // sum_{p' < p} a_p' (tau_p - tau_p') as it grows
                let mut last_tau = phases[0].tau;
                // (tau_p, f0_p, gamma_p)
                let mut heights = Vec::with_capacity(phases.len());
                for p in phases {
                    before += prefix * (p.tau - last_tau);
                    last_tau = p.tau;
                    let f0 = height + velocity * (p.tau - at) + two * c0 * before;
                    let m = total * p.tau - moment;
                    let gamma = two * c0 * (before - m / gap + period * total * q / (gap * gap));
                    heights.push((p.tau, f0, gamma));
                    prefix += p.amp;
                }
                // the first two returns by hand, as `first_nonpositive`
                // evaluates them (see the contact's case above)
                let ln_q = (q >= R::zero()).then(|| q.ln());
                for k in 0..2u64 {
                    let mut first = None;
                    for &(tau, f0, gamma) in &heights {
                        let f = match (k, ln_q) {
                            (0, _) => f0,
                            (_, Some(ln_q)) => f0 + beta * one + gamma * (ln_q * one).exp_m1(),
                            (_, None) => f0 + beta + gamma * (q - one),
                        };
                        if f <= R::zero() && count_before(tau, period, horizon) > k {
                            let at = tau + R::of(k as f64) * period;
                            first = Some(first.map_or(at, |f: R| f.min(at)));
                        }
                    }
                    if let Some(at) = first {
                        return stop.min(at);
                    }
                }
                for (tau, f0, gamma) in heights {
                    let kmax = count_before(tau, period, stop);
                    if kmax > 0
                        && let Some(k) = first_nonpositive(f0, beta, gamma, q, kmax)
                    {
                        stop = stop.min(tau + R::of(k as f64) * period);
                    }
                }
                stop
            }
        }
    }

    /// The wall after the bottom arrivals `(tau, a, n)`: `a q^k` at
    /// `tau + k P`, `k < n`, in contact or in flight throughout.
    pub(super) fn wall_after(&mut self, arrivals: &[(R, R, u64)], q: R, period: R) {
        if arrivals.is_empty() {
            return;
        }
        let two = R::of(2.0);
        let half = R::of(0.5);
        let t0 = self.ledger.at;
        let end = arrivals.iter().fold(t0, |m, &(tau, _, n)| {
            m.max(tau + R::of((n - 1) as f64) * period)
        });
        // sum A, sum A (T - t), sum A (T - t)^2 over the arrivals
        let (mut a0, mut a1, mut a2) = (R::zero(), R::zero(), R::zero());
        for &(tau, a, n) in arrivals {
            let (s0, s1, s2) = self.sums_cached(q, n);
            let d = end - tau;
            a0 += a * s0;
            a1 += a * (d * s0 - period * s1);
            a2 += a * (d * d * s0 - two * d * period * s1 + period * period * s2);
        }
        let dt = end - t0;
        let c0 = self.layers[0].wave_speed;
        let impulse = self.ledger.impulse;
        match &mut self.contact {
            ContactState::InContact { strain } => {
                self.ledger.moment += impulse * dt + half * *strain * dt * dt + a2;
                self.ledger.impulse += *strain * dt + two * a1;
                *strain += two * a0;
            }
            ContactState::Free {
                height,
                velocity,
                at,
            } => {
                self.ledger.moment += impulse * dt;
                *height += *velocity * (end - *at) + two * c0 * a1;
                *velocity += two * c0 * a0;
                *at = end;
            }
        }
        self.ledger.at = end;
        let count: u64 = arrivals.iter().map(|a| a.2).sum();
        self.note_decisions(count);
        self.record_wall();
    }
}

#[cfg(test)]
mod tests {

    /// The height just before each return, by brute force, against the
    /// closed form used to find the landing.
    #[test]
    fn the_height_closed_form_matches_a_brute_force_flight() {
        let (height, velocity, at) = (0.3, -0.05, 0.0);
        let c0 = 1.7;
        let period = 0.2;
        let q: f64 = 0.93;
        let phases = [(0.01, 0.02), (0.05, -0.01), (0.12, 0.005), (0.17, -0.03)];
        let total: f64 = phases.iter().map(|p| p.1).sum();
        let moment: f64 = phases.iter().map(|p| p.1 * p.0).sum();
        let gap = 1.0 - q;
        let beta = period * (velocity + 2.0 * c0 * total / gap);
        // brute force: arrivals in time order
        let mut arrivals = vec![];
        for k in 0..40u64 {
            for &(tau, a) in &phases {
                arrivals.push((tau + k as f64 * period, a * q.powi(k as i32), k));
            }
        }
        arrivals.sort_by(|x, y| x.0.total_cmp(&y.0));
        let (mut z, mut v, mut t) = (height, velocity, at);
        let mut prefix = 0.0;
        let mut before = 0.0;
        let mut last_tau = phases[0].0;
        let mut expected = vec![];
        for (i, &(tau, a)) in phases.iter().enumerate() {
            before += prefix * (tau - last_tau);
            last_tau = tau;
            let f0 = height + velocity * (tau - at) + 2.0 * c0 * before;
            let m = total * tau - moment;
            let gamma = 2.0 * c0 * (before - m / gap + period * total * q / (gap * gap));
            expected.push((i, f0, gamma));
            prefix += a;
        }
        for (time, amp, k) in arrivals {
            z += v * (time - t);
            t = time;
            let p = phases
                .iter()
                .position(|ph| (ph.0 + k as f64 * period - time).abs() < 1e-12)
                .unwrap();
            let (_, f0, gamma) = expected[p];
            let closed = f0 + beta * k as f64 + gamma * (q.powi(k as i32) - 1.0);
            assert!(
                (closed - z).abs() < 1e-9,
                "p = {p}, k = {k}: {closed} vs {z}"
            );
            v += 2.0 * c0 * amp;
        }
    }
}
