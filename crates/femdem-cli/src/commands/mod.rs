//! One module per subcommand.

pub mod check;
mod checkpoint;
mod output;
mod prepare;
mod progress;
pub mod run;
