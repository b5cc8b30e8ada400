//! The stress–displacement law of an intact joint (reference paper Fig. 3,
//! Eq. 5–7, 11) and the joint's nodal forces.

use femdem_core::{Real, Vec3};

use crate::{GAUSS, JointParams, joint_kinematics};

/// Normal stress of Eq. 11 (tension positive) for opening `dn`, with
/// `δ_np = 2 f_t h / p0` (Eq. 6):
///
/// * `σ = 2 (δn / δnp) f_t` for `δn < 0` (compression, linear, slope `p0/h`);
/// * `σ = [2 δn/δnp − (δn/δnp)²] f_t` for `0 ≤ δn ≤ δnp` (hardening);
/// * `σ = f_t` beyond `δnp` (held at the peak: softening is not yet
///   implemented).
#[inline]
pub fn normal_stress(p: &JointParams, h: Real, dn: Real) -> Real {
    let ft = p.tensile_strength;
    let dnp = 2.0 * ft * h / p.penalty;
    let r = dn / dnp;
    if r < 0.0 {
        2.0 * r * ft
    } else if r <= 1.0 {
        (2.0 * r - r * r) * ft
    } else {
        ft
    }
}

/// Shear stress magnitude for slip magnitude `ds ≥ 0` under normal stress
/// `sigma`: the shear strength is `f_s = c − σ tan φ` (Eq. 5, Mohr–Coulomb;
/// tension positive, and `σ ≤ f_t` gives the tension cut-off), `δ_sp =
/// 2 f_s h / p0` (Eq. 7), and `τ` follows the branches of Eq. 11 with `f_s`
/// for `f_t`. Returns 0 where `f_s ≤ 0`.
#[inline]
pub fn shear_stress(p: &JointParams, h: Real, sigma: Real, ds: Real) -> Real {
    let fs = p.cohesion - sigma * p.friction_angle.tan();
    if fs <= 0.0 {
        return 0.0;
    }
    let dsp = 2.0 * fs * h / p.penalty;
    let r = ds / dsp;
    if r <= 1.0 { (2.0 * r - r * r) * fs } else { fs }
}

/// Stored energy per unit area of one branch of Eq. 11 at ratio `r = δ/δp`,
/// for peak `f` and peak displacement `dp`: `f dp r²` in compression (the
/// linear branch `2 r f`), `f dp (r² − r³/3)` on the hardening branch, and
/// `f dp (2/3 + (r − 1))` beyond the peak.
#[inline]
fn branch_energy(f: Real, dp: Real, r: Real) -> Real {
    if r < 0.0 {
        f * dp * r * r
    } else if r <= 1.0 {
        f * dp * (r * r - r * r * r / 3.0)
    } else {
        f * dp * (2.0 / 3.0 + (r - 1.0))
    }
}

/// An intact joint: parameters, its reference mean edge length `h`, and
/// the quantities of the law that depend only on them (precomputed: the
/// force kernel runs for every joint at every step).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntactJoint {
    /// The law's parameters.
    pub params: JointParams,
    /// Mean length of the joint's edges in the reference configuration, m.
    pub h: Real,
    /// `δ_np = 2 f_t h / p0` (Eq. 6), m.
    pub delta_np: Real,
    /// `tan φ`.
    pub tan_phi: Real,
}

impl IntactJoint {
    /// The joint of parameters `params` and reference mean edge `h`.
    pub fn new(params: JointParams, h: Real) -> IntactJoint {
        IntactJoint {
            params,
            h,
            delta_np: 2.0 * params.tensile_strength * h / params.penalty,
            tan_phi: params.friction_angle.tan(),
        }
    }
}

/// Forces of one joint on its six nodes, and its stored energy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointForces {
    /// Force on `N1 … N6`, N. They sum to zero.
    pub forces: [Vec3; 6],
    /// Stored (elastic) energy, J, when asked for (else 0): the
    /// area-weighted integral of the work done along Eq. 11 to reach the
    /// current opening and slip.
    pub energy: Real,
    /// Mean normal stress over the three points, Pa (tension positive).
    pub normal_stress: Real,
}

/// Nodal forces of a joint at current positions `x = [N1 … N6]`: at each
/// Hammer point the traction `t = σ z′ + τ δs/|δs|` acts on side a (pulling
/// it towards b when the joint is open) and `−t` on side b; each is
/// integrated with weight `A/3` and shared among the face's nodes by the
/// point's barycentric coordinates. A collapsed joint (no frame) exerts no
/// force. The stored energy is computed only when `with_energy` is set.
#[inline]
pub fn joint_forces(joint: &IntactJoint, x: &[Vec3; 6], with_energy: bool) -> JointForces {
    let mut out = JointForces {
        forces: [Vec3::zeros(); 6],
        energy: 0.0,
        normal_stress: 0.0,
    };
    let Some(k) = joint_kinematics(x) else {
        return out;
    };
    let p = &joint.params;
    let ft = p.tensile_strength;
    let dnp = joint.delta_np;
    let weight = k.frame.area / 3.0;
    let two_h_over_p0 = 2.0 * joint.h / p.penalty;
    for (i, w) in GAUSS.iter().enumerate() {
        // Eq. 11, normal.
        let r = k.opening[i] / dnp;
        let sigma = if r < 0.0 {
            2.0 * r * ft
        } else if r <= 1.0 {
            (2.0 * r - r * r) * ft
        } else {
            ft
        };
        // Eq. 5 and Eq. 11, shear.
        let fs = p.cohesion - sigma * joint.tan_phi;
        let ds = k.slip[i].norm();
        let mut t = k.frame.z * sigma;
        let mut dsp = 0.0;
        if fs > 0.0 {
            dsp = fs * two_h_over_p0;
            let rs = ds / dsp;
            let tau = if rs <= 1.0 {
                (2.0 * rs - rs * rs) * fs
            } else {
                fs
            };
            if ds > 0.0 {
                t += k.slip[i] * (tau / ds);
            }
        }
        let ft_w = t * weight;
        for (node_a, node_b, xi) in [(0, 5, w[0]), (1, 4, w[1]), (2, 3, w[2])] {
            out.forces[node_a] += ft_w * xi;
            out.forces[node_b] -= ft_w * xi;
        }
        if with_energy {
            out.energy += weight * branch_energy(ft, dnp, r);
            if fs > 0.0 {
                out.energy += weight * branch_energy(fs, dsp, ds / dsp);
            }
        }
        out.normal_stress += sigma / 3.0;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params() -> JointParams {
        JointParams {
            penalty: 26e10,
            tensile_strength: 3e6,
            cohesion: 15e6,
            friction_angle: 30f64.to_radians(),
        }
    }

    #[test]
    fn initial_slopes_equal_p0_over_h() {
        let p = params();
        let h = 1e-3;
        let k = p.penalty / h;
        // At r = δ/δp the secant slope of the hardening branch is (1 − r/2)·k.
        let d = 1e-3 * 2.0 * p.tensile_strength * h / p.penalty;
        assert!((normal_stress(&p, h, d) / d / k - (1.0 - 0.5e-3)).abs() < 1e-9);
        assert!((normal_stress(&p, h, -d) / -d / k - 1.0).abs() < 1e-12);
        let ds = 1e-3 * 2.0 * p.cohesion * h / p.penalty;
        assert!((shear_stress(&p, h, 0.0, ds) / ds / k - (1.0 - 0.5e-3)).abs() < 1e-9);
    }

    #[test]
    fn peak_is_reached_at_delta_p_and_continuous() {
        let p = params();
        let h = 1e-3;
        let dnp = 2.0 * p.tensile_strength * h / p.penalty;
        assert!((normal_stress(&p, h, dnp) - p.tensile_strength).abs() < 1e-6);
        let below = normal_stress(&p, h, dnp * (1.0 - 1e-9));
        let above = normal_stress(&p, h, dnp * (1.0 + 1e-9));
        assert!((below - above).abs() < 1e-6 * p.tensile_strength);
    }

    /// The kernel's inlined law agrees with the reference functions.
    #[test]
    fn kernel_matches_normal_and_shear_stress_functions() {
        let p = params();
        let joint = IntactJoint::new(p, 1e-3);
        let base = [
            Vec3::zeros(),
            Vec3::new(1e-3, 0.0, 0.0),
            Vec3::new(0.0, 1e-3, 0.0),
        ];
        for (dn, ds) in [(-3e-8, 2e-8), (1e-8, 5e-8), (4e-8, 1e-9), (1e-9, 3e-7)] {
            let d = Vec3::new(ds, 0.0, dn);
            let x = [
                base[0],
                base[1],
                base[2],
                base[2] + d,
                base[1] + d,
                base[0] + d,
            ];
            let f = joint_forces(&joint, &x, false);
            let sigma = normal_stress(&p, joint.h, dn);
            let tau = shear_stress(&p, joint.h, sigma, ds);
            let area = 0.5e-6;
            let fb: Vec3 = f.forces[3..].iter().sum();
            assert!(
                (fb.z + sigma * area).abs() < 1e-9 * (sigma.abs() * area).max(1e-12),
                "normal at {dn}"
            );
            assert!(
                (fb.x + tau * area).abs() < 1e-9 * (tau.abs() * area).max(1e-12),
                "shear at {ds}"
            );
        }
    }

    #[test]
    fn shear_strength_follows_mohr_coulomb() {
        let p = params();
        let h = 1e-3;
        for sigma in [-20e6, -5e6, 0.0, 2e6] {
            let fs = p.cohesion - sigma * p.friction_angle.tan();
            let far = shear_stress(&p, h, sigma, 1.0);
            assert!((far - fs).abs() < 1e-9 * fs, "σ = {sigma}");
        }
    }

    /// Forces are minus the gradient of the stored energy on the hardening
    /// branch (with no slip, the normal law is conservative).
    #[test]
    fn forces_are_energy_gradient_in_pure_opening() {
        let p = params();
        let joint = IntactJoint::new(p, 1e-3);
        let base = [
            Vec3::zeros(),
            Vec3::new(1e-3, 0.0, 0.0),
            Vec3::new(0.0, 1e-3, 0.0),
        ];
        let dn = 0.4 * 2.0 * p.tensile_strength * joint.h / p.penalty;
        let open = Vec3::new(0.0, 0.0, dn);
        let x = [
            base[0],
            base[1],
            base[2],
            base[2] + open,
            base[1] + open,
            base[0] + open,
        ];
        let f = joint_forces(&joint, &x, true);
        let sum: Vec3 = f.forces.iter().sum();
        assert!(sum.norm() < 1e-9 * f.forces[0].norm());
        // Moving the whole side b by ε along z changes the energy by −Σ f_b · ε.
        let eps = dn * 1e-5;
        let mut xp = x;
        let mut xm = x;
        for n in 3..6 {
            xp[n].z += eps;
            xm[n].z -= eps;
        }
        let de = (joint_forces(&joint, &xp, true).energy - joint_forces(&joint, &xm, true).energy)
            / (2.0 * eps);
        let fb: Real = (3..6).map(|n| f.forces[n].z).sum();
        assert!(
            (de + fb).abs() < 1e-6 * fb.abs(),
            "dE/dz = {de}, f_b = {fb}"
        );
    }
}
