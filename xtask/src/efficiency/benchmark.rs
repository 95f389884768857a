//! The ipa targets again with the plans read as their benchmark reads
//! them (grey above 250 free, every other value an obstacle).

use rayon::prelude::*;

use super::{Outcome, Setting, mean, run_one, short};

/// The target line for `s`'s maps read as the ipa benchmark reads them:
/// the best planner `name` (index `p` of the runs `at`) planned again,
/// rooms on, on each map that reads differently, and the mean time
/// efficiency with those maps so read.
pub(super) fn benchmark_line<'r>(
    s: &Setting,
    p: usize,
    name: &str,
    at: &dyn Fn(usize, usize, bool) -> &'r Outcome,
    failures: &mut Vec<String>,
) -> anyhow::Result<String> {
    let mut differ = Vec::new();
    for (m, (map_name, map)) in s.maps.iter().enumerate() {
        if let Some(theirs) = crate::ipa_benchmark_reading(map_name, map)? {
            differ.push((m, theirs));
        }
    }
    let again: Vec<Outcome> = differ
        .par_iter()
        .map(|(_, map)| run_one(name, map, s.radius, true))
        .collect();
    // (time efficiency, turns per 10 m² covered) of every map, so read.
    let mut figures: Vec<Option<(f64, f64)>> = (0..s.maps.len())
        .map(|m| match at(p, m, true) {
            Outcome::Done(r) => Some((r.efficiency, r.turns_per_10m2)),
            _ => None,
        })
        .collect();
    let mut parts = Vec::new();
    for ((m, _), outcome) in differ.iter().zip(&again) {
        let map_name = short(&s.maps[*m].0);
        let (Outcome::Done(ours), Outcome::Done(theirs)) = (at(p, *m, true), outcome) else {
            if let Outcome::Failed(e) = outcome {
                failures.push(format!("{name} on {map_name} read as its benchmark: {e}"));
            }
            figures[*m] = None;
            continue;
        };
        if theirs.collisions > 0 || theirs.coverage < 0.99 {
            failures.push(format!(
                "{name} on {map_name} read as its benchmark: coverage {:.4}, {} collisions",
                theirs.coverage, theirs.collisions
            ));
        }
        figures[*m] = Some((theirs.efficiency, theirs.turns_per_10m2));
        parts.push(format!(
            "  - {map_name}: free {:.0} → {:.0} m², covered {:.0} → {:.0} m², time efficiency {:.3} → {:.3}, turns per 10 m² {:.1} → {:.1}, coverage {:.4}, {} collisions",
            ours.free_m2,
            theirs.free_m2,
            ours.covered_m2,
            theirs.covered_m2,
            ours.efficiency,
            theirs.efficiency,
            ours.turns_per_10m2,
            theirs.turns_per_10m2,
            theirs.coverage,
            theirs.collisions
        ));
    }
    if differ.is_empty() {
        return Ok(String::new());
    }
    let verdict = |ok: bool| if ok { "met" } else { "**not met**" };
    let all: Option<Vec<(f64, f64)>> = figures.into_iter().collect();
    let mean_line = all.map_or_else(
        || "a map failed, so no mean".to_string(),
        |v| {
            let e = mean(&v.iter().map(|f| f.0).collect::<Vec<_>>());
            let t = mean(&v.iter().map(|f| f.1).collect::<Vec<_>>());
            let turns = s.target_turns.map_or_else(String::new, |target| {
                format!(
                    "; turns per 10 m² covered {t:.1}, {} against ≤ {target}",
                    verdict(t <= target)
                )
            });
            format!(
                "the mean time efficiency so read {e:.3}, {} against the target of {:.2}{turns}",
                verdict(e >= s.target_efficiency),
                s.target_efficiency
            )
        },
    );
    Ok(format!(
        "- the same targets with the plans read as their benchmark reads them (`../shared/maps/ipa-floorplans/SOURCE.md`: grey above 250 free, every other value an obstacle; this page follows the contract's defaults for an image without a yaml, grey above 205 free): {mean_line}; {} of {} plans read differently (the start again the first cell of the largest admissible region):\n{}\n",
        parts.len(),
        s.maps.len(),
        parts.join("\n"),
    ))
}
