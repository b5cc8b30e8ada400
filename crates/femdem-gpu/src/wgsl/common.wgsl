// What every femdem kernel shares: the uniform at binding 0 and the item
// number of an invocation over a grid of workgroups of 64
// (`buffers::dispatch` in the crate).

struct Params {
    count: u32,
    flags: u32,
    // A kernel's own number (reduce.wgsl: the items it sums).
    extra: u32,
    pad1: u32,
}

@group(0) @binding(0) var<uniform> params: Params;

// The item of this invocation: workgroups are numbered along x, then y.
fn item(wg: vec3<u32>, nwg: vec3<u32>, local: u32) -> u32 {
    return (wg.y * nwg.x + wg.x) * 64u + local;
}
