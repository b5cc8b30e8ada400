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

/// The Euclidean norm.
pub fn norm(v: &[Real]) -> Real {
    v.iter().map(|x| x * x).sum::<Real>().sqrt()
}
