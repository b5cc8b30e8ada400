//! Bodies and their rigid-body freedom: inertia relief.
//!
//! A body is a connected set of nodes, tied by tets and by intact joints.
//! Its six rigid motions (three translations, three rotations about its
//! centre `c`, scaled by its radius `L`)
//!
//! ```text
//! φₖ(x) = eₖ,    φ₃₊ₖ(x) = eₖ × (x − c) / L,    k = 1, 2, 3,
//! ```
//!
//! are free where they move no held component: the null space of
//! `G = Σ_held φ φᵀ` (6 × 6, summed over the body's held components). A
//! body fixed on a face has none; a body under pressures only (the
//! polyaxial cube) has all six; a column on rollers has those the rollers
//! allow.
//!
//! With the free rigid modes `Ψ` (columns over the body's unknowns) and
//! the lumped masses `M`, the load `f` splits into a rigid acceleration
//! `a = Ψ α`, `(Ψᵀ M Ψ) α = Ψᵀ f`, and a self-equilibrated rest
//! `f_b = f − M Ψ α` (`Ψᵀ f_b = 0`: inertia relief). `K u = f_b` is then
//! solvable; its solution is made unique by removing its rigid part in
//! the mass metric, `u ← u − Ψ (Ψᵀ M Ψ)⁻¹ Ψᵀ M u` (the centre of mass does
//! not move). Started from that `u` at rest, the explicit run accelerates
//! the body rigidly by `a` under the d'Alembert stresses of `f_b`, which is
//! what the dynamic run does once its vibrations have died out.

use femdem_core::{Real, Vec3};
use femdem_solver::Model;
use nalgebra::{DMatrix, Matrix6, SymmetricEigen};

use crate::dofs::{Dofs, HELD};

/// A threshold on the eigenvalues of `G` relative to its trace: below it a
/// rigid mode counts as free. A held component contributes `O(1)` to the
/// trace (the modes are scaled by the body's radius), so a constrained mode
/// has an eigenvalue of order one; a free one, zero to round-off.
const FREE_MODE: Real = 1e-9;

/// A body with rigid-body freedom and its inertia-relief operators.
#[derive(Clone, Debug)]
pub struct FreeBody {
    /// The body's unknowns, ascending.
    pub dofs: Vec<u32>,
    /// The free rigid modes `Ψ` on `dofs`, column by column
    /// (`modes[k][d]` for unknown `dofs[d]`).
    pub modes: Vec<Vec<Real>>,
    /// `(Ψᵀ M Ψ)⁻¹`.
    pub inverse_mass: DMatrix<Real>,
}

impl FreeBody {
    /// `α = (Ψᵀ M Ψ)⁻¹ Ψᵀ W v`, `W` the diagonal `weight` (or `I`).
    fn coordinates(&self, v: &[Real], weight: Option<&[Real]>) -> nalgebra::DVector<Real> {
        let w = |d: usize| weight.map_or(1.0, |m| m[d]);
        let p = nalgebra::DVector::from_iterator(
            self.modes.len(),
            self.modes
                .iter()
                .map(|psi| psi.iter().zip(&self.dofs).map(|(p, &d)| p * w(d as usize) * v[d as usize]).sum()),
        );
        &self.inverse_mass * p
    }

    /// Removes the part of the force `f` that accelerates the body
    /// rigidly: `f ← f − M Ψ α`, `α = (Ψᵀ M Ψ)⁻¹ Ψᵀ f`. Returns `α`, the
    /// rigid acceleration's coordinates.
    pub fn relieve(&self, f: &mut [Real], mass: &[Real]) -> nalgebra::DVector<Real> {
        let alpha = self.coordinates(f, None);
        for (psi, a) in self.modes.iter().zip(alpha.iter()) {
            for (p, &d) in psi.iter().zip(&self.dofs) {
                f[d as usize] -= mass[d as usize] * p * a;
            }
        }
        alpha
    }

    /// Removes the rigid part of the displacement `u` in the mass metric:
    /// `u ← u − Ψ (Ψᵀ M Ψ)⁻¹ Ψᵀ M u`.
    pub fn remove_rigid(&self, u: &mut [Real], mass: &[Real]) {
        let beta = self.coordinates(u, Some(mass));
        for (psi, b) in self.modes.iter().zip(beta.iter()) {
            for (p, &d) in psi.iter().zip(&self.dofs) {
                u[d as usize] -= p * b;
            }
        }
    }
}

/// Disjoint sets of nodes.
struct UnionFind(Vec<u32>);

impl UnionFind {
    fn find(&mut self, mut i: u32) -> u32 {
        while self.0[i as usize] != i {
            let up = self.0[self.0[i as usize] as usize];
            self.0[i as usize] = up;
            i = up;
        }
        i
    }

    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
            self.0[hi as usize] = lo;
        }
    }
}

/// The bodies of `model`: nodes tied by its tets and by the joints for
/// which `intact[j]` holds, plus the extra `ties` (node pairs). Each body
/// is its nodes, ascending; bodies are ordered by their first node.
pub fn connected_bodies(model: &Model, intact: &[bool], ties: &[(u32, u32)]) -> Vec<Vec<u32>> {
    let n = model.num_nodes();
    let mut sets = UnionFind((0..n as u32).collect());
    for tet in &model.tets {
        for k in 1..4 {
            sets.union(tet[0], tet[k]);
        }
    }
    for (joint, _) in model.joints.iter().zip(intact).filter(|(_, ok)| **ok) {
        for k in 1..6 {
            sets.union(joint[0], joint[k]);
        }
    }
    for &(a, b) in ties {
        sets.union(a, b);
    }
    let mut root_body = vec![u32::MAX; n];
    let mut bodies: Vec<Vec<u32>> = Vec::new();
    for i in 0..n as u32 {
        let r = sets.find(i) as usize;
        if root_body[r] == u32::MAX {
            root_body[r] = bodies.len() as u32;
            bodies.push(Vec::new());
        }
        bodies[root_body[r] as usize].push(i);
    }
    bodies
}

/// The free rigid modes of one body (see the module doc), or `None` when
/// its held components rule out every rigid motion or it has no unknown.
pub fn free_body(model: &Model, dofs: &Dofs, nodes: &[u32], mass: &[Real]) -> Option<FreeBody> {
    let x = |i: u32| model.x0[i as usize];
    let centre = nodes.iter().map(|&i| x(i)).sum::<Vec3>() / nodes.len() as Real;
    let radius = nodes.iter().map(|&i| (x(i) - centre).norm()).fold(0.0, Real::max).max(Real::MIN_POSITIVE);
    // φₖ at node i, component c.
    let phi = |i: u32, c: usize| -> [Real; 6] {
        let r = (x(i) - centre) / radius;
        let mut m = [0.0; 6];
        m[c] = 1.0;
        for k in 0..3 {
            let e = Vec3::ith(k, 1.0);
            m[3 + k] = e.cross(&r)[c];
        }
        m
    };
    let mut g = Matrix6::<Real>::zeros();
    let mut body_dofs = Vec::new();
    for &i in nodes {
        for c in 0..3 {
            if dofs.index[i as usize][c] == HELD {
                let p = nalgebra::Vector6::from(phi(i, c));
                g += p * p.transpose();
            } else {
                body_dofs.push((dofs.index[i as usize][c], i, c));
            }
        }
    }
    if body_dofs.is_empty() {
        return None;
    }
    let eigen = SymmetricEigen::new(g);
    let limit = FREE_MODE * g.trace().max(1.0);
    let free: Vec<nalgebra::Vector6<Real>> =
        (0..6).filter(|&k| eigen.eigenvalues[k] <= limit).map(|k| eigen.eigenvectors.column(k).into_owned()).collect();
    if free.is_empty() {
        return None;
    }
    body_dofs.sort_unstable();
    let modes: Vec<Vec<Real>> = free
        .iter()
        .map(|v| body_dofs.iter().map(|&(_, i, c)| nalgebra::Vector6::from(phi(i, c)).dot(v)).collect())
        .collect();
    let r = modes.len();
    let mut mr = DMatrix::<Real>::zeros(r, r);
    for a in 0..r {
        for b in 0..r {
            mr[(a, b)] =
                body_dofs.iter().enumerate().map(|(d, &(k, _, _))| modes[a][d] * mass[k as usize] * modes[b][d]).sum();
        }
    }
    let inverse_mass = mr.try_inverse()?;
    Some(FreeBody { dofs: body_dofs.iter().map(|&(k, _, _)| k).collect(), modes, inverse_mass })
}
