//! The stable time step of the explicit scheme.
//!
//! The central-difference (leapfrog) update is stable for an undamped
//! linear system when `Δt ≤ 2 / ω_max`, `ω_max²` being the largest
//! eigenvalue of `M⁻¹K`. With viscous damping of ratio `ξ` in that mode the
//! limit becomes `Δt ≤ (2/ω_max)(√(1 + ξ²) − ξ)`. femdem estimates `ω_max²`
//! directly, by the Lanczos iteration on `M^{-1/2} K M^{-1/2}`, where `K v`
//! is the directional derivative of the internal forces (tets and joints
//! together, at the initial state) taken by a small finite difference. The
//! largest Ritz value converges to `ω_max²` from below, and fast at the edge
//! of the spectrum (plain power iteration stalls when the top of the
//! spectrum is clustered, which happens when joint and tet modes have
//! similar frequencies, and then underestimates `ω_max`). The user-facing
//! step is `safety × Δt_crit` (safety < 1 covers the residual error and the
//! stiffening of large deformation).
//!
//! The viscous term of Eq. 1 adds a damping matrix `C` (the viscous force
//! of a velocity field `w` is `−C w`); the largest damping rate
//! `β_max = λ_max(M⁻¹C)` is found by a second Lanczos iteration, and the two
//! are combined as explained at [`stable_time_step`].
//!
//! An element-by-element estimate is also given for reference: the
//! smallest `ℓ / c_p` over tets (`ℓ` the shortest altitude, `c_p` the P-wave
//! speed).

use femdem_core::{Real, Vec3};
use femdem_fracture::JointHistory;
use rayon::prelude::*;

use crate::forces::{Dissipation, Want, Workspace, internal_forces};
use crate::model::Model;

/// The result of [`stable_time_step`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StableStep {
    /// Largest angular frequency found, `√λ_max(M⁻¹K)`, rad/s.
    pub omega_max: Real,
    /// Largest damping rate found, `λ_max(M⁻¹C)`, 1/s.
    pub beta_max: Real,
    /// `β_max / (2 ω_max)`: the damping ratio the bound assumes.
    pub damping_ratio: Real,
    /// Bound on the contact springs' frequency, rad/s (0 without contact;
    /// see [`contact_omega`]).
    pub contact_omega: Real,
    /// Critical time step `2 / (√(ω² + ω_c² + β²/4) + β/2)`, s.
    pub critical: Real,
    /// The smallest `ℓ_min / c_p` over the deformable tets, s (for
    /// reference).
    pub element_transit: Real,
    /// Power iterations used (stiffness and damping together).
    pub iterations: usize,
}

/// Largest eigenvalue of the symmetric operator `z ↦ apply(z)` restricted
/// to the free nodes, by the Lanczos iteration (no reorthogonalisation: only
/// the extreme Ritz value is wanted, and it converges first and is not
/// disturbed by the loss of orthogonality, which only duplicates converged
/// values). The largest eigenvalue of the tridiagonal matrix is checked
/// every 10 iterations; the iteration stops when it changes by less than
/// 1e-7 relative. Returns the estimate and the iterations used.
fn lanczos_max(
    n: usize,
    free: &[bool],
    max_iterations: usize,
    mut apply: impl FnMut(&[Vec3]) -> Vec<Vec3>,
) -> (Real, usize) {
    // Deterministic start vector (a fixed hash of the index).
    let mut q: Vec<Vec3> = (0..n)
        .map(|i| {
            let h = |k: u64| {
                let mut s = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ k.wrapping_mul(0xD1B5_4A32_D192_ED03);
                s ^= s >> 31;
                s = s.wrapping_mul(0xBF58_476D_1CE4_E5B9);
                s ^= s >> 29;
                (s >> 11) as Real / (1u64 << 53) as Real - 0.5
            };
            if free[i] { Vec3::new(h(1), h(2), h(3)) } else { Vec3::zeros() }
        })
        .collect();
    let norm = |v: &[Vec3]| v.iter().map(|x| x.norm_squared()).sum::<Real>().sqrt();
    let q_norm = norm(&q);
    if q_norm == 0.0 {
        return (0.0, 0);
    }
    q.iter_mut().for_each(|v| *v /= q_norm);
    let mut q_prev = vec![Vec3::zeros(); n];
    let mut alpha: Vec<Real> = Vec::new();
    let mut beta: Vec<Real> = Vec::new();
    let mut estimate = 0.0;
    for it in 0..max_iterations {
        let mut w = apply(&q);
        let b_prev = beta.last().copied().unwrap_or(0.0);
        for i in 0..n {
            w[i] -= q_prev[i] * b_prev;
        }
        let a: Real = w.iter().zip(&q).map(|(x, y)| x.dot(y)).sum();
        for i in 0..n {
            w[i] -= q[i] * a;
        }
        alpha.push(a);
        let b = norm(&w);
        let done = b <= 1e-14 * a.abs() || it + 1 == max_iterations;
        if (it + 1) % 10 == 0 || done {
            let k = alpha.len();
            let t = nalgebra::DMatrix::from_fn(k, k, |r, c| {
                if r == c {
                    alpha[r]
                } else if r + 1 == c {
                    beta[r]
                } else if c + 1 == r {
                    beta[c]
                } else {
                    0.0
                }
            });
            let top = t.symmetric_eigenvalues().iter().copied().fold(Real::NEG_INFINITY, Real::max);
            let converged = (top - estimate).abs() <= 1e-7 * top.abs();
            estimate = top;
            if converged || done {
                return (estimate, it + 1);
            }
        }
        beta.push(b);
        std::mem::swap(&mut q_prev, &mut q);
        q = w.into_iter().map(|v| v / b).collect();
    }
    (estimate, max_iterations)
}

/// Estimates the critical time step of `model` with the nodes in `held`
/// (prescribed or rigid) excluded; `max_iterations` bounds each Lanczos
/// iteration.
///
/// For a mode of frequency `ω` and damping rate `β = c/m` (ratio
/// `ξ = β/2ω`) the leapfrog update with lagged viscous forces is stable for
/// `Δt ≤ 2/(√(ω² + β²/4) + β/2)`; using the largest `ω` and the largest `β`
/// over all modes (which need not be the same mode: the stiffest mode may be
/// a joint mode the tets' viscosity hardly damps, while the most damped one
/// is a tet mode) gives a bound that holds for every mode.
pub fn stable_time_step(model: &Model, held: &[bool], max_iterations: usize) -> StableStep {
    let n = model.num_nodes();
    let free: Vec<bool> = (0..n).map(|i| !held[i] && model.mass[i] > 0.0).collect();
    let inv_sqrt_m: Vec<Real> = (0..n).map(|i| if free[i] { 1.0 / model.mass[i].sqrt() } else { 0.0 }).collect();
    let min_size = model
        .joint_law
        .iter()
        .map(|j| j.h)
        .chain(model.tet_ref.iter().map(|r| r.volume.cbrt()))
        .fold(Real::INFINITY, Real::min);
    let mut ws = Workspace::new(model);
    let zero_v = vec![Vec3::zeros(); n];
    // A scratch history: the probing moves are far below any peak opening.
    let mut history = vec![JointHistory::default(); model.joints.len()];
    internal_forces(model, &model.x0, &zero_v, &mut history, &mut ws, Want::default(), Dissipation::None);
    let f0 = ws.internal.clone();
    let mut xp = model.x0.clone();

    // Stiffness: K w ≈ −(f(x0 + εw) − f0)/ε, ε making the largest move 1e-6 of the smallest size.
    let (lambda, it_k) = lanczos_max(n, &free, max_iterations, |z| {
        let wmax = z.iter().zip(&inv_sqrt_m).map(|(v, s)| v.norm() * s).fold(0.0, Real::max);
        let eps = 1e-6 * min_size / wmax;
        xp.par_iter_mut().enumerate().for_each(|(i, p)| *p = model.x0[i] + z[i] * (inv_sqrt_m[i] * eps));
        internal_forces(model, &xp, &zero_v, &mut history, &mut ws, Want::default(), Dissipation::None);
        (0..n).map(|i| -(ws.internal[i] - f0[i]) * (inv_sqrt_m[i] / eps)).collect()
    });
    // Damping: C w = −(f(x0, v = w) − f0), exactly linear in w.
    let viscous = model.materials.iter().any(|(_, m)| m.viscosity() > 0.0);
    let (beta, it_c) = if viscous {
        lanczos_max(n, &free, max_iterations, |z| {
            let w: Vec<Vec3> = z.iter().zip(&inv_sqrt_m).map(|(v, s)| v * *s).collect();
            internal_forces(model, &model.x0, &w, &mut history, &mut ws, Want::default(), Dissipation::None);
            (0..n).map(|i| -(ws.internal[i] - f0[i]) * inv_sqrt_m[i]).collect()
        })
    } else {
        (0.0, 0)
    };
    let omega = lambda.max(0.0).sqrt();
    let beta = beta.max(0.0);
    StableStep {
        omega_max: omega,
        beta_max: beta,
        damping_ratio: if omega > 0.0 { beta / (2.0 * omega) } else { 0.0 },
        contact_omega: 0.0,
        critical: critical(omega, 0.0, beta),
        element_transit: element_transit(model),
        iterations: it_k + it_c,
    }
}

/// `2 / (√(ω² + ω_c² + β²/4) + β/2)`.
fn critical(omega: Real, omega_c: Real, beta: Real) -> Real {
    let rate = (omega * omega + omega_c * omega_c + 0.25 * beta * beta).sqrt() + 0.5 * beta;
    if rate > 0.0 { 2.0 / rate } else { Real::INFINITY }
}

impl StableStep {
    /// The step with contact springs of frequency bound `omega_c` added:
    /// `λ_max(M⁻¹(K + K_c)) ≤ λ_max(M⁻¹K) + λ_max(M⁻¹K_c)`, so
    /// `ω² + ω_c²` bounds the stiffest mode of the model in contact.
    pub fn with_contact(self, omega_c: Real) -> StableStep {
        StableStep { contact_omega: omega_c, critical: critical(self.omega_max, omega_c, self.beta_max), ..self }
    }
}

/// Reference volume and largest face area of tet `t`.
fn volume_and_largest_face(model: &Model, t: usize) -> (Real, Real) {
    let p = model.tets[t].map(|n| model.x0[n as usize]);
    let area = femdem_core::tet::FACES
        .iter()
        .map(|f| femdem_core::tet::triangle_area(&p[f[0]], &p[f[1]], &p[f[2]]))
        .fold(0.0, Real::max);
    (femdem_core::tet::signed_volume(&p), area)
}

/// A bound on the frequency of the contact springs of penalty `p` (Pa):
/// `ω_c² = max_t k_t / m_t` over the deformable tets, where
/// `k_t = 8 p A² / (3 V)` is the stiffness of a shallow face-on overlap of
/// two tets like `t` (`F = 2 p A (4 δ / H)`, `H = 3V/A` the altitude on
/// the largest face `A`: see `femdem-contact`'s closed-form test) and `m_t`
/// the lightest of its nodes (all of the pair's stiffness on one node).
///
/// It assumes a tet's contact partners are not much thinner than itself.
/// Measured on two cubes colliding face on (`tests/contact_step.rs`): the
/// largest stable multiple of this step (of 1, 1.25, 1.5, … 4) is 1.25, 2,
/// 3 and 3 for `p` = 0.1 E, E, 10 E and 100 E, and 4 is unstable.
pub fn contact_omega(model: &Model, penalty: Real) -> Real {
    (0..model.tets.len())
        .filter(|&t| !model.tet_material[t].is_rigid())
        .map(|t| {
            let (v, a) = volume_and_largest_face(model, t);
            let k = 8.0 * penalty * a * a / (3.0 * v);
            let m = model.tets[t].iter().map(|&n| model.mass[n as usize]).fold(Real::INFINITY, Real::min);
            k / m
        })
        .fold(0.0, Real::max)
        .sqrt()
}

/// Smallest `ℓ_min / c_p` over the deformable tets.
pub fn element_transit(model: &Model) -> Real {
    (0..model.tets.len())
        .filter_map(|t| model.tet_material[t].index().map(|i| (t, i)))
        .map(|(t, i)| {
            let (v, amax) = volume_and_largest_face(model, t);
            let altitude = 3.0 * v / amax;
            altitude / model.materials[i].1.p_wave_speed() * model.mass_scaling.sqrt()
        })
        .fold(Real::INFINITY, Real::min)
}
