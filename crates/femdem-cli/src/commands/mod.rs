//! One module per subcommand.

pub mod check;
mod output;
pub(crate) mod prepare;
mod progress;
pub mod run;
