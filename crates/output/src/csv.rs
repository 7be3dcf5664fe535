//! CSV through the `csv` crate and serde: a table's header is the field
//! names of its row struct, declared once.
//!
//! Numbers: the `csv` crate writes floats with `ryu` (`1.0`, `1e-7`); a
//! field wrapped in [`Plain`] is written as Rust's `Display` writes it (`1`,
//! `0.0000001`), the shortest text that reads back to the same number.

use serde::{Serialize, Serializer};
use std::fmt::Display;
use std::io::Write;

/// A value written as its `Display` text (for floats: `1`, not `1.0`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plain<T>(pub T);

impl<T: Display> Serialize for Plain<T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(&self.0)
    }
}

/// The one dialect: comma-separated, `\n`-terminated, a cell quoted only
/// where it must be (a comma, a quote or a line break inside), quotes
/// doubled.
fn writer<W: Write>(out: W) -> csv::Writer<W> {
    csv::WriterBuilder::new()
        .quote_style(csv::QuoteStyle::Necessary)
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(out)
}

/// Writes `rows` to `out`: a header of the row type's field names, then one
/// line per row. No rows, no header (the names come from a row).
pub fn write_csv<T: Serialize, W: Write>(
    out: W,
    rows: impl IntoIterator<Item = T>,
) -> std::io::Result<()> {
    let mut w = writer(out);
    for row in rows {
        w.serialize(row)?;
    }
    w.flush()
}

/// The text of [`write_csv`].
pub fn to_csv<T: Serialize>(rows: impl IntoIterator<Item = T>) -> std::io::Result<String> {
    let mut text = Vec::new();
    write_csv(&mut text, rows)?;
    String::from_utf8(text).map_err(std::io::Error::other)
}

/// A table of numbers under a header of column names: `Display` text, and
/// an empty cell where a number is not finite.
pub fn numbers_csv(header: &[&str], rows: &[Vec<f64>]) -> std::io::Result<String> {
    let mut text = Vec::with_capacity(rows.len() * 40);
    {
        let mut w = writer(&mut text);
        w.write_record(header)?;
        for row in rows {
            w.write_record(row.iter().map(|v| {
                if v.is_finite() {
                    v.to_string()
                } else {
                    String::new()
                }
            }))?;
        }
        w.flush()?;
    }
    String::from_utf8(text).map_err(std::io::Error::other)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Serialize)]
    struct Row<'a> {
        x: Plain<f64>,
        ryu: f64,
        count: u64,
        label: &'a str,
        maybe: Option<Plain<f64>>,
        #[serde(skip_serializing_if = "Option::is_none")]
        timing: Option<Option<Plain<f64>>>,
    }

    fn row(x: f64, label: &str, maybe: Option<f64>, timing: Option<Option<f64>>) -> Row<'_> {
        Row {
            x: Plain(x),
            ryu: x,
            count: 3,
            label,
            maybe: maybe.map(Plain),
            timing: timing.map(|t| t.map(Plain)),
        }
    }

    #[test]
    fn floats_are_written_as_display_writes_them() {
        let text = to_csv([
            row(1.0, "a", Some(1e-7), None),
            row(0.1 + 0.2, "b", None, None),
        ])
        .unwrap();
        assert_eq!(
            text,
            "x,ryu,count,label,maybe\n\
             1,1.0,3,a,0.0000001\n\
             0.30000000000000004,0.30000000000000004,3,b,\n"
        );
    }

    #[test]
    fn a_skipped_column_is_absent_from_header_and_rows_and_none_is_empty() {
        let text = to_csv([
            row(2.0, "a", None, Some(Some(0.5))),
            row(2.0, "b", None, Some(None)),
        ])
        .unwrap();
        assert_eq!(
            text,
            "x,ryu,count,label,maybe,timing\n2,2.0,3,a,,0.5\n2,2.0,3,b,,\n"
        );
    }

    #[test]
    fn cells_are_quoted_only_where_needed() {
        let rows = [
            row(1.0, "a, \"b\"", None, None),
            row(1.0, "line\nbreak", None, None),
        ];
        assert_eq!(
            to_csv(&rows).unwrap(),
            "x,ryu,count,label,maybe\n1,1.0,3,\"a, \"\"b\"\"\",\n1,1.0,3,\"line\nbreak\",\n"
        );
        let plain = [row(0.5, "elastic", Some(2.0), None)];
        assert_eq!(
            to_csv(&plain).unwrap(),
            "x,ryu,count,label,maybe\n0.5,0.5,3,elastic,2\n"
        );
    }

    #[test]
    fn numbers_tables_leave_non_finite_cells_empty() {
        let text = numbers_csv(
            &["n", "e"],
            &[
                vec![1.0, 0.25],
                vec![2.0, f64::NAN],
                vec![f64::INFINITY, 1e21],
            ],
        )
        .unwrap();
        assert_eq!(text, "n,e\n1,0.25\n2,\n,1000000000000000000000\n");
    }
}
