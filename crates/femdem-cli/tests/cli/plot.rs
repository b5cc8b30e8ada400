//! `femdem plot` on a short run of the small Brazilian disc (it has
//! `[output.load_strain]`): the default plots and a chosen pair of columns
//! are PNG files of 900 × 600 px; an unknown column is refused listing the
//! columns there are; a missing or empty history is refused naming the
//! path.

use crate::common::femdem;
use std::path::{Path, PathBuf};

/// A 20 µs run of the small disc (about 250 steps) into a fresh `name`.
fn short_run(name: &str) -> PathBuf {
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&out);
    let o = femdem(&[
        "run",
        "crates/femdem-cli/tests/cases/small_brazilian.toml",
        "--out",
        out.to_str().unwrap(),
        "--set",
        "solver.end_time=2e-5",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    out
}

/// Fails unless `path` is a PNG file (signature, then the IHDR chunk) of
/// `width` × `height` px.
fn assert_png(path: &Path, width: u32, height: u32) {
    let png = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{}: not a PNG", path.display());
    assert_eq!(&png[12..16], b"IHDR", "{}", path.display());
    let size = |at: usize| u32::from_be_bytes(png[at..at + 4].try_into().unwrap());
    assert_eq!((size(16), size(20)), (width, height), "{}", path.display());
    assert!(png.len() > 10_000, "{}: {} bytes, too few for a drawn chart", path.display(), png.len());
}

#[test]
fn plot_writes_the_load_strain_energy_and_failure_plots() {
    let out = short_run("plot-defaults");
    let o = femdem(&["plot", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8(o.stdout).unwrap();
    let listed: Vec<&str> = stdout.lines().collect();
    let expected: Vec<PathBuf> =
        ["load_strain", "energies", "failures"].iter().map(|n| out.join(format!("plot_{n}.png"))).collect();
    assert_eq!(listed, expected.iter().map(|p| p.to_str().unwrap()).collect::<Vec<_>>());
    for path in &expected {
        assert_png(path, 900, 600);
    }
}

#[test]
fn plot_draws_chosen_columns_into_the_named_file() {
    let out = short_run("plot-columns");
    let file = out.join("figures").join("load.png");
    let o = femdem(&["plot", out.to_str().unwrap(), "--x", "strain", "--y", "load", "--out", file.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(String::from_utf8(o.stdout).unwrap().trim(), file.to_str().unwrap());
    assert_png(&file, 900, 600);
    // A history file is accepted in place of its folder; the default name
    // says what is drawn.
    let o = femdem(&["plot", out.join("history.csv").to_str().unwrap(), "--y", "kinetic", "--y", "tet_elastic"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_png(&out.join("plot_kinetic-tet_elastic_vs_time.png"), 900, 600);
}

#[test]
fn an_unknown_column_is_refused_listing_the_columns() {
    let out = short_run("plot-unknown-column");
    for args in [["--y", "lode"], ["--x", "tme"]] {
        let mut all = vec!["plot", out.to_str().unwrap(), "--y", "load"];
        all.extend(args);
        let o = femdem(&all);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?}");
        assert!(err.contains(&format!("{} has no column `{}`", out.join("history.csv").display(), args[1])), "{err}");
        assert!(err.contains("its columns are: time, step, kinetic,") && err.contains("load, strain"), "{err}");
    }
    let pngs =
        std::fs::read_dir(&out).unwrap().filter(|e| e.as_ref().unwrap().path().extension() == Some("png".as_ref()));
    assert_eq!(pngs.count(), 0, "nothing is drawn");
}

#[test]
fn a_missing_or_empty_history_is_refused_naming_the_path() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("plot-no-history");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let o = femdem(&["plot", dir.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains(&format!("{} holds no history.csv", dir.display())), "{err}");

    let missing = dir.join("missing");
    let o = femdem(&["plot", missing.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains(&format!("{}: no such directory", missing.display())), "{err}");

    std::fs::write(dir.join("history.csv"), "# case: x.toml\ntime,kinetic\n").unwrap();
    let o = femdem(&["plot", dir.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("history.csv has no rows yet"), "{err}");

    std::fs::write(dir.join("history.csv"), "").unwrap();
    let o = femdem(&["plot", dir.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("history.csv is empty"), "{err}");
}

/// A history with a NaN (a run the guard stopped) is drawn without it,
/// and the plot says how many points of which column it left out.
#[test]
fn points_that_are_not_finite_are_named_in_a_warning() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("plot-nan");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("history.csv"),
        "# case: x.toml\ntime,kinetic,tet_elastic\n0,0,0\n1e-6,NaN,1\n2e-6,1,inf\n3e-6,2,2\n",
    )
    .unwrap();
    let o = femdem(&["plot", dir.to_str().unwrap(), "--y", "kinetic", "--y", "tet_elastic"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("1 of the 4 points of `kinetic` are not finite (NaN or ±inf) and are not drawn"), "{err}");
    assert!(err.contains("1 of the 4 points of `tet_elastic` are not finite"), "{err}");
    assert!(dir.join("plot_kinetic-tet_elastic_vs_time.png").is_file());
}

/// A CSV that is not a run's history (the run's `failures.csv`) has none
/// of the default plots' columns: refused, saying so and listing its
/// columns (it wrote nothing and exited 0); with `--y` it is drawn. A
/// history of one row draws single points, which a line plot does not
/// show: a warning. A header without rows in a file that is not a history
/// is not blamed on a run.
#[test]
fn a_csv_that_is_not_a_history_and_a_single_row_are_said_so() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("plot-not-history");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let failures = dir.join("failures.csv");
    std::fs::write(&failures, "time,joint,x,y,z,area,mode\n1e-6,3,0,0,0,1e-6,2\n2e-6,5,0,0,0,1e-6,1\n").unwrap();
    let o = femdem(&["plot", failures.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    assert!(err.contains("has none of the columns `femdem plot` draws by default"), "{err}");
    assert!(err.contains("it is not a run's history.csv") && err.contains("time, joint, x, y, z, area, mode"), "{err}");
    let o = femdem(&["plot", failures.to_str().unwrap(), "--y", "area"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(dir.join("plot_area_vs_time.png").is_file());

    let one = dir.join("one").join("history.csv");
    std::fs::create_dir_all(one.parent().unwrap()).unwrap();
    std::fs::write(&one, "# case: x.toml\ntime,step,kinetic,balance\n0,0,0,0\n").unwrap();
    let o = femdem(&["plot", one.parent().unwrap().to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("has one row: each curve is a single point"), "{err}");

    let empty = dir.join("empty.csv");
    std::fs::write(&empty, "a,b\n").unwrap();
    let err = String::from_utf8(femdem(&["plot", empty.to_str().unwrap()]).stderr).unwrap();
    assert!(err.contains("has a header and no rows: nothing to draw") && !err.contains("the run"), "{err}");
}
