//! Everything a report writes that is not its content: the HTML page shell
//! with the one text escape, CSV through the `csv` crate with serde (each
//! header declared once, as a struct's fields), and report directories that
//! appear whole or not at all.
//!
//! Architecture invariant: one page shell, one CSV writer. The report,
//! cost, paper and diagram crates build only their content; this crate
//! knows nothing about impacts.

#![warn(missing_docs)]

pub mod csv;
mod dir;
mod page;

pub use crate::csv::{Plain, numbers_csv, to_csv, write_csv};
pub use dir::ReportDir;
pub use page::{FONT, Head, Layout, Stylesheet, escape, page};
