//! The output directory of `femdem run`: where it is, the targets refused
//! outright (the file system's root, the home directory, the case file's
//! own folder, anything that is not a directory), and the results of an
//! earlier run in it, which a new run refuses to mix with unless given
//! `--overwrite`, which removes them first.
//!
//! femdem's own files, recognised by name (nothing else is ever removed):
//! `history.csv`, `failures.csv`, checkpoints (`checkpoint_<12
//! digits>.femdem-ckpt`, `.checkpoint.tmp`), every `S.pvd` that is a VTK
//! collection with its frames `S_<6 digits>.vtu` (this case's series and
//! its fracture series whatever their content), the plots `femdem plot`
//! writes (`plot_*.png`), and the `.tmp` files of any of these.

use std::fs;
use std::io::{BufRead, BufReader, Read};
use std::path::{Component, Path, PathBuf};

use anyhow::{Context, Result, bail};

use crate::checkpoint;
use femdem_case::LoadedCase;

/// The comment line of `history.csv` that names the case (see
/// `output::history_comments`).
pub const CASE_COMMENT: &str = "case: ";

/// The file a run holds an exclusive lock on for as long as it writes to
/// its output directory (see [`lock`]). It stays in the directory, empty
/// of meaning once no process holds it; it is neither a result nor
/// anything `--overwrite` removes.
pub const LOCK: &str = ".femdem.lock";

/// Takes the output directory `dir` (created if missing) for this run: an
/// exclusive lock on its [`LOCK`] file, held until the returned file is
/// dropped (the operating system releases it when the process ends, however
/// it ends). Two runs writing into one directory at once (a sweep started
/// in parallel with the same `--out`) interleaved their frames, and the
/// history of one of them was lost while both reported success.
///
/// # Errors
/// When another process holds the lock (naming the directory), or the
/// directory or file cannot be made. Where the file system has no locks,
/// the run goes ahead unguarded.
pub fn lock(dir: &Path) -> Result<fs::File> {
    fs::create_dir_all(dir).with_context(|| format!("creating the output directory {}", dir.display()))?;
    let path = dir.join(LOCK);
    let file = fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .with_context(|| format!("creating the lock file {}", path.display()))?;
    match file.try_lock() {
        Ok(()) => Ok(file),
        Err(fs::TryLockError::WouldBlock) => bail!(
            "output directory {} is being written by another femdem run (it holds {}); wait for it to end, or \
             name another directory with --out",
            dir.display(),
            path.display()
        ),
        // A file system without locks (some network ones) cannot keep two
        // runs apart; that is no reason to refuse the one run.
        Err(fs::TryLockError::Error(_)) => Ok(file),
    }
}

/// The output directory of a run of `case` (file stem `stem`): `--resume
/// DIR`, else `--out`, else `[output] dir` (relative to the case file;
/// an empty one is refused even with `--out`), else `out/<stem>`.
pub fn resolve(
    case: &LoadedCase,
    stem: &str,
    out: Option<PathBuf>,
    resume: &Option<Option<PathBuf>>,
) -> Result<PathBuf> {
    // An empty `dir` is a fault of the case, refused as `check` refuses it,
    // whatever --out says.
    femdem_case::setup::check_dir(case)?;
    let from_case = case.case.output.as_ref().and_then(|o| o.get_ref().dir.as_ref()).map(|d| case.dir().join(d));
    Ok(match (resume, out) {
        (Some(Some(from)), Some(out)) if from != &out => {
            bail!("--resume {} and --out {} name different directories", from.display(), out.display())
        }
        (Some(Some(from)), _) => from.clone(),
        (_, out) => out.or(from_case).unwrap_or_else(|| Path::new("out").join(stem)),
    })
}

/// Fails, naming `dir` and why, if it is a target no run may write into:
/// an existing path that is not a directory, the root of the file system,
/// the home directory (`$HOME`), or the folder holding the case file
/// `case_file` (the results would lie among the case's inputs).
pub fn refuse_dangerous(dir: &Path, case_file: &Path) -> Result<()> {
    let shown = dir.display();
    if fs::metadata(dir).is_ok_and(|m| !m.is_dir()) {
        bail!(
            "output directory {shown}: it exists and is not a directory; name a directory with --out or \
             `[output] dir`"
        );
    }
    let full = normalised(dir);
    let why = if full.parent().is_none() {
        Some("it is the root of the file system".to_owned())
    } else if std::env::var_os("HOME").is_some_and(|home| !home.is_empty() && normalised(Path::new(&home)) == full) {
        Some("it is the home directory".to_owned())
    } else {
        let case_dir = case_file.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
        (normalised(case_dir) == full).then(|| {
            format!(
                "it is the folder of the case file {}, and the results would lie among the case's inputs",
                case_file.display()
            )
        })
    };
    if let Some(why) = why {
        let resolved = if full == dir { String::new() } else { format!(" ({})", full.display()) };
        bail!(
            "refusing to write results into {shown}{resolved}: {why}; name a folder of its own with --out or \
             `[output] dir`"
        );
    }
    Ok(())
}

/// `path` made absolute, `.` and `..` resolved and symbolic links followed
/// as far as it exists (the rest taken as written).
fn normalised(path: &Path) -> PathBuf {
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_owned());
    let mut out = PathBuf::new();
    for c in absolute.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                out.pop();
            }
            c => {
                out.push(c);
                if let Ok(real) = fs::canonicalize(&out) {
                    out = real;
                }
            }
        }
    }
    out
}

/// What a directory holds: femdem's own files and the others.
#[derive(Debug, Default)]
pub struct Survey {
    /// femdem's files (names in the directory), sorted.
    pub ours: Vec<String>,
    /// Everything else (names; directories end in `/`), sorted: never
    /// removed.
    pub kept: Vec<String>,
    /// Whether a checkpoint is among `ours` (the earlier run can be
    /// continued with `--resume`).
    pub checkpoint: bool,
    /// The case named by the `# case:` line of its `history.csv`, if any.
    pub case: Option<String>,
}

/// Sorts the entries of `dir` into femdem's files (of any earlier run, and
/// those a run of a case with file stem `stem` writes) and the others. A
/// directory that does not exist holds nothing.
pub fn survey(dir: &Path, stem: &str) -> Result<Survey> {
    let mut survey = Survey::default();
    let entries = match fs::read_dir(dir) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(survey),
        Err(e) => return Err(e).with_context(|| format!("reading the output directory {}", dir.display())),
    };
    let mut names = Vec::new();
    for entry in entries {
        let entry = entry.with_context(|| format!("reading the output directory {}", dir.display()))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if entry.file_type().is_ok_and(|t| t.is_dir()) {
            survey.kept.push(format!("{name}/"));
        } else {
            names.push(name);
        }
    }
    // Series: this case's two, and every collection femdem wrote.
    let mut series = vec![stem.to_owned(), format!("{stem}_fractures")];
    for name in &names {
        if let Some(s) = name.strip_suffix(".pvd").filter(|_| is_collection(&dir.join(name))) {
            series.push(s.to_owned());
        }
    }
    let ours = |name: &str| {
        let name = name.strip_suffix(".tmp").unwrap_or(name);
        matches!(name, "history.csv" | "failures.csv")
            || checkpoint::is_checkpoint_name(name)
            || (name.starts_with("plot_") && name.ends_with(".png"))
            || series.iter().any(|s| is_series_file(name, s))
    };
    for name in names {
        if name == LOCK {
            continue;
        }
        if ours(&name) || name == checkpoint::TEMPORARY {
            survey.checkpoint |= checkpoint::is_checkpoint_name(&name);
            survey.ours.push(name);
        } else {
            survey.kept.push(name);
        }
    }
    survey.ours.sort();
    survey.kept.sort();
    if survey.ours.iter().any(|n| n == "history.csv") {
        survey.case = case_of(&dir.join("history.csv"));
    }
    Ok(survey)
}

/// Whether `name` is `{series}.pvd` or a frame `{series}_<6 digits>.vtu`.
fn is_series_file(name: &str, series: &str) -> bool {
    let Some(rest) = name.strip_prefix(series) else {
        return false;
    };
    rest == ".pvd"
        || rest
            .strip_prefix('_')
            .and_then(|r| r.strip_suffix(".vtu"))
            .is_some_and(|d| d.len() == 6 && d.bytes().all(|b| b.is_ascii_digit()))
}

/// Whether `path` starts as the VTK collections (`.pvd`) femdem writes do.
fn is_collection(path: &Path) -> bool {
    let mut start = Vec::new();
    let read = fs::File::open(path).and_then(|f| f.take(200).read_to_end(&mut start));
    read.is_ok() && String::from_utf8_lossy(&start).contains("<VTKFile type=\"Collection\"")
}

/// The case a `history.csv` names in its leading comment lines.
fn case_of(history: &Path) -> Option<String> {
    let file = fs::File::open(history).ok()?;
    BufReader::new(file)
        .lines()
        .map_while(|l| l.ok().filter(|l| l.starts_with('#')))
        .find_map(|l| l.trim_start_matches('#').trim_start().strip_prefix(CASE_COMMENT).map(|c| c.trim().to_owned()))
}

/// Up to `n` names of `names`, then how many more.
fn some_of(names: &[String], n: usize) -> String {
    let mut s = names.iter().take(n).cloned().collect::<Vec<_>>().join(", ");
    if names.len() > n {
        s.push_str(&format!(" and {} more", names.len() - n));
    }
    s
}

/// `n` and the noun `one` or its plural `many`.
fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// femdem's files `ours` in short: each series' frames counted with its
/// collection (`bar.pvd with 21 frames`), the other files by name.
fn summary(ours: &[String]) -> String {
    let frame_of = |name: &str| {
        let base = name.strip_suffix(".vtu")?;
        let (series, digits) = base.rsplit_once('_')?;
        (digits.len() == 6 && digits.bytes().all(|b| b.is_ascii_digit())).then(|| series.to_owned())
    };
    let mut frames: Vec<(String, usize)> = Vec::new();
    let mut others = Vec::new();
    for name in ours {
        match frame_of(name) {
            Some(series) => match frames.iter_mut().find(|(s, _)| *s == series) {
                Some((_, n)) => *n += 1,
                None => frames.push((series, 1)),
            },
            None => others.push(name.clone()),
        }
    }
    for (series, n) in frames {
        let pvd = format!("{series}.pvd");
        let frames = count(n, "frame", "frames");
        match others.iter_mut().find(|o| **o == pvd) {
            Some(o) => *o = format!("{pvd} with {frames}"),
            None => others.push(format!("{series}_*.vtu ({frames})")),
        }
    }
    some_of(&others, 6)
}

/// Fails, unless `overwrite`, when `dir` holds results of an earlier run
/// (femdem's files, of this case or another): a new run would overwrite
/// some and leave others stale. `case_name` is this run's case file name.
pub fn refuse_earlier_results(dir: &Path, stem: &str, case_name: &str, overwrite: bool) -> Result<()> {
    if overwrite {
        return Ok(());
    }
    let s = survey(dir, stem)?;
    if s.ours.is_empty() {
        return Ok(());
    }
    let whose = match &s.case {
        Some(c) if c == case_name => "of an earlier run of this case".to_owned(),
        Some(c) => format!("of case {c}"),
        None => "of an earlier run".to_owned(),
    };
    let resume = if s.checkpoint { ", continue the interrupted run with --resume" } else { "" };
    let kept = if s.kept.is_empty() {
        String::new()
    } else {
        format!("; {} not written by femdem: kept", some_of(&s.kept, 3))
    };
    bail!(
        "output directory {} already holds the results {whose}: {}; a new run would overwrite some and leave the \
         rest stale. Run with --overwrite to remove them first (only femdem's own files{kept}){resume}, or name \
         another directory with --out",
        dir.display(),
        summary(&s.ours),
    )
}

/// Removes femdem's files from `dir` (see the module doc); returns a line
/// saying what was removed and what was kept, when anything was removed.
pub fn clear(dir: &Path, stem: &str) -> Result<Option<String>> {
    let s = survey(dir, stem)?;
    for name in &s.ours {
        let path = dir.join(name);
        fs::remove_file(&path).with_context(|| format!("--overwrite: removing {}", path.display()))?;
    }
    if !s.ours.is_empty() {
        let kept = if s.kept.is_empty() {
            String::new()
        } else {
            format!("; kept {} femdem did not write: {}", count(s.kept.len(), "entry", "entries"), some_of(&s.kept, 5))
        };
        return Ok(Some(format!(
            "--overwrite: removed the results of an earlier run from {} ({}){kept}",
            dir.display(),
            summary(&s.ours)
        )));
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn series_files_are_the_collection_and_six_digit_frames() {
        assert!(is_series_file("bar.pvd", "bar"));
        assert!(is_series_file("bar_000012.vtu", "bar"));
        assert!(is_series_file("bar_fractures_000012.vtu", "bar_fractures"));
        assert!(!is_series_file("bar_fractures_000012.vtu", "bar"));
        assert!(!is_series_file("bar_12.vtu", "bar"));
        assert!(!is_series_file("bar_00001x.vtu", "bar"));
        assert!(!is_series_file("barn.pvd", "bar"));
        assert!(!is_series_file("bar_000012.vtk", "bar"));
    }

    #[test]
    fn a_summary_counts_each_series_frames_with_its_collection() {
        let names = ["bar.pvd", "bar_000000.vtu", "bar_000001.vtu", "history.csv", "old_000003.vtu"];
        let names: Vec<String> = names.iter().map(|n| n.to_string()).collect();
        assert_eq!(summary(&names), "bar.pvd with 2 frames, history.csv, old_*.vtu (1 frame)");
    }

    #[test]
    fn a_survey_keeps_unknown_files_and_reads_the_case_name() {
        let dir = std::env::temp_dir().join(format!("femdem-outdir-survey-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(dir.join("sub")).unwrap();
        let files = [
            ("history.csv", "# case: other.toml\n# title: x\ntime\n0\n"),
            ("failures.csv", "time\n"),
            ("other.pvd", "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"),
            ("other_000000.vtu", ""),
            ("mine_000003.vtu", ""),
            ("checkpoint_000000000100.femdem-ckpt", ""),
            ("plot_energies.png", ""),
            ("notes.txt", "mine"),
            ("theirs.pvd", "not a collection"),
            ("theirs_000000.vtu", ""),
            ("other_1.vtu", ""),
        ];
        for (name, text) in files {
            fs::write(dir.join(name), text).unwrap();
        }
        let s = survey(&dir, "mine").unwrap();
        assert_eq!(
            s.ours,
            [
                "checkpoint_000000000100.femdem-ckpt",
                "failures.csv",
                "history.csv",
                "mine_000003.vtu",
                "other.pvd",
                "other_000000.vtu",
                "plot_energies.png"
            ]
        );
        assert_eq!(s.kept, ["notes.txt", "other_1.vtu", "sub/", "theirs.pvd", "theirs_000000.vtu"]);
        assert!(s.checkpoint);
        assert_eq!(s.case.as_deref(), Some("other.toml"));
        let err = refuse_earlier_results(&dir, "mine", "mine.toml", false).unwrap_err().to_string();
        assert!(err.contains("of case other.toml") && err.contains("--overwrite") && err.contains("--resume"), "{err}");
        refuse_earlier_results(&dir, "mine", "mine.toml", true).unwrap();
        clear(&dir, "mine").unwrap();
        let left: Vec<String> =
            fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
        assert_eq!(left.len(), 5, "{left:?}");
        assert!(survey(&dir, "mine").unwrap().ours.is_empty());
        refuse_earlier_results(&dir, "mine", "mine.toml", false).unwrap();
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn normalising_resolves_dots_against_existing_folders() {
        assert_eq!(normalised(Path::new("/tmp/../")), PathBuf::from("/"));
        assert_eq!(normalised(Path::new("/no-such-femdem-dir/a/../..")), PathBuf::from("/"));
        let here = std::env::current_dir().unwrap().canonicalize().unwrap();
        assert_eq!(normalised(Path::new(".")), here);
    }
}
