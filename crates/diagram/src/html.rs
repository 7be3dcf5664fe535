//! A self-contained page: the diagram with tooltips, and the event table.

use crate::figure::{Diagram, DiagramOptions, Picture};
use impact_output::{FONT, Head, Layout, Stylesheet, escape};
use impact_wave::Direction;
use std::fmt::Write as _;

/// Rows of the event table kept at most (the page says how many were left).
const MAX_ROWS: usize = 5_000;

/// The page: the figure (with `<title>` tooltips on fronts and events) and a
/// table of every front's birth (time, place, kind, amplitude, parents) and
/// every contact event.
pub fn page(d: &Diagram, options: &DiagramOptions) -> String {
    let svg = d.to_svg(&DiagramOptions {
        tooltips: true,
        ..options.clone()
    });
    let mut h = String::new();
    let _ = write!(
        h,
        r#"<h1>{}</h1>
<p>Point at a front or an event for its amplitude and ancestry. e = {:.9}, t_c = {:.6}, N_b = {} ({} separations).</p>
{svg}
<h2>Events</h2>
<table><tr><th>time</th><th>place</th><th class="l">kind</th><th>strain jump</th><th class="l">front</th><th class="l">parents</th></tr>
"#,
        escape(&d.title),
        d.outcome.restitution,
        d.outcome.contact_time,
        d.outcome.bounces,
        d.outcome.separations
    );
    let mut rows: Vec<(f64, String)> = Vec::new();
    for (i, c) in d.outcome.contacts.iter().enumerate() {
        if i > 0 {
            rows.push((c[0], format!(r#"<tr><td>{:.6}</td><td>0</td><td class="l">reconnection</td><td></td><td class="l"></td><td class="l"></td></tr>"#, c[0])));
        }
        let kind = if i + 1 == d.outcome.contacts.len() {
            "final takeoff"
        } else {
            "separation"
        };
        rows.push((c[1], format!(r#"<tr><td>{:.6}</td><td>0</td><td class="l">{kind}</td><td></td><td class="l"></td><td class="l"></td></tr>"#, c[1])));
    }
    let layers = d.rod.layers();
    for (_, p) in &d.pictures {
        let Picture::Exact { fronts, .. } = p else {
            continue;
        };
        for f in fronts {
            let l = &layers[f.layer];
            let place = match f.direction {
                Direction::Up => l.bottom,
                Direction::Down => l.top,
            };
            let kind = match (f.parents.is_empty(), f.born == 0.0) {
                (true, true) => "impact",
                (true, false) => "landing",
                _ if place == 0.0 => "wall reflection",
                _ if place == d.rod.total_length() => "top reflection",
                _ => "interface",
            };
            let dir = if f.direction == Direction::Up {
                "up"
            } else {
                "down"
            };
            rows.push((
                f.born,
                format!(
                    r#"<tr id="front-{}"><td>{:.6}</td><td>{:.4}</td><td class="l">{kind}</td><td>{:.4e}</td><td class="l">{} ({dir}, layer {})</td><td class="l">{:?}</td></tr>"#,
                    f.id,
                    f.born,
                    place,
                    f.jump,
                    f.id,
                    f.layer + 1,
                    f.parents
                ),
            ));
        }
    }
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total = rows.len();
    for (_, r) in rows.iter().take(MAX_ROWS) {
        h.push_str(r);
        h.push('\n');
    }
    h.push_str("</table>\n");
    if total > MAX_ROWS {
        let _ = writeln!(h, "<p>{} more events not listed.</p>", total - MAX_ROWS);
    }
    impact_output::page(
        &Head {
            title: &d.title,
            style: Stylesheet::shared()
                .rule("body", &format!("{FONT} margin: 1.5em;"))
                .rule(
                    "td, th",
                    "border: 1px solid #bbb; padding: 2px 6px; text-align: right;",
                )
                .rule("td.l", "text-align: left;")
                .rule(
                    "line.front:hover",
                    "stroke: #e08214; stroke-width: 2.5; stroke-opacity: 1;",
                ),
            layout: Layout::Compact,
        },
        &h,
    )
}
