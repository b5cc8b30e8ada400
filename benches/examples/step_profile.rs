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
//! would. Prints the tets, joints and steps, to turn counts into
//! instructions per tet-step.

use femdem_benches::disc_solver;
use femdem_solver::Want;

fn main() {
    let mut args = std::env::args().skip(1);
    let h_mm: f64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(3.0);
    let steps: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(20);
    let energy = args.next().is_some_and(|a| a == "energy");
    let mut s = disc_solver(h_mm * 1e-3, true);
    let mut failed = 0;
    for n in 0..steps {
        let want = Want { stress: false, energy: energy && n % 5 == 0 };
        failed += s.step(want).new_failures.len();
    }
    println!("tets            {}", s.model().num_deformable_tets());
    println!("joints          {}", s.model().joints.len());
    println!("steps           {steps}");
    println!("tet-steps       {}", s.model().num_deformable_tets() * steps);
    println!("failures        {failed}");
}
