//! `impact merge`: shards of one run joined into what the whole run writes.

use crate::args::MergeArgs;
use crate::compare::{finish, grid_of};
use crate::input;
use crate::output::write_atomically;
use impact_report::ComparePoint;
use impact_study::journal::{header, merge as join};
use impact_study::{Row, RowFormat};

/// Every journal error here is the user's to fix.
fn input_error(e: impact_study::JournalError) -> anyhow::Error {
    input(crate::flags::journal_message(&e))
}

pub fn merge(a: MergeArgs) -> anyhow::Result<()> {
    let first = header(&a.journals[0]).map_err(input_error)?;
    match first.command.as_str() {
        "sweep" => {
            let (h, rows) = join::<Row>(&a.journals).map_err(input_error)?;
            let timing = h.settings["timing"].as_bool().unwrap_or(false);
            let format = RowFormat::from_path(&a.out);
            write_atomically(&a.out, |w| format.write(&rows, timing, w))?;
            eprintln!("wrote {} rows to {}", rows.len(), a.out.display());
            Ok(())
        }
        "compare" => {
            let (h, points) = join::<ComparePoint>(&a.journals).map_err(input_error)?;
            let grid = grid_of(&h.settings)?;
            finish(&a.out, &h.settings, &grid, &points, None)
        }
        other => Err(input(format!(
            "{}: unknown journal command '{other}'",
            a.journals[0].display()
        ))),
    }
}
