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

/// `page` with what a run cannot repeat masked: in every table, the cells
/// of the columns headed by one of `time_columns` (wall-clock times), and
/// every line containing one of `time_lines` (replaced by the marker
/// alone). Two runs of a seeded experiment give the same stable page.
#[must_use]
pub fn stable(page: &str, time_columns: &[&str], time_lines: &[&str]) -> String {
    let mut out = String::new();
    // Column indices to mask in the current table.
    let mut masked: Vec<usize> = Vec::new();
    let mut in_table = false;
    for line in page.lines() {
        let is_row = line.starts_with('|');
        if let Some(marker) = time_lines.iter().find(|m| line.contains(**m)) {
            out.push_str(marker);
        } else if is_row && !in_table {
            // A header row: find the columns to mask.
            masked = line
                .split('|')
                .enumerate()
                .filter(|(_, h)| time_columns.contains(&h.trim()))
                .map(|(i, _)| i)
                .collect();
            out.push_str(line);
        } else if is_row {
            let cells: Vec<&str> = line
                .split('|')
                .enumerate()
                .map(|(i, c)| {
                    if masked.contains(&i) && !c.contains("---") {
                        " * "
                    } else {
                        c
                    }
                })
                .collect();
            out.push_str(&cells.join("|"));
        } else {
            out.push_str(line);
        }
        in_table = is_row;
        out.push('\n');
    }
    out
}

/// Compares a freshly generated page with the committed one after
/// [`stable`]; `Err` names the first line that differs.
///
/// # Errors
/// The first differing line of the two stable pages.
pub fn same_page(
    name: &str,
    generated: &str,
    time_columns: &[&str],
    time_lines: &[&str],
) -> Result<(), String> {
    let file = crate::root().join(format!("docs/reproduction/{name}.md"));
    let committed =
        std::fs::read_to_string(&file).map_err(|e| format!("{}: {e}", file.display()))?;
    let (a, b) = (
        stable(generated, time_columns, time_lines),
        stable(&committed, time_columns, time_lines),
    );
    if a == b {
        return Ok(());
    }
    let (la, lb): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    let k = (0..la.len().max(lb.len()))
        .find(|&k| la.get(k) != lb.get(k))
        .unwrap_or(0);
    Err(format!(
        "docs/reproduction/{name}.md drifted from `cargo xtask reproduce {name}` at line {}:\n  generated: {}\n  committed: {}",
        k + 1,
        la.get(k).unwrap_or(&""),
        lb.get(k).unwrap_or(&"")
    ))
}

/// The directory of the reproduction pages.
pub(crate) fn dir() -> anyhow::Result<std::path::PathBuf> {
    let d = crate::root().join("docs/reproduction");
    std::fs::create_dir_all(&d)?;
    Ok(d)
}

/// Where a page's figures go: `figures`, or (for a drift test, which wants
/// the page alone) a scratch folder removed when the guard drops.
pub(crate) struct FigureDir {
    path: std::path::PathBuf,
    scratch: bool,
}

impl FigureDir {
    /// `figures`, or a new scratch folder named after the page `name`.
    pub(crate) fn new(figures: Option<&std::path::Path>, name: &str) -> anyhow::Result<Self> {
        Ok(match figures {
            Some(f) => Self {
                path: f.to_path_buf(),
                scratch: false,
            },
            None => {
                let path = std::env::temp_dir()
                    .join(format!("oxcover-{name}-figures-{}", std::process::id()));
                std::fs::create_dir_all(&path)?;
                Self {
                    path,
                    scratch: true,
                }
            }
        })
    }

    /// The path of the figure `file` in this folder.
    pub(crate) fn join(&self, file: &str) -> std::path::PathBuf {
        self.path.join(file)
    }
}

impl Drop for FigureDir {
    fn drop(&mut self) {
        if self.scratch {
            let _ = std::fs::remove_dir_all(&self.path);
        }
    }
}

/// Quantile (nearest rank, `q` in 0..=1) of sorted values.
pub(crate) fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let i = ((sorted.len() - 1) as f64 * q).round() as usize;
    sorted[i.min(sorted.len() - 1)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stable_masks_time_columns_and_lines_only() {
        let page = "intro 3 maps\n| map | moves | s |\n|---|---:|---:|\n| a | 12 | 0.7 |\n\n*Generated in 5 s.*\n";
        let other = page.replace("0.7", "1.9").replace("5 s", "8 s");
        let cols = ["s"];
        let lines = ["*Generated"];
        assert_eq!(stable(page, &cols, &lines), stable(&other, &cols, &lines));
        let moved = page.replace("12", "13");
        assert_ne!(stable(page, &cols, &lines), stable(&moved, &cols, &lines));
        let intro = page.replace("3 maps", "4 maps");
        assert_ne!(stable(page, &cols, &lines), stable(&intro, &cols, &lines));
    }
}
