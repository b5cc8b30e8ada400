// Stage 5 on the device: the central-difference update of `femdem_solver`'s `advance_chunk`,
//   v_{n+1/2} = v_{n-1/2} + dt (f_int + f_ext) / m   (m > 0; else v unchanged),
// f_ext = f_surface + w (flag bit 1: the surface loads' nodal forces of
// surface.wgsl; without it, zero), f_int the internal forces plus, with
// flag bit 2, the contact forces the host's contact pass sent down
// (`internal + contact`, as the CPU adds them),
// prescribed components imposed (claims: 0 free, 1 fixed, 2 + d driven by
// drive d: its target when active, else free), x_{n+1} = x_n + dt v_{n+1/2},
// v_{n-1/2} kept as the next step's v_{n-3/2} (flag bit 0), and each node's
// terms of the power sums: w . v_old, w . v_new, m/2 v_old . v_new
// (`terms`, summed by reduce.wgsl in the CPU's chunk order).
//
// drives[4d..4d+4] = target x, y, z, active (1 or 0); scalars[0] = dt.

@group(0) @binding(1) var<storage, read_write> x: array<f64>;
@group(0) @binding(2) var<storage, read_write> v: array<f64>;
@group(0) @binding(3) var<storage, read_write> v_before: array<f64>;
@group(0) @binding(4) var<storage, read> internal: array<f64>;
@group(0) @binding(5) var<storage, read> mass: array<f64>;
@group(0) @binding(6) var<storage, read> weight: array<f64>;
@group(0) @binding(7) var<storage, read> claims: array<u32>;
@group(0) @binding(8) var<storage, read> drives: array<f64>;
@group(0) @binding(9) var<storage, read> scalars: array<f64>;
@group(0) @binding(10) var<storage, read_write> terms: array<f64>;
@group(0) @binding(11) var<storage, read> f_surface: array<f64>;
@group(0) @binding(12) var<storage, read> f_contact: array<f64>;

fn dot3(a: vec3<f64>, b: vec3<f64>) -> f64 {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>,
        @builtin(local_invocation_index) local: u32) {
    let i = item(wg, nwg, local);
    if (i >= params.count) {
        return;
    }
    let dt = scalars[0];
    let m = mass[i];
    let w = vec3<f64>(weight[3u * i], weight[3u * i + 1u], weight[3u * i + 2u]);
    // f_ext = f_surface + w, as the CPU adds them (a node without surface
    // loads: 0 + w).
    var f_s = vec3<f64>(0.0, 0.0, 0.0);
    if ((params.flags & 2u) != 0u) {
        f_s = vec3<f64>(f_surface[3u * i], f_surface[3u * i + 1u], f_surface[3u * i + 2u]);
    }
    let f_ext = f_s + w;
    var f_in = vec3<f64>(internal[3u * i], internal[3u * i + 1u], internal[3u * i + 2u]);
    if ((params.flags & 4u) != 0u) {
        f_in = f_in + vec3<f64>(f_contact[3u * i], f_contact[3u * i + 1u], f_contact[3u * i + 2u]);
    }
    let old = vec3<f64>(v[3u * i], v[3u * i + 1u], v[3u * i + 2u]);
    var v_new = old;
    if (m > 0.0) {
        v_new = old + (f_in + f_ext) * (dt / m);
    }
    for (var c = 0u; c < 3u; c++) {
        let claim = claims[3u * i + c];
        if (claim == 1u) {
            v_new[c] = 0.0;
        } else if (claim >= 2u) {
            let d = claim - 2u;
            if (drives[4u * d + 3u] == 1.0) {
                v_new[c] = drives[4u * d + c];
            }
        }
    }
    terms[3u * i] = dot3(w, old);
    terms[3u * i + 1u] = dot3(w, v_new);
    terms[3u * i + 2u] = 0.5 * m * dot3(old, v_new);
    if ((params.flags & 1u) != 0u) {
        v_before[3u * i] = old.x;
        v_before[3u * i + 1u] = old.y;
        v_before[3u * i + 2u] = old.z;
    }
    v[3u * i] = v_new.x;
    v[3u * i + 1u] = v_new.y;
    v[3u * i + 2u] = v_new.z;
    x[3u * i] = x[3u * i] + v_new.x * dt;
    x[3u * i + 1u] = x[3u * i + 1u] + v_new.y * dt;
    x[3u * i + 2u] = x[3u * i + 2u] + v_new.z * dt;
}
