// Writes vectors into a per-node array: dst[3 nodes[k] + c] = values[3 k + c]
// (the contact forces the host's contact pass computed, on the nodes it
// touched now or at the pass before, zero where it no longer touches).

@group(0) @binding(1) var<storage, read> nodes: array<u32>;
@group(0) @binding(2) var<storage, read> values: array<f64>;
@group(0) @binding(3) var<storage, read_write> dst: array<f64>;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>,
        @builtin(local_invocation_index) local: u32) {
    let k = item(wg, nwg, local);
    if (k >= params.count) {
        return;
    }
    let n = nodes[k];
    for (var c = 0u; c < 3u; c++) {
        dst[3u * n + c] = values[3u * k + c];
    }
}
