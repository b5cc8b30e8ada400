//! Results do not depend on the thread count: the same loaded, damped,
//! joint-meshed block stepped in a 1-thread and a 2-thread rayon pool ends
//! in bit-identical positions, velocities, energies and reactions (the
//! passes write per-element slots summed per node in a fixed order, and
//! every sum over elements is taken per fixed-size chunk, then in chunk
//! order). Nor on which joint kernel ran: the SIMD lanes (steps that ask
//! for no energy) and the scalar kernel (steps that do) give the same bits;
//! nor on which compilation of the tet and joint passes ran (the processor's widest
//! vector unit or the baseline build's, `femdem_solver::VectorPath`).

use crate::common::{box_mesh, model, rock, solver};
use femdem_core::Vec3;
use femdem_material::Law;
use femdem_solver::select::{NodeSelection, group_faces, select_nodes};
use femdem_solver::{
    Fixed, Loads, Ramp, Solver, SurfaceKind, SurfaceLoad, VectorPath, VelocityDrive, Want, widest_name,
};

fn run() -> Solver {
    run_asking(|n| Want { energy: n % 10 == 0, stress: n == 299 })
}

fn run_asking(want: impl Fn(usize) -> Want) -> Solver {
    run_on(VectorPath::Widest, want)
}

fn run_on(path: VectorPath, want: impl Fn(usize) -> Want) -> Solver {
    let mesh = box_mesh([0.0; 3], [0.1, 0.05, 0.05], 0.008, 0.12, true);
    let (jointed, m) = model(&mesh, Law::NeoHookean, rock(200.0), 10.0 * 26e9);
    let sel = |g: &str| select_nodes(&jointed, &NodeSelection { group: Some(g.into()), ..Default::default() }).unwrap();
    let loads = Loads {
        gravity: Vec3::new(0.0, 0.0, -9.81),
        fixed: vec![Fixed { nodes: sel("xmin"), components: [true; 3] }],
        drives: vec![VelocityDrive {
            name: "pull".into(),
            nodes: sel("xmax"),
            velocity: Vec3::new(0.05, 0.0, 0.0),
            components: [true, false, false],
            ramp: Ramp { ramp_time: 1e-5, stop_time: None },
            start_time: None,
        }],
        surfaces: vec![SurfaceLoad {
            name: "top".into(),
            faces: group_faces(&jointed, "zmax").unwrap(),
            kind: SurfaceKind::Pressure(1e6),
            ramp: Ramp { ramp_time: 1e-5, stop_time: None },
        }],
    };
    let mut s = solver(m, loads, 0.9);
    s.set_vector_path(path);
    for n in 0..300 {
        s.step(want(n));
    }
    s
}

#[test]
fn one_and_two_threads_give_identical_bits() {
    let pool = |n| rayon::ThreadPoolBuilder::new().num_threads(n).build().unwrap();
    let a = pool(1).install(run);
    let b = pool(2).install(run);
    assert_eq!(a.state(), b.state(), "positions/velocities differ");
    assert_eq!(a.energies(), b.energies());
    assert_eq!(a.record(), b.record());
    assert_eq!(a.workspace().stress, b.workspace().stress);
    assert!(a.state().x.iter().zip(&a.model().x0).any(|(x, x0)| x != x0), "the block must move");
}

/// The joint pass takes four joints at a time in SIMD lanes when a step
/// asks for no energy and the scalar kernel when it does; both give the
/// law's results bit for bit, so asking for energies at every step or at
/// none changes no position, velocity or joint history.
#[test]
fn lanes_and_scalar_joint_kernels_give_identical_bits() {
    let lanes = run_asking(|_| Want::default());
    let scalar = run_asking(|_| Want { energy: true, stress: false });
    assert_eq!(lanes.state(), scalar.state(), "positions/velocities/joint histories differ");
    assert_eq!(lanes.failures(), scalar.failures());
    assert!(lanes.state().joints.iter().any(|h| h.damage.iter().any(|&d| d > 0.0) || h.failed), "no joint was damaged");
}

/// The tet and joint passes run compiled for the processor's widest vector unit
/// (x86-64-v3 where it has AVX2) or as the baseline build compiled it; both
/// do the same IEEE-754 operations in the same order (no fused
/// multiply-add), so the tet and joint lanes, the scalar kernels and the
/// joints' histories agree bit for bit. On a processor without AVX2 both paths are the same
/// code and the test shows only that.
#[test]
fn widest_and_baseline_passes_give_identical_bits() {
    eprintln!("widest vector unit here: {}", widest_name());
    let widest = run_on(VectorPath::Widest, |_| Want::default());
    let baseline = run_on(VectorPath::Baseline, |_| Want::default());
    assert_eq!(widest.state(), baseline.state(), "positions/velocities/joint histories differ");
    assert_eq!(widest.failures(), baseline.failures());
    assert_eq!(widest.record(), baseline.record());
    assert!(
        widest.state().joints.iter().any(|h| h.damage.iter().any(|&d| d > 0.0) || h.failed),
        "no joint was damaged"
    );
}
