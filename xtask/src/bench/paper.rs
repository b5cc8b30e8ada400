//! `cargo xtask bench --paper [--threads N] [--size H]`: the multi-layer
//! case of the paper at its own mesh size (24 mm, about 603k tets) with its
//! face pressures ramped over 0.1 ms instead of 2 ms, run by `femdem` for
//! the ramp and about 450 steps more; prints the tet-steps per second over
//! the steps after the ramp, once every pre-existing fracture face carries
//! its full load (the contact-dominated regime of issue 28's target), and
//! over the first 130 steps. Some 15 minutes on 2 cores; not run by CI.
//! A prebuilt `femdem` named by the environment variable `FEMDEM_BIN` is
//! run instead of building one (an earlier build, to measure against).
//!
//! The rates come from femdem's progress lines, which give the cumulative
//! throughput since the loop started: `steps · tets / throughput` is the
//! wall time at each line, and a window's rate is its steps times the tets
//! over the difference of those times.

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};

use anyhow::{Context, Result, bail};

/// The face pressures' ramp, s.
const RAMP: f64 = 1.0e-4;
/// The end time: the ramp and about 450 steps of the 24 mm mesh.
const END: f64 = 1.9e-4;

/// Runs the benchmark (see the module documentation).
pub fn run(threads: &str, size: &str) -> Result<()> {
    let root = crate::root();
    let femdem = crate::validate::runner::binary("bench --paper")?;
    let out = root.join("target").join("bench-paper");
    let mut sets = vec![format!("mesh.parts.0.element_size={size}"), format!("solver.end_time={END}")];
    sets.push("output.interval=1.0".into());
    sets.extend((0..6).map(|k| format!("loads.{k}.ramp_time={RAMP}")));
    let mut cmd = Command::new(&femdem);
    let run = ["run", "cases/paper/multilayer.toml", "--overwrite", "--progress-interval", "2", "--threads"];
    cmd.args(run)
        .arg(threads)
        .arg("--out")
        .arg(&out)
        .args(sets.iter().flat_map(|s| ["--set", s.as_str()]))
        .current_dir(&root)
        .stderr(Stdio::piped());
    eprintln!("bench --paper: {cmd:?}");
    let mut child = cmd.spawn().context("starting femdem")?;
    let stderr = child.stderr.take().context("femdem's stderr")?;
    let (mut tets, mut dt, mut points) = (0.0, 0.0, Vec::new());
    for line in BufReader::new(stderr).lines() {
        let line = line?;
        eprintln!("{line}");
        if let Some(rest) = line.strip_prefix("femdem: ")
            && let Some(n) = rest.split(' ').next().and_then(|n| n.parse::<f64>().ok())
        {
            tets = n;
            dt = number_after(rest, "dt = ").unwrap_or(0.0);
        }
        if let (Some(step), Some(rate)) = (number_after(&line, "step "), number_before(&line, " element-steps/s")) {
            points.push((step, step * tets / rate));
        }
    }
    if !child.wait()?.success() {
        bail!("femdem failed");
    }
    if tets == 0.0 || dt == 0.0 || points.len() < 4 {
        bail!("femdem printed too few progress lines to time a window");
    }
    let ramp_steps = RAMP / dt;
    let window = |from: f64, to: f64| -> Option<(f64, f64, f64)> {
        let near = |s: f64| points.iter().min_by(|a, b| (a.0 - s).abs().total_cmp(&(b.0 - s).abs())).copied();
        let (a, b) = (near(from)?, near(to)?);
        (b.0 > a.0).then(|| (a.0, b.0, (b.0 - a.0) * tets / (b.1 - a.1)))
    };
    let last = points.last().map_or(0.0, |p| p.0);
    println!(
        "multi-layer, element size {size} m: {tets} tets, dt = {dt:.4e} s, ramp {ramp_steps:.0} steps, {threads} threads"
    );
    for (name, from, to) in [("first 130 steps", 0.0, 130.0), ("after the ramp", ramp_steps, last)] {
        match window(from, to) {
            Some((a, b, rate)) => println!("{name}: steps {a:.0}-{b:.0}, {rate:.3e} tet-steps/s"),
            None => println!("{name}: no window"),
        }
    }
    Ok(())
}

/// The number right after `key` in `line`.
fn number_after(line: &str, key: &str) -> Option<f64> {
    let rest = &line[line.find(key)? + key.len()..];
    let end =
        rest.find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | 'e' | 'E' | '-' | '+'))).unwrap_or(rest.len());
    rest[..end].parse().ok()
}

/// The number right before `key` in `line`.
fn number_before(line: &str, key: &str) -> Option<f64> {
    let head = &line[..line.find(key)?];
    head.rsplit(' ').next()?.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn progress_lines_are_read() {
        let line = "step 513/971  t = 1.0043e-4 s  0 joints failed  6.483e5 element-steps/s  eta 300 s";
        assert_eq!(number_after(line, "step "), Some(513.0));
        assert_eq!(number_before(line, " element-steps/s"), Some(6.483e5));
        let header = "603099 tets (603099 deformable), 1163214 joints, 2412396 nodes; dt = 1.9574e-7 s (0.90 of …";
        assert_eq!(number_after(header, "dt = "), Some(1.9574e-7));
    }
}
