//! One module per subcommand.

pub mod check;
pub mod plot;
mod progress;
pub mod run;
