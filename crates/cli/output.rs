//! Human-readable summaries and safe file writing.

use impact_model::{Outcome, StopReason, Timed};
use std::fmt::Write as _;
use std::path::Path;

/// Writes `path` through a temporary sibling renamed into place, so an
/// interrupted or failed run never leaves a partial file behind.
pub fn write_atomically(
    path: &Path,
    fill: impl FnOnce(&mut std::io::BufWriter<std::fs::File>) -> std::io::Result<()>,
) -> anyhow::Result<()> {
    use anyhow::Context;
    use std::io::Write;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = path.with_file_name(format!(".{name}.partial"));
    let result = (|| {
        let file = std::fs::File::create(&tmp)?;
        let mut w = std::io::BufWriter::new(file);
        fill(&mut w)?;
        w.flush()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.with_context(|| format!("cannot write {}", path.display()))
}

fn seconds(s: f64) -> String {
    if s < 1e-3 {
        format!("{:.1} µs", s * 1e6)
    } else if s < 1.0 {
        format!("{:.2} ms", s * 1e3)
    } else {
        format!("{s:.2} s")
    }
}

/// A time or length with 7 significant digits, in plain or scientific form.
fn num(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 || (1e-3..1e6).contains(&a) {
        let digits = (6 - a.log10().floor().max(0.0) as i32).max(0) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{v:.6e}")
    }
}

/// What a chain's `e` is known to within: for a ladder, its distance from
/// the `N -> infinity` limit and that limit's estimate (the outcome's
/// `error_bound`); for one chain, that nothing measures its distance from
/// the continuum. `None` for the other engines.
fn chain_error_line(o: &Outcome) -> Option<String> {
    if o.engine != impact_model::EngineKind::Chain {
        return None;
    }
    Some(match (&o.extrapolation, o.error_bound) {
        (Some(x), Some(bound)) => format!(
            "|e - e(N -> infinity)| <= {bound:.1e}  (this chain {:.1e} from the limit, the limit's estimate {:.1e})",
            (o.restitution - x.value).abs(),
            x.error
        ),
        _ => "not estimated: one chain is its own model (its distance from N -> infinity: drop --n on a viscous scene, or --engine wave on an elastic one)".to_string(),
    })
}

/// What would take a merged ladder a level finer, the check its bound
/// asks for when its levels are not yet seen converging.
fn finer_level(stop: Option<impact_model::LadderStop>) -> String {
    use impact_model::LadderStop;
    match stop {
        Some(LadderStop::Budget { needed }) => {
            format!("--event-budget {needed} or more runs the next level, one more check")
        }
        Some(LadderStop::Target) => {
            "the ladder stopped at --target: a smaller one, with the --event-budget for it, runs the next level".to_string()
        }
        Some(LadderStop::EventLimit) => {
            "the next level needs a larger --max-events".to_string()
        }
        Some(LadderStop::FinestLattice) => {
            "the ladder reached its finest lattice; an exact run (--resolution exact) checks it, if it fits".to_string()
        }
        None => "a smaller --merge-window is one more check".to_string(),
    }
}

/// The readable summary of one run.
pub fn summary(title: &str, o: &Timed<Outcome>) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "{title}");
    let engine = match o.engine {
        impact_model::EngineKind::Wave => "wave (exact front tracing)",
        impact_model::EngineKind::Chain => match o.viscous_kernel.as_deref() {
            Some("implicit") => {
                "chain (mass-spring-dashpot, implicit kernel: SDIRK2 on springs and dashpots)"
            }
            Some(_) => "chain (Beeman springs, SDIRK2 dashpots)",
            None => "chain (Beeman mass-spring)",
        },
        impact_model::EngineKind::RigidBottom => {
            "rigid-bottom (rigid mass under the elastic stack)"
        }
    };
    let _ = writeln!(s, "  engine               {engine}");
    let _ = writeln!(s, "  wall contact         {}", o.wall_contact.describe());
    if let Some(x) = &o.extrapolation {
        let _ = writeln!(
            s,
            "  restitution e        {:.9} +- {:.1e}  (N -> infinity, Richardson)",
            x.value, x.error
        );
        let runs: Vec<String> = x
            .sizes
            .iter()
            .zip(&x.values)
            .map(|(n, e)| format!("{n}: {e:.9}"))
            .collect();
        let _ = writeln!(s, "  chains N: e          {}", runs.join(", "));
        let order = x
            .order
            .map_or("none (changes not monotone)".to_string(), |p| {
                format!("{p:.2}")
            });
        let _ = writeln!(s, "  observed order in N  {order}");
        if let Some(note) = &x.note {
            let _ = writeln!(s, "  not clean            {note}: estimate widened");
        }
        let last = x.sizes.last().copied().unwrap_or(0);
        let _ = writeln!(s, "  (the figures below are the chain of N = {last})");
    }
    let _ = writeln!(s, "  restitution e        {:.12}", o.restitution);
    if let Some(est) = &o.error_estimate {
        let mut parts = vec![];
        for (name, value) in [
            ("dropped fronts", est.dropped),
            ("merged fronts", est.merged),
            ("rounding", est.rounding),
            ("reduced model", est.reduced),
            ("tolerances", est.tolerances),
        ] {
            if value > 0.0 {
                parts.push(format!("{name} {value:.1e}"));
            }
        }
        if let Some(loss) = est.double_precision_loss {
            parts.push(format!("double precision alone was off by {loss:.1e}"));
        }
        if let Some(ladder) = &est.ladder_set_aside {
            parts.push(format!(
                "exact: the merged levels did not converge, and gave {:.10} +- {:.1e}",
                ladder.restitution, ladder.merged_bound
            ));
        }
        if est.merged_converging == Some(false) {
            // (such bounds have been found 3.4 to 37 times too small
            // against finer ladders, and on a stack of real materials
            // whose levels sit on a plateau down to a fortieth of a
            // transit, its finer lattices lie 1,500 to 3,600 bounds away:
            // README. No factor is promised, and the next level is one
            // more check, not a proof.)
            let tried = est.exact_again_unfinished.map_or(String::new(), |events| {
                format!("; the exact run, tried again with {events} events, did not finish")
            });
            let check = format!(
                "the merged estimate may be low, by any factor ({}{tried})",
                finer_level(est.ladder_stop)
            );
            parts.push(match est.merged_observed_order {
                Some(order) => format!(
                    "the merged levels show order {order:.1}, below {}: {check}",
                    impact_wave::SLOWEST_ORDER
                ),
                None => format!("the merged levels are not yet seen converging: {check}"),
            });
        }
        let _ = writeln!(
            s,
            "  error bound          |e - e_exact| <= {:.1e}  ({})",
            est.bound,
            if parts.is_empty() {
                "exact".to_string()
            } else {
                parts.join(", ")
            }
        );
    }
    if let Some(line) = chain_error_line(o).filter(|_| o.error_estimate.is_none()) {
        let _ = writeln!(s, "  error bound          {line}");
    }
    if let Some(v) = o.restitution_from_velocity {
        let _ = writeln!(s, "  e from mean velocity {v:.12}");
    }
    let _ = write!(
        s,
        "  contact time t_c     {}  (t_c / 2 sum t_i = {:.6}",
        num(o.contact_time),
        o.reduced_contact_time
    );
    if let Some(n1) = o.n1 {
        let _ = write!(s, ", n1 = {n1:.6}");
    }
    let _ = writeln!(s, ")");
    // the error bound is on e; a merged lattice moves the small fronts
    // that decide a chatter's shortest flights, so its count is its own
    let merged = o.truncation.is_some_and(|t| t.merged_fronts > 0);
    let lattice = if merged && o.separations > 1 {
        "; counted on the merged lattice, not bounded: finer lattices may count otherwise"
    } else {
        ""
    };
    let _ = writeln!(
        s,
        "  bounces N_b          {}  ({} separation{}{lattice})",
        o.bounces,
        o.separations,
        if o.separations == 1 { "" } else { "s" }
    );
    let contacts: Vec<String> = o
        .contacts
        .iter()
        .take(8)
        .map(|c| format!("[{}, {}]", num(c[0]), num(c[1])))
        .collect();
    let more = if o.contacts.len() > 8 {
        format!(" ... ({} in all)", o.contacts.len())
    } else {
        String::new()
    };
    let _ = writeln!(s, "  contacts             {}{more}", contacts.join(" "));
    let transits: Vec<String> = o
        .transit_times
        .iter()
        .enumerate()
        .map(|(i, t)| format!("t{} = {}", i + 1, num(*t)))
        .collect();
    let _ = writeln!(s, "  transit times        {}", transits.join(", "));
    let stop = match o.stop_reason {
        StopReason::Escaped => "free for good (no further contact is possible)",
        StopReason::Horizon => "horizon reached, rod free",
        StopReason::HorizonInContact => "horizon reached IN CONTACT: t_c is only a lower bound",
        StopReason::RestsOnWall => {
            "at rest against the wall for good (held by the paper's wall law): e = 0 up to the energy left"
        }
    };
    let _ = writeln!(s, "  stopped at t = {}  {stop}", num(o.end_time));
    if let Some(events) = o.events {
        let rate = events as f64 / o.seconds.max(1e-12);
        let _ = write!(
            s,
            "  work                 {events} events in {} ({:.1} M events/s)",
            seconds(o.seconds),
            rate / 1e6
        );
        if let Some(t) = o.truncation {
            let _ = write!(
                s,
                "; dropped {} fronts (sum of velocity jumps {:.1e} v_b), merged {}",
                t.dropped_fronts, t.dropped_velocity, t.merged_fronts
            );
        }
        let blocks = o
            .error_estimate
            .as_ref()
            .map_or(&[][..], |e| &e.answered_blocks[..]);
        let nested = o
            .error_estimate
            .as_ref()
            .map_or(&[][..], |e| &e.nested_layers[..]);
        for [a, b] in blocks {
            // their fronts are traced once, outside the event count
            let _ = write!(
                s,
                "; the layers of t{} to t{} answered as one block by its traced response",
                a + 1,
                b + 1
            );
            for f in nested.iter().filter(|&&f| (*a..=*b).contains(&f)) {
                let _ = write!(s, ", t{} within it by its own", f + 1);
            }
        }
        let _ = writeln!(s);
    }
    if let Some(steps) = o.steps {
        let _ = writeln!(
            s,
            "  work                 {steps} steps in {}",
            seconds(o.seconds)
        );
    }
    s
}

/// A rate or count to three significant digits, never rounded to zero:
/// `0.355`, `35.5`, `35500`.
pub fn three_digits(v: f64) -> String {
    if !v.is_finite() || v == 0.0 {
        return format!("{v}");
    }
    let decimals = (2 - v.abs().log10().floor() as i32).max(0) as usize;
    format!("{v:.decimals$}")
}

#[cfg(test)]
mod tests {
    #[test]
    fn three_digits_never_rounds_a_rate_to_zero() {
        assert_eq!(super::three_digits(0.3549), "0.355");
        assert_eq!(super::three_digits(35.49), "35.5");
        assert_eq!(super::three_digits(35490.0), "35490");
        assert_eq!(super::three_digits(0.0), "0");
    }
}
