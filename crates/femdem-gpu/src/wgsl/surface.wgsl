// Surface loads on the current geometry (`femdem_solver::loads::surface_forces`):
// each face carries s A t, t = -p n (pressure, positive inward) or a fixed
// traction per unit current area, shared equally by its three nodes:
//   area_normal = (b - a) x (c - a) / 2   (outward, |.| = area),
//   pressure:  f = (-area_normal) (p s),    traction: f = t (|area_normal| s),
//   each node's share f / 3; a load at factor s = 0 applies nothing.
//
// Three passes, chosen by params.flags:
//   0, one invocation per face: its share (terms[5j..5j+3]) and its power
//      against the old velocities, share . (v_a + v_b + v_c) added node by
//      node (terms[5j+3]);
//   1, one invocation per loaded node: its surface force, the shares of
//      its faces added from zero in face order (faces are load after load,
//      so this is the CPU's (load, face) order), into f_surface;
//   2, one invocation per face, after the update: its power against the
//      new velocities (terms[5j+4]).
// table[6k..6k+6] = kind (0 pressure, 1 traction), s, p, tx, ty, tz of
// load k.

@group(0) @binding(1) var<storage, read> x: array<f64>;
@group(0) @binding(2) var<storage, read> v: array<f64>;
@group(0) @binding(3) var<storage, read> faces: array<u32>;
@group(0) @binding(4) var<storage, read> face_load: array<u32>;
@group(0) @binding(5) var<storage, read> table: array<f64>;
@group(0) @binding(6) var<storage, read_write> terms: array<f64>;
@group(0) @binding(7) var<storage, read> loaded: array<u32>;
@group(0) @binding(8) var<storage, read> offsets: array<u32>;
@group(0) @binding(9) var<storage, read> entries: array<u32>;
@group(0) @binding(10) var<storage, read_write> f_surface: array<f64>;

fn at(a: u32) -> vec3<f64> {
    return vec3<f64>(x[3u * a], x[3u * a + 1u], x[3u * a + 2u]);
}

fn vel(a: u32) -> vec3<f64> {
    return vec3<f64>(v[3u * a], v[3u * a + 1u], v[3u * a + 2u]);
}

fn dot3(a: vec3<f64>, b: vec3<f64>) -> f64 {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

fn share_of(j: u32) -> vec3<f64> {
    return vec3<f64>(terms[5u * j], terms[5u * j + 1u], terms[5u * j + 2u]);
}

// Power of face j's share against the velocities in `v`, node by node.
fn power(j: u32) -> f64 {
    let f = share_of(j);
    var p: f64 = 0.0;
    for (var k = 0u; k < 3u; k++) {
        p = p + dot3(f, vel(faces[3u * j + k]));
    }
    return p;
}

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>,
        @builtin(local_invocation_index) local: u32) {
    let i = item(wg, nwg, local);
    if (i >= params.count) {
        return;
    }
    let which = params.flags;
    if (which == 1u) {
        var sum = vec3<f64>(0.0, 0.0, 0.0);
        for (var e = offsets[i]; e < offsets[i + 1u]; e++) {
            sum = sum + share_of(entries[e]);
        }
        let n = loaded[i];
        f_surface[3u * n] = sum.x;
        f_surface[3u * n + 1u] = sum.y;
        f_surface[3u * n + 2u] = sum.z;
        return;
    }
    if (which == 2u) {
        terms[5u * i + 4u] = power(i);
        return;
    }
    let k = face_load[i];
    let s = table[6u * k + 1u];
    var share = vec3<f64>(0.0, 0.0, 0.0);
    if (s != 0.0) {
        let a = at(faces[3u * i]);
        let b = at(faces[3u * i + 1u]);
        let c = at(faces[3u * i + 2u]);
        let u = b - a;
        let w = c - a;
        let n = vec3<f64>(u.y * w.z - u.z * w.y, u.z * w.x - u.x * w.z, u.x * w.y - u.y * w.x) * 0.5;
        var force: vec3<f64>;
        if (table[6u * k] == 0.0) {
            force = -n * (table[6u * k + 2u] * s);
        } else {
            let t = vec3<f64>(table[6u * k + 3u], table[6u * k + 4u], table[6u * k + 5u]);
            force = t * (sqrt(n.x * n.x + n.y * n.y + n.z * n.z) * s);
        }
        share = force / 3.0;
    }
    terms[5u * i] = share.x;
    terms[5u * i + 1u] = share.y;
    terms[5u * i + 2u] = share.z;
    terms[5u * i + 3u] = power(i);
}
