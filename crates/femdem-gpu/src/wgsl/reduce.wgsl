// Sums of per-item values in the CPU's order (femdem_solver's passes sum
// chunks of 512 items from zero, in order, then the chunks' sums from
// zero, in order), so equal values give equal sums bit for bit.
//
// Values: input[stride * k + offset] for items k < params.extra; flag bit
// 0 leaves out values that are not finite (the CPU's dissipation rate;
// they count as +0, which adds nothing to a sum begun at +0: such a sum is
// never -0). shape = stride, offset, slot.
//
// One workgroup per chunk (params.count = 64 × the workgroups): its 64
// invocations load the chunk's values into workgroup memory side by side
// (neighbouring items from neighbouring invocations), then invocation 0
// adds them in order. Pass 1 (flags bit 1 clear): workgroup c writes
// partial[c]. Pass 2 (flags bit 1 set, one workgroup): total[slot] = the
// chunk sums added in order, loaded a chunk's width at a time.

@group(0) @binding(1) var<storage, read> input: array<f64>;
@group(0) @binding(2) var<storage, read_write> partial: array<f64>;
@group(0) @binding(3) var<storage, read_write> total: array<f64>;
@group(0) @binding(4) var<storage, read> shape: array<u32>;

const CHUNK: u32 = 512u;

var<workgroup> values: array<f64, 512>;

// Invocation 0's in-order sum of values[0..n], continuing from `start`:
// eight loads ahead of their eight additions, so that the loads overlap
// and only the additions wait on each other.
fn add_in_order(start: f64, n: u32) -> f64 {
    var sum = start;
    var k = 0u;
    for (; k + 8u <= n; k += 8u) {
        let a = array<f64, 8>(values[k], values[k + 1u], values[k + 2u], values[k + 3u],
                              values[k + 4u], values[k + 5u], values[k + 6u], values[k + 7u]);
        sum = sum + a[0];
        sum = sum + a[1];
        sum = sum + a[2];
        sum = sum + a[3];
        sum = sum + a[4];
        sum = sum + a[5];
        sum = sum + a[6];
        sum = sum + a[7];
    }
    for (; k < n; k++) {
        sum = sum + values[k];
    }
    return sum;
}

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>,
        @builtin(local_invocation_index) local: u32) {
    // Uniform across the workgroup: the barriers below are reached by all
    // of its invocations or by none.
    let c = wg.y * nwg.x + wg.x;
    let items = params.extra;
    let chunks = (items + CHUNK - 1u) / CHUNK;
    if ((params.flags & 2u) != 0u) {
        if (c != 0u) {
            return;
        }
        var sum: f64 = 0.0;
        for (var first = 0u; first < chunks; first += CHUNK) {
            let n = min(CHUNK, chunks - first);
            for (var k = local; k < n; k += 64u) {
                values[k] = partial[first + k];
            }
            workgroupBarrier();
            if (local == 0u) {
                sum = add_in_order(sum, n);
            }
            workgroupBarrier();
        }
        if (local == 0u) {
            total[shape[2]] = sum;
        }
        return;
    }
    if (c >= chunks) {
        return;
    }
    let stride = shape[0];
    let offset = shape[1];
    let first = c * CHUNK;
    let n = min(CHUNK, items - first);
    for (var k = local; k < n; k += 64u) {
        var value = input[stride * (first + k) + offset];
        if ((params.flags & 1u) != 0u && !(abs(value) <= 1.7976931348623157e308)) {
            value = 0.0;
        }
        values[k] = value;
    }
    workgroupBarrier();
    if (local == 0u) {
        partial[c] = add_in_order(0.0, n);
    }
}
