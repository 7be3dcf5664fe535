//! The report's self-contained page: summary, figures inlined as SVG, the
//! worst points and every verdict. Written as well-formed XML (XHTML), no
//! scripts, styles or images fetched from anywhere.

use crate::compare::{ComparePoint, Summary};
use impact_output::{Head, Layout, Stylesheet, escape};
use std::fmt::Write as _;

fn f(v: Option<f64>, digits: usize) -> String {
    v.map_or_else(|| "-".to_string(), |v| format!("{v:.digits$}"))
}

/// The page, with `figures` (SVG documents) inlined.
pub fn page(
    settings: &serde_json::Value,
    summary: &Summary,
    points: &[ComparePoint],
    figures: &[&str],
) -> String {
    let mut h = String::new();
    let _ = write!(
        h,
        r#"<h1>Exact engine vs discrete chain</h1>
<p>Each point of the <code>(x, alpha)</code> grid was run with the exact front-tracing engine and with the chain; differences are chain minus exact, at the largest chain size.</p>
<h2>Summary</h2>
<table>
<tr><th>points</th><td>{}</td></tr>
<tr><th>max |de|</th><td>{:.3e}</td></tr>
<tr><th>median |de|</th><td>{:.3e}</td></tr>
<tr><th>filtered N_b equal</th><td>{:.1}%</td></tr>
<tr><th>within every tolerance</th><td>{:.1}%</td></tr>
<tr><th>failed</th><td>{}</td></tr>
</table>
<h2>Verdicts</h2>
<table><tr><th>verdict</th><th>points</th><th class="l">meaning</th></tr>
"#,
        summary.points,
        summary.max_abs_de,
        summary.median_abs_de,
        100.0 * summary.bounces_agree,
        100.0 * summary.agree,
        summary.failed
    );
    for (v, count) in &summary.verdicts {
        let _ = writeln!(
            h,
            r#"<tr><td class="l">{}</td><td>{count}</td><td class="l">{}</td></tr>"#,
            v.name(),
            escape(v.explanation())
        );
    }
    h.push_str("</table>\n<h2>Maps</h2>\n<div class=\"figs\">\n");
    for fig in figures {
        // inline the figure without its XML prologue-free root as is
        h.push_str(fig);
    }
    h.push_str("</div>\n<h2>Worst points</h2>\n<table>\n<tr><th>x</th><th>alpha</th><th>e exact</th><th>e chain</th><th>de</th><th>e extrapolated</th><th>order</th><th>N_b exact</th><th>N_b chain</th><th>reduced t_c exact</th><th>reduced t_c chain</th><th class=\"l\">verdict</th></tr>\n");
    for &i in &summary.worst {
        let p = &points[i];
        let (ex, ch) = (p.exact.as_ref(), p.finest());
        let _ = writeln!(
            h,
            r#"<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class="l">{}</td></tr>"#,
            p.x,
            p.alpha,
            f(ex.map(|o| o.restitution), 6),
            f(ch.map(|o| o.restitution), 6),
            f(p.de(), 6),
            f(p.extrapolated_restitution, 6),
            f(p.observed_order, 2),
            ex.map_or("-".into(), |o| o.bounces.to_string()),
            ch.map_or("-".into(), |o| o.bounces.to_string()),
            f(ex.map(|o| o.reduced_contact_time), 4),
            f(ch.map(|o| o.reduced_contact_time), 4),
            p.verdict.name()
        );
    }
    let settings = serde_json::to_string_pretty(settings).unwrap_or_default();
    let _ = write!(
        h,
        "</table>\n<h2>Settings</h2>\n<pre>{}</pre>\n<p>Every point is in <code>report.json</code> and <code>points.csv</code> beside this page.</p>\n",
        escape(&settings)
    );
    impact_output::page(
        &Head {
            title: "impact compare: exact engine vs chain",
            style: Stylesheet::shared()
                .extend("body", "color: #222;")
                .extend("table", "margin: 1em 0;")
                .rule(
                    "td, th",
                    "border: 1px solid #bbb; padding: 3px 8px; text-align: right;",
                )
                .rule("td.l", "text-align: left;")
                .rule(
                    ".figs svg",
                    "max-width: 640px; height: auto; margin-right: 1em;",
                )
                .rule("code", "background: #f4f4f4; padding: 0 3px;"),
            layout: Layout::Spread,
        },
        &h,
    )
}
