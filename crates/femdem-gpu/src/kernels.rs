//! The WGSL sources of the kernels, each with the shared parts it needs
//! (WGSL has no include): `common.wgsl` (the uniform and the item number)
//! and `math.wgsl` (f64 `ln` and `exp`).

/// The uniform and the item number.
const COMMON: &str = include_str!("wgsl/common.wgsl");
/// f64 `ln64` and `exp64`.
const MATH: &str = include_str!("wgsl/math.wgsl");

/// The tet pass (Eq. 1–2).
pub(crate) fn tets() -> String {
    const _: () = assert!(femdem_material::J_FLOOR == 1e-2, "wgsl/tets.wgsl's J_FLOOR");
    [COMMON, MATH, include_str!("wgsl/tets.wgsl")].concat()
}

/// The joint pass (Eq. 3–13). Its softening curve takes `(1 − D)^c` as a
/// cube of a square, which holds for `c = 6` only.
pub(crate) fn joints() -> String {
    use femdem_fracture::softening::{A, B, C};
    const _: () = assert!(C == 6.0, "wgsl/joints.wgsl's z(D) assumes c = 6");
    const _: () = assert!(A == 0.63 && B == 1.8, "wgsl/joints.wgsl's ZA, ZB are Eq. 12's a, b");
    const _: () = assert!(femdem_fracture::DOMINANT_SHARE == 0.75, "wgsl/joints.wgsl's DOMINANT_SHARE");
    [COMMON, MATH, include_str!("wgsl/joints.wgsl")].concat()
}

/// The update of stage 5 (with the contact forces the host sends down,
/// where a scene has contact).
pub(crate) fn update() -> String {
    [COMMON, include_str!("wgsl/update.wgsl")].concat()
}

/// Sums in the CPU's chunk order.
pub(crate) fn reduce() -> String {
    [COMMON, include_str!("wgsl/reduce.wgsl")].concat()
}

/// The potential contact force of Eq. 17 between pairs of tets.
pub(crate) fn pairs() -> String {
    [COMMON, include_str!("wgsl/pairs.wgsl"), include_str!("wgsl/pair_bound.wgsl")].concat()
}

/// Surface loads' nodal forces and powers.
pub(crate) fn surface() -> String {
    [COMMON, include_str!("wgsl/surface.wgsl")].concat()
}

/// Vectors written into a per-node array.
pub(crate) fn scatter() -> String {
    [COMMON, include_str!("wgsl/scatter.wgsl")].concat()
}

/// Listed nodes' state.
pub(crate) fn compact() -> String {
    [COMMON, include_str!("wgsl/compact.wgsl")].concat()
}

/// The gather of slots into nodal forces.
pub(crate) fn gather() -> String {
    [COMMON, include_str!("wgsl/gather.wgsl")].concat()
}

/// `ln64` (flag 0) or `exp64` (flag 1) of every element of an array: the
/// math functions' test harness ([`crate::math`]).
pub(crate) fn math_probe() -> String {
    [COMMON, MATH, include_str!("wgsl/math_probe.wgsl")].concat()
}
