//! A fragmented body on the CPU and resident on a GPU (`Solver::use_device`,
//! contact pass on the host, the pairs' Eq. 17 on the device), side by
//! side, for issue 35's measurement:
//!
//! ```text
//! RAYON_NUM_THREADS=16 target/release/examples/gpu_contact 3400 100 [SNAPSHOT]
//! ```
//!
//! takes the quick polyaxial cube at step `FROM` (first argument, default
//! 3400: 416 joints failed by then with this build, more at nearly every
//! step) from `SNAPSHOT` where given and taken at that step (the file
//! `polyaxial_cube_at` writes, `target/contact_profile/cube50_FROM.snap`;
//! `benches/gpu/prepare.sh` carries it), else from
//! `femdem_benches::polyaxial_cube_at` (which steps there on a first run),
//! and steps it `STEPS` times (second argument, default 100) on the CPU
//! and then from the same state on the device (`STEPS` = 0: only makes the
//! snapshot), and prints both rates in tet-steps/s, each run's time by
//! stage (`Solver::stage_times`), whether the two runs broke the same
//! joints, how far their positions ended apart, the host's time around
//! each kind of the device run's read-backs by part (`Gpu::take_transfers`:
//! submit, wait, read the mapped bytes; the pairs' upload), and then the
//! device's `Bulk::timings`: read-back round trips, each kernel, and the
//! contact pairs' kernel alone on the last list the pass sent, repeated in
//! one submission and one a submission, and the read-back of its results
//! alone (the measurements that split the device's pair time between the
//! kernel and the transfers). Without a device it measures the CPU and
//! says why.

use std::time::Instant;

use femdem_benches::{polyaxial_cube, polyaxial_cube_at};
use femdem_solver::{Gpu, Residency, Solver, Want};

/// Tet-steps per second of `steps` steps of `s`, and the joints that
/// failed in them.
fn rate(s: &mut Solver, steps: usize) -> (f64, usize) {
    let failed = s.failures().len();
    let start = Instant::now();
    for _ in 0..steps {
        s.step(Want::default());
    }
    let seconds = start.elapsed().as_secs_f64();
    ((s.model().num_deformable_tets() * steps) as f64 / seconds, s.failures().len() - failed)
}

/// One run's stage times, a line.
fn stages(s: &Solver) -> String {
    s.stage_times().map_or(String::new(), |t| {
        t.per_step_ms().iter().map(|(name, ms)| format!("{name} {ms:.3}")).collect::<Vec<_>>().join(", ")
    })
}

fn main() {
    let mut args = std::env::args().skip(1);
    let from: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(3400);
    let steps: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(100);
    let built = Instant::now();
    let carried = args.next().and_then(|f| std::fs::read(f).ok()).filter(|bytes| {
        let mut s = polyaxial_cube();
        s.restore(bytes).is_ok() && s.state().step == from
    });
    let snapshot = carried.unwrap_or_else(|| polyaxial_cube_at(from).snapshot());
    if steps == 0 {
        // Only the snapshot (`benches/gpu/prepare.sh`).
        return;
    }
    // Both runs from the snapshot, so that each one's stage times cover
    // its window only.
    let mut cpu = polyaxial_cube();
    cpu.restore(&snapshot).expect("the snapshot of the same cube");
    println!(
        "model           {} tets, {} joints ({} failed), at step {from} (ready in {:.1} s)",
        cpu.model().num_deformable_tets(),
        cpu.model().joints.len(),
        cpu.failures().len(),
        built.elapsed().as_secs_f64()
    );
    let (on_cpu, failed_cpu) = rate(&mut cpu, steps);
    println!(
        "cpu             {on_cpu:.3e} tet-steps/s ({} threads), {failed_cpu} joints failed",
        rayon::current_num_threads()
    );
    println!("cpu stages      ms a step: {}", stages(&cpu));
    let pairs = cpu.contact().map_or(0, |c| c.candidates().len());
    println!("candidates      {pairs} pairs at the end");
    let gpu = match Gpu::new() {
        Ok(g) => g,
        Err(e) => {
            println!("gpu             not measured: {e}");
            return;
        }
    };
    let mut dev = polyaxial_cube();
    dev.restore(&snapshot).expect("the snapshot of the same cube");
    if let Err(e) = dev.use_device(&gpu, Residency::Auto) {
        println!("gpu             not measured: {e}");
        return;
    }
    println!("device          {}", dev.device_summary().unwrap_or_default());
    dev.device_transfers();
    let (on_gpu, failed_gpu) = rate(&mut dev, steps);
    let transfers = dev.device_transfers().unwrap_or_default();
    println!("gpu             {on_gpu:.3e} tet-steps/s, {failed_gpu} joints failed");
    println!("gpu / cpu       {:.2}", on_gpu / on_cpu);
    println!("gpu stages      ms a step: {}", stages(&dev));
    dev.sync_device();
    let same = cpu.failures().iter().map(|f| (f.joint, f.mode)).eq(dev.failures().iter().map(|f| (f.joint, f.mode)));
    let apart = cpu.state().x.iter().zip(&dev.state().x).map(|(a, b)| (a - b).norm()).fold(0.0, f64::max);
    println!("same failures   {same}; positions apart {apart:.3e} m after {steps} steps");
    println!("gpu read-backs  host wall time a step, by kind and part:");
    for p in transfers {
        let per_step = p.seconds / steps as f64 * 1e3;
        // A rate for the parts that only move bytes (the wait includes the
        // kernels).
        let moves = matches!(p.part, femdem_solver::Part::Read | femdem_solver::Part::Upload);
        let rate = if moves && p.bytes > 0 && p.seconds > 0.0 {
            format!(
                ", {:.2} MB a call, {:.2} GB/s",
                p.bytes as f64 / p.calls as f64 / 1e6,
                p.bytes as f64 / p.seconds / 1e9
            )
        } else {
            String::new()
        };
        println!("  {:<28}{per_step:>8.3} ms ({} calls{rate})", p.name(), p.calls);
    }
    for t in dev.device_timings(20).unwrap_or_default() {
        let items = t.items.map_or(String::new(), |n| format!(" ({n})"));
        println!("  {:<40}{:>10.1} µs{items}", t.what, t.seconds * 1e6);
    }
}
