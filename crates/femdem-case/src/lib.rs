//! femdem's case format as a library: a TOML case file read with errors
//! that name the file, the line, the column and the key ([`load`]);
//! `--set` overrides applied to it ([`overrides`]); its memory estimated
//! before anything is built ([`memory`]); and its mesh, joints, model,
//! loads and time step built into a solver ready to step
//! ([`prepare::prepare`]).
//!
//! This crate and the command line (with xtask) are the only ones that
//! know the TOML case format; the physics crates below never see it. It
//! writes nothing to the terminal: what it finds is returned.
//!
//! ```no_run
//! let prepared = femdem_case::prepare::prepare(std::path::Path::new("cases/brazilian-split.toml"), None, &[])?;
//! let run = prepared.run.expect("the case has a [solver] section");
//! println!("{} tets, dt = {:.3e} s", run.solver.model().tets.len(), run.solver.dt());
//! # Ok::<(), anyhow::Error>(())
//! ```

pub mod coincident;
pub mod format;
#[cfg(test)]
mod fuzz;
pub mod memory;
pub mod mesh;
pub mod numbers;
pub mod outline;
pub mod overrides;
pub mod placement;
pub mod prepare;
pub mod probes;
pub mod refinement;
pub mod setup;
pub mod zones;

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

use serde::Deserialize;

pub use format::{CASE_VERSION, Case};
pub use overrides::Overrides;

/// An error located in a case file.
#[derive(Debug)]
pub struct CaseError {
    /// The case file.
    pub path: PathBuf,
    /// 1-based line and column, when known.
    pub at: Option<(usize, usize)>,
    /// The message, naming the key where there is one.
    pub message: String,
}

impl fmt::Display for CaseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let message = numbers::shortened(&self.message);
        match self.at {
            Some((l, c)) => write!(f, "{}:{l}:{c}: {message}", self.path.display()),
            None => write!(f, "{}: {message}", self.path.display()),
        }
    }
}

impl std::error::Error for CaseError {}

/// A parsed case with its source, for locating later errors.
pub struct LoadedCase {
    /// The case, with the `--set` overrides applied.
    pub case: Case,
    /// Where it was read from.
    pub path: PathBuf,
    /// Its text.
    pub source: String,
    /// The `--set` overrides.
    pub overrides: Overrides,
}

impl LoadedCase {
    /// An error at byte range `span` of the source, or of a `--set`
    /// argument (see [`Overrides::blame`]), which it then names instead of
    /// a line.
    pub fn error_at(&self, span: Range<usize>, message: impl Into<String>) -> CaseError {
        located(&self.path, &self.source, &self.overrides, span, message.into())
    }

    /// The directory that relative paths in the case are taken from.
    pub fn dir(&self) -> &Path {
        self.path.parent().unwrap_or(Path::new("."))
    }
}

/// 1-based line and column (in characters) of byte `offset` of `text`.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// Where to point an error at. Serde reports an unknown key of a `kind`-
/// tagged table (the parts) at the table's header; the key's own line is
/// found by looking for `` `key` = `` at a line start between that header
/// and the next one.
fn key_offset(source: &str, span: Range<usize>, message: &str) -> usize {
    let key = message.strip_prefix("unknown field `").and_then(|m| m.split('`').next());
    let (Some(key), Some(text)) = (key, source.get(span.start..)) else {
        return span.start;
    };
    let mut offset = span.start;
    for (i, line) in text.split_inclusive('\n').enumerate() {
        let trimmed = line.trim_start();
        if i > 0 && trimmed.starts_with('[') {
            break;
        }
        if trimmed.strip_prefix(key).is_some_and(|rest| rest.trim_start().starts_with('=')) {
            return offset + (line.len() - trimmed.len());
        }
        offset += line.len();
    }
    span.start
}

/// Whether trimmed line `l` is a table header, not a row of a multi-line
/// array (`[0.0, 1.0],`).
fn header(l: &str) -> bool {
    let rest = l.strip_prefix("[[").or_else(|| l.strip_prefix('[')).unwrap_or("").trim_start();
    l.starts_with('[') && rest.starts_with(|c: char| c.is_ascii_alphabetic() || matches!(c, '_' | '"' | '\''))
}

/// The key path of the table whose header starts byte range `span` of
/// `source`: `solver`, `loads[3]` for the fourth `[[loads]]`,
/// `materials[0].cohesion` for a table inside a list's element, and so on
/// down nested lists (`mesh.regions[0].joints_within[1]`); with `whole`,
/// a list's path without the index of the element. Serde reports a
/// missing key at the table's header (the span starts at its first `[`).
/// `None` where the span does not start a header: the root's (empty),
/// a table made implicitly by a longer header (the span of its key in
/// that header), a misspelt table's unknown key.
fn table_path(source: &str, span: Range<usize>, whole: bool) -> Option<String> {
    let line_start = source.get(..span.start)?.rfind('\n').map_or(0, |i| i + 1);
    let raw = source.get(line_start..)?.lines().next()?;
    let line = raw.trim();
    if span.is_empty() || span.start != line_start + (raw.len() - raw.trim_start().len()) || !header(line) {
        return None;
    }
    // A header's list flag and dotted path.
    let name = |l: &str| -> Option<(bool, String)> {
        let h = l.split('#').next()?.trim();
        let inner = h.trim_start_matches('[').split(']').next()?;
        Some((h.starts_with("[["), inner.split('.').map(str::trim).collect::<Vec<_>>().join(".")))
    };
    // Every header before this one's line.
    let mut headers: Vec<(bool, String)> =
        source[..line_start].lines().map(str::trim).filter(|l| header(l)).filter_map(name).collect();
    let (list, path) = name(line)?;
    headers.push((list && !whole, path));
    Some(indexed(&headers, headers.len() - 1))
}

/// The path of header `k` of `headers` (list flag and dotted path, in file
/// order) with the index of each list element it lies in: the innermost
/// list before it whose path begins its own gives the prefix, and a list's
/// index counts its headers since that enclosing element began.
fn indexed(headers: &[(bool, String)], k: usize) -> String {
    let (list, path) = &headers[k];
    let parent = headers[..k].iter().rposition(|(l, q)| *l && path.starts_with(&format!("{q}.")));
    let head = match parent {
        Some(j) => format!("{}{}", indexed(headers, j), &path[headers[j].1.len()..]),
        None => path.clone(),
    };
    if !list {
        return head;
    }
    let since = parent.map_or(0, |j| j + 1);
    let index = headers[since..k].iter().filter(|(l, q)| *l && q == path).count();
    format!("{head}[{index}]")
}

/// The element of a `[[list]]` that `error` comes from, where serde
/// reports it at the list's first header (an error inside a `kind`-tagged
/// table, such as a load or a part, loses its own place): each element in
/// turn is copied over all the others, and the first whose copies give the
/// same message is the one. Its span, or `None` where the error is not at
/// a list's header or the list has one element.
fn element_at_fault(
    source: &str,
    document: &toml::Spanned<toml::de::DeTable<'_>>,
    error: &toml::de::Error,
) -> Option<Range<usize>> {
    use toml::de::DeValue;
    let span = error.span().filter(|s| !s.is_empty())?;
    let line = source.get(span.start..)?.lines().next()?.trim();
    let path = line.strip_prefix("[[")?.split(']').next()?;
    let keys: Vec<&str> = path.split('.').map(str::trim).collect();
    // The list at `keys` in `value`.
    fn list<'a, 'i>(value: &'a mut DeValue<'i>, keys: &[&str]) -> Option<&'a mut [toml::Spanned<DeValue<'i>>]> {
        match (value, keys) {
            (DeValue::Array(a), []) => Some(&mut **a),
            (DeValue::Table(t), [k, rest @ ..]) => list(t.get_mut(*k)?.get_mut(), rest),
            _ => None,
        }
    }
    let root = || DeValue::Table(document.get_ref().clone());
    let mut original = root();
    let elements = list(&mut original, &keys)?;
    if elements.len() < 2 {
        return None;
    }
    let message = error.message().trim_end();
    elements.iter().find_map(|element| {
        let mut copy = root();
        list(&mut copy, &keys)?.iter_mut().for_each(|e| *e = element.clone());
        let DeValue::Table(t) = copy else { return None };
        let again = Case::deserialize(toml::de::Deserializer::from(toml::Spanned::new(document.span(), t)));
        again.err().filter(|e| e.message().trim_end() == message).map(|_| element.span())
    })
}

/// The parser's "duplicate key" at byte `start` of `source`, with what is
/// duplicated: a table header given twice, or a key given twice in a table
/// (named with the table's header).
fn duplicate(source: &str, start: usize) -> String {
    let line_start = source.get(..start).and_then(|b| b.rfind('\n')).map_or(0, |i| i + 1);
    let line = source.get(line_start..).and_then(|l| l.lines().next()).unwrap_or("").trim();
    if header(line) {
        let name = line.split('#').next().unwrap_or(line).trim();
        let hint = if name.starts_with("[[") { "" } else { "; a list of tables is written `[[name]]`" };
        return format!("duplicate table: `{name}` is given a second time here (give each table once{hint})");
    }
    // The key the parser points at, where its span starts one (an inline
    // table's key), else the line's.
    let at = source.get(start..).unwrap_or("");
    let key = at
        .split(['=', '\n'])
        .next()
        .map(str::trim)
        .filter(|k| !k.is_empty() && !k.contains([',', '{', '[']))
        .unwrap_or_else(|| line.split('=').next().unwrap_or("").trim());
    let table = source
        .get(..line_start)
        .unwrap_or("")
        .lines()
        .rev()
        .map(str::trim)
        .find(|l| header(l))
        .map(|h| h.split('#').next().unwrap_or(h).trim());
    match table {
        Some(t) => format!("duplicate key: `{key}` is given a second time in `{t}`"),
        None => format!("duplicate key: `{key}` is given a second time"),
    }
}

/// The key of the value that starts at byte `start` of `source`: the bare
/// or quoted (basic `"…"` or literal `'…'`) key before the `=` that
/// precedes it on its line (in an inline table, the innermost one). `None`
/// where the value is not written as `key = value` on that line (an
/// array's later element, say).
fn value_key(source: &str, start: usize) -> Option<&str> {
    let before = source.get(..start)?;
    let line = &before[before.rfind('\n').map_or(0, |i| i + 1)..];
    let head = line.trim_end().strip_suffix('=')?.trim_end();
    let key = head.rsplit(['{', ',']).next()?.trim();
    let bare = |k: &str| k.chars().all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'));
    let quoted = key.len() >= 2 && ['"', '\''].iter().any(|&q| key.starts_with(q) && key.ends_with(q));
    (!key.is_empty() && (bare(key) || quoted)).then_some(key)
}

/// An error at byte range `span` of `source` (a line and column of the
/// file) or of a `--set` argument of `overrides` (named before the
/// message, with no line).
fn located(path: &Path, source: &str, overrides: &Overrides, span: Range<usize>, message: String) -> CaseError {
    match overrides.blame(&span, &message) {
        Some(arg) => CaseError { path: path.to_path_buf(), at: None, message: format!("--set {arg}: {message}") },
        None => CaseError {
            path: path.to_path_buf(),
            at: Some(line_col(source, span.start)),
            message: overrides.noted(&span, message),
        },
    }
}

/// Reads and parses `path`, applies the `--set` arguments `sets` (each
/// `key.path=value`, see [`overrides`]) to the parsed document, and
/// deserialises it, checking the format version.
///
/// # Errors
/// A [`CaseError`] for an unreadable file, bad TOML, a malformed `--set`
/// argument, an unknown key, a missing key, a value of the wrong type, or
/// an unsupported version; one that comes from a `--set` argument names
/// it.
pub fn load(path: &Path, sets: &[String]) -> Result<LoadedCase, CaseError> {
    let error = |message: String| CaseError { path: path.to_path_buf(), at: None, message };
    let source = std::fs::read_to_string(path).map_err(|e| error(format!("cannot read the case file: {e}")))?;
    let mut overrides = Overrides::parse(sets, source.len()).map_err(error)?;
    let (case, applied) = {
        let document = toml::de::DeTable::parse(&source).map_err(|e| {
            let at = e.span().map(|s| line_col(&source, key_offset(&source, s, e.message())));
            let message = e.message().trim_end();
            let message = match e.span() {
                Some(s) if message == "duplicate key" => duplicate(&source, s.start),
                _ => message.to_string(),
            };
            CaseError { path: path.to_path_buf(), at, message }
        })?;
        let (document, applied) = overrides.apply(document).map_err(error)?;
        let case = Case::deserialize(toml::de::Deserializer::from(document.clone()));
        let element = case.as_ref().err().and_then(|e| element_at_fault(&source, &document, e));
        (case.map_err(|e| (e, element)), applied)
    };
    overrides.record(applied);
    let case = case.map_err(|(e, element)| {
        let message = e.message().trim_end().to_string();
        let Some(s) = element.or_else(|| e.span()) else { return error(message) };
        if overrides.blame(&s, &message).is_some() {
            return located(path, &source, &overrides, s, message);
        }
        if !overrides.is_empty() {
            // Serde reports some errors at a table, naming no key: they
            // are the overrides' if the file alone does not give them.
            let alone = toml::from_str::<Case>(&source);
            let same = alone.as_ref().err().is_some_and(|a| a.message().trim_end() == message && a.span() == e.span());
            if !same {
                let near = overrides.in_table(&s);
                let args =
                    if near.is_empty() { overrides.args() } else { near.into_iter().map(String::from).collect() };
                return error(format!("--set {}: {message}", args.join(" --set ")));
            }
        }
        let at = Some(line_col(&source, key_offset(&source, s.clone(), &message)));
        // Serde reports a bad value at the value alone: name its key; and a
        // missing key at its table's header: name the table. A `[[name]]`
        // header whose key takes one table (`[[solver]]`), whatever serde
        // says of it, is the list's slip, not its first element's.
        let whole = source.get(s.start..).and_then(|l| l.lines().next()).is_some_and(|l| {
            let l = l.trim();
            let path = l.trim_start_matches('[').split(']').next().unwrap_or("");
            l.starts_with("[[") && !format::TABLE_LISTS.contains(&path.rsplit('.').next().unwrap_or("").trim())
        });
        let message = match (value_key(&source, s.start), table_path(&source, s.clone(), whole)) {
            (Some(key), _) if !message.contains(&format!("`{key}`")) => format!("`{key}`: {message}"),
            (None, Some(table)) if whole => {
                format!("{table}: {message} (`[[{table}]]` starts a list of tables; one table is written `[{table}]`)")
            }
            (None, Some(table)) => format!("{table}: {message}"),
            _ => message,
        };
        CaseError { path: path.to_path_buf(), at, message: overrides.noted(&s, message) }
    })?;
    let loaded = LoadedCase { case, path: path.to_path_buf(), source, overrides };
    if *loaded.case.version.get_ref() != CASE_VERSION {
        return Err(loaded.error_at(
            loaded.case.version.span(),
            format!("`version` is {}, but this femdem reads case format {CASE_VERSION}", loaded.case.version.get_ref()),
        ));
    }
    Ok(loaded)
}

#[cfg(test)]
mod tests {
    use super::line_col;

    #[test]
    fn a_value_is_named_by_the_key_before_it() {
        let t = "[[platens]]\nvelocity = [1, 2]\nnodes = { group = 3, box = 4 }\nlist = [\n  5,\n]\n";
        let at = |v: &str| super::value_key(t, t.find(v).unwrap());
        assert_eq!(at("[1, 2]"), Some("velocity"));
        assert_eq!(at("3,"), Some("group"));
        assert_eq!(at("4 }"), Some("box"));
        assert_eq!(at("5,"), None);
        assert_eq!(at("[[platens]]"), None);
        let q = "\"young\" = \"a\"\n'poisson' = \"b\"\n";
        let at = |v: &str| super::value_key(q, q.find(v).unwrap());
        assert_eq!(at("\"a\""), Some("\"young\""));
        assert_eq!(at("\"b\""), Some("'poisson'"));
    }

    #[test]
    fn a_duplicate_names_the_key_and_its_table_or_the_table() {
        let t = "[solver]\nsafety = 0.5\n\n[[materials]] # rock\ndensity = 1.0\ndensity = 2.0\n[solver]\n";
        let key = super::duplicate(t, t.rfind("density").unwrap());
        assert_eq!(key, "duplicate key: `density` is given a second time in `[[materials]]`");
        let table = super::duplicate(t, t.rfind("[solver]").unwrap() + 1);
        assert!(table.starts_with("duplicate table: `[solver]` is given a second time here"), "{table}");
        assert!(table.ends_with("a list of tables is written `[[name]]`)"), "{table}");
        // A multi-line array's rows are not headers.
        let t = "[[mesh.parts]]\npolygon = [\n  [0.0, 0.0],\n  [1.0, 0.0],\n]\nthickness = 1\nthickness = 2\n";
        let key = super::duplicate(t, t.rfind("thickness").unwrap());
        assert_eq!(key, "duplicate key: `thickness` is given a second time in `[[mesh.parts]]`");
    }

    #[test]
    fn a_table_is_named_by_its_path_and_index() {
        let t = "[solver] # s\n[[loads]]\na = 1\n[[mesh.parts]]\n[[mesh.parts.zones]]\n[[mesh.parts]]\n\
                 [[mesh.parts.zones]]\n[[mesh.parts.zones]]\n[[ loads ]]\nb = [\n  [1, 2],\n]\n[loads.nodes]\n";
        let start = |needle: &str, n: usize| t.match_indices(needle).nth(n).unwrap().0;
        let at =
            |needle: &str, n: usize| super::table_path(t, start(needle, n)..start(needle, n) + needle.len(), false);
        assert_eq!(at("[solver]", 0).as_deref(), Some("solver"));
        assert_eq!(at("[[loads]]", 0).as_deref(), Some("loads[0]"));
        assert_eq!(at("[[ loads ]]", 0).as_deref(), Some("loads[1]"));
        assert_eq!(at("[[mesh.parts]]", 1).as_deref(), Some("mesh.parts[1]"));
        assert_eq!(at("[[mesh.parts.zones]]", 0).as_deref(), Some("mesh.parts[0].zones[0]"));
        assert_eq!(at("[[mesh.parts.zones]]", 2).as_deref(), Some("mesh.parts[1].zones[1]"));
        assert_eq!(at("[loads.nodes]", 0).as_deref(), Some("loads[1].nodes"));
        assert_eq!(at("a = 1", 0), None);
        assert_eq!(at("[1, 2]", 0), None);
        // The list itself, for a list given where one table is wanted.
        let first = start("[[loads]]", 0);
        assert_eq!(super::table_path(t, first..first + 9, true).as_deref(), Some("loads"));
        // The root's empty span, and a key's span inside a header (a table
        // made implicitly, `mesh` of `[[mesh.parts]]`), name no table.
        assert_eq!(super::table_path(t, 0..0, false), None);
        let mesh = start("[[mesh.parts]]", 0) + 2;
        assert_eq!(super::table_path(t, mesh..mesh + 4, false), None);
    }

    #[test]
    fn line_col_counts_from_one() {
        let t = "a = 1\nbb = 2\n";
        assert_eq!(line_col(t, 0), (1, 1));
        assert_eq!(line_col(t, 6), (2, 1));
        assert_eq!(line_col(t, 8), (2, 3));
    }
}
