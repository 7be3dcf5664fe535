//! Where a leap's fronts go: the trains it sends into the neighbours,
//! deposited on their lattices in a merged run; in an exact one left to
//! wait in the lane as trains (`lane::Trains`), or, where that cannot be
//! foreseen, spawned front by front in birth order.

use super::Train;
use super::crossing::{count_before_near, pow};
use super::exact::Placed;
use crate::engine::Tracer;
use crate::error::WaveError;
use crate::geometric::sums;
use crate::lane::{Direction, Lane, MergeRule, Ring, Trains, foresee, sum_on_points};
use crate::real::Real;
use crate::runs::sort_stably;
use crate::window::Window;

/// Fronts going into one exact lane at the end of a leap, as
/// [`Tracer::spawn_front`] would take them: what it drops and the merges
/// it notes are kept for the tracer's ledgers.
struct Spawning<'a, R> {
    lane: &'a mut Lane<R>,
    window: Window<R>,
    thr: R,
    id: u32,
    /// The jumps added (the layer's base moves by them).
    total: R,
    dropped: Vec<(R, R)>,
    /// Merges of births more than zero apart: `(gap, born)`.
    merges: Vec<(R, R)>,
}

impl<R: Real> Spawning<'_, R> {
    #[inline(always)]
    fn put(&mut self, born: R, jump: R) {
        if jump.abs() < self.thr {
            if jump != R::zero() {
                self.dropped.push((born, jump));
            }
            return;
        }
        self.total += jump;
        match self.lane.push_exact(born, jump, self.id, self.window) {
            None => self.id += 1,
            Some((gap, _)) => {
                if gap > R::zero() {
                    self.merges.push((gap, born));
                }
            }
        }
    }

    /// Leaves the ringing trains waiting in the lane as trains
    /// (`lane::Trains`), where what [`Spawning::put`] would do with their
    /// fronts is foreseen (`lane::foresee`): none dropped, the merges among
    /// them noted as `put` notes them. False, and nothing changed,
    /// otherwise. Their jumps are added to the layer's base in closed form
    /// (a sum of geometric series, not front by front: the base, which
    /// only the fields read, moves by the rounding of that sum).
    fn keep_waiting(&mut self, rings: &[Placed<R>]) -> bool {
        // (the short trains' test below, before foreseeing: the lane can
        // hold no more fronts than the trains give, and a leap over a
        // chatter's contact gives one or two a train)
        let given: u64 = rings.iter().map(|t| t.1.count).sum();
        if given < SPAWNED_BELOW * rings.len() as u64 {
            return false;
        }
        let rings: Vec<Ring<R>> = rings
            .iter()
            .map(|&(_, t)| Ring {
                start: t.start,
                period: t.period,
                q: t.q,
                count: t.count,
                jump: t.c,
            })
            .collect();
        let Some(mut given) = foresee(&rings, self.window, self.thr, self.lane.newest_born())
        else {
            return false;
        };
        // short trains are spawned: they save little, and cost memory (a
        // steel base under rubber sends 123 leaps' trains of 5 to 60
        // fronts each: kept waiting, they took the run's peak from 13.9 to
        // 14.9 MiB; from 64 fronts a train on, its peak is unchanged)
        if given.held < SPAWNED_BELOW * rings.len() as u64 {
            return false;
        }
        for r in &rings {
            self.total += r.jump * sums(r.q, r.count).0;
        }
        self.merges.append(&mut given.gaps);
        let held = given.held;
        self.lane
            .add_trains(Trains::new(rings, self.window, given, self.id));
        // (ids mean something only when fronts are recorded, and then no
        // layer leaps)
        self.id = self.id.wrapping_add(held as u32);
        true
    }
}

/// Trains that give fewer fronts than this many a train are spawned.
const SPAWNED_BELOW: u64 = 64;

/// The births of ringing trains round by round: round `k` of every train
/// (sorted by start), then round `k + 1`; jumps by one product a round.
/// Stops when `put` says no.
fn rounds<R: Real>(rings: &[Placed<R>], mut put: impl FnMut(R, R) -> bool) {
    let count = rings.iter().map(|t| t.1.count).max().unwrap_or(0);
    let mut jumps: Vec<R> = rings.iter().map(|t| t.1.c).collect();
    for k in 0..count {
        let kk = R::of(k as f64);
        for ((_, t), jump) in rings.iter().zip(jumps.iter_mut()) {
            if k < t.count {
                if !put(t.start + kk * t.period, *jump) {
                    return;
                }
                *jump = *jump * t.q;
            }
        }
    }
}

/// Whether [`rounds`] gives the births in order: rings (sorted, one
/// period) whose starts lie within a period by more than rounding, so that
/// the rounded births of round `k` stay before those of round `k + 1`.
fn rounds_in_order<R: Real>(rings: &[Placed<R>]) -> bool {
    let (Some(first), Some(last)) = (rings.first(), rings.last()) else {
        return true;
    };
    let period = first.1.period;
    let end = rings
        .iter()
        .map(|t| t.1.start + R::of(t.1.count as f64) * period)
        .fold(R::zero(), |m, x| if x > m { x } else { m });
    let rounding = R::of(8.0 * f64::EPSILON) * (end.abs() + period);
    rings.iter().all(|t| t.1.period == period) && last.1.start - first.1.start + rounding < period
}

/// Whether every single (sorted) is born before the first ring starts.
fn singles_first<R: Real>(singles: &[Placed<R>], rings: &[Placed<R>]) -> bool {
    singles
        .last()
        .zip(rings.first())
        .is_none_or(|(s, r)| s.1.start <= r.1.start)
}

impl<R: Real> Tracer<R> {
    /// Deposits a train of fronts into `lane` as its merge rule would, one
    /// by one: the large ones kept (while the lane keeps any), the rest on
    /// its lattice with their jump and first moment, the tail under the
    /// drop threshold dropped and accounted for. Inlined: an exact leap
    /// emits two trains a phase, and the call was a tenth of the 20
    /// hardest points' work (callgrind).
    #[inline(always)]
    pub(super) fn emit(&mut self, lane: usize, train: Train<R>) -> Result<(), WaveError> {
        if train.count == 0 || train.c == R::zero() {
            return Ok(());
        }
        let layer = self.lanes[lane].layer;
        let thr = self.layers[layer].drop_strain();
        // alive while above the drop threshold
        let alive = if train.q == R::zero() {
            u64::from(train.c.abs() >= thr).min(train.count)
        } else {
            self.life_within(train.c, train.q, thr, 0, train.count)
        };
        if alive < train.count {
            self.drop_tail(layer, train, alive);
        }
        let train = Train {
            count: alive,
            ..train
        };
        match self.lanes[lane].rule {
            MergeRule::Simultaneous { .. } => {
                self.exact_trains.push(lane, train);
                Ok(())
            }
            MergeRule::Lattice {
                spacing,
                keep_above,
                keep_at_most,
            } => self.emit_on_lattice(lane, train, (spacing, keep_above, keep_at_most)),
        }
    }

    /// [`Tracer::emit`] into a lattice lane of `(spacing, keep_above,
    /// keep_at_most)` ([`MergeRule::Lattice`]), the train's living fronts
    /// (the tail already dropped).
    fn emit_on_lattice(
        &mut self,
        lane: usize,
        train: Train<R>,
        (spacing, keep_above, keep_at_most): (R, R, usize),
    ) -> Result<(), WaveError> {
        let alive = train.count;
        let layer = self.lanes[lane].layer;
        let mut deposits = std::mem::take(&mut self.deposits);
        let dir = self.lanes[lane].direction;
        let born = |k: u64| train.start + R::of(k as f64) * train.period;
        let amp = |k: u64| train.c * pow(train.q, k);
        let mut k = 0;
        while k < alive && amp(k).abs() >= keep_above && self.lanes[lane].kept < keep_at_most {
            self.spawn_front(layer, dir, born(k), amp(k))?;
            k += 1;
        }
        let mut total = R::zero();
        let mut merged = 0u64;
        // full cells hold one or two counts of fronts: their sums repeat;
        // the amplitude at a cell's first front follows by q^len
        let mut first = amp(k);
        let mut len = 0;
        while k < alive {
            // the fronts born in one lattice cell [j w, (j + 1) w)
            let j = (born(k) / spacing).floor();
            let (lo, hi) = (j * spacing, (j + R::one()) * spacing);
            // (a cell's count is the one before's, or one more or less)
            let end = (k + count_before_near(born(k), train.period, hi, len))
                .min(alive)
                .max(k + 1);
            len = end - k;
            self.leap_work += 1;
            let (s0, s1, _) = self.sums_cached(train.q, len);
            let step = self.sums_cached(train.q, len + 1).0 - s0; // q^len
            let jump = first * s0;
            let moment = first * (born(k) * s0 + train.period * s1);
            let at_hi = (moment - jump * lo) / spacing;
            for (at, d) in [(lo, jump - at_hi), (hi, at_hi)] {
                if d != R::zero() {
                    deposits.push((lane, at, d));
                }
            }
            total += jump;
            merged += len;
            k = end;
            first = first * step;
        }
        match dir {
            Direction::Up => self.up_base[layer] += total,
            Direction::Down => self.down_base[layer] += total,
        }
        self.drops.truncation.merged_fronts += merged;
        self.deposits = deposits;
        Ok(())
    }

    /// The tail of `train` from front `alive` on, under the drop threshold
    /// of `layer`: dropped as the loop would drop it one by one, counted,
    /// and its force accounted in closed form.
    #[cold]
    fn drop_tail(&mut self, layer: usize, train: Train<R>, alive: u64) {
        let tail = train.count - alive;
        let aq = train.q.abs();
        let first = (train.c * pow(train.q, alive)).abs();
        let born = train.start + R::of(alive as f64) * train.period;
        let (s0, s1, _) = sums(aq, tail);
        let l = self.layers[layer];
        let d = &mut self.drops;
        d.truncation.dropped_fronts += tail;
        d.truncation.dropped_velocity += (first * s0 * l.wave_speed / self.impact_speed).to_f64();
        let force = (l.modulus * first * s0).to_f64();
        d.dropped_force += force;
        d.dropped_force_time += (l.modulus * first * (born * s0 + train.period * s1)).to_f64();
    }

    /// Places the deposits gathered by `emit` into their lanes, one pass a
    /// lane, and puts the lanes' heads in the queue.
    pub(super) fn place_deposits(&mut self) -> Result<(), WaveError> {
        let all = std::mem::take(&mut self.deposits);
        // lane by lane in increasing order, each lane's deposits in the
        // order they were gathered (a leap feeds two lanes at most)
        let mut lanes: Vec<usize> = Vec::with_capacity(2);
        for &(lane, _, _) in &all {
            if !lanes.contains(&lane) {
                lanes.push(lane);
            }
        }
        lanes.sort_unstable();
        let mut batch = std::mem::take(&mut self.batch);
        for lane in lanes {
            batch.clear();
            batch.extend(all.iter().filter(|d| d.0 == lane).map(|d| (d.1, d.2)));
            if let MergeRule::Lattice { spacing, .. } = self.lanes[lane].rule {
                sum_on_points(&mut batch, spacing, &mut self.point_sums);
            }
            self.lanes[lane].place_all(&mut batch, &mut self.spare_fronts);
            self.reschedule_layer(self.lanes[lane].layer)?;
        }
        self.deposits = all;
        self.deposits.clear();
        self.batch = batch;
        Ok(())
    }

    /// Spawns the fronts of the trains an exact leap sent into its
    /// neighbours, lane by lane in birth order, as [`Tracer::spawn_front`]
    /// would one by one (under the drop threshold dropped, born together
    /// merged): the single fronts (from fronts that were going up as the
    /// leap began) and the ringing trains round by round, merged. Rounds
    /// come in birth order when the trains' starts lie within one period,
    /// as a leap's do; otherwise (rounding at the edge) the births are
    /// sorted first. Where every single comes before the trains, the
    /// ringing trains are left to wait as trains if what spawning them
    /// would do is foreseen ([`Spawning::keep_waiting`]).
    pub(super) fn place_exact_trains(&mut self) -> Result<(), WaveError> {
        if self.exact_trains.is_empty() {
            return Ok(());
        }
        let mut gathered = std::mem::take(&mut self.exact_trains);
        for k in 0..gathered.by_lane() {
            let (lane, singles, rings) = gathered.in_order(k);
            let births = singles.len() as u64 + rings.iter().map(|t| t.1.count).sum::<u64>();
            self.leap_work += births;
            let layer = self.lanes[lane].layer;
            let MergeRule::Simultaneous { window } = self.lanes[lane].rule else {
                unreachable!("a merged run's leaps deposit on lattices")
            };
            let mut into = Spawning {
                lane: &mut self.lanes[lane],
                window,
                thr: self.layers[layer].drop_strain,
                id: self.next_id,
                total: R::zero(),
                dropped: Vec::new(),
                merges: Vec::new(),
            };
            if !rounds_in_order(rings) {
                // (rounding at the edge: births sorted, singles first on ties)
                into.lane.reserve(births as usize);
                let mut all: Vec<(R, R)> = Vec::with_capacity(births as usize);
                all.extend(singles.iter().map(|t| (t.1.start, t.1.c)));
                rounds(rings, |born, jump| {
                    all.push((born, jump));
                    true
                });
                // (singles, then each round: a few sorted runs)
                sort_stably(&mut all, &mut Vec::new(), |b| b.0);
                for (born, jump) in all {
                    into.put(born, jump);
                }
            } else if singles_first(singles, rings) {
                for t in singles {
                    into.put(t.1.start, t.1.c);
                }
                if !into.keep_waiting(rings) {
                    into.lane.reserve(births as usize);
                    rounds(rings, |born, jump| {
                        into.put(born, jump);
                        true
                    });
                }
            } else {
                // a chatter's contact: fronts that were going up as it
                // began still arrive while its trains ring; two sorted
                // streams merged, singles first on ties (what a stable sort
                // of singles then rounds gives)
                into.lane.reserve(births as usize);
                let mut singles = singles.iter().peekable();
                rounds(rings, |born, jump| {
                    while let Some(t) = singles.next_if(|t| t.1.start <= born) {
                        into.put(t.1.start, t.1.c);
                    }
                    into.put(born, jump);
                    true
                });
                for t in singles {
                    into.put(t.1.start, t.1.c);
                }
            }
            let Spawning {
                id,
                total,
                dropped,
                merges,
                ..
            } = into;
            self.next_id = id;
            match self.lanes[lane].direction {
                Direction::Up => self.up_base[layer] += total,
                Direction::Down => self.down_base[layer] += total,
            }
            for (born, jump) in dropped {
                self.drop_front(layer, born, jump);
            }
            for (gap, at) in merges {
                self.note_combined(gap, at);
            }
            self.reschedule_layer(layer)?;
        }
        gathered.clear();
        self.exact_trains = gathered;
        Ok(())
    }
}
