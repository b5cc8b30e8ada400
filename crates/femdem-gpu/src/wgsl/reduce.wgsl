// Sums of per-item values in the CPU's order (femdem_solver's passes sum
// chunks of 512 items from zero, in order, then the chunks' sums from
// zero, in order), so equal values give equal sums bit for bit.
//
// Values: input[stride * k + offset] for items k < params.extra; flag bit
// 0 leaves out values that are not finite (the CPU's dissipation rate).
// Pass 1 (flags bit 1 clear, one invocation per chunk): invocation c
// writes partial[c]. Pass 2 (flags bit 1 set, one invocation): total[slot]
// = the sum of the chunk sums. shape = stride, offset, slot.

@group(0) @binding(1) var<storage, read> input: array<f64>;
@group(0) @binding(2) var<storage, read_write> partial: array<f64>;
@group(0) @binding(3) var<storage, read_write> total: array<f64>;
@group(0) @binding(4) var<storage, read> shape: array<u32>;

const CHUNK: u32 = 512u;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>,
        @builtin(local_invocation_index) local: u32) {
    let c = item(wg, nwg, local);
    if (c >= params.count) {
        return;
    }
    let stride = shape[0];
    let offset = shape[1];
    let slot = shape[2];
    let items = params.extra;
    let chunks = (items + CHUNK - 1u) / CHUNK;
    if ((params.flags & 2u) != 0u) {
        if (c == 0u) {
            var sum: f64 = 0.0;
            for (var k = 0u; k < chunks; k++) {
                sum = sum + partial[k];
            }
            total[slot] = sum;
        }
        return;
    }
    if (c >= chunks) {
        return;
    }
    var sum: f64 = 0.0;
    let end = min((c + 1u) * CHUNK, items);
    for (var k = c * CHUNK; k < end; k++) {
        let value = input[stride * k + offset];
        if ((params.flags & 1u) != 0u && !(abs(value) <= 1.7976931348623157e308)) {
            continue;
        }
        sum = sum + value;
    }
    partial[c] = sum;
}
