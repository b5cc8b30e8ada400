//! Where a device step's time goes: the round trip of a read-back
//! (blocking and polling in a loop), the host's cost of recording one
//! kernel, and each kernel of stage 1 and a sum over the nodes, each timed
//! over repeated dispatches in one submission (so that the round trip
//! divides out). A measurement for benchmarks (`gpu_step`), not part of a
//! step.

use std::time::Instant;

use crate::buffers::{submit_and_read, submit_and_read_with};
use crate::bulk::{Bulk, Evaluate};
use crate::transfers::ReadBack;

/// Records one kernel's pass into an encoder.
type Encode<'a> = dyn Fn(&mut wgpu::CommandEncoder) + 'a;

/// One line of [`Bulk::timings`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timing {
    /// What was timed.
    pub what: &'static str,
    /// Mean wall time of one, s.
    pub seconds: f64,
    /// How many items it ran over, where not the model's tets, joints or
    /// nodes (the contact pairs), or the bytes a read-back moved.
    pub items: Option<u64>,
}

impl Bulk {
    /// Times, `reps` times each: an empty submission with an 8-byte
    /// read-back, blocking and then polling in a loop; recording one tet
    /// pass on the host; the tet pass, the joint pass, the gather and (once
    /// the update is enabled) the kinetic-energy sum over the nodes on the
    /// device. The kernels run on the device's current state; positions,
    /// velocities and the joints' histories, flags and failures are as
    /// before afterwards (the histories are saved and restored: the joint
    /// pass would advance them), and so is the device's wait mode. Where
    /// the contact pass has sent pairs (`Bulk::pair_geometry`), also the
    /// pair kernel on the last list (its length in [`Timing::items`]),
    /// repeated in one submission and then one a submission as a step runs
    /// it, and the read-back of its results alone (bytes in `items`). The
    /// forces and energies of the last evaluation are not: the next step
    /// computes them afresh.
    pub fn timings(&mut self, reps: usize) -> Vec<Timing> {
        let reps = reps.max(1);
        let gpu = self.gpu.clone();
        let saved = self.joint_state().map(|b| {
            let copy = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("saved joint state"),
                size: b.size(),
                usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            (b, copy)
        });
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        for (b, copy) in &saved {
            encoder.copy_buffer_to_buffer(b, 0, copy, 0, b.size());
        }
        gpu.queue.submit([encoder.finish()]);
        let spin = gpu.spin_wait();
        let new_encoder = || gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        let read_one = |encoder| {
            submit_and_read(&gpu, encoder, &[(&self.x, 0, 8)]);
        };
        let mut out = Vec::new();
        for (what, poll) in [("round trip, blocking wait", false), ("round trip, polling in a loop", true)] {
            gpu.set_spin_wait(poll);
            read_one(new_encoder());
            let start = Instant::now();
            for _ in 0..reps {
                read_one(new_encoder());
            }
            out.push(Timing { what, seconds: start.elapsed().as_secs_f64() / reps as f64, items: None });
        }
        gpu.set_spin_wait(spin);
        let want = Evaluate::default();
        let mut encoder = new_encoder();
        let start = Instant::now();
        for _ in 0..reps {
            self.encode_tets(&mut encoder, want);
        }
        let seconds = start.elapsed().as_secs_f64() / reps as f64;
        out.push(Timing { what: "host: record one kernel", seconds, items: None });
        read_one(encoder);
        let kernels: [(&'static str, &Encode<'_>); 4] = [
            ("tet pass (Eq. 1-2)", &|e| self.encode_tets(e, want)),
            ("joint pass (Eq. 3-13)", &|e| self.encode_joints(e, false)),
            ("gather", &|e| self.encode_gather(e)),
            ("sum over the nodes (2 passes)", &|e| {
                self.encode_kinetic_sum(e);
            }),
        ];
        // No sum to time before the update is enabled.
        let bulk_kernels = if self.motion.is_some() { 4 } else { 3 };
        let mut timed: Vec<(&'static str, &Encode<'_>, Option<u64>)> =
            kernels[..bulk_kernels].iter().map(|&(what, encode)| (what, encode, None)).collect();
        // The contact pairs' kernel on the last list the contact pass sent
        // (it writes only its results, which the next pass overwrites).
        let last = self.last_pairs();
        let bulk: &Bulk = self;
        let pairs = last.as_ref().map(|(pipeline, count, within)| {
            move |e: &mut wgpu::CommandEncoder| bulk.encode_pairs(e, pipeline, *count, *within)
        });
        if let (Some(encode), Some((_, count, _))) = (&pairs, &last) {
            timed.push(("contact pairs (Eq. 17), the last list", encode, Some(u64::from(*count))));
        }
        for (what, encode, items) in timed {
            let mut encoder = new_encoder();
            encode(&mut encoder);
            read_one(encoder);
            let mut encoder = new_encoder();
            for _ in 0..reps {
                encode(&mut encoder);
            }
            let start = Instant::now();
            read_one(encoder);
            out.push(Timing { what, seconds: start.elapsed().as_secs_f64() / reps as f64, items });
        }
        // The pair kernel as a step runs it, alone in its submission and
        // waited for (where the repeated ones above may overlap), and the
        // read-back of its results without it: what splits the step's wait
        // for the pairs between the kernel and the copy.
        if let (Some(encode), Some((_, count, _)), Some((results, bytes))) = (&pairs, &last, self.last_pairs_out()) {
            let start = Instant::now();
            for _ in 0..reps {
                let mut encoder = new_encoder();
                encode(&mut encoder);
                read_one(encoder);
            }
            let seconds = start.elapsed().as_secs_f64() / reps as f64;
            out.push(Timing { what: "contact pairs, one a submission", seconds, items: Some(u64::from(*count)) });
            let start = Instant::now();
            for _ in 0..reps {
                // Read in place, as the step reads them (no copy made).
                submit_and_read_with(&gpu, ReadBack::Other, new_encoder(), &[(results, 0, bytes)], |_| ());
            }
            let seconds = start.elapsed().as_secs_f64() / reps as f64;
            out.push(Timing { what: "read back the pairs' results, bytes", seconds, items: Some(bytes) });
        }
        let mut encoder = new_encoder();
        for (b, copy) in &saved {
            encoder.copy_buffer_to_buffer(copy, 0, b, 0, b.size());
        }
        read_one(encoder);
        out
    }
}
