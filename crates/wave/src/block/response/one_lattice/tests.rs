//! One lattice against the same lattice taken point by point, against
//! each layer's own lattice, and against what a block must do.

use super::super::tests::{
    assert_first_order, assert_same_moments, assert_transparent, running_apart, shape,
    three_stiff_layers,
};
use super::super::{Shape, Trace};
use crate::lane::LatticePoints;

/// `shape` with every lane on its finest lattice but taken as the trace
/// takes lanes of their own lattices, point by point
/// (`Trace::take_lane`): the oracle of the shifted runs.
fn one_lattice_point_by_point(shape: &Shape<f64>) -> Shape<f64> {
    let mut shifted = shape.clone();
    shifted.share_one_lattice();
    Shape {
        powers: None,
        work_share: vec![1.0; shape.layers.len()],
        ..shifted
    }
}

fn one_lattice(shape: &Shape<f64>) -> Shape<f64> {
    let mut s = shape.clone();
    s.share_one_lattice();
    s
}

/// Per port: the taps, and the exact fronts `(delay, jump)`; and the
/// force of what the trace left when done (`sum E |d|`).
type Response = (Vec<Vec<f64>>, Vec<Vec<(f64, f64)>>, f64);

/// The whole trace, taps and exact fronts per port.
fn traced(shape: &Shape<f64>, input: usize) -> Response {
    let mut trace = Trace::start(shape, input);
    trace.extend(shape, 0, 1 << 40);
    assert!(trace.done, "the trace ends");
    (trace.taps, trace.exact, trace.rest.1)
}

/// Runs landed shifted give the taps that the same lattice gives point
/// by point, to rounding (`1e-12` of the unit input: the places are
/// summed in another order, and the point-by-point trace drops fronts
/// under `1e-19` of it where the shifted one keeps them), and the same
/// exact fronts: three blocks (two with an upper port, one at the free
/// top) from each input, on lattices of a fifth and a twentieth of each
/// transit. The two traces' steps differ where the fastest layer is swept
/// (`sweep.rs`), and so do the instants at which they find what they hold
/// below `REST` and end: what either left then may be in the other's last
/// taps, and is allowed on top of rounding at its force doubled (a front
/// passes at most twice its force through an interface; the scale of it,
/// not a bound: the taps found `2e-12` apart where that allows `4e-11`,
/// and a landing gone wrong moves taps of `1e-3` and more).
#[test]
fn shifted_runs_land_as_points_placed_one_by_one() {
    let (below, block, above) = three_stiff_layers();
    let moduli = [below.modulus, above.modulus];
    for share in [0.2, 0.05] {
        let shapes = [
            shape(below, &block, Some(above), share),
            shape(below, &block[1..], Some(above), share),
            shape(below, &block[..2], None, share),
        ];
        for s in &shapes {
            for input in 0..s.port_spacing.len() {
                let (taps, exact, left) = traced(&one_lattice(s), input);
                let (want, want_exact, left_too) = traced(&one_lattice_point_by_point(s), input);
                assert_eq!(exact, want_exact);
                for (o, (a, b)) in taps.iter().zip(&want).enumerate() {
                    let n = a.len().max(b.len());
                    let at = |v: &[f64], k: usize| v.get(k).copied().unwrap_or(0.0);
                    let apart = (0..n)
                        .map(|k| (at(a, k) - at(b, k)).abs())
                        .fold(0.0, f64::max);
                    let largest = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                    let ends = 2.0 * (left + left_too) / moduli[o];
                    assert!(
                        apart <= 1e-12 + ends && largest > 1e-3,
                        "share {share}, input {input}, port {o}: {apart:e} (largest tap {largest:e})"
                    );
                }
            }
        }
    }
}

/// A lattice keeps each front's jump and first moment where it puts it,
/// so the whole response's jumps and their first moment at each port are
/// the same on one lattice as on each layer's own, to rounding.
#[test]
fn one_lattice_keeps_the_responses_jumps_and_first_moments() {
    let (below, block, above) = three_stiff_layers();
    for share in [0.2, 0.05] {
        let own = shape(below, &block, Some(above), share);
        let one = one_lattice(&own);
        for input in 0..2 {
            assert_same_moments(&own, &one, input);
        }
    }
}

/// Both lattices are first-order models of one response: the running
/// sums of the two at each port differ by less on lattices of a twentieth
/// of each transit than on lattices of a fifth, by half or more, and by
/// at most `1e-3` of the unit input there.
#[test]
fn one_lattice_converges_with_each_layers_own() {
    let (below, block, above) = three_stiff_layers();
    let apart = |share: f64, input: usize, o: usize| {
        let own = shape(below, &block, Some(above), share);
        running_apart(&own, &one_lattice(&own), input, o)
    };
    assert_first_order(apart, 1e-3);
}

/// At zero frequency a block is not there (see the test of that name for
/// each layer's own lattice): on one lattice too, what it sends back with
/// its face's reflection is what the interface between its neighbours
/// reflects, and what it passes is what that interface transmits.
#[test]
fn a_block_on_one_lattice_is_transparent_at_zero_frequency() {
    let (below, block, above) = three_stiff_layers();
    for share in [0.2, 0.05] {
        let between = one_lattice(&shape(below, &block, Some(above), share));
        let top = one_lattice(&shape(below, &block[..2], None, share));
        assert_transparent(&between, &top, (&below, &above));
    }
}

/// A shifted add against its definition (a map from lattice point to the
/// sum of what was added there): runs landing inside the lane, past its
/// newest point, before its oldest and into an emptied lane, with the
/// oldest points taken in between: a run's points next to each other,
/// or up to eight points apart (a slower lane's run), or a few to a
/// point (a faster lane's, class by class).
#[test]
fn a_shifted_run_adds_its_two_shares_on_each_point() {
    let mut lane = LatticePoints::<f64>::default();
    let mut held = std::collections::BTreeMap::<i64, f64>::new();
    let mut next = crate::test_random::xorshift(0x9e37_79b9_7f4a_7c15u64);
    for step in 0..2000i64 {
        let k = step / 4 + (next() % 40) as i64 - 20;
        let run: Vec<f64> = (0..next() % 12)
            .map(|_| (next() % 1000) as f64 / 64.0 - 7.0)
            .collect();
        let (lo, hi) = (0.75, -0.125);
        let stride = [1, 1, 2, 3, 8][(next() % 5) as usize];
        if next().is_multiple_of(2) {
            lane.add_strided(k, stride, &run, lo, hi);
            for (j, &d) in run.iter().enumerate() {
                let at = k + (j * stride) as i64;
                *held.entry(at).or_insert(0.0) += lo * d;
                *held.entry(at + 1).or_insert(0.0) += hi * d;
            }
        } else {
            // a run of a lane `stride` times finer, its classes' shares
            let shares: Vec<(usize, f64, f64)> = (0..stride)
                .map(|_| ((next() % 2) as usize, lo, hi))
                .collect();
            lane.add_classes(k, &run, &shares);
            for (j, &d) in run.iter().enumerate() {
                let (off, lo, hi) = shares[j % stride];
                let at = k + (j / stride + off) as i64;
                *held.entry(at).or_insert(0.0) += lo * d;
                *held.entry(at + 1).or_insert(0.0) += hi * d;
            }
        }
        if step % 37 == 36 {
            let take = (next() % 60) as usize;
            for _ in 0..take {
                if lane.points.pop_front().is_none() {
                    break;
                }
                lane.base += 1;
            }
            held.retain(|&p, _| p >= lane.base);
        }
        for (&p, &want) in &held {
            let got = usize::try_from(p - lane.base)
                .ok()
                .and_then(|i| lane.points.get(i))
                .copied()
                .unwrap_or(0.0);
            assert!(
                (got - want).abs() <= 1e-12 * (1.0 + want.abs()),
                "step {step}: point {p}: {got} against {want}"
            );
        }
        let total: f64 = lane.points.iter().map(|x| x.abs()).sum();
        let want: f64 = held.values().map(|x| x.abs()).sum();
        assert!((total - want).abs() <= 1e-9 * (1.0 + want), "step {step}");
    }
}

/// A layer far slower than the block's fastest goes on a lattice a power
/// of two coarser, no finer than twice its own lattice (seed 3's rod 32,
/// two of whose layers are 77,000 times slower than its fastest, would
/// have held 7 M points a trace on the fastest's lattice): a layer a
/// hundred thousand times slower holds fewer than twice the points it
/// holds on its own lattice, its lattice nests the fastest's, and its
/// runs land as points placed one by one (to `1e-11` of the input: the
/// fast lanes' points lie millions of cells from the trace's start, and
/// each side computes their places in its own order).
#[test]
fn a_far_slower_layer_goes_on_a_coarser_lattice_of_the_same_points() {
    let (below, block, above) = three_stiff_layers();
    let fastest = block
        .iter()
        .map(|l| l.transit_time)
        .fold(f64::INFINITY, f64::min);
    let mut slow = block[2];
    // the same impedance, a hundred thousand times the fastest transit
    let stretch = 1e5 * fastest / slow.transit_time;
    slow.length *= stretch;
    slow.top = slow.length;
    slow.transit_time *= stretch;
    let with_slow = [block[0], block[1], slow];
    let mut own = shape(below, &with_slow, Some(above), 0.05);
    // (ports fine enough to hold many taps while the slow layer rings)
    own.port_spacing = vec![1e-3 * slow.transit_time; 2];
    assert!(own.fits_one_lattice());
    let one = one_lattice(&own);
    let finest = one.spacing[1];
    for (m, (&s, &o)) in one.spacing.iter().zip(&own.spacing).enumerate() {
        let power = (s / finest).log2();
        assert_eq!(power, power.round(), "layer {m}: {s:e} on {finest:e}");
        assert!(
            o / 2.0 < s && s <= o,
            "layer {m}: {s:e} against its own {o:e}"
        );
        assert_eq!(one.work_share[m], s / o);
    }
    assert!(one.spacing[2] / finest >= 65536.0);
    // (a trace of three slow transits: the whole would take many
    // hundred thousand of the fast layer's transits)
    let until = 3000;
    for input in 0..2 {
        let mut a = Trace::start(&one, input);
        a.extend(&one, 0, until);
        let point_by_point = one_lattice_point_by_point(&own);
        let mut b = Trace::start(&point_by_point, input);
        b.extend(&point_by_point, 0, until);
        // (the taps final in both)
        let last = a
            .final_through(&one, 0)
            .min(b.final_through(&point_by_point, 0));
        let last = usize::try_from(last).unwrap_or(0).min(a.taps[0].len());
        let apart = a.taps[0][..last]
            .iter()
            .zip(&b.taps[0])
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        let largest = b.taps[0].iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(
            apart <= 1e-11 && largest > 1e-3 && last > 2000,
            "input {input}: {apart:e} over {last} taps"
        );
    }
}

/// A block's fastest layer is swept point by point within the others'
/// step (`sweep.rs`), and its points land as the same lattice taken point
/// by point within its own step lands them, to rounding, on every tap
/// final in both: the fast layer inside the block (its neighbours far
/// slower, or one only 1.5 times), at its lower port, at its upper port,
/// and under the free top, from each input.
#[test]
fn a_swept_layer_lands_as_its_points_placed_one_by_one() {
    let (below, block, above) = three_stiff_layers();
    // the middle layer a hundred times faster, at its impedance
    let mut fast = block[1];
    fast.length /= 100.0;
    fast.top = fast.length;
    fast.transit_time /= 100.0;
    // and a layer of the first one's impedance, only 1.5 times slower
    let mut near = block[0];
    let stretch = 1.5 * fast.transit_time / near.transit_time;
    near.length *= stretch;
    near.top = near.length;
    near.transit_time *= stretch;
    let cases = [
        (vec![block[0], fast, block[2]], Some(above), 1),
        (vec![near, fast, block[2]], Some(above), 1),
        (vec![fast, block[2]], Some(above), 0),
        (vec![block[0], fast], Some(above), 1),
        (vec![block[0], fast], None, 1),
    ];
    for (layers, top, f) in cases {
        let mut own = shape(below, &layers, top, 0.2);
        // (ports fine enough to hold many taps while the block rings)
        let slowest = layers.iter().map(|l| l.transit_time).fold(0.0, f64::max);
        own.port_spacing = vec![0.02 * slowest; own.port_spacing.len()];
        let one = one_lattice(&own);
        let point_by_point = one_lattice_point_by_point(&own);
        for input in 0..one.port_spacing.len() {
            let mut a = Trace::start(&one, input);
            assert_eq!(a.swept, Some(f), "{} layers", layers.len());
            let mut b = Trace::start(&point_by_point, input);
            assert_eq!(b.swept, None);
            for o in 0..one.port_spacing.len() {
                a.extend(&one, o, 300);
                b.extend(&point_by_point, o, 300);
            }
            assert!(!a.done && !b.done, "the traces still ring");
            assert_eq!(a.exact, b.exact);
            for o in 0..one.port_spacing.len() {
                let last = a
                    .final_through(&one, o)
                    .min(b.final_through(&point_by_point, o));
                let last = usize::try_from(last + 1).unwrap_or(0);
                let at = |v: &[f64], k: usize| v.get(k).copied().unwrap_or(0.0);
                let apart = (0..last)
                    .map(|k| (at(&a.taps[o], k) - at(&b.taps[o], k)).abs())
                    .fold(0.0, f64::max);
                let largest = b.taps[o].iter().fold(0.0f64, |m, x| m.max(x.abs()));
                assert!(
                    apart <= 1e-12 && largest > 1e-3 && last >= 300,
                    "{} layers, fast {f}, input {input}, port {o}: {apart:e} over {last} taps",
                    layers.len()
                );
            }
        }
    }
}
