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

/// Four 3×3 matrices, `m[c][r]` the entry in row `r` and column `c`.
/// Every operation is written out entry by entry (no `array::map` or
/// `from_fn`, which the compiler may keep out of line, i.e. out of a
/// dispatched caller's instruction set).
#[derive(Clone, Copy)]
struct M3([[F4; 3]; 3]);

/// Builds an [`M3`] from an expression in `r` and `c` (literals).
macro_rules! m3 {
    (|$r:ident, $c:ident| $e:expr) => {
        M3([m3!(@col $r, $c, 0, $e), m3!(@col $r, $c, 1, $e), m3!(@col $r, $c, 2, $e)])
    };
    (@col $r:ident, $c:ident, $cc:literal, $e:expr) => {
        [m3!(@at $r, $c, 0, $cc, $e), m3!(@at $r, $c, 1, $cc, $e), m3!(@at $r, $c, 2, $cc, $e)]
    };
    (@at $r:ident, $c:ident, $rr:literal, $cc:literal, $e:expr) => {{
        let ($r, $c): (usize, usize) = ($rr, $cc);
        $e
    }};
}

impl M3 {
    /// The matrices `m` (one a lane).
    #[inline(always)]
    fn gather(m: [&femdem_core::Mat3; TET_LANES]) -> M3 {
        m3!(|r, c| F4([m[0][(r, c)], m[1][(r, c)], m[2][(r, c)], m[3][(r, c)]]))
    }
    /// `self b`, in nalgebra's order.
    #[inline(always)]
    fn mul(&self, b: &M3) -> M3 {
        let (a, b) = (&self.0, &b.0);
        m3!(|i, j| a[0][i] * b[j][0] + a[1][i] * b[j][1] + a[2][i] * b[j][2])
    }
    #[inline(always)]
    fn transpose(&self) -> M3 {
        let a = &self.0;
        m3!(|r, c| a[r][c])
    }
    #[inline(always)]
    fn add(&self, o: &M3) -> M3 {
        let (a, b) = (&self.0, &o.0);
        m3!(|r, c| a[c][r] + b[c][r])
    }
    #[inline(always)]
    fn scale(&self, s: F4) -> M3 {
        let a = &self.0;
        m3!(|r, c| a[c][r] * s)
    }
    #[inline(always)]
    fn div(&self, s: F4) -> M3 {
        let a = &self.0;
        m3!(|r, c| a[c][r] / s)
    }
    /// `Mat3::identity() * s`, entry by entry.
    #[inline(always)]
    fn identity_times(s: F4) -> M3 {
        m3!(|r, c| F4::splat(if r == c { 1.0 } else { 0.0 }) * s)
    }
    /// The matrices with columns `c`.
    #[inline(always)]
    fn from_cols(c: [F4x3; 3]) -> M3 {
        let [a, b, d] = c;
        M3([[a.x, a.y, a.z], [b.x, b.y, b.z], [d.x, d.y, d.z]])
    }
    /// Column `c`.
    #[inline(always)]
    fn col(&self, c: usize) -> F4x3 {
        let [x, y, z] = self.0[c];
        F4x3 { x, y, z }
    }
    /// `cof A`: columns `a₁ × a₂`, `a₂ × a₀`, `a₀ × a₁` (`law::cofactor`).
    #[inline(always)]
    fn cofactor(&self) -> M3 {
        let (c0, c1, c2) = (self.col(0), self.col(1), self.col(2));
        M3::from_cols([c1.cross(c2), c2.cross(c0), c0.cross(c1)])
    }
}

/// Edge matrices `[p₁ − p₀, p₂ − p₀, p₃ − p₀]` of four tets.
#[inline(always)]
fn edge_matrix(p: &[[Vec3; 4]; TET_LANES]) -> M3 {
    let node = |k: usize| F4x3::gather([p[0][k], p[1][k], p[2][k], p[3][k]]);
    let p0 = node(0);
    M3::from_cols([node(1).sub(p0), node(2).sub(p0), node(3).sub(p0)])
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
    let [m0, m1, m2, m3] = materials;
    let [r0, r1, r2, r3] = references;
    let lambda = F4([m0.lambda(), m1.lambda(), m2.lambda(), m3.lambda()]);
    let mu = F4([m0.mu(), m1.mu(), m2.mu(), m3.mu()]);
    let eta = F4([m0.viscosity(), m1.viscosity(), m2.viscosity(), m3.viscosity()]);
    let volume = F4([r0.volume, r1.volume, r2.volume, r3.volume]);
    let inv_dm = M3::gather([&r0.inv_dm, &r1.inv_dm, &r2.inv_dm, &r3.inv_dm]);
    // `tet_forces`: F, cof F, J, Ḟ and the guarded L̂ = Ḟ cof(F)ᵀ / Ĵ.
    let f = edge_matrix(x).mul(&inv_dm);
    let cof = f.cofactor();
    let j = f.col(0).dot(cof.col(0));
    let f_dot = edge_matrix(v).mul(&inv_dm);
    let jh = j.max(F4::splat(J_FLOOR));
    let l = f_dot.mul(&cof.transpose()).div(jh);
    // `law::response`, neo-Hookean: D = sym(L̂), U′(Ĵ), and
    // P = μF + (U′(Ĵ) I + η D) cof F.
    let d = l.add(&l.transpose()).scale(F4::splat(0.5));
    let ln_jh = jh.ln();
    let du = (lambda * ln_jh - mu) / jh;
    let p = f.scale(mu).add(&M3::identity_times(du).add(&d.scale(eta)).mul(&cof));
    // [f₁ f₂ f₃] = −V₀ P Dm⁻ᵀ, f₀ = −(f₁ + f₂ + f₃).
    let h = p.mul(&inv_dm.transpose()).scale(-volume);
    let (f1, f2, f3) = (h.col(0), h.col(1), h.col(2));
    let sum = f1.add(f2).add(f3);
    let f0 = F4x3 { x: -sum.x, y: -sum.y, z: -sum.z };
    for (lane, out) in forces.iter_mut().enumerate() {
        out[0] = f0.lane(lane);
        out[1] = f1.lane(lane);
        out[2] = f2.lane(lane);
        out[3] = f3.lane(lane);
    }
    true
}
