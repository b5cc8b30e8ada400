// An upper bound on a pair's Eq. 17 contact, `femdem_contact::contact_bound`
// on the device, operation for operation (the derivation is in
// `femdem-contact/src/bound.rs`): every nodal force and the resultant of
// the pair's contact are at most p times
//
//   S (max_{A∩B} φ_A + max_{A∩B} φ_B),
//
// S the surface area of the axis-aligned box of the overlap's vertices
// (nodes of one tet inside the other, crossings of one tet's edges with
// the other's face planes inside it) and φ = 4 min_j λ_j bounded by the
// least of the largest coordinates over those vertices. Each test of a
// point against a plane accepts values down to -η, η the larger of the
// two tets' slacks (bound.rs, "Rounding"); a tet flat or a slack beyond
// MAX_SLACK gives no bound.
//
// Rust's f64::max and f64::min return the other operand where one is NaN
// (WGSL leaves max and min of a NaN unspecified): `rmax` and `rmin`.

const SLACK: f64 = 1e-9;
const MAX_SLACK: f64 = 1e-6;
const EPSILON: f64 = 2.220446049250313e-16;

// The largest finite f64, doubled at run time for +∞ (WGSL has no literal
// for it, and a constant expression may not overflow).
var<private> largest: f64 = 1.7976931348623157e308;

fn infinity() -> f64 {
    return largest + largest;
}

fn rmax(a: f64, b: f64) -> f64 {
    if (a != a) {
        return b;
    }
    if (b != b) {
        return a;
    }
    return select(b, a, a > b);
}

fn rmin(a: f64, b: f64) -> f64 {
    if (a != a) {
        return b;
    }
    if (b != b) {
        return a;
    }
    return select(b, a, a < b);
}

// The box of the overlap's vertices and the largest coordinates in each
// tet over them (bound.rs's Hull).
var<private> hull_lo: vec3<f64>;
var<private> hull_hi: vec3<f64>;
var<private> hull_max: array<vec4<f64>, 2>;
var<private> hull_any: bool;

fn hull_add(p: vec3<f64>, own: vec4<f64>, other: vec4<f64>, swapped: bool) {
    hull_any = true;
    hull_lo = vec3<f64>(rmin(hull_lo.x, p.x), rmin(hull_lo.y, p.y), rmin(hull_lo.z, p.z));
    hull_hi = vec3<f64>(rmax(hull_hi.x, p.x), rmax(hull_hi.y, p.y), rmax(hull_hi.z, p.z));
    var la = own;
    var lb = other;
    if (swapped) {
        la = other;
        lb = own;
    }
    for (var j = 0u; j < 4u; j++) {
        hull_max[0][j] = rmax(hull_max[0][j], la[j]);
        hull_max[1][j] = rmax(hull_max[1][j], lb[j]);
    }
}

// bound.rs's slack: max(SLACK, 1024 u (1 + M (R + X))), M the sum of the
// absolute entries of `bary`'s matrix (column by column, as nalgebra
// iterates), R and X the sums of the absolute coordinates of t's nodes
// relative to bary's first node and absolute.
fn slack(t: array<vec3<f64>, 4>, bary: Bary) -> f64 {
    var m: f64 = 0.0;
    var rows = array<vec3<f64>, 3>(bary.r0, bary.r1, bary.r2);
    for (var c = 0u; c < 3u; c++) {
        for (var r = 0u; r < 3u; r++) {
            m = m + abs(rows[r][c]);
        }
    }
    var rel: f64 = 0.0;
    var at: f64 = 0.0;
    for (var k = 0u; k < 4u; k++) {
        let d = abs(t[k] - bary.x0);
        rel = rel + ((d.x + d.y) + d.z);
        let p = abs(t[k]);
        at = at + ((p.x + p.y) + p.z);
    }
    return rmax(SLACK, 1024.0 * ((EPSILON / 2.0) * (1.0 + m * (rel + at))));
}

const EDGES = array<vec2<u32>, 6>(vec2<u32>(0u, 1u), vec2<u32>(0u, 2u), vec2<u32>(0u, 3u), vec2<u32>(1u, 2u),
                                  vec2<u32>(1u, 3u), vec2<u32>(2u, 3u));

// Adds to the hull the nodes of t inside the other tet and the crossings
// of t's edges with the other tet's face planes inside it; l[k] are node
// k's coordinates in the other tet (bound.rs's one_way).
fn hull_one_way(tet: array<vec3<f64>, 4>, coords: array<vec4<f64>, 4>, swapped: bool, eta: f64) {
    var t = tet;
    var l = coords;
    var edges = EDGES;
    var out: array<u32, 4>;
    for (var k = 0u; k < 4u; k++) {
        var bits = 0u;
        for (var j = 0u; j < 4u; j++) {
            if (l[k][j] < -eta) {
                bits = bits | (1u << j);
            }
        }
        out[k] = bits;
    }
    if ((out[0] & out[1] & out[2] & out[3]) != 0u) {
        return;
    }
    for (var k = 0u; k < 4u; k++) {
        if (out[k] == 0u) {
            var unit = vec4<f64>(0.0, 0.0, 0.0, 0.0);
            unit[k] = 1.0;
            hull_add(t[k], unit, l[k], swapped);
        }
    }
    for (var e = 0u; e < 6u; e++) {
        let p = edges[e].x;
        let q = edges[e].y;
        if ((out[p] & out[q]) != 0u) {
            continue;
        }
        for (var j = 0u; j < 4u; j++) {
            let sp = l[p][j];
            let sq = l[q][j];
            if (!((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0))) {
                continue;
            }
            let s = sp / (sp - sq);
            let lp = l[p];
            let lq = l[q];
            let other = vec4<f64>(lp.x + (lq.x - lp.x) * s, lp.y + (lq.y - lp.y) * s, lp.z + (lq.z - lp.z) * s,
                                  lp.w + (lq.w - lp.w) * s);
            if (other.x < -eta || other.y < -eta || other.z < -eta || other.w < -eta) {
                continue;
            }
            var own = vec4<f64>(0.0, 0.0, 0.0, 0.0);
            own[p] = 1.0 - s;
            own[q] = s;
            hull_add(t[p] + (t[q] - t[p]) * s, own, other, swapped);
        }
    }
}

// 4 max(min_j m_j + η, 0), the min from +∞ (bound.rs's phi).
fn hull_phi(m: vec4<f64>, eta: f64) -> f64 {
    let least = rmin(rmin(rmin(rmin(infinity(), m.x), m.y), m.z), m.w);
    return 4.0 * rmax(least + eta, 0.0);
}

struct Bound {
    // Whether the pair has a bound (neither tet flat, the slack within
    // MAX_SLACK, the value not NaN).
    ok: bool,
    value: f64,
}

// femdem_contact::contact_bound of tets a and b with their coordinates.
fn pair_bound(a: array<vec3<f64>, 4>, b: array<vec3<f64>, 4>, in_a: Bary, in_b: Bary) -> Bound {
    if (!in_a.ok || !in_b.ok) {
        return Bound(false, 0.0);
    }
    let eta = rmax(slack(a, in_b), slack(b, in_a));
    if (eta != eta || eta > MAX_SLACK) {
        return Bound(false, 0.0);
    }
    var la: array<vec4<f64>, 4>;
    var lb: array<vec4<f64>, 4>;
    for (var k = 0u; k < 4u; k++) {
        la[k] = bary_at(in_b, a[k]);
        lb[k] = bary_at(in_a, b[k]);
    }
    let inf = infinity();
    hull_lo = vec3<f64>(inf, inf, inf);
    hull_hi = -hull_lo;
    hull_max[0] = vec4<f64>(-inf, -inf, -inf, -inf);
    hull_max[1] = hull_max[0];
    hull_any = false;
    hull_one_way(a, la, false, eta);
    hull_one_way(b, lb, true, eta);
    if (!hull_any) {
        return Bound(true, 0.0);
    }
    let e = (hull_hi - hull_lo) + (abs(hull_hi) + abs(hull_lo)) * (8.0 * EPSILON);
    let area = 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
    let bound = area * (1.0 * hull_phi(hull_max[0], eta) + 1.0 * hull_phi(hull_max[1], eta));
    return Bound(bound == bound, bound);
}
