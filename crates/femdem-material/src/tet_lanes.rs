//! Four tets at a time: the forces of [`tet_forces`](crate::tet_forces)
//! for the neo-Hookean law (Eq. 1–2) in lanes ([`F4`], four `f64`), with
//! every operation of the scalar kernel in the same order, so its forces
//! bit for bit.
//!
//! The scalar kernel is nalgebra code; the lanes follow nalgebra's
//! evaluation order: a matrix product's entry is
//! `(a₀ b₀ + a₁ b₁) + a₂ b₂` (nalgebra's `gemv` builds each column as
//! `a₀ b₀`, then adds `a₁ b₁` and `a₂ b₂` to it), a dot product
//! `(x x′ + y y′) + z z′`, a matrix times a scalar entry by entry, and
//! `Mat3::identity() * du` has `0 · du` off the diagonal. The stress and
//! the stored energy are not computed: a step that asks for them uses the
//! scalar kernel. Written on [`F4`] so that a caller compiled for a wider
//! vector unit (`femdem_solver`'s run-time dispatch) packs the lanes into
//! it.

use femdem_core::Vec3;
use femdem_core::lanes::{F4, F4x3};

use crate::law::{J_FLOOR, Law};
use crate::{Material, TetReference};

/// Tets per lane group.
pub const TET_LANES: usize = 4;

/// Four 3×3 matrices, column by column.
#[derive(Clone, Copy)]
struct M3([F4x3; 3]);

impl M3 {
    /// Entry `(r, c)`.
    #[inline(always)]
    fn at(&self, r: usize, c: usize) -> F4 {
        let col = &self.0[c];
        [col.x, col.y, col.z][r]
    }
    #[inline(always)]
    fn from_fn(f: impl Fn(usize, usize) -> F4) -> M3 {
        M3([0, 1, 2].map(|c| F4x3 { x: f(0, c), y: f(1, c), z: f(2, c) }))
    }
    /// The matrices `m` (one a lane).
    #[inline(always)]
    fn gather(m: [&femdem_core::Mat3; TET_LANES]) -> M3 {
        M3::from_fn(|r, c| F4([m[0][(r, c)], m[1][(r, c)], m[2][(r, c)], m[3][(r, c)]]))
    }
    /// `self b`, in nalgebra's order.
    #[inline(always)]
    fn mul(&self, b: &M3) -> M3 {
        M3::from_fn(|i, j| self.at(i, 0) * b.at(0, j) + self.at(i, 1) * b.at(1, j) + self.at(i, 2) * b.at(2, j))
    }
    #[inline(always)]
    fn transpose(&self) -> M3 {
        M3::from_fn(|r, c| self.at(c, r))
    }
    #[inline(always)]
    fn add(&self, o: &M3) -> M3 {
        M3::from_fn(|r, c| self.at(r, c) + o.at(r, c))
    }
    #[inline(always)]
    fn scale(&self, s: F4) -> M3 {
        M3::from_fn(|r, c| self.at(r, c) * s)
    }
    #[inline(always)]
    fn div(&self, s: F4) -> M3 {
        M3::from_fn(|r, c| self.at(r, c) / s)
    }
    /// `Mat3::identity() * s`, entry by entry.
    #[inline(always)]
    fn identity_times(s: F4) -> M3 {
        M3::from_fn(|r, c| F4::splat(if r == c { 1.0 } else { 0.0 }) * s)
    }
    /// `cof A`: columns `a₁ × a₂`, `a₂ × a₀`, `a₀ × a₁` (`law::cofactor`).
    #[inline(always)]
    fn cofactor(&self) -> M3 {
        let [c0, c1, c2] = self.0;
        M3([c1.cross(c2), c2.cross(c0), c0.cross(c1)])
    }
}

/// Edge matrices `[p₁ − p₀, p₂ − p₀, p₃ − p₀]` of four tets.
#[inline(always)]
fn edge_matrix(p: &[[Vec3; 4]; TET_LANES]) -> M3 {
    let node = |k: usize| F4x3::gather([p[0][k], p[1][k], p[2][k], p[3][k]]);
    let p0 = node(0);
    M3([node(1).sub(p0), node(2).sub(p0), node(3).sub(p0)])
}

/// The forces of four neo-Hookean tets with current nodes `x` and nodal
/// velocities `v`, written into `forces`: those of
/// [`tet_forces`](crate::tet_forces) bit for bit. Returns `false` and
/// writes nothing when any of the four has another law.
#[inline(always)]
pub fn tet_forces_lanes(
    laws: [Law; TET_LANES],
    materials: [&Material; TET_LANES],
    references: [&TetReference; TET_LANES],
    x: &[[Vec3; 4]; TET_LANES],
    v: &[[Vec3; 4]; TET_LANES],
    forces: &mut [[Vec3; 4]; TET_LANES],
) -> bool {
    if laws.iter().any(|&l| l != Law::NeoHookean) {
        return false;
    }
    let per_tet = |f: &dyn Fn(usize) -> f64| F4([f(0), f(1), f(2), f(3)]);
    let lambda = per_tet(&|l| materials[l].lambda());
    let mu = per_tet(&|l| materials[l].mu());
    let eta = per_tet(&|l| materials[l].viscosity());
    let volume = per_tet(&|l| references[l].volume);
    let inv_dm = M3::gather(references.map(|r| &r.inv_dm));
    // `tet_forces`: F, cof F, J, Ḟ and the guarded L̂ = Ḟ cof(F)ᵀ / Ĵ.
    let f = edge_matrix(x).mul(&inv_dm);
    let cof = f.cofactor();
    let j = f.0[0].dot(cof.0[0]);
    let f_dot = edge_matrix(v).mul(&inv_dm);
    let floor = F4::splat(J_FLOOR);
    let l = f_dot.mul(&cof.transpose()).div(j.max(floor));
    // `law::response`, neo-Hookean: D = sym(L̂), U′(Ĵ), and
    // P = μF + (U′(Ĵ) I + η D) cof F.
    let d = l.add(&l.transpose()).scale(F4::splat(0.5));
    let jh = j.max(floor);
    let ln_jh = jh.ln();
    let du = (lambda * ln_jh - mu) / jh;
    let p = f.scale(mu).add(&M3::identity_times(du).add(&d.scale(eta)).mul(&cof));
    // [f₁ f₂ f₃] = −V₀ P Dm⁻ᵀ, f₀ = −(f₁ + f₂ + f₃).
    let h = p.mul(&inv_dm.transpose()).scale(-volume);
    let [f1, f2, f3] = h.0;
    let sum = f1.add(f2).add(f3);
    let f0 = F4x3 { x: -sum.x, y: -sum.y, z: -sum.z };
    for (lane, out) in forces.iter_mut().enumerate() {
        *out = [f0.lane(lane), f1.lane(lane), f2.lane(lane), f3.lane(lane)];
    }
    true
}
