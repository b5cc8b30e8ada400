//! The integration tests of `femdem-material`, one module per topic, linked into
//! one test binary (one link instead of one per file).

mod common;

mod balance;
mod energy_consistency;
mod lanes;
mod objectivity;
mod params;
mod single_element;
mod small_strain;
mod viscous;
