// ln64 (flags 0) or exp64 (flags 1) of each input, for the ulp tests.

@group(0) @binding(1) var<storage, read> input: array<f64>;
@group(0) @binding(2) var<storage, read_write> output: array<f64>;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>,
        @builtin(local_invocation_index) local: u32) {
    let i = item(wg, nwg, local);
    if (i >= params.count) {
        return;
    }
    if (params.flags == 0u) {
        output[i] = ln64(input[i]);
    } else {
        output[i] = exp64(input[i]);
    }
}
