//! Room kept from one run to the next on a thread. A sweep runs thousands
//! of points one after another, each with a fresh [`Tracer`]: growing the
//! same lanes and leap buffers from nothing at every point (about seventy
//! reallocations and their copies a point) was 7 % of the 20 hardest
//! points' instructions. A tracer takes the room its thread kept when it is
//! built and gives it back, emptied, when it is dropped. Only capacity
//! passes from one run to the next, never content, so a run's results do
//! not depend on what ran before it on the thread. Room beyond
//! [`KEPT_AT_MOST`] bytes is freed, not kept: one huge run does not pin
//! its memory for the rest of a sweep.

use crate::engine::Tracer;
use crate::lane::{Front, Lane};
use crate::leap::{ExactTrains, LeapScratch, TogetherRoom};
use crate::real::Real;
use std::any::Any;
use std::cell::RefCell;

/// The most room a thread keeps between runs, in bytes.
pub(crate) const KEPT_AT_MOST: usize = 8 << 20;

/// A tracer's growable buffers, emptied.
#[derive(Debug, Default)]
pub(crate) struct Room<R> {
    pub(crate) lanes: Vec<Vec<Front<R>>>,
    pub(crate) deposits: Vec<(usize, R, R)>,
    pub(crate) exact_trains: ExactTrains<R>,
    pub(crate) scratch: LeapScratch<R>,
    pub(crate) batch: Vec<(R, R)>,
    pub(crate) point_sums: Vec<R>,
    pub(crate) together: TogetherRoom<R>,
    pub(crate) spare_fronts: Vec<Front<R>>,
}

impl<R: Real> Room<R> {
    /// The bytes it holds.
    fn bytes(&self) -> usize {
        self.lanes.iter().map(vec_bytes).sum::<usize>()
            + vec_bytes(&self.deposits)
            + self.exact_trains.bytes()
            + self.scratch.bytes()
            + vec_bytes(&self.batch)
            + vec_bytes(&self.point_sums)
            + self.together.bytes()
            + vec_bytes(&self.spare_fronts)
    }
}

/// The bytes a vector's room holds.
pub(crate) fn vec_bytes<T>(v: &Vec<T>) -> usize {
    v.capacity() * size_of::<T>()
}

thread_local! {
    /// The room the thread's last tracer gave back (of its arithmetic).
    static KEPT: RefCell<Option<Box<dyn Any>>> = const { RefCell::new(None) };
}

/// The room this thread kept, if it was kept for arithmetic `R`; else
/// none.
pub(crate) fn take<R: Real>() -> Room<R> {
    KEPT.try_with(|k| k.borrow_mut().take())
        .ok()
        .flatten()
        .and_then(|kept| kept.downcast::<Room<R>>().ok())
        .map(|room| *room)
        .unwrap_or_default()
}

/// Keeps `room` for the thread's next tracer, unless it is too large.
fn give_back<R: Real>(room: Room<R>) {
    if room.bytes() > KEPT_AT_MOST {
        return;
    }
    // (during the thread's own teardown there is nothing to keep it for)
    let _ = KEPT.try_with(|k| {
        if let Ok(mut kept) = k.try_borrow_mut() {
            *kept = Some(Box::new(room));
        }
    });
}

impl<R: Real> Drop for Tracer<R> {
    fn drop(&mut self) {
        give_back(self.empty_room());
    }
}

impl<R: Real> Tracer<R> {
    /// Its growable buffers, emptied, for the thread's next tracer
    /// ([`crate::room`]); the tracer is left without them.
    fn empty_room(&mut self) -> Room<R> {
        use std::mem::take;
        let mut deposits = take(&mut self.deposits);
        deposits.clear();
        let mut exact_trains = take(&mut self.exact_trains);
        exact_trains.clear();
        let mut batch = take(&mut self.batch);
        batch.clear();
        let mut point_sums = take(&mut self.point_sums);
        point_sums.clear();
        let mut spare_fronts = take(&mut self.spare_fronts);
        spare_fronts.clear();
        Room {
            lanes: self.lanes.iter_mut().map(Lane::take_room).collect(),
            deposits,
            exact_trains,
            scratch: take(&mut self.scratch).emptied(),
            batch,
            point_sums,
            together: take(&mut self.together).emptied(),
            spare_fronts,
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::{WaveConfig, simulate};
    use impact_model::{Bilayer, Outcome};

    fn point(x: f64, alpha: f64) -> Outcome {
        let rod = Bilayer::new(x, alpha)
            .and_then(|b| b.scene().validate())
            .expect("a valid bilayer");
        simulate(&rod, &WaveConfig::default()).expect("the point finishes")
    }

    /// The hard corner (a run that leaps and grows its lanes to thousands
    /// of fronts) gives the same outcome on a fresh thread and on one whose
    /// room other runs grew first: a small point, a merged six-layer-like
    /// run's worth of lanes (a rod with a larger room), and the corner
    /// itself.
    #[test]
    fn a_run_does_not_depend_on_what_ran_before_it_on_its_thread() {
        let fresh = std::thread::spawn(|| point(0.995, 0.005))
            .join()
            .expect("the fresh thread finishes");
        for (x, alpha) in [(0.5, 0.5), (0.9, 0.005), (0.995, 0.005)] {
            let _ = point(x, alpha);
            assert_eq!(point(0.995, 0.005), fresh, "after ({x}, {alpha})");
        }
    }
}
