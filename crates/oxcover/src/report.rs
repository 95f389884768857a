//! The JSON reports of `plan --report` and `simulate --report`, and the
//! human-readable metric rows.
//!
//! The report is the metrics object of `eval` plus the planner's name, its
//! parameters, `plan_ms`, and the coverage before the boundary pass (so paper
//! reproductions can show the raw planner); `PlanOutcome::report` in
//! [`crate::pipeline`] fills it.

use serde::Serialize;

use crate::metrics::Metrics;

/// Parameters a plan was made with.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PlanParameters {
    /// The map file.
    pub map: String,
    /// Robot radius in metres.
    pub robot_radius: f64,
    /// Tool radius in metres.
    pub tool_radius: f64,
    /// Map resolution in metres per cell.
    pub resolution: f64,
    /// Start `[x, y]` in metres (the path's first waypoint).
    pub start: [f64; 2],
    /// Seed.
    pub seed: u64,
    /// Whether the boundary pass ran.
    pub boundary_pass: bool,
    /// Whether the plan was asked to go room by room.
    pub rooms: bool,
    /// Linear speed for `est_time_s` (m/s).
    pub speed: f64,
    /// Turning rate for `est_time_s` (rad/s).
    pub turn_rate: f64,
    /// The fixed sweep angle in degrees, when one was asked for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sweep_angle_deg: Option<f64>,
    /// Side of a coverage cell in metres (one tool diameter, at least one map cell).
    pub coverage_cell_m: f64,
}

/// Boundary-pass statistics.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BoundaryStats {
    /// Coverable cells the planner left uncovered.
    pub pending_cells: usize,
    /// Anchor cells chosen to cover them.
    pub anchors: usize,
    /// Fine cells the pass appended.
    pub appended_cells: usize,
    /// Length the pass added (m): the finished path's segments that end at
    /// one of its waypoints.
    pub length_m: f64,
    /// Its share of the path's length.
    pub length_share: f64,
}

/// The `plan --report` object.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PlanReport {
    /// Planner name.
    pub planner: String,
    /// Parameters.
    pub parameters: PlanParameters,
    /// Planning time in milliseconds.
    pub plan_ms: f64,
    /// Coverage of the planner's own path.
    pub coverage_without_boundary_pass: f64,
    /// What the boundary pass did (null when off).
    pub boundary: Option<BoundaryStats>,
    /// Room units planned one after another (null: the whole map at once,
    /// because rooms were off or the map has one room).
    pub room_units: Option<usize>,
    /// The coverage target's cells (absent without targets).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub targets: Option<crate::targets::TargetSummary>,
    /// The metrics of the final path (flattened into the object).
    #[serde(flatten)]
    pub metrics: Metrics,
}

/// The `simulate --report` object: the metrics of the EXECUTED trajectory
/// and how it was executed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SimulateReport {
    /// Planner name.
    pub planner: String,
    /// Tracking controller (`kanayama` or `klancar`).
    pub controller: String,
    /// Control step (s).
    pub dt: f64,
    /// Odometry noise `σ`.
    pub odometry_noise: f64,
    /// Duration of the run (s).
    pub duration_s: f64,
    /// Energy used (J).
    pub energy_j: f64,
    /// Root-mean-square tracking error (m).
    pub tracking_rms_m: f64,
    /// Largest tracking error (m).
    pub tracking_max_m: f64,
    /// Coverage of the plan itself, for comparison.
    pub planned_coverage: f64,
    /// Set when the run ended at its time cap short of the path's end with
    /// less coverage than the plan (`null` otherwise).
    pub warning: Option<String>,
    /// The metrics of the executed trajectory (flattened into the object).
    #[serde(flatten)]
    pub metrics: Metrics,
}

/// `(key, value)` rows for tables and legends.
#[must_use]
pub fn metric_rows(m: &Metrics) -> Vec<(String, String)> {
    let mut rows = vec![
        ("coverage".to_string(), format!("{:.4}", m.coverage)),
        ("collisions".to_string(), m.collisions.to_string()),
        ("length_m".to_string(), format!("{:.2}", m.length_m)),
        ("turns".to_string(), m.turns.to_string()),
        ("rotation_rad".to_string(), format!("{:.1}", m.rotation_rad)),
        (
            "redundancy".to_string(),
            m.redundancy
                .map_or_else(|| "-".to_string(), |r| format!("{r:.3}")),
        ),
        ("steps".to_string(), format!("{:.0}", m.steps)),
        ("est_time_s".to_string(), format!("{:.0}", m.est_time_s)),
        ("bound_time_s".to_string(), format!("{:.0}", m.bound_time_s)),
        (
            "time_efficiency".to_string(),
            m.time_efficiency
                .map_or_else(|| "-".to_string(), |r| format!("{r:.3}")),
        ),
    ];
    rows.push((
        "covered".to_string(),
        format!("{}/{}", m.covered_cells, m.coverable_cells),
    ));
    rows
}

/// A two-column text table.
#[must_use]
pub fn table(rows: &[(String, String)]) -> String {
    let kw = rows.iter().map(|(k, _)| k.len()).max().unwrap_or(0);
    let vw = rows.iter().map(|(_, v)| v.len()).max().unwrap_or(0);
    rows.iter()
        .map(|(k, v)| format!("  {k:<kw$}  {v:>vw$}\n"))
        .collect()
}
