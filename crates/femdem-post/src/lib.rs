//! Reading and measuring what `femdem run` wrote, for `femdem plot`, for
//! `cargo xtask validate`, for the tests and for any program that
//! post-processes femdem's results:
//!
//! | module | what it reads or measures |
//! |---|---|
//! | [`table`] | `history.csv` and `failures.csv` as named columns, with the history's comment lines |
//! | [`columns`] | the names and units of the columns `femdem run` writes |
//! | [`failures`] | failed joints with their mode typed ([`failures::FailureMode`]) |
//! | [`frames`] | the `.pvd` series and `.vtu` frames |
//! | [`brazilian`] | the load–strain curve, its peak, Eq. 23's f_bt, the first load drop, failure locations |
//! | [`hondros`] | Hondros' (Frocht's) elastic stresses of a disc under diametral load, against a frame's |
//! | [`diametral`] | the elastic shortening of a disc between flat rigid platens (the load–strain curve before failure) |
//! | [`mohr`] | the Mohr–Coulomb reach of applied principal stresses and Eq. 24's band angle |
//! | [`bands`] | shear-band and facet directions of failed faces |
//! | [`tips`] | the tips and junctions of a fracture map, and how near failures lie to them |
//! | [`mechanism`] | a limit-equilibrium estimate of the weakest piece a fracture network can release |
//! | [`fragments`] | the pieces a body has broken into and their sieve curve |
//!
//! It knows the files' formats, not the solver: nothing here steps a model.
//!
//! ```no_run
//! let dir = std::path::Path::new("out/brazilian-split");
//! let history = femdem_post::table::Table::history(dir)?;
//! let peak = history.col("load")?.into_iter().fold(0.0, f64::max);
//! let modes = femdem_post::failures::Modes::of(femdem_post::failures::Failure::read_all(dir)?.iter());
//! println!("peak load {peak:.1} N; failures {}", modes.text());
//! # Ok::<(), anyhow::Error>(())
//! ```

pub mod bands;
pub mod brazilian;
pub mod columns;
pub mod diametral;
pub mod failures;
pub mod fragments;
pub mod frames;
pub mod hondros;
pub mod mechanism;
pub mod mohr;
pub mod table;
pub mod tips;
