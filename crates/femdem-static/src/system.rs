//! The factorised system and the corrections it gives: `A = K + ε M` on
//! floating bodies (`K` elsewhere), factorised once, used by the linear
//! refinement and by the correction to the explicit model's equilibrium.

use femdem_core::Real;

use crate::StaticError;
use crate::bodies::FreeBody;
use crate::sparse::{Cholesky, SymmetricCsc};

/// The stiffness, its shifted factorisation and the free bodies.
pub struct System {
    /// The stiffness `K` on the unknowns.
    pub k: SymmetricCsc,
    /// The bodies with rigid-body freedom.
    pub free: Vec<FreeBody>,
    /// The lumped mass of each unknown, kg.
    pub mass: Vec<Real>,
    chol: Cholesky,
}

impl System {
    /// Factorises `K + ε M` with `ε = shift · max Kᵢᵢ/mᵢ` on the unknowns
    /// of `free` bodies.
    ///
    /// # Errors
    /// [`StaticError::Factorisation`].
    pub fn new(k: SymmetricCsc, free: Vec<FreeBody>, mass: Vec<Real>, shift: Real) -> Result<System, StaticError> {
        let stiffest = k.diagonal().iter().zip(&mass).map(|(kd, m)| kd / m).fold(0.0, Real::max);
        let mut diagonal = vec![0.0; k.n];
        for body in &free {
            for &d in &body.dofs {
                diagonal[d as usize] = shift * stiffest * mass[d as usize];
            }
        }
        let chol = Cholesky::new(&k.shifted(&diagonal))?;
        Ok(System { k, free, mass, chol })
    }

    /// Entries of the Cholesky factor.
    pub fn factor_entries(&self) -> usize {
        self.chol.factor_entries()
    }

    /// Takes out of the force `r` what accelerates the free bodies
    /// rigidly (inertia relief).
    pub fn relieve(&self, r: &mut [Real]) {
        for body in &self.free {
            body.relieve(r, &self.mass);
        }
    }

    /// One correction: `u ← u + A⁻¹ r` for a relieved `r` (overwritten),
    /// then the rigid part of `u` removed in the mass metric.
    pub fn correct(&self, r: &mut [Real], u: &mut [Real]) {
        self.chol.solve_in_place(r);
        for (ui, di) in u.iter_mut().zip(r.iter()) {
            *ui += di;
        }
        self.remove_rigid(u);
    }

    /// `A⁻¹ r` in place.
    pub fn solve(&self, r: &mut [Real]) {
        self.chol.solve_in_place(r);
    }

    /// Removes the rigid part of `u` on the free bodies (mass metric).
    pub fn remove_rigid(&self, u: &mut [Real]) {
        for body in &self.free {
            body.remove_rigid(u, &self.mass);
        }
    }
}

impl System {
    /// Iterative refinement of `K u = f_b` from `u = 0` (`f_b` relieved):
    /// `r = f_b − K u`, rigid part of `r` removed, `u ← u + A⁻¹ r`, until
    /// `‖r‖ ≤ tolerance · f_norm`. Returns `u`, the relative residual and
    /// the steps taken.
    ///
    /// # Errors
    /// [`StaticError::NotConverged`] after `max_iterations` steps or on a
    /// residual that is not finite.
    pub fn refine(
        &self,
        f_b: &[Real],
        f_norm: Real,
        tolerance: Real,
        max_iterations: usize,
    ) -> Result<(Vec<Real>, Real, usize), StaticError> {
        let relative = |r: &[Real]| if f_norm > 0.0 { norm(r) / f_norm } else { 0.0 };
        let n = f_b.len();
        let (mut u, mut r, mut ku) = (vec![0.0; n], f_b.to_vec(), vec![0.0; n]);
        let mut residual = relative(&r);
        let mut iterations = 0;
        while residual > tolerance {
            if iterations == max_iterations || !residual.is_finite() {
                return Err(StaticError::NotConverged { residual, tolerance, iterations });
            }
            self.relieve(&mut r);
            self.correct(&mut r, &mut u);
            self.k.mul(&u, &mut ku);
            for ((ri, fi), kui) in r.iter_mut().zip(f_b).zip(&ku) {
                *ri = fi - kui;
            }
            residual = relative(&r);
            iterations += 1;
        }
        Ok((u, residual, iterations))
    }
}

/// The Euclidean norm.
pub fn norm(v: &[Real]) -> Real {
    v.iter().map(|x| x * x).sum::<Real>().sqrt()
}
