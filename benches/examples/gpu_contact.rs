//! A fragmented body on the CPU and resident on a GPU (`Solver::use_device`,
//! contact pass on the host, the pairs' Eq. 17 on the device), side by
//! side, for issue 35's measurement:
//!
//! ```text
//! RAYON_NUM_THREADS=16 target/release/examples/gpu_contact 3400 100
//! ```
//!
//! takes the quick polyaxial cube at step `FROM` (first argument, default
//! 3400: about 800 joints failed, more at nearly every step;
//! `femdem_benches::polyaxial_cube_at`, which makes its snapshot under
//! `target/contact_profile/` on a first run), steps it `STEPS` times
//! (second argument, default 100) on the CPU and then from the same state
//! on the device, and prints both rates in tet-steps/s, each run's time by
//! stage (`Solver::stage_times`), whether the two runs broke the same
//! joints, how far their positions ended apart, and then the device's
//! `Bulk::timings`: read-back round trips, each kernel, and the contact
//! pairs' kernel alone on the last list the pass sent (the measurement
//! that splits the device's pair time between the kernel and the
//! transfers). Without a device it measures the CPU and says why.

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
    let mut cpu = polyaxial_cube_at(from);
    let snapshot = cpu.snapshot();
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
    let (on_gpu, failed_gpu) = rate(&mut dev, steps);
    println!("gpu             {on_gpu:.3e} tet-steps/s, {failed_gpu} joints failed");
    println!("gpu / cpu       {:.2}", on_gpu / on_cpu);
    println!("gpu stages      ms a step: {}", stages(&dev));
    dev.sync_device();
    let same = cpu.failures().iter().map(|f| (f.joint, f.mode)).eq(dev.failures().iter().map(|f| (f.joint, f.mode)));
    let apart = cpu.state().x.iter().zip(&dev.state().x).map(|(a, b)| (a - b).norm()).fold(0.0, f64::max);
    println!("same failures   {same}; positions apart {apart:.3e} m after {steps} steps");
    for t in dev.device_timings(20).unwrap_or_default() {
        let items = t.items.map_or(String::new(), |n| format!(" ({n} items)"));
        println!("  {:<40}{:>10.1} µs{items}", t.what, t.seconds * 1e6);
    }
}
