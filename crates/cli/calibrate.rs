//! `impact calibrate`: the paper's layer restitution `e_i` and `tau c / L`.

use crate::args::CalibrateArgs;
use crate::input;
use crate::jobs::Bar;
use crate::output::write_atomically;
use impact_chain::calibrate::{calibration_grid, calibration_point};
use impact_model::calibration;
use impact_study::par_map;

pub fn calibrate(a: CalibrateArgs) -> anyhow::Result<()> {
    let law = a.wall_contact;
    let (lowest, widest) = calibration::range(law);
    let outside = |flag: &str, range: String, got: f64| {
        input(format!(
            "--{flag} must be a number in {range} (the calibrated range; got {got})"
        ))
    };
    if let Some(e) = a.restitution {
        let t = calibration::tau_c_over_l(law, e)
            .ok_or_else(|| outside("restitution", format!("[{lowest:.4}, 1]"), e))?;
        return print(&a, "restitution", e, "tau_c_over_l", t);
    }
    if let Some(t) = a.tau_c_over_l {
        let e = calibration::restitution(law, t)
            .ok_or_else(|| outside("tau-c-over-l", format!("[0, {widest}]"), t))?;
        return print(&a, "tau_c_over_l", t, "restitution", e);
    }
    if a.masses < 2 {
        return Err(input(format!("--n must be at least 2 (got {})", a.masses)));
    }
    let grid = calibration_grid(law);
    eprintln!(
        "calibrating {} points with chains of {} and {} masses...",
        grid.len(),
        a.masses,
        2 * a.masses
    );
    let start = std::time::Instant::now();
    let points = par_map(&grid, &Bar::new("points"), |&t| {
        calibration_point(t, a.masses, law)
    })
    .into_iter()
    .collect::<Result<Vec<_>, _>>()?;
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| format!("data/calibration/kelvin-voigt-{law}.csv").into());
    let comment = format!(
        "Restitution of a homogeneous Kelvin-Voigt rod vs tau c / L (paper Sec. IV, Fig. 2).\n\
         Wall contact law: {}.\n\
         Written by `impact calibrate --regenerate --wall-contact {law} --n {}` in {:.0} s.\n\
         Each entry: the chain at N = {} and {} masses, Richardson-extrapolated (first order in N);\n\
         richardson_correction is the size of that correction, an estimate of the error left.",
        law.describe(),
        a.masses,
        start.elapsed().as_secs_f64(),
        a.masses,
        2 * a.masses
    );
    let entries: Vec<calibration::TableEntry> = points
        .iter()
        .map(|p| calibration::TableEntry {
            tau_c_over_l: p.tau_c_over_l,
            restitution: p.restitution,
            richardson_correction: p.correction,
        })
        .collect();
    write_atomically(&out, |w| calibration::write_table(w, &comment, &entries))?;
    eprintln!(
        "wrote {} in {:.1} s; rebuild to use it",
        out.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

fn print(a: &CalibrateArgs, from: &str, x: f64, to: &str, y: f64) -> anyhow::Result<()> {
    if a.json {
        println!("{{\"{from}\":{x},\"{to}\":{y}}}");
    } else {
        println!("{from} = {x}  ->  {to} = {y:.6}");
    }
    Ok(())
}
