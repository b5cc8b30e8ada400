// ln64 (flags 0), exp64 (1), ln(1 + x) (2) or x - ln(1 + x) (3) of each input, for the ulp tests.

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
    } else if (params.flags == 1u) {
        output[i] = exp64(input[i]);
    } else if (params.flags == 2u) {
        output[i] = ln1p_and_excess(input[i]).x;
    } else {
        output[i] = ln1p_and_excess(input[i]).y;
    }
}
