//! The intact jointed step on the CPU and with stage 1 on a GPU
//! (`Solver::use_device`), side by side, for issue 34's measurement:
//!
//! ```text
//! RAYON_NUM_THREADS=16 target/release/examples/gpu_step 1000000 200
//! ```
//!
//! builds the jointed box of about `TETS` tets (first argument, default
//! 100,000; `femdem_benches::box_solver`, spinning so that every element
//! strains and the viscous term runs), steps it `STEPS` times (second
//! argument, default 100) after 5 steps of warm-up, on the CPU and then
//! from the same state with the device, and prints both rates in
//! tet-steps/s, their ratio, and how far the two runs' positions ended
//! apart (round-off), then where the device's step time goes (read-back
//! round trips, each kernel) and the resident step's rate again, on a
//! device warm from the first window, with the other way of waiting for
//! read-backs (polling the device in a loop, the default on a GPU, or
//! blocking) and with the default. Without a device it measures the CPU
//! and says why.

use std::time::Instant;

use femdem_benches::box_solver;
use femdem_solver::{Gpu, Residency, Solver, Want};

/// Tet-steps per second of `steps` steps of `s` after 5 of warm-up.
fn rate(s: &mut Solver, steps: usize) -> f64 {
    for _ in 0..5 {
        s.step(Want::default());
    }
    let start = Instant::now();
    for _ in 0..steps {
        s.step(Want::default());
    }
    let seconds = start.elapsed().as_secs_f64();
    (s.model().num_deformable_tets() * steps) as f64 / seconds
}

fn main() {
    let mut args = std::env::args().skip(1);
    let tets: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(100_000);
    let steps: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(100);
    let built = Instant::now();
    let mut cpu = box_solver(tets);
    println!(
        "model           {} tets, {} joints, {} nodes (built in {:.1} s)",
        cpu.model().num_deformable_tets(),
        cpu.model().joints.len(),
        cpu.model().num_nodes(),
        built.elapsed().as_secs_f64()
    );
    let snapshot = cpu.snapshot();
    let on_cpu = rate(&mut cpu, steps);
    println!("cpu             {on_cpu:.3e} tet-steps/s ({} threads)", rayon::current_num_threads());
    let gpu = match Gpu::new() {
        Ok(g) => g,
        Err(e) => {
            println!("gpu             not measured: {e}");
            return;
        }
    };
    let mut dev = box_solver(tets);
    dev.restore(&snapshot).expect("the same model");
    let opened = Instant::now();
    dev.use_device(&gpu, Residency::Auto).expect("the device takes the model");
    println!("device          {} (model uploaded in {:.1} s)", gpu.adapter(), opened.elapsed().as_secs_f64());
    println!("bytes a step    {}", dev.device_bytes_per_step());
    let on_gpu = rate(&mut dev, steps);
    println!("gpu             {on_gpu:.3e} tet-steps/s");
    println!("gpu / cpu       {:.2}", on_gpu / on_cpu);
    dev.sync_device();
    println!("stages          {}", dev.device_stages().unwrap_or("none"));
    let apart = cpu.state().x.iter().zip(&dev.state().x).map(|(a, b)| (a - b).norm()).fold(0.0, f64::max);
    let size = cpu.model().x0.iter().map(|p| p.norm()).fold(0.0, f64::max);
    println!("positions apart {apart:.3e} m after {} steps (coordinates up to {size:.3e} m)", steps + 5);
    // Where the device's step time goes, and the resident step again with
    // read-backs polling the device in a loop instead of blocking.
    for t in dev.device_timings(20).unwrap_or_default() {
        let items = t.items.map_or(String::new(), |n| format!(" ({n} items)"));
        println!("  {:<34}{:>10.1} µs{items}", t.what, t.seconds * 1e6);
    }
    // Then the other way of waiting, and the default again: a GPU's
    // clocks rise under load, so the first window (after 5 steps) can be
    // slower than these, taken on a device warm from the others.
    let spin = gpu.spin_wait();
    let how = |spin| if spin { "polling" } else { "blocking" };
    for spin in [!spin, spin] {
        gpu.set_spin_wait(spin);
        let warm = rate(&mut dev, steps);
        println!("gpu, warm, {:<9}{warm:.3e} tet-steps/s ({:.2} of the first)", how(spin), warm / on_gpu);
    }
}
