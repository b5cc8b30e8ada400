//! Anderson acceleration of the correction's fixed-point iteration.
//!
//! The modified Newton correction is the fixed-point iteration
//! `u ← u + g(u)`, `g(u) = A⁻¹ r_b(u)`, which contracts slowly where
//! joints have softened (their tangent is far below the initial one that
//! `A` holds). Anderson's mixing (Walker & Ni 2011, type II, depth `m`)
//! takes the combination of the last `m` steps that best cancels `g`:
//!
//! ```text
//! γ = argmin ‖g_k − ΔG γ‖₂,    u_{k+1} = u_k + g_k − (ΔU + ΔG) γ
//! ```
//!
//! with `ΔU`, `ΔG` the differences of the last `m + 1` iterates and steps.
//! For a linear `g` it is a GMRES in disguise; here it turns the slow
//! linear tail of the iteration into a fast one. The least-squares problem
//! is `m × m` (normal equations, Cholesky with a relative Tikhonov floor),
//! sums in a fixed order.

use femdem_core::Real;
use nalgebra::{DMatrix, DVector};

/// The mixing depth.
pub const DEPTH: usize = 5;

/// The iterates and steps Anderson's mixing remembers.
#[derive(Default)]
pub struct Anderson {
    last: Option<(Vec<Real>, Vec<Real>)>,
    du: Vec<Vec<Real>>,
    dg: Vec<Vec<Real>>,
}

impl Anderson {
    /// Forgets the history (after a step that made things worse).
    pub fn restart(&mut self) {
        *self = Anderson::default();
    }

    /// The next iterate from `u` and its step `g`.
    pub fn next(&mut self, u: &[Real], g: &[Real]) -> Vec<Real> {
        if let Some((u_last, g_last)) = self.last.take() {
            self.du.push(u.iter().zip(&u_last).map(|(a, b)| a - b).collect());
            self.dg.push(g.iter().zip(&g_last).map(|(a, b)| a - b).collect());
            if self.du.len() > DEPTH {
                self.du.remove(0);
                self.dg.remove(0);
            }
        }
        self.last = Some((u.to_vec(), g.to_vec()));
        let mut next: Vec<Real> = u.iter().zip(g).map(|(a, b)| a + b).collect();
        let m = self.dg.len();
        if m == 0 {
            return next;
        }
        let dot = |a: &[Real], b: &[Real]| a.iter().zip(b).map(|(p, q)| p * q).sum::<Real>();
        let mut normal = DMatrix::<Real>::zeros(m, m);
        let mut rhs = DVector::<Real>::zeros(m);
        for i in 0..m {
            for j in 0..=i {
                normal[(i, j)] = dot(&self.dg[i], &self.dg[j]);
                normal[(j, i)] = normal[(i, j)];
            }
            rhs[i] = dot(&self.dg[i], g);
        }
        let floor = 1e-12 * (0..m).map(|i| normal[(i, i)]).fold(0.0, Real::max);
        for i in 0..m {
            normal[(i, i)] += floor;
        }
        let Some(chol) = normal.cholesky() else {
            self.restart();
            return next;
        };
        let gamma = chol.solve(&rhs);
        for (k, c) in gamma.iter().enumerate() {
            for ((x, du), dg) in next.iter_mut().zip(&self.du[k]).zip(&self.dg[k]) {
                *x -= c * (du + dg);
            }
        }
        next
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a linear fixed-point problem `u = M u + b` with a slow
    /// contraction (0.95), plain iteration needs hundreds of steps to
    /// 10⁻¹⁰; Anderson's mixing of depth 5 on a 4-unknown problem is exact
    /// after at most 5 steps (a Krylov method on 4 unknowns).
    #[test]
    fn anderson_solves_a_slow_linear_fixed_point() {
        let m = [[0.95, 0.01, 0.0, 0.0], [0.0, 0.5, 0.1, 0.0], [0.02, 0.0, 0.9, 0.0], [0.0, 0.0, 0.1, 0.3]];
        let b = [1.0, -2.0, 0.5, 3.0];
        let step = |u: &[Real]| -> Vec<Real> {
            (0..4).map(|i| (0..4).map(|j| m[i][j] * u[j]).sum::<Real>() + b[i] - u[i]).collect()
        };
        let mut a = Anderson::default();
        let mut u = vec![0.0; 4];
        for _ in 0..8 {
            let g = step(&u);
            u = a.next(&u, &g);
        }
        let g = step(&u);
        let size = u.iter().map(|x| x.abs()).fold(0.0, Real::max);
        assert!(g.iter().all(|x| x.abs() < 1e-9 * size), "{g:?}");
    }
}
