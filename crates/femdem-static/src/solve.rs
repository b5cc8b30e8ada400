//! The static solve: assembly, inertia relief on free bodies, a shifted
//! sparse Cholesky factorisation, refinement to a checked residual, and the
//! correction to the explicit model's own equilibrium.
//!
//! With `K` the stiffness on the unknowns, `f` the loads, `M` the lumped
//! masses and `Ψ` the free rigid modes of each body (`crate::bodies`):
//!
//! 1. `f_b = f − M Ψ α`, `(Ψᵀ M Ψ) α = Ψᵀ f` (inertia relief);
//! 2. `A = K + ε M` on the unknowns of bodies with free rigid modes
//!    (`ε = shift · max Kᵢᵢ/mᵢ` over the model: a shift of their zero
//!    eigenvalues, so that `A` is positive definite), `A = K` elsewhere;
//!    `A = L Lᵀ` (faer, AMD ordering, sequential);
//! 3. `u₀ = 0`, then repeatedly `r = f_b − K u`, rigid part of `r` removed
//!    (round-off), `u ← u + A⁻¹ r`, rigid part of `u` removed in the mass
//!    metric — iterative refinement, whose error shrinks by
//!    `ε / (ε + ω₁²)` per step (`ω₁` a body's lowest elastic frequency), so
//!    a few steps reach round-off; `A = K` converges in one;
//! 4. stop when `‖K u − f_b‖ ≤ tolerance ‖f‖`, else fail with
//!    [`StaticError::NotConverged`]: the answer is never returned
//!    unchecked;
//! 5. with [`StaticOptions::correct`], modified Newton iterations from
//!    there on the explicit model's out-of-balance force
//!    (`crate::correction`), Anderson-mixed (`crate::anderson`; a mixed
//!    step that doubles the residual restarts the mixing from the best
//!    iterate), until it is below `model_tolerance ‖f‖` (or near the
//!    model's round-off floor), else [`StaticError::ModelNotConverged`].
//!
//! Every step but the force evaluation of step 5 is sequential and sums in
//! a fixed order; that evaluation is femdem-solver's force pass, the same
//! bit for bit for any thread count. So is the result.

use std::time::Instant;

use femdem_core::{Real, Vec3};
use femdem_solver::{Loads, Model, held_nodes};

use crate::StaticError;
use crate::assembly::assemble;
use crate::bodies::{FreeBody, connected_bodies, free_body};
use crate::correction::{Correction, JointCount, ModelResidual, correct};
use crate::dofs::Dofs;
use crate::loads::{gather, nodal_loads, scatter};
use crate::system::{System, norm};

/// The knobs of the static solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StaticOptions {
    /// The relative residual of the linear system, `‖K u − f_b‖ / ‖f‖`, to
    /// reach (default 1e-10).
    pub tolerance: Real,
    /// Whether to correct the linear solution to the explicit model's own
    /// equilibrium (default true; `crate::correction`).
    pub correct: bool,
    /// The relative out-of-balance force of the explicit model,
    /// `‖f_ext + f_int‖ / ‖f‖` after inertia relief, to reach when
    /// correcting (default 1e-7), or 4 times the explicit model's round-off
    /// floor where that is larger. The floor: a joint's opening is a
    /// difference of positions, so it carries an error of `ulp(x)` (about
    /// 10⁻¹⁷ m in a body of centimetres) against openings of 10⁻⁹ m at a
    /// MPa; the force noise is about `‖diag(K) ε |x0|‖` (`ε` the machine
    /// epsilon), which matches where the iterations stall (measured 0.6–0.7
    /// of it), and it grows relative to the load as the load falls.
    pub model_tolerance: Real,
    /// Iterations allowed in each of the two phases (default 50).
    pub max_iterations: usize,
    /// The shift of floating bodies relative to the stiffest unknown,
    /// `ε / max Kᵢᵢ/mᵢ` (default 1e-8; see the module doc).
    pub shift: Real,
}

impl Default for StaticOptions {
    fn default() -> StaticOptions {
        StaticOptions { tolerance: 1e-10, correct: true, model_tolerance: 1e-7, max_iterations: 50, shift: 1e-8 }
    }
}

/// What a static solve found, and what it cost.
#[derive(Clone, Debug, PartialEq)]
pub struct StaticSolution {
    /// Displacement of every node from its reference position, m (zero on
    /// held components).
    pub displacement: Vec<Vec3>,
    /// Relative residual of the linear system, `‖K u − f_b‖ / ‖f‖`, at
    /// its solution (0 without load).
    pub residual: Real,
    /// Relative out-of-balance force of the explicit model at the returned
    /// displacement, after inertia relief (`None` when not corrected).
    pub model_residual: Option<Real>,
    /// Share of the load that accelerates free bodies rigidly,
    /// `‖f − f_b‖ / ‖f‖` (0 for balanced loads and fixed bodies).
    pub unbalanced: Real,
    /// Rigid acceleration of each node of a free body under the unbalanced
    /// load, m/s² (zero elsewhere): what the explicit run starts doing.
    pub rigid_acceleration: Vec<Vec3>,
    /// Bodies with unknowns (connected by tets and intact joints).
    pub bodies: usize,
    /// Bodies with rigid-body freedom (inertia relief applied).
    pub free_bodies: usize,
    /// Unknowns.
    pub dofs: usize,
    /// Entries of the stiffness's lower triangle.
    pub matrix_entries: usize,
    /// Entries of the Cholesky factor.
    pub factor_entries: usize,
    /// Refinement steps of the linear system.
    pub iterations: usize,
    /// Correction steps to the explicit model's equilibrium.
    pub corrections: usize,
    /// The explicit model's relative out-of-balance force before each
    /// correction and at the end (empty when not corrected).
    pub correction_history: Vec<Real>,
    /// The explicit model's round-off floor relative to the load (see
    /// [`StaticOptions::model_tolerance`]); 0 when not corrected.
    pub model_floor: Real,
    /// Joints the explicit model finds past their peak, or failed, at the
    /// returned displacement (when corrected).
    pub joints: JointCount,
    /// Wall times of the stages, s.
    pub seconds: Timings,
}

/// Wall times of the stages, s.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timings {
    /// Bodies, loads and stiffness assembly.
    pub assembly: Real,
    /// Symbolic and numeric factorisation.
    pub factorisation: Real,
    /// Refinement of the linear system.
    pub solve: Real,
    /// Correction to the explicit model's equilibrium.
    pub correction: Real,
}

impl StaticSolution {
    /// Bytes the factor and the matrix held: 8 per factor entry, 12 per
    /// matrix entry (value and row), a rough measure of the solve's memory.
    pub fn memory_bytes(&self) -> usize {
        8 * self.factor_entries + 12 * self.matrix_entries
    }
}

/// Puts `model` into equilibrium under `loads` at `t = 0` (module doc):
/// small-strain linear elasticity of the deformable tets, the initial
/// tangent of every joint (all intact, as at the start of a run), held
/// components at zero displacement, inertia relief on free bodies, then
/// (by default) corrected to the explicit model's own equilibrium.
/// `initial_contacts` are the tet pairs that start in contact across
/// pre-existing fracture faces; the solve refuses them (it does not
/// linearise contact).
///
/// # Errors
/// [`StaticError`]: inconsistent constraints, initial contacts, a bad
/// joint stiffness or load, a failed factorisation, or a residual above
/// its tolerance.
pub fn static_solve(
    model: &Model,
    loads: &Loads,
    initial_contacts: &[(u32, u32)],
    options: &StaticOptions,
) -> Result<StaticSolution, StaticError> {
    check(options)?;
    if !initial_contacts.is_empty() {
        return Err(StaticError::InitialContact { pairs: initial_contacts.len() });
    }
    held_nodes(model, loads)?;
    let start = Instant::now();
    let dofs = Dofs::new(model, loads);
    let intact = vec![true; model.joints.len()];
    let nodes_of = connected_bodies(model, &intact, &[]);
    let bodies = nodes_of
        .iter()
        .filter(|b| b.iter().any(|&i| dofs.index[i as usize].iter().any(|&d| d != crate::dofs::HELD)))
        .count();
    let mass = gather(&dofs, &model.mass.iter().map(|&m| Vec3::repeat(m)).collect::<Vec<_>>());
    let free: Vec<FreeBody> = nodes_of.iter().filter_map(|nodes| free_body(model, &dofs, nodes, &mass)).collect();
    let f = gather(&dofs, &nodal_loads(model, loads)?);
    let k = assemble(model, &dofs, &intact)?;
    let assembly = start.elapsed().as_secs_f64();

    let start = Instant::now();
    let system = System::new(k, free, mass, options.shift)?;
    let factorisation = start.elapsed().as_secs_f64();

    let start = Instant::now();
    let mut f_b = f.clone();
    system.relieve(&mut f_b);
    let f_norm = norm(&f);
    let unbalanced =
        if f_norm > 0.0 { norm(&f.iter().zip(&f_b).map(|(a, b)| a - b).collect::<Vec<_>>()) / f_norm } else { 0.0 };
    let accel: Vec<Real> = f.iter().zip(&f_b).zip(&system.mass).map(|((a, b), m)| (a - b) / m).collect();
    let (mut u, residual, iterations) = system.refine(&f_b, f_norm, options.tolerance, options.max_iterations)?;
    let solve = start.elapsed().as_secs_f64();

    let start = Instant::now();
    let mut report = Correction::default();
    if options.correct && f_norm > 0.0 {
        let floor = round_off_floor(&system, &gather(&dofs, &model.x0)) / f_norm;
        let accept = options.model_tolerance.max(FLOOR_MARGIN * floor);
        let mut eval = ModelResidual::new(model, loads, &dofs);
        report = correct(&system, &mut eval, &mut u, f_norm, accept, options.max_iterations)?;
        report.floor = floor;
    }
    let correction = start.elapsed().as_secs_f64();
    Ok(StaticSolution {
        displacement: scatter(&dofs, &u),
        residual,
        model_residual: report.residual,
        unbalanced,
        rigid_acceleration: scatter(&dofs, &accel),
        bodies,
        free_bodies: system.free.len(),
        dofs: dofs.count,
        matrix_entries: system.k.nnz(),
        factor_entries: system.factor_entries(),
        iterations,
        corrections: report.iterations,
        correction_history: report.history,
        model_floor: report.floor,
        joints: report.joints,
        seconds: Timings { assembly, factorisation, solve, correction },
    })
}

/// How far above the round-off floor the correction is accepted.
const FLOOR_MARGIN: Real = 4.0;

/// `‖diag(K) ε |x0|‖`: the force noise of evaluating the explicit model at
/// positions of the size of `x0` (see [`StaticOptions::model_tolerance`]).
fn round_off_floor(system: &System, x0: &[Real]) -> Real {
    let diagonal = system.k.diagonal();
    norm(&diagonal.iter().zip(x0).map(|(k, x)| k * x.abs() * Real::EPSILON).collect::<Vec<_>>())
}

fn check(options: &StaticOptions) -> Result<(), StaticError> {
    let bad = |what: &str, v: Real| Err(StaticError::Options(format!("{what} must lie in (0, 1), got {v}")));
    if !(options.tolerance > 0.0 && options.tolerance < 1.0) {
        return bad("tolerance", options.tolerance);
    }
    if !(options.model_tolerance > 0.0 && options.model_tolerance < 1.0) {
        return bad("model_tolerance", options.model_tolerance);
    }
    if !(options.shift > 0.0 && options.shift < 1.0) {
        return bad("shift", options.shift);
    }
    Ok(())
}
