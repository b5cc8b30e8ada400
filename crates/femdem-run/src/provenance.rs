//! What produced a result: the femdem version and commit, the processor,
//! the vector instructions the build uses and those the tet and joint
//! passes chose at run time, the worker threads and the GPU the step ran on
//! (if any). Written at the head of every
//! `history.csv` and at the end of every run summary, so that a number in a
//! report can be traced to what computed it.

/// The version and the commit the binary was built from (`build.rs`).
pub fn build() -> String {
    format!("{} (commit {})", env!("CARGO_PKG_VERSION"), env!("FEMDEM_COMMIT"))
}

/// The processor's model name (`/proc/cpuinfo`; the architecture alone
/// where that cannot be read).
pub fn cpu() -> String {
    let model = std::fs::read_to_string("/proc/cpuinfo").ok().and_then(|text| {
        text.lines()
            .find(|l| l.starts_with("model name") || l.starts_with("Model"))
            .and_then(|l| l.split_once(':'))
            .map(|(_, name)| name.split_whitespace().collect::<Vec<_>>().join(" "))
    });
    match model {
        Some(m) if !m.is_empty() => format!("{m} ({})", std::env::consts::ARCH),
        _ => std::env::consts::ARCH.to_owned(),
    }
}

/// The vector instructions the build targets, fixed at compile time (all
/// code but the dispatched passes uses these and nothing wider), and the
/// unit the tet and joint passes and the contact pair kernel run on,
/// chosen at run time
/// (`femdem_solver::widest_name`).
pub fn simd() -> String {
    let mut on: Vec<&str> = Vec::new();
    macro_rules! feature {
        ($($name:tt),*) => {
            $(if cfg!(target_feature = $name) { on.push($name); })*
        };
    }
    feature!("sse2", "sse4.1", "avx", "avx2", "fma", "avx512f", "neon");
    let build = if on.is_empty() { "none (scalar)".to_owned() } else { on.join(", ") };
    format!(
        "{build} (fixed at build); tet, joint and contact pair passes on {} (chosen at run time)",
        femdem_solver::widest_name()
    )
}

/// The provenance lines, `key: value`, for a history header (each behind
/// `# `) or a run summary; `gpu` is the device the step runs on and what
/// of it runs there (`Solver::device`, `Solver::device_stages`), if any.
pub fn lines(gpu: Option<&str>) -> Vec<String> {
    vec![
        format!("femdem: {}", build()),
        format!("cpu: {}", cpu()),
        format!("simd: {}", simd()),
        format!("threads: {}", rayon::current_num_threads()),
        format!("gpu: {}", gpu.unwrap_or("none")),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every line names its value; the version is the crate's, and the
    /// commit is a hash (with `-dirty` for a changed work tree) or
    /// `unknown`, never empty.
    #[test]
    fn the_lines_name_version_commit_cpu_simd_threads_and_gpu() {
        let lines = lines(None);
        let keys: Vec<&str> = lines.iter().map(|l| l.split_once(": ").unwrap().0).collect();
        assert_eq!(keys, ["femdem", "cpu", "simd", "threads", "gpu"]);
        assert!(lines.iter().all(|l| !l.split_once(": ").unwrap().1.is_empty()));
        let commit = env!("FEMDEM_COMMIT");
        let hash = commit.trim_end_matches("-dirty");
        assert!(commit == "unknown" || (hash.len() == 12 && hash.chars().all(|c| c.is_ascii_hexdigit())), "{commit}");
        assert!(lines[0].starts_with(&format!("femdem: {} (commit ", env!("CARGO_PKG_VERSION"))));
        assert!(lines[3]["threads: ".len()..].parse::<usize>().unwrap() >= 1);
        assert_eq!(lines[4], "gpu: none");
        assert_eq!(super::lines(Some("llvmpipe: stage 1"))[4], "gpu: llvmpipe: stage 1");
    }
}
