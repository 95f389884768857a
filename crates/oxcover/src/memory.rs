//! The memory a plan needs, estimated before anything is allocated, and the
//! budget it must fit in.
//!
//! [`estimate`] is a linear model of the peak resident memory of `oxcover
//! plan`: bytes per map cell (the problem's masks and distance transforms,
//! the room segmentation, the metrics' coverage grid) plus bytes per
//! coverage cell (the planner's own structures and the path), plus a fixed
//! part. Its coefficients were measured with `/usr/bin/time -v` on
//! generated 2048² maps at two tool sizes, rooms on and off, and rounded
//! up; `docs/benchmarks.md` ("Memory") has the measurements and the check
//! on a 16384² map. [`PlanRequest::memory_limit`](crate::pipeline::PlanRequest::memory_limit)
//! is checked against it by [`plan`](crate::pipeline::plan), which refuses
//! with [`Error::MemoryLimit`] instead of being killed mid-run.
//!
//! The default budget ([`default_limit`]) is [`DEFAULT_SHARE`] of the
//! machine's memory, or of the control group's limit when that is lower
//! (a container).

use crate::error::{Error, Result};

/// Share of the machine's memory a plan may use by default.
pub const DEFAULT_SHARE: f64 = 0.75;

/// Fixed part of every run (program, tables, pictures), bytes.
const FIXED: f64 = 64.0 * 1024.0 * 1024.0;

/// Bytes per map cell and per coverage cell of each planner's run, rooms
/// off and on: `(planner, [map, coverage] off, [map, coverage] on)`: the
/// measured slopes (peak RSS on 2048² maps, tool radius 0.5 and 2 cells,
/// less a fixed 10 MB) plus 15 %, rounded up. Planners not listed use
/// [`FALLBACK`].
const PER_CELL: &[(&str, [f64; 2], [f64; 2])] = &[
    ("dtc", [26.0, 68.0], [41.0, 68.0]),
    ("rect-priority", [24.0, 163.0], [35.0, 163.0]),
    ("stc", [30.0, 63.0], [41.0, 63.0]),
    ("spiral-stc", [30.0, 66.0], [41.0, 66.0]),
    ("bsa", [30.0, 62.0], [41.0, 62.0]),
    ("boustrophedon", [30.0, 28.0], [43.0, 28.0]),
    ("trapezoidal", [30.0, 28.0], [43.0, 28.0]),
    ("border-expansion", [63.0, 45.0], [63.0, 45.0]),
    ("lanes", [31.0, 29.0], [43.0, 29.0]),
    ("smooth", [71.0, 65.0], [70.0, 65.0]),
];

/// Coefficients for planners without a measurement at this scale (they
/// refuse or take hours on large maps first): the largest measured.
const FALLBACK: [f64; 2] = [63.0, 163.0];

/// Estimated peak memory, in bytes, of planning with `planner` (rooms on or
/// off) on a map of `map_cells` cells whose coverage grid has
/// `coverage_cells` cells.
#[must_use]
pub fn estimate(planner: &str, rooms: bool, map_cells: u64, coverage_cells: u64) -> u64 {
    let [a, b] = PER_CELL
        .iter()
        .find(|(name, _, _)| *name == planner)
        .map_or(FALLBACK, |(_, off, on)| if rooms { *on } else { *off });
    let bytes = FIXED + a * map_cells as f64 + b * coverage_cells as f64;
    bytes.min(u64::MAX as f64) as u64
}

/// The machine's memory in bytes: `MemTotal` of `/proc/meminfo`, or the
/// control group's memory limit when that is lower. `None` where neither
/// can be read.
#[must_use]
pub fn machine_memory() -> Option<u64> {
    let total = std::fs::read_to_string("/proc/meminfo").ok().and_then(|m| {
        m.lines()
            .find_map(|l| l.strip_prefix("MemTotal:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
            .map(|kib| kib.saturating_mul(1024))
    });
    let group = [
        "/sys/fs/cgroup/memory.max",
        "/sys/fs/cgroup/memory/memory.limit_in_bytes",
    ]
    .iter()
    .filter_map(|f| std::fs::read_to_string(f).ok())
    .filter_map(|t| t.trim().parse::<u64>().ok())
    .min();
    match (total, group) {
        (Some(t), Some(g)) => Some(t.min(g)),
        (t, g) => t.or(g),
    }
}

/// The default budget: [`DEFAULT_SHARE`] of [`machine_memory`] (`None`, no
/// limit, where the machine's memory is unknown).
#[must_use]
pub fn default_limit() -> Option<u64> {
    machine_memory().map(|m| (m as f64 * DEFAULT_SHARE) as u64)
}

/// A size such as `8G`, `512M`, `1.5GiB` or `1000000` (bytes); binary units.
///
/// # Errors
/// [`Error::BadParameter`] naming `--memory-limit`.
pub fn parse_size(text: &str) -> Result<u64> {
    let bad = || Error::BadParameter {
        name: "--memory-limit",
        value: text.to_string(),
        expected: "a size such as 8G, 512M or 2000000000 (bytes), above 0".into(),
    };
    let t = text.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let number: f64 = number.parse().map_err(|_| bad())?;
    let scale = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 1.0,
        "k" | "kb" | "kib" => 1024.0,
        "m" | "mb" | "mib" => 1024.0 * 1024.0,
        "g" | "gb" | "gib" => 1024.0 * 1024.0 * 1024.0,
        "t" | "tb" | "tib" => 1024.0 * 1024.0 * 1024.0 * 1024.0,
        _ => return Err(bad()),
    };
    let bytes = number * scale;
    if bytes.is_finite() && bytes >= 1.0 && bytes < u64::MAX as f64 {
        Ok(bytes as u64)
    } else {
        Err(bad())
    }
}

/// `bytes` for people: `512 MiB`, `17.6 GiB`.
#[must_use]
pub fn show(bytes: u64) -> String {
    let b = bytes as f64;
    let gib = 1024.0 * 1024.0 * 1024.0;
    if b >= gib {
        format!("{:.1} GiB", b / gib)
    } else {
        format!("{:.0} MiB", (b / (1024.0 * 1024.0)).max(1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_binary_units() {
        assert_eq!(parse_size("512M").unwrap(), 512 << 20);
        assert_eq!(parse_size("8G").unwrap(), 8 << 30);
        assert_eq!(parse_size("1.5GiB").unwrap(), 3 << 29);
        assert_eq!(parse_size("1000").unwrap(), 1000);
        for bad in ["", "0", "-1G", "8X", "G", "1e999", "nan"] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn estimates_grow_with_the_map_and_the_planner() {
        let n = 16384u64 * 16384;
        let b = estimate("boustrophedon", false, n, n);
        assert!(b > 10 << 30 && b < 20 << 30, "{}", show(b));
        assert!(estimate("rect-priority", false, n, n) > b);
        assert!(estimate("boustrophedon", true, n, n) > b);
        assert!(estimate("boustrophedon", false, n, n / 36) < b);
        assert!(estimate("some-new-planner", true, n, n) >= estimate("rect-priority", true, n, n));
    }

    #[test]
    fn this_machine_has_memory() {
        let m = machine_memory().unwrap();
        assert!(m > 1 << 28);
        assert!(default_limit().unwrap() < m);
    }
}
