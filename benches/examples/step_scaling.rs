//! The cost of one explicit step per tet against the mesh size, and the
//! memory per tet: builds a jointed unit box of about `N` tets (first
//! argument, default 10⁴; [`femdem_benches::box_solver`]), runs `STEPS`
//! steps (second argument, default 20) on `THREADS` worker threads (third
//! argument, default all cores) after two warm-up steps, and prints the
//! tet-steps per second, the CPU time per tet-step (which the other
//! processes on a shared machine do not inflate, as they do the wall
//! time), and the process's resident memory per tet
//! (`VmRSS` once the solver is built, and the peak `VmHWM`, which includes
//! the transient of joint insertion), read from `/proc/self/status`.
//!
//! ```text
//! cargo build --release -p femdem-benches --example step_scaling
//! for n in 10000 100000 1000000; do target/release/examples/step_scaling $n 20 2; done
//! ```
//!
//! Run each size in its own process: the memory figures are the process's.
//! `docs/performance.md` ("The issue's targets") holds the measurements.

use std::time::Instant;

use femdem_benches::box_solver;
use femdem_solver::Want;

/// A `/proc/self/status` field in KiB (Linux only).
fn status_kib(field: &str) -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with(field))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// CPU time of the process so far (user + system), s, from
/// `/proc/self/stat` (clock ticks of 1/100 s; Linux only): unlike the wall
/// time, it does not grow when other processes share the cores.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let after_name = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = after_name.split_whitespace().collect();
    let (utime, stime): (f64, f64) = (fields.get(11)?.parse().ok()?, fields.get(12)?.parse().ok()?);
    Some((utime + stime) / 100.0)
}

fn main() {
    let mut args = std::env::args().skip(1);
    let target: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(10_000);
    let steps: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(20);
    let threads: usize = args
        .next()
        .and_then(|a| a.parse().ok())
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("thread pool");
    let t0 = Instant::now();
    let mut s = pool.install(|| box_solver(target));
    let build = t0.elapsed().as_secs_f64();
    let (rss, peak) = (status_kib("VmRSS:"), status_kib("VmHWM:"));
    let tets = s.model().num_deformable_tets();
    pool.install(|| {
        for _ in 0..2 {
            s.step(Want::default());
        }
    });
    let mut failed = 0;
    let (t1, cpu0) = (Instant::now(), cpu_seconds());
    pool.install(|| {
        for _ in 0..steps {
            failed += s.step(Want::default()).new_failures.len();
        }
    });
    let (wall, cpu1) = (t1.elapsed().as_secs_f64(), cpu_seconds());
    let rate = (tets * steps) as f64 / wall;
    println!("tets            {tets}");
    println!("joints          {}", s.model().joints.len());
    println!("threads         {threads}");
    println!("build           {build:.2} s");
    println!("steps           {steps} in {wall:.3} s, {failed} joints failed (0: the intact step was measured)");
    println!("tet-steps/s     {rate:.4e}");
    if let (Some(a), Some(b)) = (cpu0, cpu1) {
        println!("CPU             {:.2} s: {:.0} CPU-ns per tet-step", b - a, 1e9 * (b - a) / (tets * steps) as f64);
    }
    if let (Some(rss), Some(peak)) = (rss, peak) {
        println!(
            "memory          {:.0} B per tet resident after building ({:.1} MiB)",
            rss * 1024.0 / tets as f64,
            rss / 1024.0
        );
        println!("                {:.0} B per tet at the peak ({:.1} MiB)", peak * 1024.0 / tets as f64, peak / 1024.0);
    }
}
