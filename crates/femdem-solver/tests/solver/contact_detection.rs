//! Contact detection does not change the answer: two cubes colliding
//! obliquely with friction (μ = 0.3, so the friction springs stick and
//! slip) end in bit-identical states
//!
//! * whether candidates are detected at every step (buffer 0) or only when
//!   a node has moved half of a 0.4 mm buffer (a twelfth of the element size):
//!   every pair that overlaps is a candidate either way (see
//!   `Contact::needs_detection`), and forces are summed in ascending pair
//!   order; the buffered run must detect far less often;
//! * in a 1-thread and a 2-thread rayon pool (the pairs are evaluated in
//!   parallel and summed in a fixed order);
//! * with the pair kernel compiled for the processor's widest vector unit
//!   or as the baseline build compiled it (`femdem_solver::VectorPath`:
//!   the same operations in the same order, no fused multiply-add). On a
//!   processor without AVX2 both are the same code, and this shows only
//!   that.

use crate::common::{at_step, box_mesh, model, rock, stable};
use femdem_core::Vec3;
use femdem_material::Law;
use femdem_solver::{ContactModel, ContactSettings, Loads, Solver, VectorPath, Want, widest_name};

const STEPS: usize = 1000;

fn run(buffer: f64, force: ContactModel) -> Solver {
    run_on(buffer, force, VectorPath::Widest)
}

fn run_on(buffer: f64, force: ContactModel, path: VectorPath) -> Solver {
    let mut mesh = box_mesh([0.0; 3], [0.02, 0.02, 0.02], 0.005, 0.1, false);
    let other = box_mesh([0.0202, 0.008, 0.0], [0.0402, 0.028, 0.02], 0.005, 0.1, false);
    mesh.append(&other);
    let (_, m) = model(&mesh, Law::NeoHookean, rock(0.0), 0.0);
    let dt = 0.2 * stable(&m, &Loads::default(), 300).critical;
    let mut s = at_step(m, Loads::default(), dt);
    s.enable_contact(ContactSettings { friction: 0.3, buffer, model: force, ..ContactSettings::new(26e9) }, &[]);
    s.set_vector_path(path);
    // Head-on at 2 m/s each, with a shear of 1 m/s each along y.
    s.set_velocity(|x| if x.x < 0.0201 { Vec3::new(2.0, 1.0, 0.0) } else { Vec3::new(-2.0, -1.0, 0.0) });
    let mut in_contact = 0;
    for n in 0..STEPS {
        s.step(Want { energy: n % 100 == 0, ..Want::default() });
        in_contact += usize::from(s.contact().unwrap().active_pairs > 0);
    }
    eprintln!("dt = {:.3e} s, {in_contact} steps in contact", s.dt());
    s
}

#[test]
fn the_buffer_and_the_thread_count_do_not_change_the_bits() {
    same_bits(ContactModel::Potential);
}

/// The same with the energy-conserving model, whose pairs that separate
/// keep their kicks after detection has dropped them (`contact/onset.rs`):
/// they are summed in their place among the candidates.
#[test]
fn the_buffer_and_the_thread_count_do_not_change_the_bits_of_the_gradient_model() {
    same_bits(ContactModel::Gradient);
}

fn same_bits(model: ContactModel) {
    let pool = |n| rayon::ThreadPoolBuilder::new().num_threads(n).build().unwrap();
    let every_step = pool(2).install(|| run(0.0, model));
    let buffered = pool(2).install(|| run(4e-4, model));
    let one_thread = pool(1).install(|| run(4e-4, model));
    let baseline = pool(2).install(|| run_on(4e-4, model, VectorPath::Baseline));
    eprintln!("widest vector unit here: {}", widest_name());
    let c = |s: &Solver| s.contact().unwrap().detections;
    let travel = every_step.dt() * STEPS as f64 * 5f64.sqrt();
    eprintln!(
        "detections: {} every step, {} with a 0.4 mm buffer over {STEPS} steps (each cube travels ≈ {travel:.2e} m)",
        c(&every_step),
        c(&buffered)
    );
    assert!(every_step.contact().unwrap().detections > 0);
    assert!(every_step.energies().friction > 0.0, "friction must dissipate: {:?}", every_step.energies());
    assert_eq!(every_step.state(), buffered.state());
    assert_eq!(every_step.energies(), buffered.energies());
    assert_eq!(buffered.state(), one_thread.state());
    assert_eq!(buffered.energies(), one_thread.energies());
    assert_eq!(buffered.state(), baseline.state(), "the widest and the baseline pair kernels differ");
    assert_eq!(buffered.energies(), baseline.energies());
    assert!(c(&every_step) as usize >= STEPS - 1);
    assert!(c(&buffered) * 10 < c(&every_step), "the buffer must cut detections tenfold");
}
