//! A block in the event loop: arrivals at its ports, and the deliveries
//! its ports' keys schedule.

use super::Blocks;
use crate::engine::{StepKind, Tracer, past};
use crate::error::WaveError;
use crate::lane::{Direction, Lane};
use crate::queue::EventKey;
use crate::real::Real;

/// Multiply-adds of a response counted as one unit of work (the event
/// budget's unit is a loop iteration, about a microsecond; a multiply-add
/// took about a nanosecond, a traced front [`super::FRONT_ADDS`] of them).
/// The sums are now dense dot products (`block/inputs.rs`, about 0.3 ns a
/// multiply-add on survey rod 12) and the trace takes a lane's run of
/// fronts at once, but both keep their price: the ladders choose the
/// levels they chose, so the change is speed alone.
const ADDS_PER_WORK: u64 = 256;

impl<R: Real> Tracer<R> {
    /// The rod's blocks of fast layers (merged runs), with their layers and
    /// neighbours kept from leaping: the neighbours' lanes take the
    /// blocks' deliveries, which a leap would not see coming. `nest`: a
    /// trace may answer its fastest layer by that layer's own response
    /// (`response/nested.rs`); `one_lattice`: a trace that nests nothing
    /// runs on one lattice (`response/one_lattice.rs`); `fold`: a response's large fronts that an
    /// arrival scales under what the neighbour's lane keeps apart go on
    /// the port's lattice (`folded.rs`).
    pub(crate) fn find_blocks(&mut self, nest: bool, one_lattice: bool, fold: bool) {
        let nesting = if nest {
            super::Nesting::Allowed
        } else {
            super::Nesting::Never
        };
        let transits: Vec<f64> = self
            .layers
            .iter()
            .map(|l| l.transit_time.to_f64())
            .collect();
        let spacing = |m: usize, d: Direction| match self.lanes[Lane::<R>::index(m, d)].rule {
            crate::lane::MergeRule::Lattice { spacing, .. } => spacing,
            crate::lane::MergeRule::Simultaneous { .. } => R::zero(),
        };
        let keep_above = |m: usize, d: Direction| match self.lanes[Lane::<R>::index(m, d)].rule {
            crate::lane::MergeRule::Lattice { keep_above, .. } => keep_above,
            crate::lane::MergeRule::Simultaneous { .. } => R::zero(),
        };
        let mut chosen = Vec::new();
        let mut list = Vec::new();
        let mut probed = 0;
        for run in super::candidates(&transits) {
            if super::apart(run, &chosen)
                && self.block_pays(&transits, run, (nesting, one_lattice), &mut probed)
            {
                chosen.push(run);
                let mut block = super::Block::new(
                    &self.layers,
                    &self.interfaces,
                    run,
                    &spacing,
                    (nesting, one_lattice),
                );
                if fold {
                    block.fold_below(&keep_above);
                }
                list.push(block);
            }
        }
        self.leap_work += probed * super::FRONT_ADDS / ADDS_PER_WORK;
        let n = self.layers.len();
        for &(a, b) in &chosen {
            for m in a - 1..=(b + 1).min(n - 1) {
                self.leap_after[m] = -R::neg_infinity();
            }
        }
        self.blocks = Blocks::new(list, n);
    }

    /// Whether answering block `run` is expected to pay: even if its
    /// response rings as long as the run, or because it rings out sooner
    /// than the sums' allowance (`choice.rs`). The second is seen on a
    /// probe of the block traced on the ladder's first lattice, the same
    /// for every level of a ladder (how long a block rings is its physics,
    /// not its lattice's); the probe's fronts are added to `probed`.
    fn block_pays(
        &self,
        transits: &[f64],
        run: (usize, usize),
        trace: (super::Nesting, bool),
        probed: &mut u64,
    ) -> bool {
        let allowance = super::allowance(transits, run);
        if super::priced_run(transits) < allowance {
            return true;
        }
        let t_max = transits.iter().copied().fold(0.0, f64::max);
        let first_lattice = |m: usize, _: Direction| {
            R::of(crate::ladder::lattice_spacing(
                crate::ladder::LADDER_START,
                transits[m],
                t_max,
            ))
        };
        let mut probe =
            super::Block::new(&self.layers, &self.interfaces, run, &first_lattice, trace);
        let (rings_out, followed) = probe.rings_out_within(R::of(allowance));
        *probed += followed;
        rings_out
    }

    /// Fronts reaching a block's port at boundary `b`: the neighbour's
    /// reflection spawned as at any interface, the part that enters the
    /// block answered by its response.
    pub(crate) fn block_boundary(
        &mut self,
        b: usize,
        t: R,
        (from_below, from_above): (R, R),
        (bi, input): (usize, usize),
        parents: &[u32],
    ) -> Result<StepKind, WaveError> {
        let k = self.interfaces[b - 1];
        let d = if input == 0 {
            self.spawn(
                b - 1,
                Direction::Down,
                t,
                k.up_reflected * from_below,
                parents,
            )?;
            from_below
        } else {
            self.spawn(b, Direction::Up, t, k.down_reflected * from_above, parents)?;
            from_above
        };
        let mut late = std::mem::take(&mut self.blocks.late);
        late.clear();
        let (work, folded) = self.blocks.list[bi].arrive(input, t, d, &mut late);
        self.leap_work += work / ADDS_PER_WORK;
        self.drops.truncation.merged_fronts += folded;
        for &(o, born, jump) in &late.spawned {
            let (layer, dir) = self.blocks.list[bi].ports[o].out;
            self.spawn(layer, dir, born, jump, &[])?;
        }
        for &(o, born, jump) in &late.deposited {
            let (layer, dir) = self.blocks.list[bi].ports[o].out;
            self.spawn_deposited(layer, dir, born, jump)?;
        }
        self.blocks.late = late;
        for o in 0..self.blocks.list[bi].ports.len() {
            self.deliver(bi, o)?;
        }
        Ok(StepKind::Interface(b))
    }

    /// A port's deliveries due now, from its key's event.
    pub(crate) fn block_delivery(&mut self, bi: usize, o: usize) -> Result<StepKind, WaveError> {
        self.deliver(bi, o)?;
        Ok(StepKind::Interface(self.blocks.list[bi].ports[o].boundary))
    }

    /// Spawns port `o`'s deliveries due by now and schedules its next.
    fn deliver(&mut self, bi: usize, o: usize) -> Result<(), WaveError> {
        let mut due = std::mem::take(&mut self.blocks.spawns);
        due.clear();
        let block = &mut self.blocks.list[bi];
        let (next, work, on_lattice) = block.due(o, self.now, &mut due);
        let mut folded = std::mem::take(&mut block.folded_due);
        let rest = block.take_rest();
        let (layer, dir) = block.ports[o].out;
        let key = EventKey::Layer(block.ports[o].key_layer as u32);
        self.leap_work += work / ADDS_PER_WORK;
        if let Some((velocity, force, force_time)) = rest {
            self.drop_rest(velocity, force, force_time);
        }
        // the lattice points, what was folded on them (deposited after
        // their sums: a folded front's lower share came after its point's
        // sum before too, its upper share before it, which matters only
        // where that sum is kept apart), the exact fronts
        for &(born, jump) in &due[..on_lattice] {
            self.spawn(layer, dir, born, jump, &[])?;
        }
        for &(born, jump) in &folded {
            self.spawn_deposited(layer, dir, born, jump)?;
        }
        for &(born, jump) in &due[on_lattice..] {
            self.spawn(layer, dir, born, jump, &[])?;
        }
        folded.clear();
        self.blocks.list[bi].folded_due = folded;
        self.blocks.spawns = due;
        match next {
            Some(at) => self.queue.schedule(key, at, self.now).map_err(past),
            None => {
                self.queue.cancel(key);
                Ok(())
            }
        }
    }
}
