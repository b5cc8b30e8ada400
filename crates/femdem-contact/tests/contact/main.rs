//! The integration tests of `femdem-contact`, one module per topic, linked into
//! one test binary (one link instead of one per file).

mod nbs;
mod potential;
