//! The trace against what a block must do, and against its first build.

use super::*;
use impact_model::WaveConstants;

/// A layer of `length`, `modulus` and `density` as the engine holds it.
pub(super) fn layer(length: f64, modulus: f64, density: f64) -> LayerConst<f64> {
    let w = WaveConstants::of(length, modulus, density);
    LayerConst {
        bottom: 0.0,
        top: length,
        length,
        modulus,
        wave_speed: w.wave_speed,
        impedance: w.impedance,
        transit_time: w.transit_time,
        drop_strain: 0.0,
    }
}

pub(super) fn side(l: &LayerConst<f64>) -> (f64, f64) {
    (l.impedance, l.modulus)
}

/// The block between `below` and `above` (`None`: the free top), on
/// lattices of `share` of each transit, ports on a tenth of the
/// neighbours'.
pub(super) fn shape(
    below: LayerConst<f64>,
    block: &[LayerConst<f64>],
    above: Option<LayerConst<f64>>,
    share: f64,
) -> Shape<f64> {
    let coefficients = |a: &LayerConst<f64>, b: &LayerConst<f64>| {
        InterfaceCoefficients::of_sides(side(a), side(b))
    };
    let mut ports = vec![below];
    ports.extend(above);
    Shape {
        layers: block.to_vec(),
        inner: block
            .windows(2)
            .map(|w| coefficients(&w[0], &w[1]))
            .collect(),
        lower: coefficients(&below, &block[0]),
        upper: above.map(|a| coefficients(&block[block.len() - 1], &a)),
        spacing: block.iter().map(|l| share * l.transit_time).collect(),
        per_spacing: block
            .iter()
            .map(|l| 1.0 / (share * l.transit_time))
            .collect(),
        port_spacing: ports.iter().map(|l| 0.1 * l.transit_time).collect(),
        port_speed: ports.iter().map(|l| l.wave_speed).collect(),
        nest: None,
        keep_exact: true,
        powers: None,
        work_share: vec![1.0; block.len()],
    }
}

/// A block of three stiff layers between two soft neighbours: below,
/// the block, above.
pub(super) fn three_stiff_layers() -> (LayerConst<f64>, [LayerConst<f64>; 3], LayerConst<f64>) {
    let block = [
        layer(0.02, 1e4, 2.0),
        layer(0.01, 3e5, 1.0),
        layer(0.03, 2e3, 0.3),
    ];
    (layer(1.0, 1.0, 1.0), block, layer(0.7, 4.0, 0.5))
}

/// The whole response to a unit arrival at `input`: its taps at each
/// port, summed.
pub(super) fn totals(shape: &Shape<f64>, input: usize) -> Vec<f64> {
    moments(shape, input).iter().map(|m| m.0).collect()
}

/// The whole response to a unit arrival at `input`, per port: its jumps
/// summed, and their first moment in time.
pub(super) fn moments(shape: &Shape<f64>, input: usize) -> Vec<(f64, f64)> {
    let mut trace = Trace::start(shape, input);
    trace.extend(shape, 0, 1 << 40);
    assert!(trace.done, "the trace ends");
    assert!(
        trace.rest.0 < 1e-12 * shape.port_speed[input],
        "{:?}",
        trace.rest
    );
    (0..trace.taps.len())
        .map(|o| {
            let h = shape.port_spacing[o];
            let taps = trace.taps[o].iter().enumerate();
            let exact = trace.exact[o].iter();
            (
                trace.taps[o].iter().sum::<f64>() + exact.clone().map(|e| e.1).sum::<f64>(),
                taps.map(|(k, &d)| d * k as f64 * h).sum::<f64>()
                    + exact.map(|e| e.0 * e.1).sum::<f64>(),
            )
        })
        .collect()
}

/// The response's running sum at each port (what its jumps add up to by
/// each lattice point, the large fronts put on the lattice), as far as
/// the trace goes.
pub(super) fn running(shape: &Shape<f64>, input: usize, o: usize) -> Vec<f64> {
    let mut trace = Trace::start(shape, input);
    trace.extend(shape, 0, 1 << 40);
    let mut taps = trace.taps[o].clone();
    for &(at, d) in &trace.exact[o] {
        deposit(&mut taps, at, d, shape.port_spacing[o]);
    }
    let mut sum = 0.0;
    taps.iter()
        .map(|&d| {
            sum += d;
            sum
        })
        .collect()
}

/// How far apart the running sums of two shapes' responses to `input`
/// come at port `o`, at most (the shorter held at its last).
pub(super) fn running_apart(a: &Shape<f64>, b: &Shape<f64>, input: usize, o: usize) -> f64 {
    let (a, b) = (running(a, input, o), running(b, input, o));
    let at = |v: &[f64], k: usize| v.get(k).or(v.last()).copied().unwrap_or(0.0);
    (0..a.len().max(b.len()))
        .map(|k| (at(&a, k) - at(&b, k)).abs())
        .fold(0.0, f64::max)
}

/// Nested or not, the response is the same lattice model's, first order
/// in the spacing: the running sums of the two responses at each port
/// differ by at most `1e-6` of the unit input, and by half as much or
/// less on lattices of a twentieth of each transit as of a fifth (they
/// differ by `2.3e-7` and `1.8e-8` at most).
#[test]
fn a_nested_response_converges_to_the_followed_one() {
    let (below, block, above) = three_stiff_layers();
    let apart = |share: f64, input: usize, o: usize| {
        let plain = shape(below, &block, Some(above), share);
        let mut nested = plain.clone();
        nested.nest = Some(1);
        running_apart(&plain, &nested, input, o)
    };
    assert_first_order(apart, 1e-6);
}

/// `apart(share, input, port)` at each input and port at least halves
/// from lattices of a fifth of each transit to a twentieth, and is under
/// `limit` there.
pub(super) fn assert_first_order(apart: impl Fn(f64, usize, usize) -> f64, limit: f64) {
    for input in 0..2 {
        for o in 0..2 {
            let (coarse, fine) = (apart(0.2, input, o), apart(0.05, input, o));
            assert!(
                fine < coarse / 2.0 && fine < limit,
                "input {input}, port {o}: {coarse} -> {fine}"
            );
        }
    }
}

/// A lattice keeps each front's jump and first moment where it puts it,
/// and a block's sums keep them too, so the whole response's jumps and
/// their first moment at each port are the same whether the trace
/// follows its fastest layer's fronts or answers that layer by its own
/// response (`nested.rs`), to rounding, on lattices of a fifth and a
/// twentieth of each transit; and nesting follows fewer fronts.
#[test]
fn a_nested_layer_keeps_the_responses_jumps_and_first_moments() {
    let (below, block, above) = three_stiff_layers();
    for share in [0.2, 0.05] {
        let plain = shape(below, &block, Some(above), share);
        let mut nested = plain.clone();
        // (nested whatever it costs: the responses are what is checked)
        nested.nest = Some(1);
        for input in 0..2 {
            assert_same_moments(&plain, &nested, input);
            let followed = |s: &Shape<f64>| {
                let mut trace = Trace::start(s, input);
                trace.extend(s, 0, 1 << 40);
                trace.followed
            };
            assert!(
                2 * followed(&nested) < followed(&plain),
                "{} against {}",
                followed(&nested),
                followed(&plain)
            );
        }
    }
}

/// The whole responses of `a` and `b` to `input` carry the same jumps and
/// first moments at each port, to `1e-10`.
pub(super) fn assert_same_moments(a: &Shape<f64>, b: &Shape<f64>, input: usize) {
    let (x, y) = (moments(a, input), moments(b, input));
    for o in 0..x.len() {
        let close = |p: f64, q: f64| (p - q).abs() <= 1e-10 * (1.0 + p.abs());
        assert!(
            close(x[o].0, y[o].0) && close(x[o].1, y[o].1),
            "input {input}, port {o}: {:?} against {:?}",
            x[o],
            y[o]
        );
    }
}

/// A trace lane against its definition (a map from lattice point to
/// the sum of what was added there): adds inside, next to the newest,
/// past a gap, before the oldest and into an emptied lane, with the
/// oldest points taken in between. The first fast path pushed an add
/// before the oldest onto the newest end; the block tests' bounds had
/// not seen it.
#[test]
fn a_trace_lane_holds_what_was_added_on_each_point() {
    let mut lane = TraceLane::<f64>::default();
    let mut held = std::collections::BTreeMap::<i64, f64>::new();
    let mut next = crate::test_random::xorshift(0x2545_f491_4f6c_dd1du64);
    for step in 0..4000i64 {
        let k = step / 8 + (next() % 24) as i64 - 8;
        let d = (next() % 1000) as f64 / 64.0 - 7.0;
        lane.add(k, d);
        *held.entry(k).or_insert(0.0) += d;
        if step % 97 == 96 {
            // take the oldest points, as a step of the trace does
            let take = (next() % 40) as usize;
            for _ in 0..take {
                if lane.points.pop_front().is_none() {
                    break;
                }
                lane.base += 1;
            }
            held.retain(|&p, _| p >= lane.base);
        }
        let first = held.keys().next().copied();
        for (&p, &want) in &held {
            let got = usize::try_from(p - lane.base)
                .ok()
                .and_then(|i| lane.points.get(i))
                .copied();
            assert_eq!(got, Some(want), "step {step}: point {p}");
        }
        let nonzero = lane.points.iter().filter(|&&x| x != 0.0).count();
        assert_eq!(nonzero, held.values().filter(|&&x| x != 0.0).count());
        if let Some(first) = first {
            assert!(lane.base <= first);
        }
    }
}

/// The trace's step as the first build took it, front by front
/// through [`Trace::scatter`]: the oracle of the runs taken together.
fn step_front_by_front(trace: &mut Trace<f64>, shape: &Shape<f64>) {
    let end = trace.reached + trace.step;
    let mut n = 0;
    while n < trace.kept.len() {
        let (born, d, lane) = trace.kept[n];
        let at = born + shape.layers[lane / 2].transit_time;
        if at < end {
            trace.kept.swap_remove(n);
            trace.scatter(shape, lane / 2, lane % 2 == 0, at, d, true);
        } else {
            n += 1;
        }
    }
    for i in 0..trace.lanes.len() {
        let (m, up) = (i / 2, i % 2 == 0);
        let (s, transit) = (shape.spacing[m], shape.layers[m].transit_time);
        loop {
            let lane = &mut trace.lanes[i];
            let at = lane.base as f64 * s + transit;
            if at >= end {
                break;
            }
            let Some(d) = lane.points.pop_front() else {
                break;
            };
            lane.base += 1;
            if d != 0.0 {
                trace.scatter(shape, m, up, at, d, false);
            }
        }
    }
    trace.reached = end;
}

/// Lanes taken run by run give the taps and exact fronts that fronts
/// taken one by one give, bit for bit, step after step: three blocks
/// (two with an upper port, one at the free top) from each input, on
/// two lattices.
#[test]
fn runs_scatter_as_fronts_one_by_one_do() {
    let (below, block, above) = three_stiff_layers();
    for share in [0.2, 0.05] {
        let shapes = [
            shape(below, &block, Some(above), share),
            shape(below, &block[1..], Some(above), share),
            shape(below, &block[..2], None, share),
        ];
        for s in &shapes {
            for input in 0..s.port_spacing.len() {
                let mut runs = Trace::start(s, input);
                // (the exact fronts all leave within the start)
                assert!(runs.kept.is_empty());
                let mut fronts = runs.clone();
                for _ in 0..3000 {
                    if runs.kept.is_empty() && runs.lanes.iter().all(|l| l.points.is_empty()) {
                        break;
                    }
                    let end = runs.reached + runs.step;
                    for i in 0..runs.lanes.len() {
                        runs.take_lane(s, i, end);
                    }
                    runs.reached = end;
                    step_front_by_front(&mut fronts, s);
                    assert_eq!(runs.taps, fronts.taps);
                    assert_eq!(runs.exact, fronts.exact);
                }
                let points: usize = runs.lanes.iter().map(|l| l.points.len()).sum();
                assert!(points > 0 && runs.taps[0].len() > 1, "still ringing");
            }
        }
    }
}

/// At zero frequency a block is not there: stress and velocity are the
/// same through it, so everything it sends back over all time, with
/// the reflection at its face, is what the interface between its two
/// neighbours would reflect, and what it passes is what that interface
/// would transmit (a top block: what a free end reflects, `-1`). The
/// trace knows nothing of this: it scatters fronts and deposits them.
#[test]
fn a_block_is_transparent_at_zero_frequency() {
    let (below, block, above) = three_stiff_layers();
    for (share, nested) in [(0.2, false), (0.05, false), (0.2, true), (0.05, true)] {
        let mut s = shape(below, &block, Some(above), share);
        if nested {
            s.nest = Some(1);
        }
        let top = shape(below, &block[..2], None, share);
        assert_transparent(&s, &top, (&below, &above));
    }
}

/// `between` (a block between `below` and `above`) reflects and transmits
/// over all time, with its faces' reflections, what the interface between
/// its neighbours would, and `top` (a block under the free top) what a
/// free end reflects, to `1e-9`.
pub(super) fn assert_transparent(
    between: &Shape<f64>,
    top: &Shape<f64>,
    (below, above): (&LayerConst<f64>, &LayerConst<f64>),
) {
    let direct = InterfaceCoefficients::of_sides(side(below), side(above));
    let from_below = totals(between, 0);
    let from_above = totals(between, 1);
    let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
    assert!(close(
        from_below[0] + between.lower.up_reflected,
        direct.up_reflected
    ));
    assert!(close(from_below[1], direct.up_transmitted));
    assert!(close(
        from_above[1] + between.upper.unwrap().down_reflected,
        direct.down_reflected
    ));
    assert!(close(from_above[0], direct.down_transmitted));
    let free = totals(top, 0);
    assert!(close(free[0] + top.lower.up_reflected, -1.0), "{free:?}");
}

/// The response's first front: a unit arrival from below first comes
/// out above after the block's summed transits, with the product of
/// the transmissions, at its exact time (it is large).
#[test]
fn the_first_front_through_comes_out_after_the_summed_transits() {
    let below = layer(1.0, 1.0, 1.0);
    let above = layer(0.107, 2.0, 1.0);
    let block = [layer(0.3, 100.0, 1.0), layer(0.2, 400.0, 1.0)];
    let s = shape(below, &block, Some(above), 0.1);
    let through: f64 = block.iter().map(|l| l.transit_time).sum();
    let amplitude =
        s.lower.up_transmitted * s.inner[0].up_transmitted * s.upper.unwrap().up_transmitted;
    let trace = Trace::start(&s, 0);
    let (delay, jump) = trace.exact[1][0];
    let close = |a: f64, b: f64| (a - b).abs() < 1e-12 * b.abs();
    assert!(
        close(delay, through) && close(jump, amplitude),
        "{:?}",
        trace.exact
    );
    assert!(
        trace.exact[1].iter().all(|e| e.0 >= through),
        "nothing earlier"
    );
}
