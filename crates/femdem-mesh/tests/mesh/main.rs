//! The integration tests of `femdem-mesh`, one module per topic, linked into
//! one test binary (one link instead of one per file).

mod generators;
mod joints;
mod msh;
mod msh_binary;
mod msh_fuzz;
mod msh_legacy;
