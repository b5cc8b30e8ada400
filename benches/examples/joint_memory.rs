//! Inserts joints in a box of about `N` tets (first argument, default 10⁶)
//! and prints the wall time of the insertion and the process's peak
//! resident memory, read from `/proc/self/status` (`VmHWM`).

use std::time::Instant;

use femdem_benches::box_with_tets;
use femdem_mesh::generate::generate_box;
use femdem_mesh::insert_joints;

fn peak_rss_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn main() {
    let target: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(1_000_000);
    let t0 = Instant::now();
    let mesh = generate_box(&box_with_tets(target)).expect("box");
    let t_gen = t0.elapsed();
    let rss_mesh = peak_rss_kib();
    let t1 = Instant::now();
    let jointed = insert_joints(&mesh).expect("joints");
    let t_ins = t1.elapsed();
    println!("tets            {}", mesh.num_tets());
    println!("joints          {}", jointed.joints.len());
    println!("nodes           {} (from {} vertices)", jointed.mesh.num_nodes(), mesh.num_nodes());
    println!("cores           {}", available_cores());
    println!("generate        {:.3} s", t_gen.as_secs_f64());
    println!("insert_joints   {:.3} s", t_ins.as_secs_f64());
    println!("arrays          {:.1} MiB", jointed.array_bytes() as f64 / 1048576.0);
    if let (Some(before), Some(peak)) = (rss_mesh, peak_rss_kib()) {
        println!(
            "peak RSS        {:.1} MiB (after generation: {:.1} MiB)",
            peak as f64 / 1024.0,
            before as f64 / 1024.0
        );
    }
}

fn available_cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}
