//! Integration tests of the static start: agreement with a long-damped
//! explicit run, a loaded body that stays at rest, a pushed body that
//! accelerates rigidly, the hand-over to the solver, determinism and the
//! refusals.

mod at_rest;
mod column;
mod common;
mod errors;
mod pushed;
