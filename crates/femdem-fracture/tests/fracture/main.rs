//! The integration tests of `femdem-fracture`, one module per topic, linked
//! into one test binary.

mod law_reference;

mod kernel_matches_law;
mod law_capped_legacy;
mod law_coupling;
mod law_curves;
mod law_energy;
mod law_energy_paths;
mod law_failure_mode;
mod law_weak_cohesion;
