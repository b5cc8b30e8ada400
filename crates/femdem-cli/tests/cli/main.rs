//! The integration tests of `femdem-cli`, one module per topic, linked into
//! one test binary (one link instead of one per file).

mod check;
mod common;
mod device;
mod memory;
mod outdir;
mod overrides;
mod plot;
mod probes;
mod progress;
mod resume;
mod run;
mod static_start;
