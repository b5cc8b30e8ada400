//! The contact-aware stable step (`contact_omega`, `StableStep::with_contact`)
//! at the extremes of the normal penalty, from 0.1 E to 100 E: two elastic
//! cubes colliding face on, undamped and frictionless, at 0.9 of that step
//! keep their energy (kinetic + elastic, once the contact is over) within 3%
//! of the initial kinetic energy, while 4 times that step blows up (so the
//! bound is not needlessly small). The scan also prints the largest stable
//! multiple: 1.25, 2, 3 and 3 for 0.1 E, E, 10 E and 100 E when written.

use crate::common::{at_step, box_mesh, model, rock, stable};
use femdem_core::Vec3;
use femdem_material::Law;
use femdem_solver::{ContactSettings, Loads, Want, contact_omega};

const E: f64 = 26e9;

/// Collides the cubes at `factor` times the contact-aware critical step;
/// returns (energy ratio after the impact, or infinity if it blew up;
/// contact-aware / bulk critical step).
fn collide(penalty: f64, factor: f64) -> (f64, f64) {
    let mut mesh = box_mesh([0.0; 3], [0.02, 0.02, 0.02], 0.005, 0.1, false);
    let other = box_mesh([0.0201, 0.0, 0.0], [0.0401, 0.02, 0.02], 0.005, 0.1, false);
    mesh.append(&other);
    let (_, m) = model(&mesh, Law::NeoHookean, rock(0.0), 0.0);
    let bulk = stable(&m, &Loads::default(), 300);
    let stable = bulk.with_contact(contact_omega(&m, penalty));
    let mut s = at_step(m, Loads::default(), factor * stable.critical);
    s.enable_contact(ContactSettings::new(penalty), &[]);
    s.set_velocity(|x| if x.x < 0.02005 { Vec3::new(1.0, 0.0, 0.0) } else { Vec3::new(-1.0, 0.0, 0.0) });
    let e0: f64 = (0..s.model().num_nodes()).map(|i| 0.5 * s.model().mass[i] * s.state().v[i].norm_squared()).sum();
    // 1e-4 s: the cubes meet after 5e-5 s and part about 1.5e-5 s later.
    let steps = (1e-4 / s.dt()) as usize;
    for _ in 0..steps {
        s.step(Want { energy: true, ..Want::default() });
        let e = s.energies().kinetic + s.energies().tet_elastic;
        if e.is_nan() || e >= 10.0 * e0 {
            return (f64::INFINITY, stable.critical / bulk.critical);
        }
    }
    assert_eq!(s.contact().unwrap().active_pairs, 0, "the cubes must have parted");
    assert!(s.contact().unwrap().detections > 0);
    ((s.energies().kinetic + s.energies().tet_elastic) / e0, stable.critical / bulk.critical)
}

#[test]
fn contact_aware_step_is_stable_from_soft_to_stiff_penalties() {
    for penalty in [0.1 * E, E, 10.0 * E, 100.0 * E] {
        let (ratio, reduction) = collide(penalty, 0.9);
        let largest =
            [4.0, 3.0, 2.5, 2.0, 1.75, 1.5, 1.25, 1.0].into_iter().find(|&f| collide(penalty, f).0.is_finite());
        eprintln!(
            "p = {:>5} E: step {reduction:.3} of the bulk one; energy after impact at 0.9 of it {ratio:.4}; \
             largest stable multiple tried {largest:?}",
            penalty / E
        );
        assert!((ratio - 1.0).abs() < 0.03, "p = {penalty}: energy ratio {ratio}");
        assert!(collide(penalty, 4.0).0.is_infinite(), "p = {penalty}: 4× the step should be unstable");
    }
}
