//! One module per subcommand.

pub mod check;
mod checkpoint;
pub mod memory;
mod outdir;
mod output;
pub mod plot;
pub(crate) mod prepare;
mod progress;
mod provenance;
pub mod run;
