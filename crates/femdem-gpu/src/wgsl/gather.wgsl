// The gather: each node's force is the sum of its slots, tet slots first,
// then joint slots, each in increasing slot order (the CPU's order, so the
// same slots give the same sums bit for bit). Slot s of a table is
// element * nodes_per_element + local: index 3s of the flattened tet
// slots.
// Node i's slots are slots[offsets[i]..offsets[i+1]]. The joint slots are
// stored number by number (`wgsl/joints.wgsl`): component c of joint j's
// node k is joint_slots[(3k + c) n + j], n = params.extra joints.

@group(0) @binding(1) var<storage, read> tet_slots: array<f64>;
@group(0) @binding(2) var<storage, read> tet_offsets: array<u32>;
@group(0) @binding(3) var<storage, read> tet_table: array<u32>;
@group(0) @binding(4) var<storage, read> joint_slots: array<f64>;
@group(0) @binding(5) var<storage, read> joint_offsets: array<u32>;
@group(0) @binding(6) var<storage, read> joint_table: array<u32>;
@group(0) @binding(7) var<storage, read_write> internal: array<f64>;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>,
        @builtin(local_invocation_index) local: u32) {
    let i = item(wg, nwg, local);
    if (i >= params.count) {
        return;
    }
    var sum = vec3<f64>(0.0, 0.0, 0.0);
    for (var k = tet_offsets[i]; k < tet_offsets[i + 1u]; k++) {
        let s = 3u * tet_table[k];
        sum = sum + vec3<f64>(tet_slots[s], tet_slots[s + 1u], tet_slots[s + 2u]);
    }
    let n = params.extra;
    for (var k = joint_offsets[i]; k < joint_offsets[i + 1u]; k++) {
        let slot = joint_table[k];
        let s = 3u * (slot % 6u) * n + slot / 6u;
        sum = sum + vec3<f64>(joint_slots[s], joint_slots[s + n], joint_slots[s + 2u * n]);
    }
    internal[3u * i] = sum.x;
    internal[3u * i + 1u] = sum.y;
    internal[3u * i + 2u] = sum.z;
}
