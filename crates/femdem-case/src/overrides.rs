//! `--set key.path=value`: values of a case overridden from the command
//! line, e.g. `--set solver.end_time=1e-3 --set materials.0.tensile_strength=2e6`.
//!
//! The overrides are set in the parsed TOML document before it is
//! deserialised, so they meet every check a value in the file meets: an
//! unknown key is refused as one in the file is (`deny_unknown_fields`), a
//! value of the wrong type by serde, a value out of range by the setup
//! code. The key path is the TOML keys from the root joined by dots, with
//! the index of an array's entry (from 0) as a key: `materials.0.young`,
//! `solver.gravity.2`; it may be given once, and not inside another one
//! (`solver` and `solver.safety`: one would be lost or not depending on
//! their order). The value is a TOML value: a number, a quoted
//! string, a boolean, an array or an inline table. A key the file does not
//! have is added, with the tables on its path (`--set contact.penalty=1e9`
//! to a case without `[contact]`); an array entry must exist.
//!
//! Errors name the `--set` argument instead of a line of the file. To
//! tell them apart, each argument is given a place past the end of the
//! case text, as if the arguments were written after it, and its keys and
//! value carry spans there: an error serde or the setup code reports at
//! such a span is the argument's ([`Overrides::blame`]). The setup code
//! reports most errors at the span of a table (a material, a part, a
//! load), naming the key in its message; such an error is the argument's
//! too when the argument's key path goes through that table and the
//! message names a key of the path from there (`platens[1]: `drives`
//! selects no node` for `--set platens.1.drives.box.min.0=1`). An error of
//! the deserialiser at such a table (serde reports an internally tagged
//! table's errors there: the parts, the loads) is the arguments' when the
//! file alone does not give it. Any other error at a table an argument's
//! path goes through keeps its line and names the argument in a note,
//! `(this table also has --set ARG)`: the override may be its cause (a
//! box's corner that makes too many tets for its `element_size`).

use std::borrow::Cow;
use std::ops::Range;

use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// One `--set` argument.
#[derive(Clone, Debug)]
struct Override {
    /// As given on the command line.
    arg: String,
    /// The key path, split at its dots, with each key's span.
    keys: Vec<(String, Range<usize>)>,
    /// The value's text, trimmed, and its span.
    value: (String, Range<usize>),
    /// Where the argument is placed past the case text.
    span: Range<usize>,
    /// The tables the key path goes through below the root, each with its
    /// key there; set by [`Overrides::apply`].
    tables: Vec<(Range<usize>, String)>,
}

/// The `--set` arguments of a command, placed one after the other past the
/// end of the case text.
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    list: Vec<Override>,
}

impl Overrides {
    /// Parses `args`, each `key.path=value`, for a case text of
    /// `source_len` bytes.
    ///
    /// # Errors
    /// A message naming the argument: no `=`, an empty or malformed key,
    /// or a key path given twice.
    pub fn parse(args: &[String], source_len: usize) -> Result<Overrides, String> {
        let mut list: Vec<Override> = Vec::with_capacity(args.len());
        // One byte past the text, then each argument and a separator.
        let mut base = source_len + 1;
        for arg in args {
            let Some((key, value)) = arg.split_once('=') else {
                return Err(format!("--set {arg}: expected KEY=VALUE, e.g. --set solver.end_time=1e-3"));
            };
            let mut keys = Vec::new();
            let mut at = base;
            for k in key.split('.') {
                let name = k.trim();
                let bare =
                    !name.is_empty() && name.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-');
                if !bare {
                    return Err(format!(
                        "--set {arg}: `{key}` is not a key path: keys of letters, digits, `_` and `-` joined by dots, \
                         e.g. solver.end_time or materials.0.young"
                    ));
                }
                let start = at + (k.len() - k.trim_start().len());
                keys.push((name.to_owned(), start..start + name.len()));
                at += k.len() + 1;
            }
            let path: Vec<&str> = keys.iter().map(|k| k.0.as_str()).collect();
            // One path inside another would be set, or lost, depending on
            // their order.
            let within = |o: &Override| o.keys.iter().zip(&path).all(|(a, b)| a.0 == *b);
            if let Some(earlier) = list.iter().find(|o| within(o)) {
                let what = if earlier.keys.len() == path.len() { "is already set by" } else { "overlaps" };
                return Err(format!("--set {arg}: `{}` {what} --set {}", path.join("."), earlier.arg));
            }
            let value_at = base + key.len() + 1 + (value.len() - value.trim_start().len());
            let text = value.trim().to_owned();
            let value_span = value_at..value_at + text.len();
            list.push(Override {
                arg: arg.clone(),
                keys,
                value: (text, value_span),
                span: base..base + arg.len(),
                tables: Vec::new(),
            });
            base += arg.len() + 1;
        }
        Ok(Overrides { list })
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// The arguments as given.
    pub fn args(&self) -> Vec<String> {
        self.list.iter().map(|o| o.arg.clone()).collect()
    }

    /// The arguments in a form that does not depend on their order or on
    /// how a value is spelled: `key.path=value`, the value as TOML writes
    /// it (`1e-3` and `0.001` alike), sorted by key path. What a
    /// checkpoint records.
    pub fn canonical(&self) -> Vec<String> {
        let mut out: Vec<String> = self
            .list
            .iter()
            .map(|o| {
                let path: Vec<&str> = o.keys.iter().map(|k| k.0.as_str()).collect();
                let value = o.value.0.parse::<toml::Value>().map_or_else(|_| o.value.0.clone(), |v| v.to_string());
                format!("{}={value}", path.join("."))
            })
            .collect();
        out.sort();
        out
    }

    /// Sets every override in `root`, the parsed case document.
    ///
    /// # Errors
    /// The argument and the message: a value that is not a TOML value, a
    /// path through a value that is not a table or an array, an array
    /// entry that does not exist.
    pub fn apply<'i>(&'i self, root: Spanned<DeTable<'i>>) -> Result<(Spanned<DeTable<'i>>, Applied), String> {
        let span = root.span();
        let mut node = Spanned::new(span.clone(), DeValue::Table(root.into_inner()));
        let mut tables = Vec::with_capacity(self.list.len());
        for o in &self.list {
            let (text, at) = &o.value;
            let mut value = DeValue::parse(text).map_err(|e| {
                format!(
                    "--set {}: `{text}` is not a TOML value ({}); numbers, true or false, quoted strings \
                     (--set 'output.dir=\"out/a\"'), arrays ([0.0, -9.81, 0.0])",
                    o.arg,
                    e.message().trim_end()
                )
            })?;
            shift(&mut value, at.start);
            let mut path = Vec::new();
            set_in(&mut node, &o.keys, 0, value, &o.span, &mut path).map_err(|m| format!("--set {}: {m}", o.arg))?;
            // The root's span is the whole file: an error there is no
            // table's.
            path.retain(|(t, _)| *t != span);
            tables.push(path);
        }
        match node.into_inner() {
            DeValue::Table(t) => Ok((Spanned::new(span, t), Applied(tables))),
            _ => unreachable!("the root stays a table"),
        }
    }

    /// Records what [`Overrides::apply`] found, once the document that
    /// borrows them is gone.
    pub fn record(&mut self, applied: Applied) {
        for (o, t) in self.list.iter_mut().zip(applied.0) {
            o.tables = t;
        }
    }

    /// The argument an error at `span` saying `message` belongs to, if
    /// any: the argument whose place holds the span, or one whose key path
    /// goes through the table at `span` and has a key from there that the
    /// message names. For a message that lists the keys a table expects
    /// (`unknown field `x`, expected one of …`), only the part before the
    /// list counts.
    pub fn blame(&self, span: &Range<usize>, message: &str) -> Option<&str> {
        if let Some(o) = self.list.iter().find(|o| o.span.contains(&span.start)) {
            return Some(&o.arg);
        }
        let named = message.split(", expected").next().unwrap_or(message);
        let names_a_key_from = |o: &Override| {
            let from = o.tables.iter().position(|(t, _)| t == span)?;
            o.tables[from..].iter().any(|(_, key)| names_word(named, key)).then_some(())
        };
        self.list.iter().find(|o| names_a_key_from(o).is_some()).map(|o| o.arg.as_str())
    }
}

impl Overrides {
    /// The arguments whose key path goes through the table at `span`.
    pub fn in_table(&self, span: &Range<usize>) -> Vec<&str> {
        self.list.iter().filter(|o| o.tables.iter().any(|(t, _)| t == span)).map(|o| o.arg.as_str()).collect()
    }

    /// `message`, with a note naming the arguments whose key path goes
    /// through the table at `span`, if any: for an error of the file's
    /// that one of them may have caused.
    pub fn noted(&self, span: &Range<usize>, message: String) -> String {
        let near = self.in_table(span);
        if near.is_empty() {
            message
        } else {
            format!("{message} (this table also has --set {})", near.join(" --set "))
        }
    }
}

/// For each override, the tables its key path goes through and the key in
/// each, found by [`Overrides::apply`].
pub struct Applied(Vec<Vec<(Range<usize>, String)>>);

/// Whether `text` has `word` with no letter, digit or `_` on either side.
fn names_word(text: &str, word: &str) -> bool {
    let is_word = |c: char| c.is_ascii_alphanumeric() || c == '_';
    text.match_indices(word).any(|(i, _)| {
        let before = text[..i].chars().next_back();
        let after = text[i + word.len()..].chars().next();
        !before.is_some_and(is_word) && !after.is_some_and(is_word)
    })
}

/// Moves every span of `v` (its own, its entries', its keys') by `by`
/// bytes: from the value's text to its place past the case text.
fn shift(v: &mut Spanned<DeValue<'_>>, by: usize) {
    let span = v.span();
    let mut inner = std::mem::replace(v.get_mut(), DeValue::Boolean(false));
    match &mut inner {
        DeValue::Array(a) => a.iter_mut().for_each(|e| shift(e, by)),
        DeValue::Table(t) => {
            let entries: Vec<_> = std::mem::take(t).into_iter().collect();
            for (k, mut e) in entries {
                shift(&mut e, by);
                let ks = k.span();
                t.insert(Spanned::new(ks.start + by..ks.end + by, k.into_inner()), e);
            }
        }
        _ => {}
    }
    *v = Spanned::new(span.start + by..span.end + by, inner);
}

/// What a TOML value is, for messages.
fn kind(v: &DeValue<'_>) -> &'static str {
    match v {
        DeValue::String(_) => "a string",
        DeValue::Integer(_) | DeValue::Float(_) => "a number",
        DeValue::Boolean(_) => "a boolean",
        DeValue::Datetime(_) => "a date",
        DeValue::Array(_) => "an array",
        DeValue::Table(_) => "a table",
    }
}

/// Sets `keys[depth..]` below `node` to `value`, adding missing tables
/// with the span `fresh` (the argument's place). Pushes on `tables` each
/// table it goes through, with its key there.
fn set_in<'i>(
    node: &mut Spanned<DeValue<'i>>,
    keys: &'i [(String, Range<usize>)],
    depth: usize,
    value: Spanned<DeValue<'i>>,
    fresh: &Range<usize>,
    tables: &mut Vec<(Range<usize>, String)>,
) -> Result<(), String> {
    let span = node.span();
    let here = || keys[..depth].iter().map(|k| k.0.as_str()).collect::<Vec<_>>().join(".");
    let (name, key_span) = &keys[depth];
    let last = depth + 1 == keys.len();
    match node.get_mut() {
        DeValue::Table(t) => {
            tables.push((span, name.clone()));
            if last {
                t.insert(Spanned::new(key_span.clone(), Cow::Borrowed(name.as_str())), value);
                return Ok(());
            }
            if !t.contains_key(name.as_str()) {
                let next = &keys[depth + 1].0;
                if next.parse::<usize>().is_ok() {
                    let path = keys[..=depth].iter().map(|k| k.0.as_str()).collect::<Vec<_>>().join(".");
                    return Err(format!(
                        "`{path}` is not in the case, so it has no entry {next}: set the whole array \
                         (e.g. --set {path}=[...])"
                    ));
                }
                let key = Spanned::new(key_span.clone(), Cow::Borrowed(name.as_str()));
                t.insert(key, Spanned::new(fresh.clone(), DeValue::Table(DeTable::new())));
            }
            let child = t.get_mut(name.as_str()).expect("inserted above");
            set_in(child, keys, depth + 1, value, fresh, tables)
        }
        DeValue::Array(a) => {
            let len = a.len();
            let Ok(index) = name.parse::<usize>() else {
                let indices = match len {
                    0 => "it has none".to_owned(),
                    1 => "its one entry is 0".to_owned(),
                    n => format!("0 to {}", n - 1),
                };
                return Err(format!("`{}` is an array: `{name}` is not the index of an entry ({indices})", here()));
            };
            let Some(child) = a.get_mut(index) else {
                let entries = if len == 1 { "entry" } else { "entries" };
                return Err(format!(
                    "`{}` has {len} {entries}: there is no entry {index} (entries count from 0; --set cannot add one)",
                    here()
                ));
            };
            if last {
                *child = value;
                return Ok(());
            }
            set_in(child, keys, depth + 1, value, fresh, tables)
        }
        other => Err(format!("`{}` is {}, not a table: it has no key `{name}`", here(), kind(other))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(args: &[&str]) -> Result<Overrides, String> {
        Overrides::parse(&args.iter().map(|s| s.to_string()).collect::<Vec<_>>(), 100)
    }

    #[test]
    fn arguments_are_placed_past_the_case_text() {
        let o = parse(&["a.b=1", " c = [1, 2] "]).unwrap();
        assert_eq!(o.list[0].span, 101..106);
        assert_eq!(o.list[0].keys, [("a".to_string(), 101..102), ("b".to_string(), 103..104)]);
        assert_eq!(o.list[0].value, ("1".to_string(), 105..106));
        assert_eq!(o.list[1].span, 107..119);
        assert_eq!(o.list[1].keys, [("c".to_string(), 108..109)]);
        assert_eq!(o.list[1].value, ("[1, 2]".to_string(), 112..118));
    }

    #[test]
    fn malformed_arguments_are_refused_by_name() {
        for (arg, words) in [
            ("solver.end_time", "expected KEY=VALUE"),
            ("=1", "is not a key path"),
            ("solver..end_time=1", "is not a key path"),
            ("solver.\"end time\"=1", "is not a key path"),
        ] {
            let e = parse(&[arg]).unwrap_err();
            assert!(e.starts_with(&format!("--set {arg}: ")) && e.contains(words), "{e}");
        }
        let e = parse(&["solver.end_time=1", "solver . end_time=2"]).unwrap_err();
        assert!(e.contains("already set by --set solver.end_time=1"), "{e}");
        for (a, b) in
            [("solver={ end_time = 1.0 }", "solver.end_time=2"), ("solver.gravity.2=1", "solver.gravity=[0, 0, 1]")]
        {
            let e = parse(&[a, b]).unwrap_err();
            assert!(e.starts_with(&format!("--set {b}: ")) && e.contains(&format!("overlaps --set {a}")), "{e}");
        }
    }

    #[test]
    fn canonical_forms_ignore_order_and_spelling() {
        let a = parse(&["solver.end_time=1e-3", "output.fields=[\"velocity\"]"]).unwrap();
        let b = parse(&["output.fields = [ 'velocity' ]", "solver.end_time=0.001"]).unwrap();
        assert_eq!(a.canonical(), b.canonical());
        assert_eq!(a.canonical(), ["output.fields=[\"velocity\"]", "solver.end_time=0.001"]);
    }

    #[test]
    fn a_word_is_named_only_whole() {
        assert!(names_word("`interval` must be > 0", "interval"));
        assert!(!names_word("`history_interval` must be > 0", "interval"));
        assert!(names_word("solver: end_time must be > 0 s", "end_time"));
        assert!(!names_word("end_times", "end_time"));
    }
}
