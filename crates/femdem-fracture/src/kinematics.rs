//! Joint kinematics (reference paper §2.2, Fig. 2, Eq. 3).
//!
//! The local frame `x′y′z′` lies in the mid-plane through `N16`, `N25`,
//! `N34`, the midpoints of the coincident node pairs `N1–N6`, `N2–N5`,
//! `N3–N4`. `z′` is the mid-plane normal `(N25 − N16) × (N34 − N16)`,
//! normalised; it points from the tet carrying `N1 N2 N3` (side a) to the
//! tet carrying `N4 N5 N6` (side b). `x′` is along `N25 − N16` and
//! `y′ = z′ × x′`.
//!
//! At an integration point with barycentric weights `(ξ1, ξ2, ξ3)` the
//! point of face a is `ξ1 N1 + ξ2 N2 + ξ3 N3` and the matching point of face
//! b is `ξ1 N6 + ξ2 N5 + ξ3 N4`. Their difference `g = p_b − p_a` splits into
//! the normal opening `δn = g · z′` (Eq. 3; positive when the faces move
//! apart) and the slip `δs = g − δn z′`, a vector in the `x′y′` plane whose
//! magnitude enters the strength law and whose direction carries the shear
//! traction.

use femdem_core::{Real, Vec3};

/// Hammer's three-point rule on a triangle (Hammer, Marlowe & Stroud 1956):
/// barycentric coordinates of the points A, B, C, each of weight 1/3 of the
/// area; exact for quadratic integrands.
pub const GAUSS: [[Real; 3]; 3] =
    [[2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0], [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0], [1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0]];

/// The joint's local frame and mid-plane area.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointFrame {
    /// `x′`, unit.
    pub x: Vec3,
    /// `y′ = z′ × x′`, unit.
    pub y: Vec3,
    /// `z′`, the unit normal from side a to side b.
    pub z: Vec3,
    /// Area of the mid-plane triangle `N16 N25 N34`, m².
    pub area: Real,
}

/// Opening and slip at the three integration points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointKinematics {
    /// The local frame.
    pub frame: JointFrame,
    /// Normal opening `δn` at each point, m (positive: faces apart).
    pub opening: [Real; 3],
    /// Slip vector `δs` at each point (global components, in the `x′y′`
    /// plane), m.
    pub slip: [Vec3; 3],
}

impl JointKinematics {
    /// The slip at point `i` in the local `(x′, y′)` components.
    pub fn local_slip(&self, i: usize) -> [Real; 2] {
        [self.slip[i].dot(&self.frame.x), self.slip[i].dot(&self.frame.y)]
    }
}

/// Computes the frame, openings and slips of a joint from its six current
/// node positions `[N1, …, N6]`. Returns `None` when the mid-plane triangle
/// has collapsed (zero area), where no frame exists.
#[inline]
pub fn joint_kinematics(x: &[Vec3; 6]) -> Option<JointKinematics> {
    let m16 = (x[0] + x[5]) * 0.5;
    let m25 = (x[1] + x[4]) * 0.5;
    let m34 = (x[2] + x[3]) * 0.5;
    let e1 = m25 - m16;
    let n = e1.cross(&(m34 - m16));
    let twice_area = n.norm();
    let len1 = e1.norm();
    if twice_area <= 0.0 || len1 <= 0.0 || !twice_area.is_finite() {
        return None;
    }
    let z = n / twice_area;
    let xa = e1 / len1;
    let frame = JointFrame { x: xa, y: z.cross(&xa), z, area: 0.5 * twice_area };
    let mut opening = [0.0; 3];
    let mut slip = [Vec3::zeros(); 3];
    for (i, w) in GAUSS.iter().enumerate() {
        let pa = x[0] * w[0] + x[1] * w[1] + x[2] * w[2];
        let pb = x[5] * w[0] + x[4] * w[1] + x[3] * w[2];
        let g = pb - pa;
        opening[i] = g.dot(&z);
        slip[i] = g - z * opening[i];
    }
    Some(JointKinematics { frame, opening, slip })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit right triangle in z = 0 for side a, and side b shifted by `d`.
    fn joint(d: Vec3) -> [Vec3; 6] {
        let a = [Vec3::zeros(), Vec3::x(), Vec3::y()];
        [a[0], a[1], a[2], a[2] + d, a[1] + d, a[0] + d]
    }

    #[test]
    fn closed_joint_has_no_opening_or_slip() {
        let k = joint_kinematics(&joint(Vec3::zeros())).unwrap();
        assert_eq!(k.opening, [0.0; 3]);
        assert!(k.slip.iter().all(|s| s.norm() == 0.0));
        assert!((k.frame.area - 0.5).abs() < 1e-15);
        assert!((k.frame.z - Vec3::z()).norm() < 1e-15, "normal points from a to b");
    }

    #[test]
    fn uniform_separation_splits_into_opening_and_slip() {
        let d = Vec3::new(0.003, -0.004, 0.002);
        let k = joint_kinematics(&joint(d)).unwrap();
        for i in 0..3 {
            // The mid-plane moves by d/2 and stays parallel: z′ = e_z.
            assert!((k.opening[i] - 0.002).abs() < 1e-15);
            assert!((k.slip[i] - Vec3::new(0.003, -0.004, 0.0)).norm() < 1e-15);
            let [sx, sy] = k.local_slip(i);
            assert!(((sx * sx + sy * sy).sqrt() - 0.005).abs() < 1e-15);
        }
    }

    #[test]
    fn collapsed_joint_has_no_frame() {
        let p = Vec3::new(1.0, 2.0, 3.0);
        assert!(joint_kinematics(&[p; 6]).is_none());
    }
}
