//! Runs `STEPS` explicit steps (second argument, default 10) of the quick
//! polyaxial cube (`femdem_benches::polyaxial_cube`: the 50 mm Gmsh cube of
//! `cases/paper/polyaxial.toml`, 4,993 tets, contact on) from step `FROM`
//! (first argument, default 3400: some 800 joints have failed and more fail
//! at nearly every step), for a profiler. The state at `FROM` is restored
//! from a snapshot under `target/contact_profile/` (made by a first run), so
//!
//! ```text
//! target/release/examples/contact_profile 3400 0     # makes the snapshot
//! RAYON_NUM_THREADS=1 valgrind --tool=callgrind \
//!     target/release/examples/contact_profile 3400 10
//! ```
//!
//! profiles the set-up and ten fragmented steps (a profile with 2 steps,
//! subtracted, leaves the steps alone; see
//! `docs/performance.md`). Prints the tets, steps, failures, detections
//! (full, and incremental additions after failures) and contact pairs.

use femdem_benches::polyaxial_cube_at;
use femdem_solver::Want;

fn main() {
    let mut args = std::env::args().skip(1);
    let from: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(3400);
    let steps: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(10);
    let mut s = polyaxial_cube_at(from);
    let failed_before = s.failures().len();
    let detections_before = s.contact().map_or(0, |c| c.detections);
    let additions_before = s.contact().map_or(0, |c| c.additions);
    let mut failed = 0;
    let mut pairs = 0;
    let start = std::time::Instant::now();
    for _ in 0..steps {
        let r = s.step(Want::default());
        failed += r.new_failures.len();
        pairs += r.contact_pairs;
    }
    let wall = start.elapsed().as_secs_f64();
    let c = s.contact().expect("contact");
    println!("tets            {}", s.model().num_deformable_tets());
    println!("from step       {from} ({failed_before} joints failed)");
    println!("steps           {steps}");
    println!("tet-steps       {}", s.model().num_deformable_tets() * steps);
    println!("failures        {failed}");
    println!(
        "detections      {} full, {} incremental",
        c.detections - detections_before,
        c.additions - additions_before
    );
    println!("contactable     {}", c.contactable().len());
    println!("pairs in contact per step {:.1}", pairs as f64 / steps.max(1) as f64);
    println!(
        "wall            {wall:.3} s ({:.3e} tet-steps/s)",
        (s.model().num_deformable_tets() * steps) as f64 / wall
    );
    // A checksum of the state, to compare builds bit for bit.
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for x in s.state().x.iter().chain(&s.state().v) {
        for k in 0..3 {
            h = (h ^ x[k].to_bits()).wrapping_mul(0x100_0000_01b3);
        }
    }
    println!("state hash      {h:016x}");
}
