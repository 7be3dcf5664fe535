//! Setting a run up: the rod's layers in the run's arithmetic, a lane per
//! layer and direction with its merge rule, the queue, and the impact's
//! first front.

use super::{Decisions, LayerConst, Ledger, TIE_ULPS, Tracer, WallLedger, past};
use crate::config::{Record, Resolution, StopRule, WaveConfig};
use crate::error::WaveError;
use crate::lane::{Direction, Lane, MergeRule};
use crate::queue::{EventKey, EventQueue};
use crate::real::Real;
use crate::record::Recording;
use crate::wall::ContactState;
use crate::window::Window;
use impact_model::escape::EscapeBound;
use impact_model::{ContactHistory, InterfaceCoefficients, Rod, WaveConstants};

/// The merge rule of a lane, from its layer's transit time and wave speed.
type LaneRule<R> = dyn Fn(f64, f64) -> MergeRule<R>;

/// Fronts whose velocity jump is at least this fraction of the impact speed
/// stay where they were born in a merged lane...
const KEEP_ABOVE: f64 = 1e-2;
/// ...up to this many per lane: the few large fronts whose exact timing
/// decides contacts (the impact front, a landing's front), while the many
/// small ones they shed are deposited on the lattice.
const KEEP_AT_MOST: usize = 8;

impl<R: Real> Tracer<R> {
    /// Prepares a run: the impact happens at `t = 0`, launching the
    /// compression front `-v_b / c0` from the wall. A tracer runs one
    /// resolution: `Exact` and `Auto` both mean exact here (choosing between
    /// runs is [`crate::simulate`]'s job), `Merged` merges.
    pub fn new(rod: &Rod, config: WaveConfig) -> Result<Self, WaveError> {
        if let Some(i) = rod.scene().layers.iter().position(|l| l.is_viscous()) {
            return Err(WaveError::ViscousLayer { layer: i });
        }
        config.check_engine()?;
        let scaled = rod.scaled_layers();
        let units = *rod.units();
        let of = R::of;
        let vb = of(rod.scaled_impact_speed());
        let t_min = scaled
            .iter()
            .map(|l| l.transit_time)
            .fold(f64::INFINITY, f64::min);
        let t_max = scaled.iter().map(|l| l.transit_time).fold(0.0, f64::max);
        let simultaneity = of(config.simultaneity) * of(t_min);
        let window = Window {
            fixed: simultaneity,
            ulps: of(TIE_ULPS * f64::EPSILON),
            scale: of(t_min),
        };
        let (rule, merged): (Box<LaneRule<R>>, bool) = match config.resolution {
            Resolution::Exact | Resolution::Auto { .. } => (
                Box::new(move |_, _| MergeRule::Simultaneous { window }),
                false,
            ),
            Resolution::Merged {
                per_transit,
                per_longest,
            } => (
                Box::new(move |transit: f64, speed: f64| MergeRule::Lattice {
                    spacing: simultaneity.max(of(crate::ladder::lattice_spacing(
                        (per_transit, per_longest),
                        transit,
                        t_max,
                    ))),
                    keep_above: of(KEEP_ABOVE) * vb / of(speed),
                    keep_at_most: KEEP_AT_MOST,
                }),
                true,
            ),
        };
        // The layers' derived constants in the run's arithmetic, from their
        // primary quantities by the model's formulas (`WaveConstants`,
        // `InterfaceCoefficients::of_sides`): a double run gets the model's
        // numbers bit for bit, a double-double run its own. Taken from the model's doubles, they carried double
        // rounding into the double-double rerun: on the grazing line
        // `alpha = 0.1`, whose points are rerun so, `e` was 2.5 ulps from the
        // 40-digit value under a bound of 1.7 (`tests/integration/tracker.rs`).
        let layers: Vec<LayerConst<R>> = scaled
            .iter()
            .map(|l| {
                let (length, modulus) = (of(l.length), of(l.modulus));
                let waves = WaveConstants::of(length, modulus, of(l.density));
                LayerConst {
                    bottom: of(l.bottom),
                    top: of(l.top),
                    length,
                    modulus,
                    wave_speed: waves.wave_speed,
                    impedance: waves.impedance,
                    transit_time: waves.transit_time,
                    drop_strain: of(config.drop_tolerance) * vb / waves.wave_speed,
                }
            })
            .collect();
        let n = layers.len();
        // The top's lanes fold into one (its reflections carried by the
        // fronts, no events at the free end), except where fronts are
        // recorded and where a merged run may leap a fast top (a folded
        // lane is not leapt, see `leap`): a top ringing a million times
        // under a slow layer otherwise takes the loop a million steps.
        let fast_top = n >= 2
            && scaled[n - 1].transit_time * crate::leap::LEAST_TRANSITS
                < scaled[n - 2].transit_time;
        // An exact run leaps only when nothing is recorded: a recording
        // shows every event. A double-double run never does
        // (`Real::LEAPS`), but lays its lanes out as the double run it
        // checks does (a merged run's lattice lanes are its discretisation).
        let may_leap =
            config.leap_quiet_layers && (merged || !(config.record.wall || config.record.fronts));
        let leaps = R::LEAPS && may_leap;
        let fold = !(config.record.fronts || (may_leap && fast_top));
        let mut room = crate::room::take::<R>();
        let mut lanes: Vec<Lane<R>> = scaled
            .iter()
            .enumerate()
            .flat_map(|(i, l)| {
                let transit = layers[i].transit_time;
                [Direction::Up, Direction::Down]
                    .map(|d| Lane::new(i, d, transit, rule(l.transit_time, l.wave_speed)))
            })
            .collect();
        for (lane, kept) in lanes.iter_mut().zip(room.lanes.drain(..)) {
            lane.move_into(kept);
        }
        let top_up = Lane::<R>::index(n - 1, Direction::Up);
        lanes[top_up].folded = fold;
        let from_above = (0..=n)
            .map(|b| match b {
                b if b == n => None,
                b if fold && b == n - 1 => Some(top_up),
                b => Some(Lane::<R>::index(b, Direction::Down)),
            })
            .collect();
        let interfaces = layers
            .windows(2)
            .map(|w| {
                let side = |l: &LayerConst<R>| (l.impedance, l.modulus);
                InterfaceCoefficients::of_sides(side(&w[0]), side(&w[1]))
            })
            .collect();
        let c0 = layers[0].wave_speed;
        let transit_sum: f64 = scaled.iter().map(|l| l.transit_time).sum();
        let two = of(2.0);
        let mut engine = Self {
            interfaces,
            // At rest relative to the rod's motion at -v_b: a = v_b/2c, b = -v_b/2c.
            up_base: layers.iter().map(|l| vb / (two * l.wave_speed)).collect(),
            down_base: layers.iter().map(|l| -vb / (two * l.wave_speed)).collect(),
            queue: EventQueue::new(n),
            lanes,
            from_above,
            contact: ContactState::InContact { strain: R::zero() },
            ledger: WallLedger {
                at: R::zero(),
                impulse: R::zero(),
                moment: R::zero(),
            },
            history: ContactHistory::new(),
            impact_speed: vb,
            mass: scaled
                .iter()
                .fold(R::zero(), |m, l| m + of(l.density) * of(l.length)),
            escape: EscapeBound::new(of(rod.scaled_compliance_moment()), of(rod.scaled_mass())),
            window,
            grazing_strain: of(config.grazing_tolerance) * vb / c0,
            merged,
            leaps,
            leap_arrivals: config.leap_arrivals,
            arrivals_taken: 0,
            max_events: config.max_events,
            max_time: of(config.max_time_factor * transit_sum),
            stop_rule: config.stop,
            record: config.record,
            recording: Recording::default(),
            drops: Ledger::default(),
            decisions: Decisions {
                smallest_margin: f64::INFINITY,
                ..Decisions::default()
            },
            last_taken_kept: false,
            events: 0,
            folded_reflections: 0,
            leaped: 0,
            leap_work: 0,
            leap_after: crate::leap::first_leaps(&layers, fold),
            leap_retry: vec![0; n],
            bottom_weighs_after: 0,
            deposits: room.deposits,
            exact_trains: room.exact_trains,
            sums_memo: Vec::new(),
            pow_memo: [(R::zero(), 0, R::one()); 2],
            scratch: room.scratch,
            ln_memo: None,
            batch: room.batch,
            point_sums: room.point_sums,
            together: room.together,
            spare_fronts: room.spare_fronts,
            blocks: crate::block::Blocks::default(),
            group: None,
            stepped: 0,
            next_id: 0,
            now: R::zero(),
            stopped: None,
            units,
            transit_times: rod.transit_times(),
            layers,
        };
        if let StopRule::Horizon { factor } = config.stop {
            let horizon = of(factor) * of(t_max);
            engine
                .queue
                .schedule(EventKey::Horizon, horizon, R::zero())
                .map_err(past)?;
        }
        // (a recording of fronts shows every front: blocks keep theirs
        // inside their response)
        if merged && config.fast_blocks && !config.record.fronts {
            engine.find_blocks(
                config.nest_blocks,
                config.one_lattice_blocks,
                config.fold_small_exact,
            );
            engine.rule_out_leaps_blocks_forbid();
        }
        if merged && config.step_bottom_group && config.record == Record::default() {
            engine.find_group();
        }
        // The impact: the bottom is stopped, v: -v_b -> 0, so d = -v_b / c0.
        let first = -vb / c0;
        engine.contact = ContactState::InContact { strain: first };
        engine.spawn(0, Direction::Up, R::zero(), first, &[])?;
        engine.record_wall();
        Ok(engine)
    }
}
