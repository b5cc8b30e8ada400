//! One module per subcommand.

pub mod check;
mod output;
mod prepare;
mod progress;
pub mod run;
