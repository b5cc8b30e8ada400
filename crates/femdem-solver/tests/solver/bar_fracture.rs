//! A joint-meshed bar pulled slowly in uniaxial tension (reference paper
//! §2.2: Eq. 6–13, failure when two of a joint's three points carry no
//! stress).
//!
//! Expected, for a bar of cross-section `A` and tensile strength `f_t`:
//!
//! * the largest reaction, divided by `A`, equals `f_t` within 5% (the
//!   lattice has joint planes normal to the load; jitter tilts them by a few
//!   degrees, which lowers their normal stress by `cos²θ ≈ 1 − θ²`; and the
//!   loading is quasi-static: the pull reaches the peak after about 8 wave
//!   transit times, with damping, so the dynamic overshoot is small);
//! * one crack forms: the failed joints lie in a band of two cells along
//!   the bar (softening localises: once one section softens, the rest
//!   unloads). The bar's stored energy at the peak, `f_t² L / 2E` ≈ 3.5 J/m²
//!   for L = 20 mm, is below `G_f` = 10 J/m², so the softening is stable
//!   (no snap-back); the two halves then carry no force;
//! * the energy dissipated on the softening branches of the crack's joints,
//!   per unit cross-section, equals the documented relation: with the
//!   paper's Eq. 10 (`δc = 3 G_f / f_t`) `f_t (δc − δp) ∫₀¹ z ≈ 3 × 0.386
//!   G_f`, with the exact calibration `G_f`. Tolerance 15% (the issue's
//!   bound): the crack faces are tilted by the jitter (more area, mixed-mode
//!   damage).
//!
//! * the work done on the crack's joints (the energy the run's account
//!   books as fracture) equals that plus the hardening energies, `2/3 f_t
//!   δnp` and at most `2/3 f_s δsp` ≈ 3.3 J/m² for c = 15 MPa and p0 = 10 E
//!   (the tilted crack faces slip past the tiny `δsp`), within 15%
//!   (measured: 10% below that upper estimate, the shear hardening being
//!   partial).
//!
//! Printed (`--nocapture`), not asserted: the joints damaged next to the
//! crack without failing add ~0.2 J/m².

use crate::common::{at_step, box_mesh, pulled_bar_loads, rock, stable};
use femdem_core::tet::centroid;
use femdem_fracture::{GfCalibration, JointParams, softening::softening_area};
use femdem_material::Law;
use femdem_mesh::insert_joints_within;
use femdem_solver::{Model, RegionBehaviour, Want};

pub(crate) const FT: f64 = 3e6;
/// Pull velocity, m/s: the peak (strain f_t/E over the bar) is reached after
/// about 8 wave transit times.
const V: f64 = 0.05;
const GF: f64 = 10.0;

/// Pulls the bar (joints only in the tets whose centroid z lies in `zone`,
/// m, if given) and returns its peak stress (Pa), the failed joints' z,
/// the softening energy and the work on the crack per unit cross-section
/// (J/m²), and the residual pull (N).
pub(crate) fn pull(calibration: GfCalibration, zone: Option<[f64; 2]>) -> (f64, Vec<f64>, f64, f64, f64) {
    let (w, len, h) = (0.01, 0.02, 0.0025);
    let mesh = box_mesh([0.0; 3], [w, w, len], h, 0.1, true);
    let in_zone: Vec<bool> = (0..mesh.num_tets())
        .map(|t| zone.is_none_or(|[lo, hi]| (lo..=hi).contains(&centroid(&mesh.tet_points(t)).z)))
        .collect();
    let jointed = insert_joints_within(&mesh, &in_zone).unwrap();
    let p0 = 10.0 * 26e9;
    let params = JointParams {
        penalty: p0,
        tensile_strength: FT,
        cohesion: 15e6,
        friction_angle: 30f64.to_radians(),
        gf_tension: GF,
        gf_shear: GF,
        calibration,
        coupling: femdem_fracture::Coupling::default(),
    };
    let viscosity = femdem_material::critical_viscosity(h, 26e9, 2340.0) * 0.1;
    let behaviour =
        [RegionBehaviour::Deformable { law: Law::NeoHookean, material: rock(viscosity), joints: Some(params) }];
    let model = Model::new(&jointed, &behaviour, 1.0).unwrap();
    let loads = pulled_bar_loads(&jointed, w, V);
    let dt = 0.9 * stable(&model, &loads, 300).critical;
    let mut s = at_step(model, loads, dt);
    let mut peak: f64 = 0.0;
    // Pull until the top has moved 1.5 δc past the peak displacement.
    let joint = s.model().joint_law[0];
    let target = 1.5 * joint.delta_nc + 2.0 * FT / 26e9 * len;
    let end = 5e-5 / 2.0 + target / V;
    // The residual pull is the reaction averaged over the last 20 µs: the
    // freed half rings after the release, which carries no force across
    // the crack but shows in the instantaneous reaction.
    let (mut tail_sum, mut tail_n) = (0.0, 0usize);
    while s.state().time < end {
        let r = s.step(Want { energy: false, ..Want::default() }).drive_forces[0].z;
        peak = peak.max(r);
        if s.state().time > end - 2e-5 {
            tail_sum += r;
            tail_n += 1;
        }
    }
    s.step(Want { energy: true, ..Want::default() });
    let zs: Vec<f64> = s.failures().iter().map(|f| f.centroid.z).collect();
    let work: f64 = s.state().joints.iter().filter(|h| h.failed).map(|h| h.work).sum();
    let crack: f64 = s.state().joints.iter().filter(|h| h.failed).map(|h| h.dissipated).sum();
    eprintln!("work done on the crack's joints {:.3} J/m²", work / (w * w));
    let released: f64 = s.state().joints.iter().map(|h| h.released).sum();
    let damaged = s.state().joints.iter().filter(|h| !h.failed && h.damage.iter().any(|&d| d > 0.0)).count();
    let residual = tail_sum / tail_n.max(1) as f64;
    let a = w * w;
    eprintln!(
        "{calibration:?}: peak {:.4e} Pa, {} joints failed (area {:.4e} m² for A = {a:.1e} m²), crack softening {:.3} J/m², \
         released at failure {:.3} J/m², all fracture energy {:.3} J/m², {damaged} joints damaged but intact",
        peak / a,
        s.failures().len(),
        s.failures().iter().map(|f| f.area).sum::<f64>(),
        crack / a,
        released / a,
        s.energies().fracture / a
    );
    (peak / a, zs, crack / a, work / a, residual)
}

/// `per_area`: the softening energy per unit area of the calibration;
/// `zone`: as in [`pull`]. Returns the peak stress (Pa) and the failed
/// joints' z (m).
pub(crate) fn check(calibration: GfCalibration, per_area: f64, zone: Option<[f64; 2]>) -> (f64, Vec<f64>) {
    let (strength, zs, dissipated, work, residual) = pull(calibration, zone);
    assert!((strength / FT - 1.0).abs() < 0.05, "peak stress {strength} vs f_t {FT}");
    assert!(!zs.is_empty(), "the bar did not break");
    let (lo, hi) = zs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &z| (a.min(z), b.max(z)));
    assert!(hi - lo <= 2.0 * 0.0025 + 1e-9, "failed joints spread over z in [{lo}, {hi}]: more than one crack");
    assert!(residual.abs() < 0.01 * strength * 1e-4, "the halves still pull: {residual} N");
    assert!((dissipated / per_area - 1.0).abs() < 0.15, "dissipated {dissipated} J/m² vs {per_area} J/m²");
    // All the work done on the crack: softening plus the hardening branches
    // — 2/3 f_t δnp in opening, and in shear anything from 0 up to
    // 2/3 f_s δsp ≈ 3.3 J/m² (f_s ≈ c once the crack is open), depending on
    // how far the tilted faces slip before the joint breaks, which depends
    // on how damage acts on the shear hardening branch (Eq. 11 coupling:
    // measured 12.1 J/m² with `capped`, 10.7 with `printed`, paper
    // calibration 12.4). So the work is bracketed: at least the softening
    // and the normal hardening, at most the softening and both hardening
    // branches in full, with the 15% allowed on the softening above.
    let h = 0.00285;
    let normal_hardening = 2.0 / 3.0 * FT * (2.0 * FT * h / 2.6e11);
    let shear_hardening = 2.0 / 3.0 * 15e6 * (2.0 * 15e6 * h / 2.6e11);
    let (lower, upper) = (0.85 * per_area + normal_hardening, 1.15 * per_area + normal_hardening + shear_hardening);
    assert!(work >= lower && work <= upper, "work on the crack {work} J/m² outside [{lower}, {upper}] J/m²");
    (strength, zs)
}

/// The softening energy per unit area of the paper's calibration (Eq. 10):
/// `f_t (δc − δp) ∫₀¹ z`, δp = 2 f_t h / p0 (Eq. 6) with h ≈ 2.85 mm, the
/// mean joint edge.
pub(crate) fn paper_softening() -> f64 {
    let dc = 3.0 * GF / FT;
    let dp = 2.0 * FT * 0.00285 / 2.6e11;
    FT * (dc - dp) * softening_area()
}

#[test]
fn pulled_bar_breaks_at_ft_and_dissipates_the_paper_energy() {
    check(GfCalibration::Paper, paper_softening(), None);
}

#[test]
fn pulled_bar_with_exact_calibration_dissipates_gf() {
    check(GfCalibration::Exact, GF, None);
}
