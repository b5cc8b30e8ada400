//! Records the commit the binary is built from, for the provenance lines of
//! every history header and run summary (`src/provenance.rs`):
//! `FEMDEM_COMMIT`, the short hash with `-dirty` when the work tree has
//! changes, or `unknown` outside a git checkout (a source tarball, a
//! machine without git). Nothing fails for want of git.

use std::process::Command;

fn git(args: &[&str]) -> Option<String> {
    let out = Command::new("git").args(args).output().ok()?;
    out.status.success().then(|| String::from_utf8_lossy(&out.stdout).trim().to_owned())
}

fn main() {
    let commit = git(&["rev-parse", "--short=12", "HEAD"]).filter(|c| !c.is_empty());
    let dirty = git(&["status", "--porcelain", "--untracked-files=no"]).is_some_and(|s| !s.is_empty());
    let label = match commit {
        Some(c) if dirty => format!("{c}-dirty"),
        Some(c) => c,
        None => "unknown".to_owned(),
    };
    println!("cargo:rustc-env=FEMDEM_COMMIT={label}");
    // Rebuilt when the checked-out commit moves (the paths are relative to
    // this crate; absent outside a checkout, which cargo tolerates).
    for path in ["../../.git/HEAD", "../../.git/index"] {
        println!("cargo:rerun-if-changed={path}");
    }
}
