//! Closed-loop execution of a planned metre path: time parametrisation,
//! a tracking controller and the differential-drive model at a fixed step
//! ([`oxcover_robot`]), with optional odometry noise, then the contract's
//! metrics on the EXECUTED trajectory.
//!
//! Odometry noise: each wheel's actual rim speed is its command times
//! `1 + ε`, `ε ~ N(0, σ²)` drawn per step from a seeded generator. The
//! controller steers by dead reckoning (the commanded motion), so the true
//! pose drifts from what the robot believes; the true pose is what is
//! recorded and scored. With `σ = 0` both agree.

use oxcover_grid::{DiscRobot, OccupancyGrid, Point};
use oxcover_robot::{
    Controller, Kanayama, Klancar, Limits, Pose, RobotSpec, Timing, TrackingError,
};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::error::{Error, Result};
use crate::metrics::{Evaluation, MetricParams, evaluate};
use crate::report::{SimulateReport, metric_rows};

/// The bundled robot description (`fixtures/robots/floor_cleaner.ron`), the
/// default of `oxcover simulate`.
pub const FLOOR_CLEANER: &str = include_str!("../assets/floor_cleaner.ron");

/// Which tracking controller.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ControllerKind {
    /// Kanayama et al. 1990.
    Kanayama,
    /// Klancar et al. 2005, the nonlinear `sinc` controller.
    Klancar,
}

impl ControllerKind {
    fn build(self) -> Box<dyn Controller> {
        match self {
            Self::Kanayama => Box::new(Kanayama::default()),
            Self::Klancar => Box::new(Klancar::default()),
        }
    }
}

/// How to execute a path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosedLoop {
    /// The robot (drive limits and energy model).
    pub spec: RobotSpec,
    /// The controller.
    pub controller: ControllerKind,
    /// Speed, acceleration and turn-rate limits of the reference.
    pub limits: Limits,
    /// Control step (s).
    pub dt: f64,
    /// Odometry noise `σ` (relative wheel-speed error per step).
    pub odometry_noise: f64,
    /// Seed of the noise.
    pub seed: u64,
}

/// One executed sample, as written to the path file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Executed {
    /// Time (s).
    pub t: f64,
    /// True pose.
    pub pose: Pose,
    /// Commanded speed (m/s).
    pub v: f64,
    /// Commanded turn rate (rad/s).
    pub omega: f64,
    /// Energy used so far (J).
    pub energy: f64,
    /// Distance from the reference position (m).
    pub error: f64,
}

/// An executed run and its scores.
#[derive(Clone, Debug)]
pub struct Run {
    /// Samples at every control step.
    pub samples: Vec<Executed>,
    /// The contract's metrics on the executed positions.
    pub evaluation: Evaluation,
    /// Root-mean-square and largest tracking error (m).
    pub tracking_rms: f64,
    /// Largest tracking error (m).
    pub tracking_max: f64,
    /// Distance from where the robot stopped to the path's last point (m).
    pub end_gap_m: f64,
}

impl Run {
    /// A warning when the run was cut short: it ends at its time cap (the
    /// reference's duration plus a 2 s settle) with the robot farther than
    /// the tool radius from the path's end and coverage below the plan's.
    #[must_use]
    pub fn cut_short(&self, planned_coverage: f64, tool_radius: f64) -> Option<String> {
        let covered = self.evaluation.metrics.coverage;
        (self.end_gap_m > tool_radius.max(0.01) && covered < planned_coverage - 1e-3).then(|| {
            format!(
                "the run ended at its time cap ({:.1} s: the reference's time plus 2 s) {:.2} m short of the path's end, covering {covered:.4} where the plan covers {planned_coverage:.4}; the robot could not keep up with the reference (its wheel speeds or accelerations, the controller)",
                self.duration_s(),
                self.end_gap_m
            )
        })
    }

    /// Duration of the run (s): the last sample's time.
    #[must_use]
    pub fn duration_s(&self) -> f64 {
        self.samples.last().map_or(0.0, |s| s.t)
    }

    /// Energy used (J): the last sample's.
    #[must_use]
    pub fn energy_j(&self) -> f64 {
        self.samples.last().map_or(0.0, |s| s.energy)
    }

    /// The `simulate --report` object of this run of a plan by `planner`
    /// executed as `cfg` says; `planned_coverage` is the plan's own coverage.
    #[must_use]
    pub fn report(&self, planner: &str, cfg: &ClosedLoop, planned_coverage: f64) -> SimulateReport {
        SimulateReport {
            planner: planner.to_string(),
            controller: match cfg.controller {
                ControllerKind::Kanayama => "kanayama",
                ControllerKind::Klancar => "klancar",
            }
            .to_string(),
            dt: cfg.dt,
            odometry_noise: cfg.odometry_noise,
            duration_s: self.duration_s(),
            energy_j: self.energy_j(),
            tracking_rms_m: self.tracking_rms,
            tracking_max_m: self.tracking_max,
            planned_coverage,
            warning: self.cut_short(planned_coverage, self.evaluation.problem.robot.tool_radius),
            metrics: self.evaluation.metrics.clone(),
        }
    }

    /// The table rows of a run: its metrics, then duration, energy and tracking errors.
    #[must_use]
    pub fn rows(&self) -> Vec<(String, String)> {
        let mut rows = metric_rows(&self.evaluation.metrics);
        rows.push(("duration_s".into(), format!("{:.1}", self.duration_s())));
        rows.push(("energy_j".into(), format!("{:.0}", self.energy_j())));
        rows.push(("tracking_rms_m".into(), format!("{:.4}", self.tracking_rms)));
        rows.push(("tracking_max_m".into(), format!("{:.4}", self.tracking_max)));
        rows
    }
}

/// Executes the metre path `points` on `map` and scores the result for the
/// disc `robot` (the metrics' footprint).
///
/// # Errors
/// A bad step (or one giving more than
/// [`oxcover_robot::simulate::MAX_STEPS`] steps), noise or limit
/// ([`Error::BadParameter`]); a path the metrics refuse.
pub fn execute(
    map: &OccupancyGrid,
    robot: DiscRobot,
    points: &[Point],
    cfg: &ClosedLoop,
) -> Result<Run> {
    let bad = |name: &'static str, value: f64, expected: &str| Error::BadParameter {
        name,
        value: value.to_string(),
        expected: expected.into(),
    };
    if !(cfg.dt.is_finite() && cfg.dt > 0.0 && cfg.dt <= 1.0) {
        return Err(bad("--dt", cfg.dt, "a control step in seconds, in (0, 1]"));
    }
    if !(cfg.odometry_noise.is_finite() && (0.0..0.5).contains(&cfg.odometry_noise)) {
        return Err(bad(
            "--odometry-noise",
            cfg.odometry_noise,
            "a relative wheel-speed error in [0, 0.5)",
        ));
    }
    // The reference must be drivable: at its top speed, and turning in place
    // at its top turn rate, no wheel may need more than the drive allows
    // (else the robot lags ever further behind and the run "succeeds" with
    // almost nothing covered).
    let d = cfg.spec.drive;
    let need = cfg
        .limits
        .v_max
        .max(cfg.limits.omega_max * d.wheel_base / 2.0);
    if d.max_wheel_speed.is_nan() || d.max_wheel_speed < need {
        return Err(Error::BadParameter {
            name: "robot spec max_wheel_speed",
            value: d.max_wheel_speed.to_string(),
            expected: format!(
                "at least {need} m/s, what the reference's top speed {} m/s and turn rate {} rad/s ask of a wheel",
                cfg.limits.v_max, cfg.limits.omega_max
            ),
        });
    }
    let timing = Timing::new(points, cfg.limits).map_err(|e| Error::BadParameter {
        name: "limits",
        value: format!("{:?}", cfg.limits),
        expected: e.to_string(),
    })?;
    let controller = cfg.controller.build();
    let drive = cfg.spec.drive;
    let mut rng = ChaCha8Rng::seed_from_u64(cfg.seed);
    let mut normal = || {
        let u1: f64 = rng.random::<f64>().max(f64::MIN_POSITIVE);
        let u2: f64 = rng.random::<f64>();
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    };
    let start = timing.at(0.0).pose;
    let (mut believed, mut truth, mut last) = (start, start, (0.0, 0.0));
    let settle = 2.0;
    let run_s = timing.duration() + settle;
    let steps = (run_s / cfg.dt).ceil();
    if !(steps.is_finite() && steps <= oxcover_robot::simulate::MAX_STEPS as f64) {
        return Err(Error::BadParameter {
            name: "--dt",
            value: cfg.dt.to_string(),
            expected: format!(
                "a step giving at most {} steps over this {run_s:.0} s run (at least {:.2e} s)",
                oxcover_robot::simulate::MAX_STEPS,
                run_s / oxcover_robot::simulate::MAX_STEPS as f64
            ),
        });
    }
    let steps = steps as usize;
    let mut samples = Vec::with_capacity(steps + 1);
    let (mut energy, mut prev_cmd) = (0.0, (0.0, 0.0));
    for k in 0..=steps {
        let t = k as f64 * cfg.dt;
        let r = timing.at(t);
        let cmd = if k == steps {
            (0.0, 0.0)
        } else {
            drive.saturate(controller.command(&believed, &r), last, cfg.dt)
        };
        let e = TrackingError::of(&truth, &r.pose);
        samples.push(Executed {
            t,
            pose: truth,
            v: cmd.0,
            omega: cmd.1,
            energy,
            error: e.ex.hypot(e.ey),
        });
        let (a, alpha) = ((cmd.0 - prev_cmd.0) / cfg.dt, (cmd.1 - prev_cmd.1) / cfg.dt);
        energy += cfg.spec.energy.power(&drive, cmd.0, cmd.1, a, alpha) * cfg.dt;
        prev_cmd = cmd;
        believed = drive.integrate(believed, cmd.0, cmd.1, cfg.dt);
        let actual = if cfg.odometry_noise > 0.0 {
            let (l, rr) = drive.wheel_speeds(cmd.0, cmd.1);
            drive.from_wheels(
                l * (1.0 + cfg.odometry_noise * normal()),
                rr * (1.0 + cfg.odometry_noise * normal()),
            )
        } else {
            cmd
        };
        truth = drive.integrate(truth, actual.0, actual.1, cfg.dt);
        last = cmd;
    }
    let executed: Vec<Point> = samples
        .iter()
        .map(|s| Point::new(s.pose.x, s.pose.y))
        .collect();
    let evaluation = evaluate(map, robot, &executed, &MetricParams::default())?;
    let n = samples.len().max(1) as f64;
    let tracking_rms = (samples.iter().map(|s| s.error * s.error).sum::<f64>() / n).sqrt();
    let tracking_max = samples.iter().map(|s| s.error).fold(0.0, f64::max);
    let end_gap_m = match (samples.last(), points.last()) {
        (Some(s), Some(p)) => (s.pose.x - p.x).hypot(s.pose.y - p.y),
        _ => 0.0,
    };
    Ok(Run {
        samples,
        evaluation,
        tracking_rms,
        tracking_max,
        end_gap_m,
    })
}

/// `outcome`, planned for `request` on `map`, executed as [`execute`]
/// does: on the map with the request's keep-out cells blocked (collisions
/// judged for the robot's own radius) and, where the plan had a target or
/// a clearance, its coverage scored against the cells the plan had to
/// cover. What `oxcover simulate` and Python's `simulate` run.
///
/// # Errors
/// As [`execute`] and [`crate::targets::Targets::blocked_map`].
pub fn execute_plan(
    map: &OccupancyGrid,
    request: &crate::pipeline::PlanRequest,
    outcome: &crate::pipeline::PlanOutcome,
    cfg: &ClosedLoop,
) -> Result<Run> {
    let targets = &request.targets;
    let (work_map, _) = targets.blocked_map(map)?;
    let mut run = execute(&work_map, request.robot, &outcome.points, cfg)?;
    if targets.narrows() || request.clearance > 0.0 {
        let executed: Vec<Point> = run
            .samples
            .iter()
            .map(|s| Point::new(s.pose.x, s.pose.y))
            .collect();
        let mut problem = run.evaluation.problem.clone();
        problem.coverable = outcome.evaluation.problem.coverable.clone();
        run.evaluation = crate::metrics::evaluate_problem(
            map.frame(),
            problem,
            &executed,
            &MetricParams::default(),
        );
    }
    Ok(run)
}

/// The path file of an executed run: `x,y,theta,t,v,omega,energy` (the
/// contract's `x,y` first; the rest are the further columns it allows).
#[must_use]
pub fn to_csv(samples: &[Executed]) -> String {
    let mut out = String::from("x,y,theta,t,v,omega,energy\n");
    for s in samples {
        out += &format!(
            "{},{},{},{},{},{},{}\n",
            s.pose.x, s.pose.y, s.pose.theta, s.t, s.v, s.omega, s.energy
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::{PlanRequest, plan};
    use oxcover_grid::io::parse_ascii;

    fn spec() -> RobotSpec {
        RobotSpec::from_ron(include_str!("../../../fixtures/robots/floor_cleaner.ron"))
            .expect("valid spec")
    }

    fn setup() -> (OccupancyGrid, DiscRobot, Vec<Point>) {
        // 0.5 m cells: an 8 × 5 m room with a pillar.
        let text = "
            ................
            ................
            ......###.......
            ......###.......
            ................
            ................
            ................
            ................
            ................
            ................
        ";
        let (unit, _) = parse_ascii(text).unwrap();
        let map = OccupancyGrid::new(unit.cells().clone(), 0.5, Point::origin());
        let robot = DiscRobot::cell_sized(0.5);
        let out = plan(&map, &PlanRequest::new("boustrophedon", 0.5).unwrap()).unwrap();
        (map, robot, out.points)
    }

    fn config(noise: f64) -> ClosedLoop {
        ClosedLoop {
            spec: spec(),
            controller: ControllerKind::Klancar,
            limits: Limits::default(),
            dt: 0.02,
            odometry_noise: noise,
            seed: 3,
        }
    }

    #[test]
    fn a_plan_is_executed_closely_and_scored() {
        let (map, robot, points) = setup();
        let run = execute(&map, robot, &points, &config(0.0)).unwrap();
        assert!(
            run.tracking_rms < 0.02 && run.tracking_max < 0.1,
            "{} {}",
            run.tracking_rms,
            run.tracking_max
        );
        let m = &run.evaluation.metrics;
        assert!(m.coverage > 0.97, "{}", m.coverage);
        // Energy grows and stays within electronics-only and a few W more.
        let last = run.samples.last().unwrap();
        assert!(
            last.energy > 5.0 * last.t && last.energy < 8.0 * last.t,
            "{last:?}"
        );
        assert!(run.samples.windows(2).all(|w| w[1].energy >= w[0].energy));
        let csv = to_csv(&run.samples);
        assert!(csv.starts_with("x,y,theta,t,v,omega,energy\n"));
    }

    #[test]
    fn odometry_noise_is_seeded_and_makes_the_run_drift() {
        let (map, robot, points) = setup();
        let a = execute(&map, robot, &points, &config(0.05)).unwrap();
        let b = execute(&map, robot, &points, &config(0.05)).unwrap();
        assert_eq!(a.samples, b.samples);
        let clean = execute(&map, robot, &points, &config(0.0)).unwrap();
        assert!(a.tracking_rms > clean.tracking_rms);
        assert!(
            execute(
                &map,
                robot,
                &points,
                &ClosedLoop {
                    dt: 0.0,
                    ..config(0.0)
                }
            )
            .is_err()
        );
        assert!(execute(&map, robot, &points, &config(f64::NAN)).is_err());
    }
}
