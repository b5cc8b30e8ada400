//! The integration tests of `femdem-solver`, one module per topic, linked into
//! one test binary (one link instead of one per file).

mod common;

mod bar_fracture;
mod brazilian_hondros;
mod contact;
mod contact_activation;
mod contact_cycle;
mod contact_detection;
mod contact_friction;
mod contact_incremental;
mod contact_pressed;
mod contact_start;
mod contact_step;
mod determinism;
mod device;
mod energy;
mod energy_guard;
mod extremes;
mod gravity;
mod guard;
mod hold_after;
mod intervene;
mod joint_compliance;
mod joint_zone;
mod objectivity;
mod patch;
mod snapshot;
mod stability;
mod surface_work;
mod wave_speed;
