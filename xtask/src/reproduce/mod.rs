//! `cargo xtask reproduce <name>`: the paper experiments. Each writes
//! `docs/reproduction/<name>.md` (tables with the paper's figures beside ours,
//! an SVG figure, the exact command, and a discussion of differences).

mod decomposition_figure;
pub mod demir2018;
pub mod lee2011;
pub mod pavlicek2002;
pub mod pavlicek2002_camera;
pub mod siamantas2010;
pub mod siamantas2010_tracking;
pub mod zhang2008;

/// Runs the named experiment.
///
/// # Errors
/// Unknown names; failures of the experiment.
pub fn run(name: &str) -> anyhow::Result<()> {
    match name {
        "siamantas2010" => siamantas2010::run(),
        "siamantas2010-tracking" => siamantas2010_tracking::run(),
        "zhang2008" => zhang2008::run(),
        "pavlicek2002" => pavlicek2002::run(),
        "floorplans" => pavlicek2002::run_floorplans(),
        "lee2011" => lee2011::run(),
        "demir2018" => demir2018::run(),
        "pavlicek2002-camera" => pavlicek2002_camera::run(),
        other => {
            anyhow::bail!(
                "no experiment named `{other}`: expected siamantas2010, siamantas2010-tracking, zhang2008, pavlicek2002, floorplans, lee2011, demir2018 or pavlicek2002-camera"
            )
        }
    }
}

/// The directory of the reproduction pages.
pub(crate) fn dir() -> anyhow::Result<std::path::PathBuf> {
    let d = crate::root().join("docs/reproduction");
    std::fs::create_dir_all(&d)?;
    Ok(d)
}

/// Quantile (nearest rank, `q` in 0..=1) of sorted values.
pub(crate) fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let i = ((sorted.len() - 1) as f64 * q).round() as usize;
    sorted[i.min(sorted.len() - 1)]
}
