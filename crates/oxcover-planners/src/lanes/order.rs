//! The order of loops and chains: a small generalised TSP.
//!
//! Nearest neighbour over every entry of every node (entries in buckets,
//! searched ring by ring), 2-opt on the order (a reversed stretch drives
//! its nodes backwards), then an exact dynamic programme choosing every
//! node's entry for that order, its costs counting the turns at each
//! junction too ([`Transits`]). All costs are estimated seconds.
//!
//! Measured (`docs/efficiency.md`, stage table, rooms on): the
//! nearest-neighbour order alone is 2.1 % (ipa) / 1.4 % (ROS) slower.

use oxcover_grid::traverse::GridPoint;

use super::islands::Splice;
use super::layout::Chain;
use super::nodes::Node;
use super::transits::{Region, Transits};
use crate::buckets::Buckets;
use crate::time::TimeModel;

/// An angle ordered: its modelled seconds (chains and transits), its
/// chains, their order with the loops, and the island loops its lanes drive.
pub(super) struct Ordered {
    pub(super) time: f64,
    pub(super) chains: Vec<Chain>,
    pub(super) tour: Tour,
    pub(super) splices: Vec<Splice>,
}

/// Most nodes the order's 2-opt runs on.
const TWO_OPT_LIMIT: usize = 600;

/// Nodes in the order driven, each with its option.
pub(super) type Tour = Vec<(usize, usize)>;

/// Order and entry options of `nodes` from `start`, minimising estimated
/// transit time ([`Transits`]; a generalised TSP); the nearest-neighbour
/// order alone unless `improve`.
pub(super) fn order_nodes(
    nodes: &[Node<'_>],
    ends: (GridPoint, Option<GridPoint>),
    region: &mut Region<'_>,
    t: &TimeModel,
    improve: bool,
) -> (Tour, f64) {
    let n = nodes.len();
    if n == 0 {
        return (Vec::new(), 0.0);
    }
    let start = ends.0;
    let transits = Transits::new(nodes, ends, region, t);
    const START: usize = 0;
    // Nearest neighbour over every entry: the least cost, ties to the lower
    // node and option. Entries sit in buckets, searched ring by ring
    // outwards until no farther ring can hold a cheaper one (a full scan
    // was O(n²): 35 s on a 512² random grid of 20 % obstacles).
    let entries: Vec<(GridPoint, usize, usize)> = nodes
        .iter()
        .enumerate()
        .flat_map(|(i, node)| (0..node.options()).map(move |k| (node.ends(k).0, i, k)))
        .collect();
    let mut index = entry_buckets(&entries);
    let mut used = vec![false; n];
    let mut tour: Vec<(usize, usize)> = Vec::with_capacity(n);
    let mut here = start;
    let mut here_id = START;
    for _ in 0..n {
        let mut best: Option<(f64, usize, usize)> = None;
        index.search(
            here,
            &mut best,
            |best, cell| {
                cell.retain(|e| !used[e.1.0]);
                for &(_, (i, k)) in cell.iter() {
                    let c = transits.entering(here_id, i, k);
                    if best.is_none_or(|b| (c, i, k) < b) {
                        *best = Some((c, i, k));
                    }
                }
            },
            // Every entry of the next ring is at least `bound` away.
            |best, bound| best.is_some_and(|b| b.0 < bound * (1.0 - 1e-12) / t.linear_speed),
        );
        let Some((_, i, k)) = best else { break };
        used[i] = true;
        tour.push((i, k));
        here = nodes[i].ends(k).1;
        here_id = transits.exit(i, k);
    }
    // 2-opt: reversing a stretch drives its nodes backwards.
    let exit = |tour: &[(usize, usize)], i: usize| {
        if i == 0 {
            START
        } else {
            transits.exit(tour[i - 1].0, tour[i - 1].1)
        }
    };
    // 2-opt is O(n²) per round: on large regions (a whole map of tiny
    // cells) the nearest-neighbour order and the exact entry choice stand.
    let rounds = if n <= TWO_OPT_LIMIT && improve { 50 } else { 0 };
    for _round in 0..rounds {
        let mut better = false;
        for i in 0..n {
            for j in i + 1..n {
                let before_in = exit(&tour, i);
                let a_in = transits.ids[tour[i].0][tour[i].1].0;
                let b_out = transits.exit(tour[j].0, tour[j].1);
                let after = tour.get(j + 1).map(|&(m, k)| transits.ids[m][k].0);
                let onwards = |from: usize| match after {
                    Some(q) => transits.between(from, q),
                    None => transits.finishing(from),
                };
                let old = transits.between(before_in, a_in) + onwards(b_out);
                // Reversed: enter at b's old exit, leave at a's old entry.
                let new = transits.between(before_in, b_out) + onwards(a_in);
                if new < old - 1e-9 {
                    tour[i..=j].reverse();
                    for e in &mut tour[i..=j] {
                        e.1 = nodes[e.0].reversed(e.1);
                    }
                    better = true;
                }
            }
        }
        if !better {
            break;
        }
    }
    let seconds = if improve {
        best_options(nodes, &mut tour, &transits)
    } else {
        tour_seconds(&tour, &transits)
    };
    (tour, seconds)
}

/// The entries `(point, node, option)` in buckets of about two each.
fn entry_buckets(entries: &[(GridPoint, usize, usize)]) -> Buckets<(usize, usize)> {
    let (mut lo, mut hi) = (
        GridPoint::new(f64::INFINITY, f64::INFINITY),
        GridPoint::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    for (p, _, _) in entries {
        lo = GridPoint::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = GridPoint::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    let area = ((hi.x - lo.x) * (hi.y - lo.y)).max(1.0);
    let mut b = Buckets::new(lo, hi, (2.0 * area / entries.len().max(1) as f64).sqrt());
    for &(p, i, k) in entries {
        b.insert(p, (i, k));
    }
    b
}

/// The transit seconds of `tour` as it is (its entries, junction turns and
/// the way to the end).
fn tour_seconds(tour: &[(usize, usize)], transits: &Transits) -> f64 {
    let mut seconds = 0.0;
    let mut from = 0;
    let mut prev: Option<(usize, usize)> = None;
    for &(node, k) in tour {
        seconds += transits.entering(from, node, k);
        if let Some((p, q)) = prev {
            seconds += transits.junction(p, q, node, k);
        }
        from = transits.exit(node, k);
        prev = Some((node, k));
    }
    seconds + transits.finishing(from)
}

/// Chooses every node's option for the fixed order (exact: a shortest path
/// through layers of options); returns the transit seconds of the result.
fn best_options(nodes: &[Node<'_>], tour: &mut [(usize, usize)], transits: &Transits) -> f64 {
    let mut layers: Vec<Vec<(f64, usize)>> = Vec::with_capacity(tour.len());
    for (i, &(node, _)) in tour.iter().enumerate() {
        let m = nodes[node].options();
        let mut layer = Vec::with_capacity(m);
        for k in 0..m {
            let (c, from) = if i == 0 {
                (transits.entering(0, node, k), 0)
            } else {
                let prev = tour[i - 1].0;
                (0..layers[i - 1].len())
                    .map(|q| {
                        let out = transits.exit(prev, q);
                        let turn = transits.junction(prev, q, node, k);
                        (
                            layers[i - 1][q].0 + transits.entering(out, node, k) + turn,
                            q,
                        )
                    })
                    .min_by(|a, b| a.0.total_cmp(&b.0))
                    .unwrap_or((f64::INFINITY, 0))
            };
            layer.push((c, from));
        }
        layers.push(layer);
    }
    let Some(last) = layers.last() else {
        return 0.0;
    };
    let Some(&(last_node, _)) = tour.last() else {
        return 0.0;
    };
    let total = |k: usize| last[k].0 + transits.finishing(transits.exit(last_node, k));
    let mut k = (0..last.len())
        .min_by(|&a, &b| total(a).total_cmp(&total(b)))
        .unwrap_or(0);
    let seconds = total(k);
    for i in (0..tour.len()).rev() {
        tour[i].1 = k;
        k = layers[i][k].1;
    }
    seconds
}
