//! Shared helpers for the femdem benchmarks.
