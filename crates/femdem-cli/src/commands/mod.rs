//! One module per subcommand.

pub mod check;
mod checkpoint;
pub mod memory;
mod output;
pub(crate) mod prepare;
mod progress;
pub mod run;
