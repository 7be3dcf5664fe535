//! What the paper states, what we find, and whether they agree.

use serde::Serialize;

/// The verdict on one statement, computed from the numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Our numbers support the statement.
    Agrees,
    /// Our numbers contradict it; `comment` says which side is right.
    Disagrees,
}

/// One statement of the paper set against our numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Claim {
    /// The paper's words (or their gist) and where.
    pub statement: String,
    /// What the paper gives.
    pub paper: String,
    /// What we find.
    pub ours: String,
    /// Whether they agree, computed from the numbers.
    pub verdict: Verdict,
    /// When they disagree: which side the evidence supports, and why.
    pub comment: String,
}

impl Claim {
    /// A claim whose verdict is `agrees` (computed by the caller).
    pub fn new(statement: &str, paper: &str, ours: String, agrees: bool, comment: &str) -> Self {
        Self {
            statement: statement.into(),
            paper: paper.into(),
            ours,
            verdict: if agrees {
                Verdict::Agrees
            } else {
                Verdict::Disagrees
            },
            comment: comment.into(),
        }
    }
}

/// One figure (or group) of the reproduction.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Item {
    /// Short identifier (`fig2`), the anchor on the report page.
    pub id: String,
    /// Heading on the report page.
    pub title: String,
    /// Figure stems written (each as `.svg` and `.png`).
    pub figures: Vec<String>,
    /// Data files written (CSV), relative to the report directory.
    pub data: Vec<String>,
    /// The paper's statements beside our numbers.
    pub claims: Vec<Claim>,
    /// How the figure was made (engine, sizes, units), for the reader.
    pub notes: Vec<String>,
}

/// Writes `stem.svg` and `stem.png` into `dir`, returning the stem.
pub fn figure(dir: &std::path::Path, stem: &str, svg: &str) -> Result<String, crate::PaperError> {
    // stems may name a subdirectory (e.g. `cost/pareto`)
    impact_plot::write_svg_and_png(&dir.join(stem), svg)?;
    Ok(stem.to_string())
}

/// Writes `stem.csv` into `dir`: the comma-separated column names of
/// `header`, then rows of numbers (empty cells where not finite). The rows
/// come as any iterator, so a figure maps its points straight into them.
pub fn csv(
    dir: &std::path::Path,
    stem: &str,
    header: &str,
    rows: impl IntoIterator<Item = Vec<f64>>,
) -> Result<String, crate::PaperError> {
    let columns: Vec<&str> = header.split(',').collect();
    let rows: Vec<Vec<f64>> = rows.into_iter().collect();
    let text = impact_output::numbers_csv(&columns, &rows)?;
    let name = format!("{stem}.csv");
    std::fs::write(dir.join(&name), text)?;
    Ok(name)
}

/// Writes a curve of `(x, y)` points as the two-column `stem.csv` (see
/// [`csv`]): the data file of every figure that draws one plain curve.
pub fn curve_csv(
    dir: &std::path::Path,
    stem: &str,
    header: &str,
    points: &[(f64, f64)],
) -> Result<String, crate::PaperError> {
    csv(dir, stem, header, points.iter().map(|&(x, y)| vec![x, y]))
}
