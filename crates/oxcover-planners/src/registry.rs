//! The registry: every planner by its command-line name, and the options a
//! user may set on it.
//!
//! A planner's options live on the planner value (e.g.
//! [`Sweep::at_angle`]); this module is the one place that maps a name and a
//! set of [`PlannerOptions`] to such a value ([`build`]). Each entry says
//! which options its planner takes, so an option given to a planner that has
//! none of it is refused with the names of those that do.

use std::sync::Arc;

use crate::border_expansion::BorderExpansionPlanner;
use crate::bsa::Bsa;
use crate::dtc::Dtc;
use crate::error::{Error, Result};
use crate::full_dtc::FullDtc;
use crate::grid_cover::GridCover;
use crate::lanes::Lanes;
use crate::optimal::Optimal;
use crate::planner::{Planner, PlannerOptions};
use crate::rect_priority::RectPriority;
use crate::smooth::Smooth;
use crate::stc::{Stc, StcVariant};
use crate::sweep::{Decomposition, Sweep};

/// One registered planner: its default value, and how options make another.
struct Entry {
    planner: &'static dyn Planner,
    /// Takes a sweep angle.
    sweeps: bool,
    configure: fn(&PlannerOptions) -> Arc<dyn Planner>,
}

fn sweep(decomposition: Decomposition, o: &PlannerOptions) -> Arc<dyn Planner> {
    let s = Sweep::new(decomposition);
    Arc::new(o.sweep_angle_deg.map_or(s, |a| s.at_angle(a)))
}

fn entries() -> &'static [Entry] {
    static DTC: Dtc = Dtc::new();
    static FULL_DTC: FullDtc = FullDtc::new();
    static GRID_COVER: GridCover = GridCover::new();
    static RECT: RectPriority = RectPriority::new();
    static OPTIMAL: Optimal = Optimal::new();
    static STC: Stc = Stc::new(StcVariant::Plain);
    static SPIRAL_STC: Stc = Stc::new(StcVariant::Full);
    static BSA: Bsa = Bsa;
    static BOUSTROPHEDON: Sweep = Sweep::new(Decomposition::Boustrophedon);
    static TRAPEZOIDAL: Sweep = Sweep::new(Decomposition::Trapezoidal);
    static BORDER: BorderExpansionPlanner = BorderExpansionPlanner;
    static SMOOTH: Smooth = Smooth::new();
    static LANES: Lanes = Lanes::new();
    /// An entry taking no option.
    const fn plain(
        planner: &'static dyn Planner,
        configure: fn(&PlannerOptions) -> Arc<dyn Planner>,
    ) -> Entry {
        Entry {
            planner,
            sweeps: false,
            configure,
        }
    }
    static ALL: [Entry; 13] = [
        plain(&DTC, |_| Arc::new(Dtc::new())),
        plain(&FULL_DTC, |_| Arc::new(FullDtc::new())),
        plain(&GRID_COVER, |_| Arc::new(GridCover::new())),
        plain(&RECT, |_| Arc::new(RectPriority::new())),
        plain(&OPTIMAL, |_| Arc::new(Optimal::new())),
        plain(&STC, |_| Arc::new(Stc::new(StcVariant::Plain))),
        plain(&SPIRAL_STC, |_| Arc::new(Stc::new(StcVariant::Full))),
        plain(&BSA, |_| Arc::new(Bsa)),
        Entry {
            planner: &BOUSTROPHEDON,
            sweeps: true,
            configure: |o| sweep(Decomposition::Boustrophedon, o),
        },
        Entry {
            planner: &TRAPEZOIDAL,
            sweeps: true,
            configure: |o| sweep(Decomposition::Trapezoidal, o),
        },
        plain(&BORDER, |_| Arc::new(BorderExpansionPlanner)),
        plain(&SMOOTH, |_| Arc::new(Smooth::new())),
        Entry {
            planner: &LANES,
            sweeps: true,
            configure: |o| {
                let l = Lanes::new();
                Arc::new(o.sweep_angle_deg.map_or(l, |a| l.at_angle(a)))
            },
        },
    ];
    &ALL
}

/// Every planner with its default options, in the order `oxcover planners`
/// lists them.
pub fn registry() -> impl ExactSizeIterator<Item = &'static dyn Planner> {
    entries().iter().map(|e| e.planner)
}

/// The registered planner with this name, with its default options.
///
/// # Errors
/// [`Error::UnknownPlanner`].
pub fn find(name: &str) -> Result<&'static dyn Planner> {
    entry(name).map(|e| e.planner)
}

fn entry(name: &str) -> Result<&'static Entry> {
    entries()
        .iter()
        .find(|e| e.planner.name() == name)
        .ok_or_else(|| Error::UnknownPlanner(name.to_string()))
}

/// The planner `name` with `options` set.
///
/// # Errors
/// [`Error::UnknownPlanner`]; [`Error::BadParameter`] for an option the
/// planner does not take (naming the planners that do).
pub fn build(name: &str, options: &PlannerOptions) -> Result<Arc<dyn Planner>> {
    let e = entry(name)?;
    if let Some(angle) = options.sweep_angle_deg {
        if !e.sweeps {
            return Err(Error::OptionNotTaken {
                option: "--sweep-angle",
                value: format!("{angle} (with --planner {name})"),
                takers: names(|e| e.sweeps),
            });
        }
    }
    Ok((e.configure)(options))
}

fn names(keep: impl Fn(&Entry) -> bool) -> String {
    let v: Vec<&str> = entries()
        .iter()
        .filter(|e| keep(e))
        .map(|e| e.planner.name())
        .collect();
    v.join(" or ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_built_planners_keep_them() {
        let mut seen = std::collections::BTreeSet::new();
        for p in registry() {
            assert!(seen.insert(p.name()), "{} twice", p.name());
            let built = build(p.name(), &PlannerOptions::new()).unwrap();
            assert_eq!(built.name(), p.name());
        }
        assert_eq!(seen.len(), 13);
    }

    #[test]
    fn sweep_angle_only_where_taken() {
        let o = PlannerOptions::new().sweep_angle(30.0);
        assert_eq!(build("trapezoidal", &o).unwrap().name(), "trapezoidal");
        let e = build("dtc", &o)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            e.contains("only with --planner boustrophedon or trapezoidal or lanes"),
            "{e}"
        );
        assert!(matches!(find("nope"), Err(Error::UnknownPlanner(_))));
    }
}
