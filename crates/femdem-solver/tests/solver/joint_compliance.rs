//! Static compliance added by intact joints, and its p0 → ∞ limit
//! (reference paper §2.2, Eq. 6–9, 11).
//!
//! # Closed form
//!
//! A free block under equal pressures σ on its two z-faces is in uniaxial
//! stress σ_zz = −σ. Continuum: `ε_zz = σ_zz / E` (`ε_c`), exact for linear
//! tets. Joint-meshed, each interior face carries a joint of normal and
//! shear stiffness `p0/h` per unit area at small opening and slip (Eq. 6, 7,
//! 11: initial slope `2f/δp = p0/h`), `h` its mean edge length. If every tet
//! carries the same stress σ, every joint carries the traction σ n with the
//! jump `[u] = (h/p0) σ n`, and by the average-strain theorem the joints add
//! `S_j = (1/(p0 V)) Σ_j A_j h_j sym(n_j ⊗ (·) n_j)` to the compliance, built
//! from the actual joints of the mesh (`crate::common::joint_compliance`). Only
//! σ_zz is non-zero, so `ε_R = (1/E + S_j,zzzz) σ_zz` (the Poisson and shear
//! entries of S_j play no part in the axial stretch).
//!
//! Bounds (linear elasticity of the discrete model):
//!
//! - The uniform stress with tractions σ n on the joints is in nodal
//!   equilibrium with the loads: a tet's nodal forces `−V σ ∇N_a` and the
//!   Hammer integral of a uniform traction both give `σ n A/3` per face node.
//!   By the principle of minimum complementary energy `ε ≤ ε_R`, ε being
//!   the mean displacement work-conjugate to the pressures (area-weighted
//!   mean over the loaded faces) over the length.
//! - A uniform strain with no joint jump is kinematically admissible, so by
//!   minimum potential energy `ε ≥ ε_c`.
//!
//! Hence `q = (ε − ε_c)/(ε_R − ε_c) ∈ [0, 1]`. Since `S_j ∝ 1/p0`, the excess
//! strain falls as 1/p0 and the stretch tends to the continuum's: the p0 → ∞
//! limit of Eq. 8 (δp → 0), which Eq. 9's `E ≤ p0 ≤ 10E` trades against the
//! time step.
//!
//! How close q is to 1: `q = 1` exactly when the jumps of the uniform-stress
//! state are compatible. On the regular Freudenthal lattice (no jitter) the
//! bound is attained (tested below to 10⁻³; measured q − 1 = 2.8·10⁻⁵, the
//! shear-branch softening estimated below). Jitter makes joints that meet
//! at a node differ in size, and since the joint tractions are statically
//! indeterminate (three Gauss-point tractions per joint against the nodal
//! resultants), the true state shifts traction towards the stiffer ones.
//! The mesh connectivity does not depend on the jitter amplitude `j`, q is
//! smooth in the node positions, `q ≤ 1` for every j and `q = 1` at j = 0,
//! so j = 0 is a maximum and `1 − q = O(j²)`; the joint sizes scatter by
//! about j relative, and we require `1 − q ≤ j²` (1 % at j = 0.1).
//! Measured: 1 − q = 0.47 %, 0.35 %, 0.30 % at p0 = E, 10 E, 100 E (j = 0.1),
//! and 0.12 % / 1.05 % at j = 0.05 / 0.15 (p0 = E): ∝ j², about 0.45 j².
//!
//! # Procedure
//!
//! Dynamic relaxation: the pressures are applied at once on the free block
//! (no supports: they balance, and a rigid motion changes both faces' mean
//! z-displacement alike, so it does not enter ε), and a mass-proportional
//! damping `v ← (1 − c Δt) v` after each step (`Solver::damp`, which moves
//! `x_{n+1}` with `v` and books what it removes), with `c = ω_a = π c_R / L_z`
//! (`c_R = √(E_R/ρ)`, ω_a the first free–free axial mode; every underdamped
//! mode decays at `c/2`), brings it to rest; we run to `t = 40/ω_a`
//! (`e^{−20}`) and check that ε changed by < 10⁻⁶ relative over the last
//! fifth (measured with `Solver::damp`: 0.9–5.9·10⁻⁸ over the six runs). The static state does not depend on the damping. The tets use the
//! small-strain linear law (the bounds are theorems of linear elasticity).
//!
//! # Tolerances
//!
//! - `q ≤ 1 + 10⁻³` (bound) and `|q − 1| ≤ 10⁻³` on the regular lattice: the
//!   shear branch of Eq. 11 has secant stiffness `(1 − r/2) p0/h` with
//!   `r ≤ τ/(2 f_s) ≤ σ/(4 f_s) ≈ 1.7·10⁻⁴` at σ = 10 kPa (the normal branch
//!   is exactly linear in compression, and every joint is in compression or
//!   unloaded); pressures follow the current area (ΔA/A ~ 10⁻⁶); residual
//!   motion < 10⁻⁶ of ε, i.e. < 5·10⁻⁵ of the excess at p0 = 100 E.
//! - `q ≥ 1 − j²` (above), and the 1/p0 scaling of the excess to `j² + 10⁻³`.
//! - Continuum: `|ε/ε_c − 1| ≤ 10⁻⁴` (exact up to the same small effects).

use crate::common::{at_step, box_mesh, isotropic_compliance, joint_compliance, joints, rock, stable};
use femdem_material::{Law, Material};
use femdem_mesh::{TetMesh, insert_joints_within};
use femdem_solver::select::group_faces;
use femdem_solver::{Loads, Model, Ramp, RegionBehaviour, Solver, SurfaceKind, SurfaceLoad, Want};

/// Lattice cell size, m.
pub(crate) const H: f64 = 0.005;
/// Block size in cells.
pub(crate) const CELLS: [f64; 3] = [4.0, 4.0, 8.0];
/// Applied pressure, Pa.
pub(crate) const SIGMA: f64 = 1e4;

/// Strains of one relaxed block.
pub(crate) struct Stretch {
    /// Measured `|ε_zz|`.
    pub(crate) measured: f64,
    /// Continuum `σ/E`.
    pub(crate) continuum: f64,
    /// Uniform-stress estimate `(1/E + S_j,zzzz) σ`.
    pub(crate) estimate: f64,
}

impl Stretch {
    /// The fraction of the estimated joint strain that is measured.
    pub(crate) fn q(&self) -> f64 {
        (self.measured - self.continuum) / (self.estimate - self.continuum)
    }
}

/// Area-weighted mean z-displacement of `faces`.
fn mean_uz(s: &Solver, faces: &[[u32; 3]]) -> f64 {
    let (mut area, mut sum) = (0.0, 0.0);
    for f in faces {
        let [a, b, c] = f.map(|i| s.model().x0[i as usize]);
        let w = 0.5 * (b - a).cross(&(c - a)).norm();
        let u: f64 = f.iter().map(|&i| s.state().x[i as usize].z - s.model().x0[i as usize].z).sum();
        area += w;
        sum += w * u / 3.0;
    }
    sum / area
}

/// Relaxes the block of jitter `jitter` (joint-meshed with penalty `p0` if
/// `breakable`) under the two pressures and returns its stretch.
fn stretch(breakable: bool, p0: f64, jitter: f64) -> Stretch {
    let size = CELLS.map(|n| n * H);
    let mesh = box_mesh([0.0; 3], size, H, jitter, breakable);
    relax(&mesh, &vec![true; mesh.num_tets()], p0).0
}

/// Relaxes the block `mesh` (`CELLS` cells of `H`; joints of penalty `p0`
/// in the tets of `zone`, if its region is breakable) under the two
/// pressures `SIGMA` on its z faces; returns its stretch and the solver
/// at rest.
pub(crate) fn relax(mesh: &TetMesh, zone: &[bool], p0: f64) -> (Stretch, Solver) {
    let size = CELLS.map(|n| n * H);
    let mat: Material = rock(0.0);
    let jointed = insert_joints_within(mesh, zone).unwrap();
    let behaviour = RegionBehaviour::Deformable { law: Law::LinearElastic, material: mat, joints: Some(joints(p0)) };
    let m = Model::new(&jointed, &[behaviour], 1.0).unwrap();

    let s_tet = isotropic_compliance(&mat)[(2, 2)];
    let s_j = joint_compliance(&m, size.iter().product(), |_| true)[(2, 2)];

    let faces = ["zmin", "zmax"].map(|g| group_faces(&jointed, g).unwrap());
    let pressure = |name: &str, faces: &[[u32; 3]]| SurfaceLoad {
        name: name.into(),
        faces: faces.to_vec(),
        kind: SurfaceKind::Pressure(SIGMA),
        ramp: Ramp::STEP,
    };
    let loads =
        Loads { surfaces: vec![pressure("bottom", &faces[0]), pressure("top", &faces[1])], ..Default::default() };
    let dt = 0.9 * stable(&m, &loads, 400).critical;
    let mut s = at_step(m, loads, dt);

    let omega = std::f64::consts::PI * (1.0 / ((s_tet + s_j) * mat.density())).sqrt() / size[2];
    let keep = 1.0 - omega * s.dt();
    let strain = |s: &Solver| (mean_uz(s, &faces[0]) - mean_uz(s, &faces[1])) / size[2];
    let t_end = 40.0 / omega;
    let mut at_four_fifths = None;
    while s.state().time < t_end {
        s.step(Want::default());
        s.damp(keep).unwrap();
        if at_four_fifths.is_none() && s.state().time >= 0.8 * t_end {
            at_four_fifths = Some(strain(&s));
        }
    }
    let measured = strain(&s);
    let drift = (measured / at_four_fifths.unwrap() - 1.0).abs();
    eprintln!("relaxed: ε changed by {drift:.1e} over the last fifth");
    assert!(drift < 1e-6, "not at rest: ε changed by {drift:e} over the last fifth");
    (Stretch { measured, continuum: s_tet * SIGMA, estimate: (s_tet + s_j) * SIGMA }, s)
}

#[test]
fn unbreakable_block_stretches_as_the_continuum() {
    let s = stretch(false, 1.0, 0.1);
    assert!((s.measured / s.continuum - 1.0).abs() < 1e-4, "ε/ε_c = {}", s.measured / s.continuum);
}

#[test]
fn on_the_regular_lattice_the_joints_add_exactly_the_uniform_stress_compliance() {
    let e = rock(0.0).young();
    for p0_over_e in [1.0, 10.0] {
        let s = stretch(true, p0_over_e * e, 0.0);
        eprintln!(
            "regular, p0 = {p0_over_e} E: ε/ε_c = {:.5}, estimate {:.5}, q = {:.6}",
            s.measured / s.continuum,
            s.estimate / s.continuum,
            s.q()
        );
        assert!((s.q() - 1.0).abs() < 1e-3, "p0 = {p0_over_e} E: q = {}", s.q());
    }
}

#[test]
fn joint_compliance_is_bounded_by_the_estimate_and_falls_as_one_over_p0() {
    let jitter = 0.1;
    let e = rock(0.0).young();
    let runs: Vec<(f64, Stretch)> = [1.0, 10.0, 100.0].into_iter().map(|k| (k, stretch(true, k * e, jitter))).collect();
    for (k, s) in &runs {
        eprintln!(
            "jitter {jitter}, p0 = {k} E: ε/ε_c = {:.5}, estimate {:.5}, q = {:.5}",
            s.measured / s.continuum,
            s.estimate / s.continuum,
            s.q()
        );
        assert!(s.q() <= 1.0 + 1e-3, "p0 = {k} E: above the complementary-energy bound, q = {}", s.q());
        assert!(s.q() >= 1.0 - jitter * jitter, "p0 = {k} E: q = {}", s.q());
    }
    // The excess strain times p0 is constant: the joints' compliance is p0/h.
    let scaled = |(k, s): &(f64, Stretch)| (s.measured - s.continuum) * k;
    for run in &runs {
        let ratio = scaled(run) / scaled(&runs[1]);
        assert!((ratio - 1.0).abs() <= jitter * jitter + 1e-3, "p0 = {} E: ratio {ratio}", run.0);
    }
    // Eq. 8: the stretch falls towards the continuum's as p0 grows.
    assert!(runs.windows(2).all(|w| w[0].1.measured > w[1].1.measured));
    let last = &runs[2].1;
    assert!(last.measured > last.continuum && last.measured / last.continuum - 1.0 < 0.04);
}
