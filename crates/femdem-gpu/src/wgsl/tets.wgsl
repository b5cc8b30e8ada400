// The tet pass (Eq. 1-2; `femdem_material::tet_forces`): each tet's forces
// on its four nodes into its own slots, its stored energy W V0, and (flag
// bit 0) its Cauchy stress. A rigid tet (material index 0xffffffff) writes
// zero forces and energy.
//
// Per tet t: nodes tets[4t..4t+4]; reference refs[10t..10t+10] = Dm^-1 by
// columns, then V0; material materials[4m..4m+4] = lambda, mu, eta, law
// (0 neo-Hookean, 1 linear elastic). Slots: 12 numbers, node by node.
//
// Flag bit 1: the viscous dissipation rate of each tet into rate[t],
// R = eta D(v) : D(v_mean) V0 J with v_mean = (v + v_before)/2 and
// L = edges(v) cof(Ds)^T / det(Ds) (femdem_solver::forces::Dissipation;
// the CPU skips a rate that is not finite, and so does the host's sum).

@group(0) @binding(1) var<storage, read> x: array<f64>;
@group(0) @binding(2) var<storage, read> v: array<f64>;
@group(0) @binding(3) var<storage, read> tets: array<u32>;
@group(0) @binding(4) var<storage, read> refs: array<f64>;
@group(0) @binding(5) var<storage, read> tet_mat: array<u32>;
@group(0) @binding(6) var<storage, read> materials: array<f64>;
@group(0) @binding(7) var<storage, read_write> slots: array<f64>;
@group(0) @binding(8) var<storage, read_write> energy: array<f64>;
@group(0) @binding(9) var<storage, read_write> stress: array<f64>;
@group(0) @binding(10) var<storage, read> v_before: array<f64>;
@group(0) @binding(11) var<storage, read_write> rate: array<f64>;

const J_FLOOR: f64 = 1.0e-2;
const RIGID: u32 = 0xffffffffu;

// (WGSL passes no storage pointers to functions: one reader per array.)
fn position(n: u32) -> vec3<f64> {
    return vec3<f64>(x[3u * n], x[3u * n + 1u], x[3u * n + 2u]);
}

fn velocity(n: u32) -> vec3<f64> {
    return vec3<f64>(v[3u * n], v[3u * n + 1u], v[3u * n + 2u]);
}

fn mean_velocity(n: u32) -> vec3<f64> {
    let b = vec3<f64>(v_before[3u * n], v_before[3u * n + 1u], v_before[3u * n + 2u]);
    return (velocity(n) + b) * 0.5;
}

// [p1 - p0, p2 - p0, p3 - p0] by columns.
fn edges(p0: vec3<f64>, p1: vec3<f64>, p2: vec3<f64>, p3: vec3<f64>) -> mat3x3<f64> {
    return mat3x3<f64>(p1 - p0, p2 - p0, p3 - p0);
}

// cof A = det(A) A^-T, by columns: [a1 x a2, a2 x a0, a0 x a1].
fn cofactor(a: mat3x3<f64>) -> mat3x3<f64> {
    return mat3x3<f64>(cross(a[1], a[2]), cross(a[2], a[0]), cross(a[0], a[1]));
}

fn sym(a: mat3x3<f64>) -> mat3x3<f64> {
    return (a + transpose(a)) * 0.5;
}

fn frob2(a: mat3x3<f64>) -> f64 {
    return dot(a[0], a[0]) + dot(a[1], a[1]) + dot(a[2], a[2]);
}

fn diag(s: f64) -> mat3x3<f64> {
    return mat3x3<f64>(vec3<f64>(s, 0.0, 0.0), vec3<f64>(0.0, s, 0.0), vec3<f64>(0.0, 0.0, s));
}

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>,
        @builtin(local_invocation_index) local: u32) {
    let t = item(wg, nwg, local);
    if (t >= params.count) {
        return;
    }
    let m = tet_mat[t];
    if (m == RIGID) {
        for (var k = 0u; k < 12u; k++) {
            slots[12u * t + k] = 0.0;
        }
        energy[t] = 0.0;
        rate[t] = 0.0;
        return;
    }
    let n0 = tets[4u * t];
    let n1 = tets[4u * t + 1u];
    let n2 = tets[4u * t + 2u];
    let n3 = tets[4u * t + 3u];
    let r = 10u * t;
    let inv_dm = mat3x3<f64>(vec3<f64>(refs[r], refs[r + 1u], refs[r + 2u]),
                             vec3<f64>(refs[r + 3u], refs[r + 4u], refs[r + 5u]),
                             vec3<f64>(refs[r + 6u], refs[r + 7u], refs[r + 8u]));
    let volume = refs[r + 9u];
    let lambda = materials[4u * m];
    let mu = materials[4u * m + 1u];
    let eta = materials[4u * m + 2u];
    let law = materials[4u * m + 3u];

    let f = edges(position(n0), position(n1), position(n2), position(n3)) * inv_dm;
    let cof = cofactor(f);
    let j = dot(f[0], cof[0]);
    let f_dot = edges(velocity(n0), velocity(n1), velocity(n2), velocity(n3)) * inv_dm;
    // L = F' F^-1 = F' cof(F)^T / J, guarded at the floor.
    let l = f_dot * transpose(cof) * (1.0 / max(j, J_FLOOR));
    let d = sym(l);
    var p: mat3x3<f64>;
    var cauchy: mat3x3<f64>;
    var w: f64;
    if (law == 0.0) {
        // Neo-Hookean (Eq. 1) with J^ = max(J, J_FLOOR) and the volumetric
        // energy continued linearly below the floor (femdem_material::law).
        let jh = max(j, J_FLOOR);
        let ln_jh = ln64(jh);
        let du = (lambda * ln_jh - mu) / jh;
        // W from the Green-Lagrange strain E = (H + H^T + H^T H)/2,
        // H = F - I, where it is small and J > 0, without the cancellation of its
        // first-order terms; as written elsewhere (femdem_material::law,
        // "Energy at small strains"): y = J^2 - 1 = 2 tr E + 4 I2(E) + 8 det E.
        let hm = f - diag(1.0);
        let e = (hm + transpose(hm) + transpose(hm) * hm) * 0.5;
        // C = F^T F cannot tell a reflection from no deformation: J > 0 too.
        if (j > 0.0 && frob2(e) < 1.0e-2) {
            let tr = e[0][0] + e[1][1] + e[2][2];
            let i2 = 0.5 * (tr * tr - frob2(e));
            let det = dot(e[0], cross(e[1], e[2]));
            let lg = ln1p_and_excess(2.0 * tr + 4.0 * i2 + 8.0 * det);
            w = 0.5 * mu * lg.y - 2.0 * mu * i2 - 4.0 * mu * det + 0.125 * lambda * lg.x * lg.x;
        } else {
            let u = (0.5 * lambda * ln_jh - mu) * ln_jh + du * (j - jh);
            w = 0.5 * mu * (frob2(f) - 3.0) + u;
        }
        p = f * mu + (diag(du) + d * eta) * cof;
        let b = f * transpose(f);
        cauchy = b * (mu / jh) + diag((lambda * ln_jh - mu) / jh) + d * eta;
    } else {
        // Linear elastic: sigma = lambda tr(eps) I + 2 mu eps + eta D.
        let eps = sym(f) - diag(1.0);
        let tr = eps[0][0] + eps[1][1] + eps[2][2];
        cauchy = diag(lambda * tr) + eps * (2.0 * mu) + d * eta;
        w = 0.5 * lambda * tr * tr + mu * frob2(eps);
        p = cauchy;
    }
    // [f1 f2 f3] = -V0 P Dm^-T, f0 = -(f1 + f2 + f3).
    let h = p * transpose(inv_dm) * (-volume);
    let f0 = -(h[0] + h[1] + h[2]);
    let s = 12u * t;
    slots[s] = f0.x;
    slots[s + 1u] = f0.y;
    slots[s + 2u] = f0.z;
    for (var c = 0u; c < 3u; c++) {
        slots[s + 3u + 3u * c] = h[c].x;
        slots[s + 4u + 3u * c] = h[c].y;
        slots[s + 5u + 3u * c] = h[c].z;
    }
    energy[t] = w * volume;
    rate[t] = 0.0;
    let ds = edges(position(n0), position(n1), position(n2), position(n3));
    let cof_ds = cofactor(ds);
    let det_ds = dot(ds[0], cof_ds[0]);
    // A flat tet's rate is not finite: the CPU leaves it out, and a device
    // may assume values finite and not filter it (reduce.wgsl tries too).
    if ((params.flags & 2u) != 0u && eta > 0.0 && det_ds != 0.0) {
        let lv = edges(velocity(n0), velocity(n1), velocity(n2), velocity(n3)) * transpose(cof_ds) * (1.0 / det_ds);
        let lm = edges(mean_velocity(n0), mean_velocity(n1), mean_velocity(n2), mean_velocity(n3))
            * transpose(cof_ds) * (1.0 / det_ds);
        let dv = sym(lv);
        let dm = sym(lm);
        let dd = dot(dv[0], dm[0]) + dot(dv[1], dm[1]) + dot(dv[2], dm[2]);
        rate[t] = eta * dd * volume * j;
    }
    if ((params.flags & 1u) != 0u) {
        for (var c = 0u; c < 3u; c++) {
            stress[9u * t + 3u * c] = cauchy[c].x;
            stress[9u * t + 3u * c + 1u] = cauchy[c].y;
            stress[9u * t + 3u * c + 2u] = cauchy[c].z;
        }
    }
}
