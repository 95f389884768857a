//! The order: rings and spines driven nearest first.
//!
//! A ring is entered at its nearest point and driven once round, in the
//! direction closest to the current heading; a spine is entered at its
//! nearer end. A ring that would reach no cell not yet covered is dropped.
//! Transits are straight where clear, otherwise straightened shortest
//! routes. Item points sit in square buckets, so the nearest live item is
//! found without a scan of every item.

use oxcover_grid::Point;
use oxcover_grid::math::norm;
use oxcover_grid::traverse::GridPoint;

use super::Behaviour;
use super::{Item, Run};
use crate::buckets::Buckets;
use crate::error::Result;

impl<'a> Run<'a> {
    /// Drives the items nearest first (see the module docs).
    pub(super) fn drive_items(&mut self, mut items: Vec<Item>) -> Result<()> {
        let mut index =
            ItemIndex::new(self.plannable.width(), self.plannable.height(), self.bucket);
        for (i, it) in items.iter().enumerate() {
            if it.closed {
                for (j, &p) in it.points.iter().enumerate() {
                    index.insert(p, i, j);
                }
            } else {
                index.insert(it.points[0], i, 0);
                index.insert(it.points[it.points.len() - 1], i, it.points.len() - 1);
            }
        }
        let mut done = vec![false; items.len()];
        while let Some((i, entry)) = index.nearest(self.builder.last(), &done, &items) {
            done[i] = true;
            let it = Item {
                points: std::mem::take(&mut items[i].points),
                reps: std::mem::take(&mut items[i].reps),
                ..items[i]
            };
            if it.closed {
                if self.gain(&it.points, self.reach) == 0 {
                    self.stats.rings.1 += 1;
                    continue;
                }
                self.stats.rings.0 += 1;
                let seq = self.ring_sequence(&it.points, entry);
                let behaviour = if it.level == 0 {
                    Behaviour::WallFollowing
                } else {
                    Behaviour::VirtualWall
                };
                self.drive(&seq, behaviour)?;
            } else {
                let mut spine = it.points;
                if entry > 0 {
                    spine.reverse();
                }
                let gain = self.gain(&spine, self.reach);
                if gain == 0 {
                    continue;
                }
                let needed = it.reps.iter().any(|&c| !self.visited[c]);
                if !needed && !self.worth(&spine, gain) {
                    self.stats.slivers.1 += 1;
                    continue;
                }
                self.stats.slivers.0 += 1;
                self.drive(&spine, Behaviour::Sliver)?;
            }
        }
        Ok(())
    }

    /// The order in which a ring is driven from `entry` back to it, in the
    /// direction closer to the current heading.
    pub(super) fn ring_sequence(&self, ring: &[GridPoint], entry: usize) -> Vec<GridPoint> {
        let n = ring.len();
        let here = self.builder.last();
        let pts = self.builder.points();
        let forward = if pts.len() >= 2 {
            let (hx, hy) = (here.x - pts[pts.len() - 2].x, here.y - pts[pts.len() - 2].y);
            let (a, b, e) = (
                ring[(entry + 1) % n],
                ring[(entry + n - 1) % n],
                ring[entry],
            );
            (a.x - e.x) * hx + (a.y - e.y) * hy >= (b.x - e.x) * hx + (b.y - e.y) * hy
        } else {
            true
        };
        (0..=n)
            .map(|k| {
                if forward {
                    ring[(entry + k) % n]
                } else {
                    ring[(entry + n - k) % n]
                }
            })
            .collect()
    }

    /// A transit to `seq[0]`, then `seq` (straight where clear, routed where not).
    pub(super) fn drive(&mut self, seq: &[GridPoint], behaviour: Behaviour) -> Result<()> {
        let from = self.len() - 1;
        self.builder.go_to(seq[0])?;
        self.close(Behaviour::Transit, from);
        let from = self.len() - 1;
        for &q in &seq[1..] {
            if self.builder.clear(self.builder.last(), q) {
                self.builder.push(q);
            } else {
                self.builder.go_to(q)?;
            }
        }
        self.close(behaviour, from);
        Ok(())
    }
}

/// Item points in square buckets (payload: item, point index), for the
/// nearest item not yet driven.
pub(super) struct ItemIndex(Buckets<(usize, usize)>);

impl ItemIndex {
    pub(super) fn new(width: usize, height: usize, size: usize) -> Self {
        Self(Buckets::new(
            Point::new(0.0, 0.0),
            Point::new(width as f64, height as f64),
            size as f64,
        ))
    }

    pub(super) fn insert(&mut self, p: GridPoint, item: usize, index: usize) {
        self.0.insert(p, (item, index));
    }

    /// The nearest point of an item not `done` (ties: lower ring level, then
    /// lower item number). Points of items done are dropped on the way.
    pub(super) fn nearest(
        &mut self,
        p: GridPoint,
        done: &[bool],
        items: &[Item],
    ) -> Option<(usize, usize)> {
        let mut best: Option<(f64, usize, usize, usize)> = None;
        self.0.search(
            p,
            &mut best,
            |best, cell| {
                cell.retain(|e| !done[e.1.0]);
                for &(q, (item, index)) in cell.iter() {
                    let key = (norm(q.x - p.x, q.y - p.y), items[item].level, item, index);
                    if best.is_none_or(|b| (key.0, key.1, key.2) < (b.0, b.1, b.2)) {
                        *best = Some(key);
                    }
                }
            },
            |best, bound| best.is_some_and(|b| b.0 < bound),
        );
        best.map(|b| (b.2, b.3))
    }
}
