//! Validation reports: where the exact engine and the chain agree across the
//! `(x, alpha)` grid, where they do not, and why.
//!
//! Architecture invariant: the report knows the engines only through their
//! `Outcome`s and settings; it draws with `impact-plot`.

#![warn(missing_docs)]

pub mod compare;
pub mod html;
pub mod write;

pub use compare::{ComparePoint, CompareSettings, Summary, Verdict, compare_point, summarize};
pub use write::write_report;
