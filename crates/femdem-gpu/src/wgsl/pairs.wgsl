// The penalty-function potential contact force between two tets (Munjiza &
// Andrews 2000; reference paper Eq. 17): `femdem_contact::tet_tet_contact`
// on the device, one invocation per pair (the derivation is in
// `femdem-contact/src/potential.rs`). The face's part inside the other tet,
// its bound and each piece's force are the CPU's operation for operation;
// the pieces are made by clipping that part to each sub-tet on its own (the
// CPU's earlier order, fewer buffers), where the CPU now splits it by a
// tournament: the same pieces in exact arithmetic, within rounding in
// floating point (the tests' tolerance, `tests/gpu/pairs.rs`):
//
//   f_A = -p ∫_{∂A ∩ B} φ_B n_A dS + p ∫_{∂B ∩ A} φ_A n_B dS,   f_B = -f_A,
//
// φ = 4 min_i λ_i, linear (= 4 λ_i) on the sub-tet i of a face and the
// centroid. Each face of one tet is clipped to the other tet (its planes
// λ_j ≥ 0 where a corner lies outside one), then to each sub-tet i that
// can hold part of it (λ_j - λ_i ≥ 0, j ≠ i; Sutherland–Hodgman in the
// face's coordinates μ, carrying λ along); a piece of area A at centroid P
// has force -p A φ(P) n, on the face's nodes by P's coordinates in the face
// and, opposite, on the other tet's nodes by P's λ.
//
// out[30 k ..]: forces on a's four nodes (12), on b's (12), the pieces'
// Σ |F| P (3) and Σ |F| (1): the contact centre is their quotient; then
// the pair's bound and 1 where it is negligible (below).
// pairs[2 k], pairs[2 k + 1]: the tets; scalars[0]: the penalty p, Pa.
//
// With flag bit 0, `femdem_contact::tet_tet_contact_within` with
// omit = omits[k] (m²): the pair's bound first (`wgsl/pair_bound.wgsl`);
// a pair bounded by at most omit is negligible (no forces, its bound in
// out[30 k + 28], 1 in out[30 k + 29]); otherwise faces are left out while
// the bounds on their pieces fit in a budget of p · omit
// (`femdem-contact/src/potential.rs`, "Faces left out"). The CPU's
// `clip_first` only orders its work (the same result bit for bit), so
// the device always bounds first.

@group(0) @binding(1) var<storage, read> x: array<f64>;
@group(0) @binding(2) var<storage, read> tets: array<u32>;
@group(0) @binding(3) var<storage, read> pairs: array<u32>;
@group(0) @binding(4) var<storage, read> scalars: array<f64>;
@group(0) @binding(5) var<storage, read_write> out: array<f64>;
@group(0) @binding(6) var<storage, read> omits: array<f64>;

// Numbers written per pair.
const OUT: u32 = 30u;

// At most 16 vertices (a triangle clipped by 4 planes, then 3: at most 10,
// with room for the duplicates a vertex on a plane makes).
const MAX_VERTICES: u32 = 16u;

struct Polygon {
    mu: array<vec2<f64>, 16>,
    lam: array<vec4<f64>, 16>,
    n: u32,
}

// Three clipping buffers: the face inside the other tet, a sub-tet's piece
// and a spare.
var<private> bufs: array<Polygon, 3>;
// Forces on the eight nodes: a's at 0..4, b's at 4..8.
var<private> forces: array<vec3<f64>, 8>;
var<private> moment: vec3<f64>;
var<private> weight: f64;
// What is left of the budget of the faces left out, m² (0: none left out).
var<private> budget: f64;

// The faces of a tet, outward normals (femdem_core::tet::FACES).
const FACES = array<vec3<u32>, 4>(vec3<u32>(1u, 2u, 3u), vec3<u32>(0u, 3u, 2u), vec3<u32>(0u, 1u, 3u),
                                  vec3<u32>(0u, 2u, 1u));

fn node(n: u32) -> vec3<f64> {
    return vec3<f64>(x[3u * n], x[3u * n + 1u], x[3u * n + 2u]);
}

fn push(b: u32, m: vec2<f64>, l: vec4<f64>) {
    let n = bufs[b].n;
    if (n < MAX_VERTICES) {
        bufs[b].mu[n] = m;
        bufs[b].lam[n] = l;
        bufs[b].n = n + 1u;
    }
}

// The clipping function: λ_j (i = 4) or λ_j - λ_i.
fn plane(l: vec4<f64>, j: u32, i: u32) -> f64 {
    if (i >= 4u) {
        return l[j];
    }
    return l[j] - l[i];
}

// bufs[to] = the part of bufs[src] where plane(λ, j, i) ≥ 0
// (Sutherland–Hodgman; a new vertex a + (b - a) t, t = f_a / (f_a - f_b),
// in μ and λ alike).
fn clip_into(src: u32, to: u32, j: u32, i: u32) {
    bufs[to].n = 0u;
    let n = min(bufs[src].n, MAX_VERTICES);
    if (n == 0u) {
        return;
    }
    var fb = plane(bufs[src].lam[0], j, i);
    for (var k = 0u; k < n; k++) {
        var next = k + 1u;
        if (next == n) {
            next = 0u;
        }
        let fa = fb;
        fb = plane(bufs[src].lam[next], j, i);
        if (fa >= 0.0) {
            push(to, bufs[src].mu[k], bufs[src].lam[k]);
        }
        if ((fa >= 0.0) != (fb >= 0.0)) {
            let t = fa / (fa - fb);
            let ma = bufs[src].mu[k];
            let mb = bufs[src].mu[next];
            let la = bufs[src].lam[k];
            let lb = bufs[src].lam[next];
            let m = vec2<f64>(ma.x + (mb.x - ma.x) * t, ma.y + (mb.y - ma.y) * t);
            let l = vec4<f64>(la.x + (lb.x - la.x) * t, la.y + (lb.y - la.y) * t, la.z + (lb.z - la.z) * t,
                              la.w + (lb.w - la.w) * t);
            push(to, m, l);
        }
    }
}

// Whether some vertex of bufs[b] has plane(λ, j, i) < 0 (any_below), every
// vertex has it exactly 0 (all_zero), or every vertex has it < 0 (all_below).
fn any_below(b: u32, j: u32, i: u32) -> bool {
    for (var k = 0u; k < bufs[b].n; k++) {
        if (plane(bufs[b].lam[k], j, i) < 0.0) {
            return true;
        }
    }
    return false;
}

fn all_zero(b: u32, j: u32, i: u32) -> bool {
    for (var k = 0u; k < bufs[b].n; k++) {
        if (plane(bufs[b].lam[k], j, i) != 0.0) {
            return false;
        }
    }
    return true;
}

fn all_below(b: u32, j: u32, i: u32) -> bool {
    for (var k = 0u; k < bufs[b].n; k++) {
        if (!(plane(bufs[b].lam[k], j, i) < 0.0)) {
            return false;
        }
    }
    return true;
}

// Area in μ, the centroid's μ and λ of bufs[b] (a fan from the first
// vertex); zeros when the area is not positive.
struct Piece {
    area: f64,
    mu: vec2<f64>,
    lam: vec4<f64>,
}

// Area in μ of bufs[b] (a fan from the first vertex, as area_centroid).
fn area(b: u32) -> f64 {
    var sum: f64 = 0.0;
    let m0 = bufs[b].mu[0];
    let n = bufs[b].n;
    for (var k = 1u; k + 1u < n; k++) {
        let m1 = bufs[b].mu[k];
        let m2 = bufs[b].mu[k + 1u];
        sum = sum + 0.5 * ((m1.x - m0.x) * (m2.y - m0.y) - (m1.y - m0.y) * (m2.x - m0.x));
    }
    return sum;
}

// Whether the face inside the other tet (bufs[b]) is left out: its
// pieces' Σ |F| / p is at most A · 4 min_j max λ_j, and that fits in what
// is left of the budget, which it then uses up.
fn left_out(b: u32, twice_area: f64) -> bool {
    if (!(budget > 0.0)) {
        return false;
    }
    var highest = infinity();
    for (var j = 0u; j < 4u; j++) {
        var top = -infinity();
        for (var k = 0u; k < bufs[b].n; k++) {
            top = rmax(top, bufs[b].lam[k][j]);
        }
        highest = rmin(highest, top);
    }
    let bound = rmax(area(b), 0.0) * twice_area * 4.0 * rmax(highest, 0.0);
    if (bound <= budget) {
        budget = budget - bound;
        return true;
    }
    return false;
}

fn area_centroid(b: u32) -> Piece {
    var area: f64 = 0.0;
    var mu = vec2<f64>(0.0, 0.0);
    var lam = vec4<f64>(0.0, 0.0, 0.0, 0.0);
    let m0 = bufs[b].mu[0];
    let l0 = bufs[b].lam[0];
    let n = bufs[b].n;
    for (var k = 1u; k + 1u < n; k++) {
        let m1 = bufs[b].mu[k];
        let m2 = bufs[b].mu[k + 1u];
        let w = 0.5 * ((m1.x - m0.x) * (m2.y - m0.y) - (m1.y - m0.y) * (m2.x - m0.x));
        area = area + w;
        let w3 = w / 3.0;
        mu = mu + (m0 + m1 + m2) * w3;
        let l1 = bufs[b].lam[k];
        let l2 = bufs[b].lam[k + 1u];
        lam = lam + (l0 + l1 + l2) * w3;
    }
    if (area > 0.0) {
        return Piece(area, mu / area, lam / area);
    }
    return Piece(0.0, vec2<f64>(0.0, 0.0), vec4<f64>(0.0, 0.0, 0.0, 0.0));
}

// A tet's barycentric coordinates as an affine map: λ1..3 = m (p - x0),
// λ0 = 1 - λ1 - λ2 - λ3 (nalgebra's 3 × 3 inverse, as the CPU's); `ok` is
// false for a flat tet.
struct Bary {
    x0: vec3<f64>,
    r0: vec3<f64>,
    r1: vec3<f64>,
    r2: vec3<f64>,
    ok: bool,
}

fn barycentric(t: array<vec3<f64>, 4>) -> Bary {
    let c1 = t[1] - t[0];
    let c2 = t[2] - t[0];
    let c3 = t[3] - t[0];
    let m11 = c1.x;
    let m12 = c2.x;
    let m13 = c3.x;
    let m21 = c1.y;
    let m22 = c2.y;
    let m23 = c3.y;
    let m31 = c1.z;
    let m32 = c2.z;
    let m33 = c3.z;
    let minor_m12_m23 = m22 * m33 - m32 * m23;
    let minor_m11_m23 = m21 * m33 - m31 * m23;
    let minor_m11_m22 = m21 * m32 - m31 * m22;
    let det = m11 * minor_m12_m23 - m12 * minor_m11_m23 + m13 * minor_m11_m22;
    var b: Bary;
    b.x0 = t[0];
    b.ok = det != 0.0;
    if (!b.ok) {
        return b;
    }
    b.r0 = vec3<f64>(minor_m12_m23 / det, (m13 * m32 - m33 * m12) / det, (m12 * m23 - m22 * m13) / det);
    b.r1 = vec3<f64>(-minor_m11_m23 / det, (m11 * m33 - m31 * m13) / det, (m13 * m21 - m23 * m11) / det);
    b.r2 = vec3<f64>(minor_m11_m22 / det, (m12 * m31 - m32 * m11) / det, (m11 * m22 - m21 * m12) / det);
    return b;
}

fn row(r: vec3<f64>, d: vec3<f64>) -> f64 {
    return r.x * d.x + r.y * d.y + r.z * d.z;
}

fn bary_at(b: Bary, p: vec3<f64>) -> vec4<f64> {
    let d = p - b.x0;
    let l1 = row(b.r0, d);
    let l2 = row(b.r1, d);
    let l3 = row(b.r2, d);
    return vec4<f64>(1.0 - l1 - l2 - l3, l1, l2, l3);
}

// The forces of a's faces penetrating b's potential (b's coordinates
// `bary`), added to forces[own..own + 4] (a's nodes) and
// forces[other..other + 4] (b's), and the pieces' Σ |F| P, Σ |F|.
fn one_way(tet: array<vec3<f64>, 4>, bary: Bary, penalty: f64, own: u32, other: u32) {
    if (!bary.ok) {
        return;
    }
    // Local copies: arrays indexed at run time.
    var a = tet;
    var faces = FACES;
    var corners: array<vec4<f64>, 4>;
    for (var k = 0u; k < 4u; k++) {
        corners[k] = bary_at(bary, a[k]);
    }
    for (var f = 0u; f < 4u; f++) {
        let face = faces[f];
        let p0 = a[face.x];
        let e1 = a[face.y] - p0;
        let e2 = a[face.z] - p0;
        let normal = vec3<f64>(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
        let twice_area = sqrt(normal.x * normal.x + normal.y * normal.y + normal.z * normal.z);
        if (twice_area <= 0.0) {
            continue;
        }
        let n = normal / twice_area;
        var lam = array<vec4<f64>, 3>(corners[face.x], corners[face.y], corners[face.z]);
        // The whole face outside one of b's face planes.
        var outside = false;
        for (var i = 0u; i < 4u; i++) {
            if (lam[0][i] < 0.0 && lam[1][i] < 0.0 && lam[2][i] < 0.0) {
                outside = true;
            }
        }
        if (outside) {
            continue;
        }
        var ins = 0u;
        var spare = 2u;
        bufs[ins].n = 0u;
        push(ins, vec2<f64>(0.0, 0.0), lam[0]);
        push(ins, vec2<f64>(1.0, 0.0), lam[1]);
        push(ins, vec2<f64>(0.0, 1.0), lam[2]);
        // The face inside b, by b's face planes where a vertex is outside.
        for (var j = 0u; j < 4u; j++) {
            if (any_below(ins, j, 4u)) {
                clip_into(ins, spare, j, 4u);
                let s = ins;
                ins = spare;
                spare = s;
            }
        }
        if (bufs[ins].n < 3u || left_out(ins, twice_area)) {
            continue;
        }
        for (var i = 0u; i < 4u; i++) {
            // Sub-tet i: a plane λ_j - λ_i negative at every vertex keeps
            // nothing; one zero at every vertex (the face's part lies on the
            // boundary between sub-tets j and i) has its region counted with
            // the sub-tet j < i already, as the CPU's tournament counts it
            // once.
            var empty = false;
            for (var j = 0u; j < 4u; j++) {
                if (j != i && (all_below(ins, j, i) || (j < i && all_zero(ins, j, i)))) {
                    empty = true;
                }
            }
            if (empty) {
                continue;
            }
            var poly = 1u;
            var sp = spare;
            var first = true;
            for (var j = 0u; j < 4u; j++) {
                if (j == i) {
                    continue;
                }
                var src = poly;
                if (first) {
                    src = ins;
                }
                clip_into(src, sp, j, i);
                let s = poly;
                poly = sp;
                sp = s;
                first = false;
            }
            if (bufs[poly].n < 3u) {
                continue;
            }
            let piece = area_centroid(poly);
            if (piece.area <= 0.0) {
                continue;
            }
            // Rust's `max(0.0)`: 0 for a NaN too (WGSL's `max` leaves it
            // unspecified).
            let li = piece.lam[i];
            let phi = 4.0 * select(0.0, li, li > 0.0);
            let magnitude = penalty * (piece.area * twice_area) * phi;
            let force = n * -magnitude;
            let m1 = piece.mu.x;
            let m2 = piece.mu.y;
            let centroid = p0 + e1 * m1 + e2 * m2;
            moment = moment + centroid * magnitude;
            weight = weight + magnitude;
            let w = vec3<f64>(1.0 - m1 - m2, m1, m2);
            forces[own + face.x] = forces[own + face.x] + force * w.x;
            forces[own + face.y] = forces[own + face.y] + force * w.y;
            forces[own + face.z] = forces[own + face.z] + force * w.z;
            for (var k = 0u; k < 4u; k++) {
                forces[other + k] = forces[other + k] - force * piece.lam[k];
            }
        }
    }
}

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>,
        @builtin(local_invocation_index) local: u32) {
    let k = item(wg, nwg, local);
    if (k >= params.count) {
        return;
    }
    let ta = pairs[2u * k];
    let tb = pairs[2u * k + 1u];
    var a: array<vec3<f64>, 4>;
    var b: array<vec3<f64>, 4>;
    for (var c = 0u; c < 4u; c++) {
        a[c] = node(tets[4u * ta + c]);
        b[c] = node(tets[4u * tb + c]);
    }
    for (var c = 0u; c < 8u; c++) {
        forces[c] = vec3<f64>(0.0, 0.0, 0.0);
    }
    moment = vec3<f64>(0.0, 0.0, 0.0);
    weight = 0.0;
    budget = 0.0;
    let penalty = scalars[0];
    let in_a = barycentric(a);
    let in_b = barycentric(b);
    var bound = Bound(false, 0.0);
    var negligible = false;
    if ((params.flags & 1u) != 0u) {
        budget = omits[k];
        bound = pair_bound(a, b, in_a, in_b);
        negligible = bound.ok && bound.value <= budget;
    }
    if (!negligible) {
        one_way(a, in_b, penalty, 0u, 4u);
        one_way(b, in_a, penalty, 4u, 0u);
    }
    let o = OUT * k;
    for (var c = 0u; c < 8u; c++) {
        out[o + 3u * c] = forces[c].x;
        out[o + 3u * c + 1u] = forces[c].y;
        out[o + 3u * c + 2u] = forces[c].z;
    }
    out[o + 24u] = moment.x;
    out[o + 25u] = moment.y;
    out[o + 26u] = moment.z;
    out[o + 27u] = weight;
    out[o + 28u] = select(0.0, bound.value, bound.ok);
    out[o + 29u] = select(f64(0.0), f64(1.0), negligible);
}
