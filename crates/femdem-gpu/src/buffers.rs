//! Device buffers: uploads, read-backs, and dispatches over more items than
//! one dimension of workgroups holds.

use std::borrow::Cow;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;

use bytemuck::Pod;
use wgpu::util::DeviceExt;

use crate::device::{Gpu, GpuError};
use crate::transfers::{Part, ReadBack};

/// Invocations per workgroup of every kernel (`@workgroup_size(64)`).
pub(crate) const GROUP: u32 = 64;

/// A storage buffer holding `data` (at least one element's bytes: a
/// binding may not be empty), readable and writable by kernels and copies.
pub(crate) fn storage<T: Pod>(gpu: &Gpu, what: &'static str, data: &[T]) -> Result<wgpu::Buffer, GpuError> {
    let bytes: &[u8] = bytemuck::cast_slice(data);
    gpu.check_size(what, bytes.len() as u64)?;
    let padded;
    let contents = if bytes.is_empty() {
        padded = [0u8; 8];
        &padded[..]
    } else {
        bytes
    };
    Ok(gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(what),
        contents,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
    }))
}

/// A zeroed storage buffer of `len` elements of `T`.
pub(crate) fn zeroed<T: Pod>(gpu: &Gpu, what: &'static str, len: usize) -> Result<wgpu::Buffer, GpuError> {
    let bytes = (len * size_of::<T>()).max(8) as u64;
    gpu.check_size(what, bytes)?;
    Ok(gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(what),
        size: bytes,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    }))
}

/// Overwrites the start of `buffer` with `data`.
pub(crate) fn write<T: Pod>(gpu: &Gpu, buffer: &wgpu::Buffer, data: &[T]) {
    if !data.is_empty() {
        gpu.queue.write_buffer(buffer, 0, bytemuck::cast_slice(data));
    }
}

/// The first `len` elements of `buffer`, after all submitted work.
pub(crate) fn read<T: Pod>(gpu: &Gpu, buffer: &wgpu::Buffer, len: usize) -> Vec<T> {
    let bytes = (len * size_of::<T>()) as u64;
    if bytes == 0 {
        return Vec::new();
    }
    let encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    let out = submit_and_read(gpu, encoder, &[(buffer, 0, bytes)]);
    bytemuck::pod_collect_to_vec(&out[0])
}

/// Submits `encoder` with copies of `(buffer, offset, bytes)` appended and
/// returns the copied bytes, each copy starting at a multiple of 8 of the
/// result: one wait for several read-backs.
pub(crate) fn submit_and_read(
    gpu: &Gpu,
    encoder: wgpu::CommandEncoder,
    copies: &[(&wgpu::Buffer, u64, u64)],
) -> Vec<Vec<u8>> {
    submit_and_read_as(gpu, ReadBack::Other, encoder, copies)
}

/// [`submit_and_read`], its host time logged as `read_back`'s
/// ([`Gpu::take_transfers`]).
pub(crate) fn submit_and_read_as(
    gpu: &Gpu,
    read_back: ReadBack,
    encoder: wgpu::CommandEncoder,
    copies: &[(&wgpu::Buffer, u64, u64)],
) -> Vec<Vec<u8>> {
    submit_and_read_with(gpu, read_back, encoder, copies, |bytes| bytes.iter().map(|b| b.to_vec()).collect())
}

/// Submits `encoder` with copies of `(buffer, offset, bytes)` into one
/// read-back buffer, waits, and hands `decode` each copy's bytes where
/// they are mapped (each starts 8-byte aligned), so that a large
/// read-back is decoded into the caller's own kept memory rather than
/// copied into fresh allocations first: a step that read 150 MB into new
/// vectors spent more time on them than on the copy (`docs/performance.md`).
/// Its host time is logged as `read_back`'s ([`Gpu::take_transfers`]).
pub(crate) fn submit_and_read_with<R>(
    gpu: &Gpu,
    read_back: ReadBack,
    mut encoder: wgpu::CommandEncoder,
    copies: &[(&wgpu::Buffer, u64, u64)],
    decode: impl FnOnce(&[&[u8]]) -> R,
) -> R {
    let start = Instant::now();
    let starts: Vec<u64> = copies
        .iter()
        .scan(0u64, |at, &(_, _, bytes)| {
            let start = *at;
            *at += bytes.div_ceil(8) * 8;
            Some(start)
        })
        .collect();
    let total = copies.iter().map(|c| c.2.div_ceil(8) * 8).sum::<u64>().max(8);
    let staging = gpu.take_staging(total);
    for (&(buffer, offset, bytes), &start) in copies.iter().zip(&starts) {
        if bytes > 0 {
            encoder.copy_buffer_to_buffer(buffer, offset, &staging, start, bytes);
        }
    }
    gpu.queue.submit([encoder.finish()]);
    let submitted = Instant::now();
    gpu.transfers.add(read_back, Part::Submit, 0, submitted - start);
    let slice = staging.slice(..total);
    let done = Arc::new(AtomicBool::new(false));
    let mapped = done.clone();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        r.expect("mapping a read-back buffer");
        mapped.store(true, Ordering::Release);
    });
    gpu.wait(&done);
    let waited = Instant::now();
    gpu.transfers.add(read_back, Part::Wait, total, waited - submitted);
    let out = {
        let mapped = slice.get_mapped_range();
        let parts: Vec<&[u8]> =
            copies.iter().zip(&starts).map(|(c, &s)| &mapped[s as usize..(s + c.2) as usize]).collect();
        decode(&parts)
    };
    staging.unmap();
    gpu.keep_staging(staging);
    gpu.transfers.add(read_back, Part::Read, total, waited.elapsed());
    out
}

/// Read-back bytes as 64-bit floats: in place where they are 8-byte
/// aligned (as a mapped read-back is), else copied.
pub(crate) fn reals(bytes: &[u8]) -> Cow<'_, [f64]> {
    match bytemuck::try_cast_slice(bytes) {
        Ok(r) => Cow::Borrowed(r),
        Err(_) => Cow::Owned(bytemuck::pod_collect_to_vec(bytes)),
    }
}

/// The u32 words at `indices` of `buffer`, after all submitted work.
pub(crate) fn read_words(gpu: &Gpu, buffer: &wgpu::Buffer, indices: &[u32]) -> Vec<u32> {
    if indices.is_empty() {
        return Vec::new();
    }
    let encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    let copies: Vec<_> = indices.iter().map(|&i| (buffer, 4 * u64::from(i), 4)).collect();
    submit_and_read(gpu, encoder, &copies).iter().map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]])).collect()
}

/// The uniform every kernel takes at `@group(0) @binding(0)`: how many
/// items it runs over and one kernel-specific word.
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub(crate) struct Params {
    /// Items (tets, nodes, ...); invocations beyond it return at once.
    pub count: u32,
    /// The kernel's flags.
    pub flags: u32,
    pub pad: [u32; 2],
}

/// The bind groups (each with its parameter uniform) of earlier
/// dispatches, kept for the same pipeline, parameters and buffers:
/// making a uniform and a bind group costs the host 10–17 µs a dispatch
/// on an H100 or H200, several percent of a 10⁶-tet step and a third of a
/// 10⁵-tet one. A kept group holds its buffers: [`Groups::forget`] a
/// buffer that is replaced, and at most [`Groups::LIMIT`] groups are kept
/// (all are dropped when a new one would pass it).
#[derive(Debug, Default)]
pub(crate) struct Groups(Mutex<HashMap<GroupKey, wgpu::BindGroup>>);

type GroupKey = (wgpu::ComputePipeline, [u32; 4], Vec<wgpu::Buffer>);

impl Groups {
    /// The most groups kept.
    pub(crate) const LIMIT: usize = 256;

    /// Drops the kept groups that bind `buffer`.
    pub(crate) fn forget(&self, buffer: &wgpu::Buffer) {
        self.0.lock().expect("the bind groups").retain(|k, _| !k.2.contains(buffer));
    }

    /// How many groups are kept.
    #[cfg(test)]
    pub(crate) fn len(&self) -> usize {
        self.0.lock().expect("the bind groups").len()
    }
}

/// A bind group of `params` at binding 0 and `buffers` after it for
/// `pipeline`: from `groups` where kept there, else made (and kept there).
fn bind_group(
    gpu: &Gpu,
    groups: Option<&Groups>,
    pipeline: &wgpu::ComputePipeline,
    params: Params,
    buffers: &[&wgpu::Buffer],
) -> wgpu::BindGroup {
    let key = groups.map(|_| {
        let words: [u32; 4] = [params.count, params.flags, params.pad[0], params.pad[1]];
        (pipeline.clone(), words, buffers.iter().map(|&b| b.clone()).collect::<Vec<_>>())
    });
    if let (Some(groups), Some(key)) = (groups, &key)
        && let Some(group) = groups.0.lock().expect("the bind groups").get(key)
    {
        return group.clone();
    }
    let uniform = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("params"),
        contents: bytemuck::bytes_of(&params),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let mut entries = vec![wgpu::BindGroupEntry { binding: 0, resource: uniform.as_entire_binding() }];
    for (k, b) in buffers.iter().enumerate() {
        entries.push(wgpu::BindGroupEntry { binding: k as u32 + 1, resource: b.as_entire_binding() });
    }
    let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &entries,
    });
    if let (Some(groups), Some(key)) = (groups, key) {
        let mut kept = groups.0.lock().expect("the bind groups");
        if kept.len() >= Groups::LIMIT {
            kept.clear();
        }
        kept.insert(key, group.clone());
    }
    group
}

/// A compute pass of `pipeline` over `count` items with `buffers` bound at
/// `@binding(1)`, `@binding(2)`, …, recorded into `encoder`, its bind
/// group kept in `groups` where given. The items are
/// laid out over a two-dimensional grid of workgroups when one dimension
/// cannot hold them; a kernel numbers them
/// `(wg.y * nwg.x + wg.x) * 64 + local` (`ITEM` in `common.wgsl`).
pub(crate) fn dispatch(
    gpu: &Gpu,
    groups: Option<&Groups>,
    encoder: &mut wgpu::CommandEncoder,
    pipeline: &wgpu::ComputePipeline,
    params: Params,
    buffers: &[&wgpu::Buffer],
) {
    let group = bind_group(gpu, groups, pipeline, params, buffers);
    let groups = params.count.div_ceil(GROUP).max(1);
    let x = groups.min(gpu.max_groups());
    let y = groups.div_ceil(x);
    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor::default());
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, &group, &[]);
    pass.dispatch_workgroups(x, y, 1);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernels;

    /// Bytes are read as f64 in place where aligned and copied where not,
    /// with the same numbers either way.
    #[test]
    fn reals_are_read_in_place_where_aligned_and_copied_where_not() {
        let numbers = [1.5f64, -2.25e-300, f64::MAX, 0.1];
        let aligned: &[u8] = bytemuck::cast_slice(&numbers);
        assert!(matches!(reals(aligned), Cow::Borrowed(r) if r == numbers));
        // The same bytes one byte into memory aligned for f64: misaligned.
        let mut store = [0f64; 5];
        let bytes: &mut [u8] = bytemuck::cast_slice_mut(&mut store);
        bytes[1..33].copy_from_slice(aligned);
        let read = reals(&bytes[1..33]);
        assert!(matches!(read, Cow::Owned(_)));
        assert_eq!(&*read, &numbers[..]);
    }

    /// A dispatch of the same pipeline, parameters and buffers reuses its
    /// kept group; forgetting a buffer drops the groups that bind it; the
    /// kept groups never pass the limit; and what a kept group dispatches
    /// is what a fresh one does.
    #[test]
    fn bind_groups_are_kept_forgotten_and_bounded() {
        let Some(gpu) = Gpu::for_tests() else { return };
        let module = gpu.module("scatter", &kernels::scatter()).expect("the scatter kernel compiles");
        let pipeline = gpu.pipeline("scatter", &module).expect("its pipeline");
        let nodes = storage(&gpu, "nodes", &[1u32, 0]).expect("fits");
        let values = storage(&gpu, "values", &[1.0f64, 2.0, 3.0, 4.0, 5.0, 6.0]).expect("fits");
        let dst = zeroed::<f64>(&gpu, "dst", 6).expect("fits");
        let groups = Groups::default();
        let params = Params { count: 2, flags: 0, pad: [0; 2] };
        let run = |groups: Option<&Groups>| {
            let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
            encoder.clear_buffer(&dst, 0, None);
            dispatch(&gpu, groups, &mut encoder, &pipeline, params, &[&nodes, &values, &dst]);
            let bytes = submit_and_read(&gpu, encoder, &[(&dst, 0, 48)]);
            bytemuck::pod_collect_to_vec::<u8, f64>(&bytes[0])
        };
        let fresh = run(None);
        assert_eq!(fresh, [4.0, 5.0, 6.0, 1.0, 2.0, 3.0], "node 1 gets the first vector, node 0 the second");
        assert_eq!(run(Some(&groups)), fresh);
        assert_eq!(run(Some(&groups)), fresh, "the kept group binds the same buffers and parameters");
        assert_eq!(groups.len(), 1, "one group for one pipeline, parameters and buffers");
        groups.forget(&values);
        assert_eq!(groups.len(), 0, "the group that binds a forgotten buffer is dropped");
        for count in 0..=Groups::LIMIT as u32 {
            let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
            let params = Params { count: count % 3, flags: count, pad: [0; 2] };
            dispatch(&gpu, Some(&groups), &mut encoder, &pipeline, params, &[&nodes, &values, &dst]);
            assert!(groups.len() <= Groups::LIMIT, "at most the limit is kept");
        }
        assert!(groups.len() < Groups::LIMIT, "passing the limit drops the kept groups");
    }
}
