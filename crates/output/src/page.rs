//! The page shell: doctype, head (title, stylesheet), body. Pages pass
//! their content; the title is escaped here, and every other text a page
//! interpolates goes through [`escape`].

use std::fmt::Write as _;

/// Escapes text for XML (XHTML, SVG) content and attribute values.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

/// The font every page (and every figure) is set in.
pub const FONT: &str = "font-family: DejaVu Sans, Arial, sans-serif;";

/// A stylesheet: CSS rules in order, each a selector and its declarations.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Stylesheet {
    rules: Vec<(String, String)>,
}

impl Stylesheet {
    /// The shared look: the font, a bounded text width, tables with
    /// collapsed grey borders and right-aligned numbers, grey header cells.
    pub fn shared() -> Self {
        Self {
            rules: vec![
                (
                    "body".into(),
                    format!("{FONT} margin: 2em; max-width: 1300px;"),
                ),
                ("table".into(), "border-collapse: collapse;".into()),
                (
                    "td, th".into(),
                    "border: 1px solid #bbb; padding: 2px 8px; text-align: right;".into(),
                ),
                ("th".into(), "background: #eee;".into()),
            ],
        }
    }

    /// Sets the declarations of `selector`: a rule already there keeps its
    /// place (so the cascade order stays the shared one), else it is added
    /// at the end.
    pub fn rule(mut self, selector: &str, declarations: &str) -> Self {
        match self.rules.iter_mut().find(|(s, _)| s == selector) {
            Some((_, d)) => *d = declarations.to_string(),
            None => self.rules.push((selector.into(), declarations.into())),
        }
        self
    }

    /// Adds declarations to the rule of `selector` (a new rule if absent).
    pub fn extend(mut self, selector: &str, declarations: &str) -> Self {
        match self.rules.iter_mut().find(|(s, _)| s == selector) {
            Some((_, d)) => {
                d.push(' ');
                d.push_str(declarations);
            }
            None => self.rules.push((selector.into(), declarations.into())),
        }
        self
    }

    fn render(&self, separator: &str) -> String {
        self.rules
            .iter()
            .map(|(s, d)| format!("{s} {{ {d} }}"))
            .collect::<Vec<_>>()
            .join(separator)
    }
}

/// Where the shell breaks lines. Each existing page keeps the whitespace it
/// was first written with, so that its bytes do not change; a new page
/// should use [`Layout::Compact`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// Every head element and every CSS rule on its own line (the compare
    /// report).
    Spread,
    /// The head on two lines, the rules on one (the reproduction, diagrams).
    Compact,
    /// As `Compact`, with `<head>` and `</head>` joined to their neighbours
    /// (the cost report).
    Dense,
}

/// Every page opens so: an HTML5 doctype and XHTML's namespace, so that a
/// page is also well-formed XML (the tests parse them as such).
const OPENING: &str = "<!DOCTYPE html>\n<html xmlns=\"http://www.w3.org/1999/xhtml\" lang=\"en\">";

/// The head of a page.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Head<'a> {
    /// Plain text: escaped by [`page`].
    pub title: &'a str,
    /// The stylesheet in `<style>`: the shared one, extended or overridden.
    pub style: Stylesheet,
    /// Where the shell breaks lines (kept per page so its bytes do not change).
    pub layout: Layout,
}

/// A complete, self-contained XHTML page around `body` (markup that ends
/// with a newline).
pub fn page(head: &Head, body: &str) -> String {
    let title = escape(head.title);
    let mut h = String::with_capacity(body.len() + 1024);
    h.push_str(OPENING);
    let _ = match head.layout {
        Layout::Spread => write!(
            h,
            "\n<head>\n<meta charset=\"utf-8\"/>\n<title>{title}</title>\n<style>\n{}\n</style>\n</head>\n<body>\n",
            head.style.render("\n")
        ),
        Layout::Compact => write!(
            h,
            "\n<head><meta charset=\"utf-8\"/><title>{title}</title>\n<style>{}</style>\n</head><body>\n",
            head.style.render(" ")
        ),
        Layout::Dense => write!(
            h,
            "<head><meta charset=\"utf-8\"/><title>{title}</title>\n<style>{}</style></head><body>\n",
            head.style.render(" ")
        ),
    };
    h.push_str(body);
    h.push_str(match head.layout {
        Layout::Spread => "</body>\n</html>\n",
        Layout::Compact | Layout::Dense => "</body></html>\n",
    });
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escape_replaces_the_five_xml_characters() {
        assert_eq!(
            escape(r#"a < b & c > "d" 'e'"#),
            "a &lt; b &amp; c &gt; &quot;d&quot; &apos;e&apos;"
        );
        assert_eq!(escape("tau c / L = 0.1, µ"), "tau c / L = 0.1, µ");
        // escaping twice escapes the ampersands again: escape text once
        assert_eq!(escape("&lt;"), "&amp;lt;");
    }

    #[test]
    fn the_shared_stylesheet_with_a_page_addition() {
        let style = Stylesheet::shared()
            .extend("table", "margin: 1em 0;")
            .rule("code", "padding: 0 3px;");
        assert_eq!(
            style.render("\n"),
            "body { font-family: DejaVu Sans, Arial, sans-serif; margin: 2em; max-width: 1300px; }\n\
             table { border-collapse: collapse; margin: 1em 0; }\n\
             td, th { border: 1px solid #bbb; padding: 2px 8px; text-align: right; }\n\
             th { background: #eee; }\n\
             code { padding: 0 3px; }"
        );
        // a replaced rule keeps its place
        let replaced = Stylesheet::shared().rule("body", "margin: 0;");
        assert!(
            replaced
                .render(" ")
                .starts_with("body { margin: 0; } table")
        );
    }

    #[test]
    fn the_shell_escapes_the_title_and_closes_the_page() {
        let style = Stylesheet::shared().rule("th", "x: y;");
        let head = |layout| Head {
            title: "e < 1 & \"x\"",
            style: Stylesheet {
                rules: style.rules[3..].to_vec(),
            },
            layout,
        };
        let doctype = OPENING;
        let title = "<title>e &lt; 1 &amp; &quot;x&quot;</title>";
        assert_eq!(
            page(&head(Layout::Spread), "<p>b</p>\n"),
            format!(
                "{doctype}\n<head>\n<meta charset=\"utf-8\"/>\n{title}\n<style>\nth {{ x: y; }}\n</style>\n</head>\n<body>\n<p>b</p>\n</body>\n</html>\n"
            )
        );
        assert_eq!(
            page(&head(Layout::Compact), "<p>b</p>\n"),
            format!(
                "{doctype}\n<head><meta charset=\"utf-8\"/>{title}\n<style>th {{ x: y; }}</style>\n</head><body>\n<p>b</p>\n</body></html>\n"
            )
        );
        assert_eq!(
            page(&head(Layout::Dense), ""),
            format!(
                "{doctype}<head><meta charset=\"utf-8\"/>{title}\n<style>th {{ x: y; }}</style></head><body>\n</body></html>\n"
            )
        );
    }
}
