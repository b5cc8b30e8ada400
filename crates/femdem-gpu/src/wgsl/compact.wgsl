// The positions, velocities, internal and surface-load forces of listed
// nodes, twelve numbers each (x, v, f, f_surface; the last zero without
// flag bit 0, a scene without surface loads), for the host's stage 4 (the
// drives' reactions and displacements) without reading whole arrays; with
// flag bit 1, the positions and velocities alone, six numbers each (the
// nodes the host's contact pass reads).

@group(0) @binding(1) var<storage, read> x: array<f64>;
@group(0) @binding(2) var<storage, read> v: array<f64>;
@group(0) @binding(3) var<storage, read> internal: array<f64>;
@group(0) @binding(4) var<storage, read> nodes: array<u32>;
@group(0) @binding(5) var<storage, read_write> out: array<f64>;
@group(0) @binding(6) var<storage, read> f_surface: array<f64>;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>,
        @builtin(local_invocation_index) local: u32) {
    let k = item(wg, nwg, local);
    if (k >= params.count) {
        return;
    }
    let n = nodes[k];
    if ((params.flags & 2u) != 0u) {
        for (var c = 0u; c < 3u; c++) {
            out[6u * k + c] = x[3u * n + c];
            out[6u * k + 3u + c] = v[3u * n + c];
        }
        return;
    }
    for (var c = 0u; c < 3u; c++) {
        out[12u * k + c] = x[3u * n + c];
        out[12u * k + 3u + c] = v[3u * n + c];
        out[12u * k + 6u + c] = internal[3u * n + c];
        var s: f64 = 0.0;
        if ((params.flags & 1u) != 0u) {
            s = f_surface[3u * n + c];
        }
        out[12u * k + 9u + c] = s;
    }
}
