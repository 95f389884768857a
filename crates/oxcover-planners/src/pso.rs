//! Particle swarm optimisation as in Algorithm 1 of Lee et al. 2011.
//!
//! A particle is a 4-vector `x` with velocity `v`. Each round every particle
//! is scored, the global best is the best of the previous global best and the
//! particles, each particle's personal best is updated, and then, per
//! component `k`,
//! `v_k ← w v_k + c₁ r₁ (pbest_k − x_k) + c₂ r₂ (gbest_k − x_k)`,
//! `x_k ← clamp(x_k + v_k, min_k, max_k)` (the velocity shortened to the
//! clamped move). The move is accepted only if the constraint holds at the
//! new position (the paper: the new wall-point covering range still contains
//! the original one); otherwise only component 4 moves and the velocities of
//! components 1–3 are zeroed (line 21), and if even that breaks the
//! constraint the particle stays where it is (the paper does not say; this
//! keeps every particle feasible).
//!
//! The constraint is expressed by the cost returning `None`. The start `x₀`
//! must be feasible; it seeds the global best, so the result never costs more
//! than the start (property-tested). Randomness comes from a seeded ChaCha
//! generator: same seed, same result.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// PSO parameters; the default is the paper's `n = 30, w = 0.8, c₁ = 0.5, c₂ = 0.2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pso {
    /// Particles.
    pub particles: usize,
    /// Inertia weight.
    pub w: f64,
    /// Attraction to the personal best.
    pub c1: f64,
    /// Attraction to the global best.
    pub c2: f64,
    /// Rounds (the paper's "end criterion"; not given there).
    pub rounds: usize,
}

impl Default for Pso {
    fn default() -> Self {
        Self {
            particles: 30,
            w: 0.8,
            c1: 0.5,
            c2: 0.2,
            rounds: 20,
        }
    }
}

/// The outcome of [`Pso::minimise`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PsoResult {
    /// Best position found.
    pub x: [f64; 4],
    /// Its cost.
    pub cost: f64,
    /// Cost of the start.
    pub start_cost: f64,
    /// Cost evaluations.
    pub evaluations: usize,
}

impl Pso {
    /// Minimises `cost` over the box `lo ..= hi` from the feasible start `x0`
    /// (`cost` returns `None` where the constraint fails). Returns `None` if
    /// the start itself is infeasible.
    pub fn minimise(
        &self,
        x0: [f64; 4],
        lo: [f64; 4],
        hi: [f64; 4],
        seed: u64,
        mut cost: impl FnMut(&[f64; 4]) -> Option<f64>,
    ) -> Option<PsoResult> {
        let start_cost = cost(&x0)?;
        let mut evaluations = 1;
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let (mut gbest, mut gcost) = (x0, start_cost);
        let n = self.particles;
        let mut x = Vec::with_capacity(n);
        let mut v = Vec::with_capacity(n);
        let mut pbest = Vec::with_capacity(n);
        // Line 02: random positions and velocities within the box; an
        // infeasible draw starts at x0 instead (the paper zeroes components 1–3).
        for _ in 0..n {
            let mut p = [0.0; 4];
            let mut q = [0.0; 4];
            for k in 0..4 {
                p[k] = lo[k] + rng.random::<f64>() * (hi[k] - lo[k]);
                q[k] = (rng.random::<f64>() - 0.5) * (hi[k] - lo[k]) * 0.5;
            }
            evaluations += 1;
            let c = match cost(&p) {
                Some(c) => c,
                None => {
                    p = x0;
                    start_cost
                }
            };
            x.push(p);
            v.push(q);
            pbest.push((p, c));
        }
        let mut current: Vec<f64> = pbest.iter().map(|b| b.1).collect();
        for _ in 0..self.rounds {
            // Lines 04–07: global and personal bests (costs of the current positions).
            for j in 0..n {
                if current[j] < gcost {
                    (gbest, gcost) = (x[j], current[j]);
                }
                if current[j] < pbest[j].1 {
                    pbest[j] = (x[j], current[j]);
                }
            }
            // Lines 08–22: move.
            for j in 0..n {
                let mut temp = x[j];
                for k in 0..4 {
                    let (r1, r2): (f64, f64) = (rng.random(), rng.random());
                    v[j][k] = self.w * v[j][k]
                        + self.c1 * r1 * (pbest[j].0[k] - x[j][k])
                        + self.c2 * r2 * (gbest[k] - x[j][k]);
                    temp[k] = (x[j][k] + v[j][k]).clamp(lo[k], hi[k]);
                    v[j][k] = temp[k] - x[j][k];
                }
                evaluations += 1;
                if let Some(c) = cost(&temp) {
                    x[j] = temp;
                    current[j] = c;
                    continue;
                }
                let mut only4 = x[j];
                only4[3] = temp[3];
                v[j][0] = 0.0;
                v[j][1] = 0.0;
                v[j][2] = 0.0;
                evaluations += 1;
                if let Some(c) = cost(&only4) {
                    x[j] = only4;
                    current[j] = c;
                }
            }
        }
        for j in 0..n {
            if current[j] < gcost {
                (gbest, gcost) = (x[j], current[j]);
            }
        }
        Some(PsoResult {
            x: gbest,
            cost: gcost,
            start_cost,
            evaluations,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn finds_the_minimum_of_a_bowl() {
        let r = Pso::default()
            .minimise([0.9; 4], [-1.0; 4], [1.0; 4], 7, |x| {
                Some(x.iter().map(|a| (a - 0.3) * (a - 0.3)).sum())
            })
            .unwrap();
        assert!(r.cost < 1e-3, "{r:?}");
        assert!(r.cost <= r.start_cost);
    }

    #[test]
    fn respects_the_constraint_and_the_box() {
        // Unconstrained minimum at 0.5 on every axis; the constraint x0 ≤ 0.2 holds it back.
        let r = Pso::default()
            .minimise([0.0; 4], [-1.0; 4], [1.0; 4], 3, |x| {
                (x[0] <= 0.2).then(|| x.iter().map(|a| (a - 0.5) * (a - 0.5)).sum())
            })
            .unwrap();
        assert!(r.x[0] <= 0.2 && r.x.iter().all(|a| (-1.0..=1.0).contains(a)));
        assert!((r.x[0] - 0.2).abs() < 0.05, "{r:?}");
    }

    #[test]
    fn infeasible_start_is_refused() {
        assert!(
            Pso::default()
                .minimise([0.0; 4], [-1.0; 4], [1.0; 4], 0, |_| None)
                .is_none()
        );
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

        /// Whatever the (rugged, constrained) cost and the seed, PSO never
        /// returns a position costing more than the start, and its result is feasible.
        #[test]
        fn never_worse_than_the_start(
            seed in any::<u64>(),
            a in proptest::array::uniform4(-3.0..3.0f64),
            x0 in proptest::array::uniform4(-0.5..0.5f64),
        ) {
            let f = |x: &[f64; 4]| -> Option<f64> {
                let s: f64 = (0..4).map(|k| (a[k] * x[k]).sin() + x[k] * x[k]).sum();
                (x[1] - x0[1] <= 0.3).then_some(s)
            };
            let r = Pso { rounds: 10, ..Pso::default() }
                .minimise(x0, [-1.0; 4], [1.0; 4], seed, f)
                .unwrap();
            prop_assert!(r.cost <= r.start_cost);
            prop_assert_eq!(f(&r.x), Some(r.cost));
        }
    }
}
