//! The nodes the order visits: the loops no lane drives, and the chains,
//! each with the ways it may be driven (a closed loop entered at one of
//! [`LOOP_ENTRIES`] points and left there, an open run from either end, a
//! chain from any of its four corners to the opposite end).

use oxcover_grid::Vector;
use oxcover_grid::traverse::{GridPoint, cell_center};

use super::islands::Splice;
use super::layout::Chain;
use super::loops::{EdgeLoop, LOOP_ENTRIES};

/// A node of the order: a loop, or a chain.
#[derive(Clone, Copy, Debug)]
pub(super) enum Node<'a> {
    Loop(&'a EdgeLoop),
    Chain(&'a Chain),
}

impl Node<'_> {
    /// How many ways it may be driven (entries and directions).
    pub(super) fn options(&self) -> usize {
        match self {
            Node::Loop(l) if !l.closed => 2,
            Node::Loop(_) => LOOP_ENTRIES,
            Node::Chain(_) => 4,
        }
    }

    /// Where option `k` enters it and leaves it.
    pub(super) fn ends(&self, k: usize) -> (GridPoint, GridPoint) {
        match self {
            Node::Loop(l) if !l.closed => {
                let first = l
                    .pieces
                    .first()
                    .and_then(|p| p.first())
                    .copied()
                    .unwrap_or_default();
                let last = l
                    .pieces
                    .last()
                    .and_then(|p| p.last())
                    .copied()
                    .unwrap_or_default();
                let (a, b) = (cell_center(first), cell_center(last));
                if k == 0 { (a, b) } else { (b, a) }
            }
            Node::Loop(l) => {
                let (p, i) = l.entry(k);
                let c = cell_center(l.pieces[p][i]);
                (c, c)
            }
            Node::Chain(c) => c.ends(k),
        }
    }

    /// The directions option `k` is entered and left along (zero where a
    /// node is a single point). A loop's are taken over a few cells, as
    /// its straightened segments run.
    pub(super) fn headings(&self, k: usize) -> (Vector, Vector) {
        const SPAN: usize = 3;
        match self {
            Node::Loop(l) => {
                let flat: Vec<GridPoint> =
                    l.pieces.iter().flatten().map(|&c| cell_center(c)).collect();
                let n = flat.len();
                if n < 2 {
                    return (Vector::zeros(), Vector::zeros());
                }
                let span = SPAN.min(n - 1);
                if !l.closed {
                    let first = flat[span] - flat[0];
                    let last = flat[n - 1] - flat[n - 1 - span];
                    return if k == 0 {
                        (first, last)
                    } else {
                        (-last, -first)
                    };
                }
                let (p, i) = l.entry(k);
                let e: usize = l.pieces[..p].iter().map(Vec::len).sum::<usize>() + i;
                (
                    flat[(e + span) % n] - flat[e],
                    flat[e] - flat[(e + n - span) % n],
                )
            }
            Node::Chain(c) => {
                let seq = c.sequence(k);
                let n = seq.len();
                if n < 2 {
                    return (Vector::zeros(), Vector::zeros());
                }
                (seq[1] - seq[0], seq[n - 1] - seq[n - 2])
            }
        }
    }

    /// The option driving the same work backwards (exit and entry swapped).
    pub(super) fn reversed(&self, k: usize) -> usize {
        match self {
            Node::Loop(l) if !l.closed => k ^ 1,
            Node::Loop(_) => k,
            Node::Chain(c) => {
                // Backwards flips bit 0; the start side of the new first
                // lane is the old exit's side.
                let odd = c.lanes.len() % 2 == 1;
                let flip = if odd { (k & 2) ^ 2 } else { k & 2 };
                (k & 1 ^ 1) | flip
            }
        }
    }
}

/// The nodes of the order: the loops no lane drives, then the chains.
pub(super) fn nodes_of<'n>(
    loops: &'n [EdgeLoop],
    chains: &'n [Chain],
    splices: &[Splice],
) -> Vec<Node<'n>> {
    let mut driven = vec![false; loops.len()];
    for s in splices {
        driven[s.loop_index] = true;
    }
    let mut nodes: Vec<Node> = loops
        .iter()
        .zip(driven)
        .filter(|(_, d)| !d)
        .map(|(l, _)| Node::Loop(l))
        .collect();
    nodes.extend(chains.iter().map(Node::Chain));
    nodes
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::layout::Lane;
    use oxcover_grid::Point;

    #[test]
    fn chains_reverse_consistently() {
        let lanes = |k: usize| Chain {
            lanes: (0..k)
                .map(|i| Lane {
                    a: Point::new(0.0, i as f64),
                    b: Point::new(5.0, i as f64),
                })
                .collect(),
        };
        for k in 1..5 {
            let c = lanes(k);
            let node = Node::Chain(&c);
            for opt in 0..4 {
                let (a, b) = c.ends(opt);
                let (ra, rb) = c.ends(node.reversed(opt));
                assert_eq!((ra, rb), (b, a), "{k} lanes, option {opt}");
            }
        }
    }
}
