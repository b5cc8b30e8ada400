//! Runs `STEPS` explicit steps (second argument, default 20) of the
//! Brazilian disc with joints at element size `H` mm (first argument,
//! default 3.0: about 10k tets), for a profiler: the set-up (meshing, joint
//! insertion, the stable-step estimate) is outside `Solver::step`, so
//!
//! ```text
//! valgrind --tool=callgrind --collect-atstart=no --toggle-collect='*Solver::step*' \
//!     target/release/examples/step_profile 3.0 20
//! ```
//!
//! counts the steps alone (see `docs/performance.md`). Every fifth step
//! asks for energies with a third argument `energy`, as an output frame
//! would. With a third argument `paths` it alternates the tet and joint
//! passes' two compilations (the widest vector unit and the baseline build's,
//! `femdem_solver::VectorPath`) five steps at a time and prints each one's time.
//! Prints the tets, joints and steps, to turn counts into instructions per
//! tet-step, and the steps' wall-clock time.

use femdem_benches::disc_solver;
use femdem_solver::{VectorPath, Want, widest_name};

fn main() {
    let mut args = std::env::args().skip(1);
    let h_mm: f64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(3.0);
    let steps: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(20);
    let mode = args.next();
    let energy = mode.as_deref() == Some("energy");
    let paths = mode.as_deref() == Some("paths");
    let mut s = disc_solver(h_mm * 1e-3, true);
    let mut failed = 0;
    // With `paths`, five steps on each compilation of the passes in
    // turn, timed apart: a comparison in one process, which this noisy
    // machine's run-to-run drift does not blur.
    let mut on_path = [0.0f64; 2];
    let start = std::time::Instant::now();
    for n in 0..steps {
        let want = Want { stress: false, energy: energy && n % 5 == 0 };
        let k = usize::from(paths && (n / 5) % 2 == 1);
        s.set_vector_path([VectorPath::Widest, VectorPath::Baseline][k]);
        let lap = std::time::Instant::now();
        failed += s.step(want).new_failures.len();
        on_path[k] += lap.elapsed().as_secs_f64();
    }
    let seconds = start.elapsed().as_secs_f64();
    println!("tets            {}", s.model().num_deformable_tets());
    println!("joints          {}", s.model().joints.len());
    println!("steps           {steps}");
    println!("tet-steps       {}", s.model().num_deformable_tets() * steps);
    println!("failures        {failed}");
    println!("seconds         {seconds:.3}");
    println!("tet-steps/s     {:.4e}", (s.model().num_deformable_tets() * steps) as f64 / seconds);
    if paths {
        let [w, b] = on_path;
        println!("widest ({})  {w:.4} s, baseline {b:.4} s, baseline / widest {:.4}", widest_name(), b / w);
    }
}
