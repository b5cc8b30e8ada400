//! Turning a case's material, platen, load, contact and output sections
//! into a solver model, its loads and the run's settings.

mod contact;
mod loads;
mod materials;
mod output;
pub mod plausible;
mod unused;

pub use contact::{ContactCheck, activation_name, contact, contact_check, contact_noting};
pub use loads::{
    constrained_twice, loads, loads_that_stop_while_ramping, platens_that_touch_nothing, surface_loads_on_held_nodes,
    surface_loads_on_interior_faces,
};
pub use materials::{DEFAULT_PENALTY_FACTOR, behaviours, model};
pub use output::{
    CHECKPOINT_WALL_DEFAULT, CheckpointSettings, FIELDS, LoadStrain, OutputSettings, check_dir, compression,
    load_strain, output,
};
pub use unused::{
    fractures_without_contact, heterogeneity_without_joints, ramps_longer_than_the_run, regions_without_tets,
};
