//! Stress invariants for output and post-processing.
//!
//! Both functions read the symmetric part `½(σ + σᵀ)` of their argument, so
//! a stress with round-off asymmetry is handled consistently.

use femdem_core::{Mat3, Real};

/// Principal stresses `σ₁ ≥ σ₂ ≥ σ₃` (Pa), the eigenvalues of the symmetric
/// part of `stress`, in descending order (tension positive, so `σ₁` is the
/// most tensile).
///
/// Uses nalgebra's symmetric QR eigenvalue iteration; a stress with a
/// non-finite entry returns `[NaN; 3]` instead of iterating on it.
pub fn principal_stresses(stress: &Mat3) -> [Real; 3] {
    if !stress.iter().all(|x| x.is_finite()) {
        return [Real::NAN; 3];
    }
    let s = (stress + stress.transpose()) * 0.5;
    let e = s.symmetric_eigenvalues();
    let mut out = [e[0], e[1], e[2]];
    out.sort_by(|a, b| b.total_cmp(a));
    out
}

/// Von Mises equivalent stress `σ_vm = √(3/2 s:s)` (Pa), with
/// `s = σ − (tr σ / 3) I` the deviator of the symmetric part of `stress`.
/// Equals `|σ|` in uniaxial stress, `√3 τ` in pure shear, 0 for a
/// hydrostatic state.
pub fn von_mises(stress: &Mat3) -> Real {
    let sym = (stress + stress.transpose()) * 0.5;
    let dev = sym - Mat3::from_diagonal_element(sym.trace() / 3.0);
    (1.5 * dev.norm_squared()).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use femdem_core::Vec3;

    /// A diagonal stress's principal values are its diagonal, sorted.
    #[test]
    fn diagonal_stress_gives_sorted_diagonal() {
        let s = Mat3::from_diagonal(&Vec3::new(-3.0, 5.0, 1.0));
        let p = principal_stresses(&s);
        for (a, b) in p.iter().zip([5.0, 1.0, -3.0]) {
            assert!((a - b).abs() < 1e-14);
        }
    }

    /// Principal values are invariant under σ → R σ Rᵀ (rotation by 30°
    /// about z, then 45° about x); also tr σ = Σ σᵢ.
    #[test]
    fn principal_stresses_are_rotation_invariant() {
        let s = Mat3::new(4.0, 1.0, -2.0, 1.0, -1.0, 0.5, -2.0, 0.5, 3.0);
        let (c, d) = (30f64.to_radians(), 45f64.to_radians());
        let rz = Mat3::new(c.cos(), -c.sin(), 0.0, c.sin(), c.cos(), 0.0, 0.0, 0.0, 1.0);
        let rx = Mat3::new(1.0, 0.0, 0.0, 0.0, d.cos(), -d.sin(), 0.0, d.sin(), d.cos());
        let r = rx * rz;
        let a = principal_stresses(&s);
        let b = principal_stresses(&(r * s * r.transpose()));
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() < 1e-13);
        }
        assert!((a.iter().sum::<Real>() - s.trace()).abs() < 1e-13);
        assert!(a[0] >= a[1] && a[1] >= a[2]);
    }

    /// A pure shear τ has principal stresses (τ, 0, −τ).
    #[test]
    fn pure_shear_has_plus_minus_tau_principal_stresses() {
        let tau = 2.5;
        let s = Mat3::new(0.0, tau, 0.0, tau, 0.0, 0.0, 0.0, 0.0, 0.0);
        let p = principal_stresses(&s);
        assert!((p[0] - tau).abs() < 1e-14 && p[1].abs() < 1e-14 && (p[2] + tau).abs() < 1e-14);
    }

    #[test]
    fn non_finite_stress_gives_nan_without_hanging() {
        let mut s = Mat3::identity();
        s[(1, 2)] = Real::INFINITY;
        assert!(principal_stresses(&s).iter().all(|x| x.is_nan()));
    }

    /// Von Mises: uniaxial σ → |σ|; pure shear τ → √3 τ; hydrostatic → 0;
    /// adding a hydrostatic part changes nothing.
    #[test]
    fn von_mises_closed_forms() {
        let uni = Mat3::from_diagonal(&Vec3::new(-7.0, 0.0, 0.0));
        assert!((von_mises(&uni) - 7.0).abs() < 1e-14);
        let tau = 2.0;
        let shear = Mat3::new(0.0, 0.0, tau, 0.0, 0.0, 0.0, tau, 0.0, 0.0);
        assert!((von_mises(&shear) - 3f64.sqrt() * tau).abs() < 1e-14);
        assert!(von_mises(&Mat3::from_diagonal_element(-4.0)).abs() < 1e-14);
        let shifted = shear + Mat3::from_diagonal_element(10.0);
        assert!((von_mises(&shifted) - von_mises(&shear)).abs() < 1e-13);
    }
}
