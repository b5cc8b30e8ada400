//! Fuzzing the case loader: random mutations of valid case files either
//! load (mesh, joints, model, loads, time step: everything `femdem check`
//! and `femdem run` do before the first step) or are refused with an error
//! that names the file — never a panic.
//!
//! The bases (`fuzz/box.toml`, `fuzz/extrusion.toml`) hold every section
//! and almost every key of the format. A mutation replaces a value (a
//! number, string, boolean, array element or whole table) by one of
//! another type, NaN, ±∞, a negative, zero, a huge or a tiny number, or
//! removes a key; one to three mutations per case. Each case is written to
//! a file and loaded as `femdem check` loads it ([`prepare`]). The meshes
//! are a few dozen to a few hundred tets, so a case costs a few
//! milliseconds; 400 cases per base (about 5 s for both in release). A
//! one-off run of 1500 cases per base found the two bugs kept below as
//! regression tests (`femdem-mesh` `a_trace_point_outside_the_outline_is_refused`
//! and [`a_joint_insertion_error_names_the_file`]).
//!
//! The same mutations given as `--set key.path=value` to the unmutated
//! base (a removal cannot be) must be checked as the file's value is: the
//! case loads with both, or both are refused with the same message, only
//! its place differing (`--set ARG` for `file:line:col`); 200 cases per
//! base.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use proptest::prelude::*;
use toml::{Table, Value};

use crate::prepare::{MAX_THREADS, prepare};

/// Where a value sits: keys and array indices from the root.
#[derive(Clone, Debug)]
enum Step {
    Key(String),
    Index(usize),
}

/// Every value of `v` (tables and arrays included), as paths.
fn paths(v: &Value, at: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
    out.push(at.clone());
    match v {
        Value::Table(t) => {
            for (k, child) in t {
                at.push(Step::Key(k.clone()));
                paths(child, at, out);
                at.pop();
            }
        }
        Value::Array(a) => {
            for (i, child) in a.iter().enumerate() {
                at.push(Step::Index(i));
                paths(child, at, out);
                at.pop();
            }
        }
        _ => {}
    }
}

fn get_mut<'a>(v: &'a mut Value, path: &[Step]) -> Option<&'a mut Value> {
    let mut v = v;
    for s in path {
        v = match (s, v) {
            (Step::Key(k), Value::Table(t)) => t.get_mut(k)?,
            (Step::Index(i), Value::Array(a)) => a.get_mut(*i)?,
            _ => return None,
        };
    }
    Some(v)
}

/// What a mutation puts in place of a value.
#[derive(Clone, Copy, Debug)]
enum Mutation {
    Remove,
    Str,
    Bool,
    Int(i64),
    Float(f64),
    /// The value negated (numbers; others are left alone).
    Negate,
    EmptyArray,
    EmptyTable,
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        3 => Just(Mutation::Remove),
        1 => Just(Mutation::Str),
        1 => Just(Mutation::Bool),
        2 => prop::sample::select(vec![0i64, -1, 1, i64::MAX, i64::MIN, 4_294_967_296]).prop_map(Mutation::Int),
        4 => prop::sample::select(vec![
            0.0,
            -0.0,
            -1.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1e300,
            -1e300,
            1e-300,
            f64::MIN_POSITIVE,
        ])
        .prop_map(Mutation::Float),
        2 => Just(Mutation::Negate),
        1 => Just(Mutation::EmptyArray),
        1 => Just(Mutation::EmptyTable),
    ]
}

/// Applies `m` at `path` of `doc` (the root is never removed).
fn apply(doc: &mut Value, path: &[Step], m: Mutation) {
    if let (Mutation::Remove, Some((last, parent))) = (m, path.split_last()) {
        match (get_mut(doc, parent), last) {
            (Some(Value::Table(t)), Step::Key(k)) => {
                t.remove(k);
            }
            (Some(Value::Array(a)), Step::Index(i)) if *i < a.len() => {
                a.remove(*i);
            }
            _ => {}
        }
        return;
    }
    if path.is_empty() {
        return;
    }
    let Some(v) = get_mut(doc, path) else { return };
    let old = v.clone();
    let number = |v: &Value| match v {
        Value::Integer(i) => Some(*i as f64),
        Value::Float(f) => Some(*f),
        _ => None,
    };
    *v = match m {
        Mutation::Remove => return,
        Mutation::Str => Value::String("oops".into()),
        Mutation::Bool => Value::Boolean(true),
        Mutation::Int(i) => Value::Integer(i),
        Mutation::Float(f) => Value::Float(f),
        Mutation::Negate => match old {
            Value::Integer(i) => Value::Integer(i.wrapping_neg()),
            other => match number(&other) {
                Some(f) => Value::Float(-f),
                None => return,
            },
        },
        Mutation::EmptyArray => Value::Array(Vec::new()),
        Mutation::EmptyTable => Value::Table(Table::new()),
    };
}

/// A directory of its own for this test process, with the MSH fixture the
/// extrusion base uses.
fn work_dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("femdem-case-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let msh = Path::new(env!("CARGO_MANIFEST_DIR")).join("../femdem-mesh/tests/data/gmsh_two_volumes.msh");
        std::fs::copy(msh, dir.join("gmsh_two_volumes.msh")).unwrap();
        dir
    })
}

/// Loads `text` as a case file named `name` in the work directory; an
/// error must name the file.
fn load_names_the_file(text: &str, name: &str) -> Result<(), TestCaseError> {
    let path = work_dir().join(name);
    std::fs::write(&path, text).unwrap();
    if let Err(e) = prepare(&path, None, &[]) {
        let message = format!("{e:#}");
        prop_assert!(
            message.contains(&path.display().to_string()),
            "the error does not name the file: {}\n--- case ---\n{}",
            message,
            text
        );
    }
    Ok(())
}

fn mutated(base: &str, edits: &[(prop::sample::Index, Mutation)]) -> String {
    let mut doc = Value::Table(base.parse::<Table>().expect("the base parses"));
    for (at, m) in edits {
        let mut all = Vec::new();
        paths(&doc, &mut Vec::new(), &mut all);
        let path = all[at.index(all.len())].clone();
        apply(&mut doc, &path, *m);
    }
    match doc {
        Value::Table(t) => toml::to_string(&t).unwrap_or_default(),
        _ => unreachable!("the root is a table"),
    }
}

/// The key path and the TOML value of `path` in `doc`, as `--set` takes
/// them.
fn set_argument(doc: &mut Value, path: &[Step]) -> Option<String> {
    let keys: Vec<String> = path
        .iter()
        .map(|s| match s {
            Step::Key(k) => k.clone(),
            Step::Index(i) => i.to_string(),
        })
        .collect();
    let value = get_mut(doc, path)?.to_string();
    Some(format!("{}={value}", keys.join(".")))
}

/// The message of an error of case `path`, without its place: the path and
/// a `:line:col` or a `--set ARG` (its own, and those of warnings appended
/// to it), without the note naming `--set ARG`,
/// and with `path` named `CASE` wherever else it appears (with any
/// `:line:col` after it).
fn message_of(error: &str, path: &str, set: &str) -> String {
    // The message shows the `--set` argument as it shows any long number.
    let set = &*crate::numbers::shortened(set);
    let rest = error.strip_prefix(path).unwrap_or(error);
    let rest = rest.trim_start_matches(|c: char| c == ':' || c.is_ascii_digit()).trim_start();
    let rest = rest.strip_prefix(&format!("--set {set}: ")).unwrap_or(rest);
    // The file's message names the value's key, which the `--set` names.
    let key = set.split('=').next().and_then(|k| k.rsplit('.').next()).unwrap_or_default();
    let rest = rest.strip_prefix(&format!("`{key}`: ")).unwrap_or(rest);
    // An error at a table (inside a `kind`-tagged one, say) names the
    // table's path, which the `--set` key path holds.
    let tables = set.split('=').next().unwrap_or_default().split('.').scan(String::new(), |path, part| {
        match part.parse::<usize>() {
            Ok(i) => path.push_str(&format!("[{i}]")),
            Err(_) if path.is_empty() => path.push_str(part),
            Err(_) => path.push_str(&format!(".{part}")),
        }
        Some(path.clone())
    });
    let tables: Vec<String> = tables.collect();
    let rest = tables.iter().rev().find_map(|t| rest.strip_prefix(&format!("{t}: "))).unwrap_or(rest);
    let rest = rest.split(&format!(" (this table also has --set {set})")).next().unwrap_or(rest);
    let mut out = String::new();
    let mut pieces = rest.split(path);
    out.push_str(pieces.next().unwrap_or_default());
    for piece in pieces {
        out.push_str("CASE");
        out.push_str(piece.trim_start_matches(|c: char| c == ':' || c.is_ascii_digit()));
    }
    // A warning appended to the message (a unit slip under a step that
    // could not be estimated) is placed by `--set ARG` where the file's
    // is placed by `:line:col`.
    out.replace(&format!(" --set {set}: "), " ")
}

/// One mutation of `base` (named `name`), in the file and as a `--set`
/// argument to the unmutated base: both load, or both are refused with
/// the same message.
fn set_is_checked_as_the_file(
    base: &str,
    name: &str,
    at: prop::sample::Index,
    m: Mutation,
) -> Result<(), TestCaseError> {
    if matches!(m, Mutation::Remove) {
        return Ok(());
    }
    let mut doc = Value::Table(base.parse::<Table>().expect("the base parses"));
    let mut all = Vec::new();
    paths(&doc, &mut Vec::new(), &mut all);
    let path = all[at.index(all.len())].clone();
    if path.is_empty() {
        return Ok(());
    }
    apply(&mut doc, &path, m);
    let Some(set) = set_argument(&mut doc, &path) else { return Ok(()) };
    let text = match &doc {
        Value::Table(t) => toml::to_string(t).unwrap_or_default(),
        _ => unreachable!("the root is a table"),
    };
    if text.is_empty() {
        return Ok(());
    }
    let in_file = work_dir().join(format!("{name}_file.toml"));
    let by_set = work_dir().join(format!("{name}_set.toml"));
    std::fs::write(&in_file, &text).unwrap();
    std::fs::write(&by_set, base).unwrap();
    let file_result = prepare(&in_file, None, &[]).map(|_| ()).map_err(|e| format!("{e:#}"));
    let set_result = prepare(&by_set, None, std::slice::from_ref(&set)).map(|_| ()).map_err(|e| format!("{e:#}"));
    match (file_result, set_result) {
        (Ok(()), Ok(())) => {}
        (Err(f), Err(s)) => {
            let f_message = message_of(&f, &in_file.display().to_string(), &set);
            let s_message = message_of(&s, &by_set.display().to_string(), &set);
            prop_assert_eq!(f_message, s_message, "--set {}\nfile: {}\nset:  {}", set, f, s);
        }
        (f, s) => prop_assert!(false, "--set {}: the file gives {:?}, the --set {:?}", set, f, s),
    }
    Ok(())
}

const BOX: &str = include_str!("fuzz/box.toml");
const EXTRUSION: &str = include_str!("fuzz/extrusion.toml");

#[test]
fn the_bases_load() {
    for (name, text) in [("base_box.toml", BOX), ("base_extrusion.toml", EXTRUSION)] {
        let path = work_dir().join(name);
        std::fs::write(&path, text).unwrap();
        let prepared = prepare(&path, None, &[]).unwrap_or_else(|e| panic!("{name}: {e:#}"));
        assert!(prepared.run.is_some(), "{name} must reach the time step, where most checks are");
    }
}

/// Regression (found by this fuzzing): an extruded circle of element size
/// 9.2e18 m is one layer of a few prisms, and its trace lands on the
/// outline: joint insertion refused the fracture face as not interior, and
/// the error did not name the case file.
#[test]
fn a_joint_insertion_error_names_the_file() {
    let text = EXTRUSION.replacen("element_size = 0.005", "element_size = 9223372036854775807", 1);
    let path = work_dir().join("joint_insertion.toml");
    std::fs::write(&path, &text).unwrap();
    let message = format!("{:#}", prepare(&path, None, &[]).err().expect("the case is refused"));
    assert!(message.starts_with(&path.display().to_string()), "{message}");
    assert!(message.contains("inserting the joints failed"), "{message}");
}

/// Regression (found fuzzing: `threads = 100000000000000`): rayon starts
/// every thread asked for, and the run hung before any output. Above
/// [`MAX_THREADS`] the count is refused, on the command line and in the
/// case (with its file and line).
#[test]
fn a_huge_thread_count_is_refused() {
    let huge = 100_000_000_000_000usize;
    let path = work_dir().join("threads.toml");
    std::fs::write(&path, EXTRUSION.replacen("threads = 1", &format!("threads = {huge}"), 1)).unwrap();
    let message = format!("{:#}", prepare(&path, None, &[]).err().expect("refused"));
    assert!(message.starts_with(&format!("{}:", path.display())), "{message}");
    assert!(message.contains(&format!("threads = {huge} is more than the {MAX_THREADS}")), "{message}");
    let message = format!("{:#}", prepare(&path, Some(huge), &[]).err().expect("refused"));
    assert!(message.contains(&format!("--threads {huge} is more than the {MAX_THREADS}")), "{message}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn mutated_box_cases_load_or_name_the_file(
        edits in prop::collection::vec((any::<prop::sample::Index>(), mutation()), 1..4),
    ) {
        load_names_the_file(&mutated(BOX, &edits), "box.toml")?;
    }

    #[test]
    fn mutated_extrusion_cases_load_or_name_the_file(
        edits in prop::collection::vec((any::<prop::sample::Index>(), mutation()), 1..4),
    ) {
        load_names_the_file(&mutated(EXTRUSION, &edits), "extrusion.toml")?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn a_set_on_the_box_base_is_checked_as_the_file(at in any::<prop::sample::Index>(), m in mutation()) {
        set_is_checked_as_the_file(BOX, "box", at, m)?;
    }

    #[test]
    fn a_set_on_the_extrusion_base_is_checked_as_the_file(at in any::<prop::sample::Index>(), m in mutation()) {
        set_is_checked_as_the_file(EXTRUSION, "extrusion", at, m)?;
    }
}
