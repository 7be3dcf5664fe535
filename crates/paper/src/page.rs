//! The reproduction's self-contained page.

use crate::claim::{Item, Verdict};
use crate::settings::Settings;
use impact_output::{FONT, Head, Layout, Stylesheet, escape};
use std::fmt::Write as _;

/// Index page: the summary of every claim, then each item with its figures
/// (inlined SVG), data files and claims.
pub fn page(dir: &std::path::Path, settings: &Settings, items: &[Item]) -> String {
    let mut h = String::new();
    let claims: Vec<_> = items
        .iter()
        .flat_map(|i| i.claims.iter().map(move |c| (i, c)))
        .collect();
    let agree = claims
        .iter()
        .filter(|(_, c)| c.verdict == Verdict::Agrees)
        .count();
    let _ = write!(
        h,
        r#"<h1>Impact of composite soft-rigid elastic projectiles: the paper, reproduced</h1>
<p class="mode">Resolution: <b>{label}</b>{quick}. Chain sizes: Fig. 2 N = {n2}, Figs. 8-10 N = {nv}; maps on the paper's grid (step {step}).</p>
<p>{agree} of {total} statements of the paper agree with our numbers; the verdicts below are computed from the numbers, and every disagreement says which side the evidence supports.</p>
<h2>Summary</h2>
<table><tr><th>figure</th><th>the paper</th><th>gives</th><th>we find</th><th>verdict</th></tr>
"#,
        label = settings.resolution,
        quick = if settings.resolution == crate::Resolution::Quick {
            " (smaller chains and coarser scans than the paper's, for a run of a few minutes; --full uses the paper's N = 10^4)"
        } else {
            ""
        },
        n2 = settings.fig2_masses,
        nv = settings.visco_masses,
        step = settings.map_step,
        total = claims.len()
    );
    for (item, c) in &claims {
        let class = if c.verdict == Verdict::Agrees {
            "agrees"
        } else {
            "disagrees"
        };
        let _ = writeln!(
            h,
            r##"<tr class="{class}"><td><a href="#{}">{}</a></td><td>{}</td><td>{}</td><td>{}</td><td>{class}</td></tr>"##,
            escape(&item.id),
            escape(&item.id),
            escape(&c.statement),
            escape(&c.paper),
            escape(&c.ours)
        );
    }
    h.push_str("</table>\n");
    for item in items {
        let _ = writeln!(
            h,
            r#"<h2 id="{}">{}</h2>"#,
            escape(&item.id),
            escape(&item.title)
        );
        for n in &item.notes {
            let _ = writeln!(h, "<p>{}</p>", escape(n));
        }
        h.push_str("<div class=\"figs\">\n");
        for stem in &item.figures {
            // figures are inlined (self-contained); PNG and SVG files sit beside the page
            if let Ok(svg) = std::fs::read_to_string(dir.join(format!("{stem}.svg"))) {
                h.push_str(&svg);
            }
        }
        h.push_str("</div>\n<table><tr><th>the paper</th><th>gives</th><th>we find</th><th>verdict</th><th>which side the evidence supports</th></tr>\n");
        for c in &item.claims {
            let class = if c.verdict == Verdict::Agrees {
                "agrees"
            } else {
                "disagrees"
            };
            let _ = writeln!(
                h,
                r#"<tr class="{class}"><td>{}</td><td>{}</td><td>{}</td><td>{class}</td><td>{}</td></tr>"#,
                escape(&c.statement),
                escape(&c.paper),
                escape(&c.ours),
                escape(&c.comment)
            );
        }
        h.push_str("</table>\n");
        let files: Vec<String> = item
            .figures
            .iter()
            .flat_map(|f| [format!("{f}.svg"), format!("{f}.png")])
            .chain(item.data.iter().cloned())
            .collect();
        let _ = writeln!(h, "<p>Files: {}</p>", escape(&files.join(", ")));
    }
    impact_output::page(
        &Head {
            title: &format!(
                "Impact of composite soft-rigid elastic projectiles: reproduction ({})",
                settings.resolution
            ),
            style: Stylesheet::shared()
                .rule(
                    "body",
                    &format!("{FONT} margin: 2em; max-width: 1400px; color: #222;"),
                )
                .extend("table", "margin: 0.8em 0;")
                .rule(
                    "td, th",
                    "border: 1px solid #bbb; padding: 3px 8px; text-align: left; vertical-align: top;",
                )
                .rule(".agrees", "background: #e5f5e0;")
                .rule(".disagrees", "background: #fde0dd;")
                .rule(
                    ".figs svg",
                    "max-width: 560px; height: auto; margin: 0 1em 1em 0;",
                )
                .rule(".mode", "background: #fff3cd; padding: 0.5em;"),
            layout: Layout::Compact,
        },
        &h,
    )
}
