//! Splitting a triangular prism into three tets so that neighbouring prisms
//! share faces exactly.
//!
//! Rule: with the bottom triangle's vertex ids sorted `a < b < c` and primes
//! marking the vertices above them, each quadrilateral side face
//! `(i, j, j', i')`, `i < j`, is cut by the diagonal from `i` to `j'`. Two
//! prisms that share a side face see the same two vertex ids and hence cut it
//! the same way, so the tet faces match. The tets are
//! `(a, b, c, c')`, `(a, b, c', b')`, `(a, b', c', a')`.

/// Returns the three tets of the prism with bottom `bottom` and top `top`
/// (`top[k]` above `bottom[k]`), all with positive volume given `coords`.
pub(crate) fn split_prism(bottom: [u32; 3], top: [u32; 3], coords: &[[f64; 3]]) -> [[u32; 4]; 3] {
    let mut order = [0usize, 1, 2];
    order.sort_unstable_by_key(|&k| bottom[k]);
    let [ia, ib, ic] = order;
    let (a, b, c) = (bottom[ia], bottom[ib], bottom[ic]);
    let (a2, b2, c2) = (top[ia], top[ib], top[ic]);
    [[a, b, c, c2], [a, b, c2, b2], [a, b2, c2, a2]].map(|t| orient(t, coords))
}

/// Swaps two nodes of `t` if its volume is negative.
pub(crate) fn orient(mut t: [u32; 4], coords: &[[f64; 3]]) -> [u32; 4] {
    let p = t.map(|n| {
        let c = coords[n as usize];
        femdem_core::Vec3::new(c[0], c[1], c[2])
    });
    if femdem_core::tet::signed_volume(&p) < 0.0 {
        t.swap(2, 3);
    }
    t
}
