//! Fuzzing the MSH 4.1 reader: no input makes it panic. Every input is
//! either read into a mesh or refused with [`MeshError::Msh`] naming a line
//! of the file; a mesh it reads then goes through the same steps as in a
//! run (`check`, and `insert_joints` when the check passes), which must not
//! panic either.
//!
//! Inputs: arbitrary bytes (with and without a valid `$MeshFormat` head, so
//! the section parsers are reached), and structured mutations of the Gmsh
//! fixture `tests/data/gmsh_two_volumes.msh` (116 nodes, 2 volumes, 860
//! lines): lines deleted, duplicated or swapped, and tokens replaced by
//! huge, negative, non-finite or garbage ones. 4096 cases per property
//! (about 0.5 s each in release mode); a one-off run of 50,000 cases per
//! property (200,000 inputs, 19 s) found no panic.

use femdem_mesh::MeshError;
use femdem_mesh::check::check;
use femdem_mesh::insert_joints;
use femdem_mesh::msh::read_msh;
use proptest::prelude::*;

const FIXTURE: &str = include_str!("../data/gmsh_two_volumes.msh");

/// Tokens that stress the parsers: out of range for every integer type the
/// reader uses (`usize`, `u32`, `u64`, `i32`), negative, non-finite,
/// malformed, and a section marker inside a record.
const NASTY: [&str; 24] = [
    "0",
    "-1",
    "-0",
    "1e308",
    "-1e308",
    "1e-320",
    "NaN",
    "nan",
    "inf",
    "-inf",
    "2147483647",
    "2147483648",
    "-2147483649",
    "4294967295",
    "4294967296",
    "18446744073709551615",
    "18446744073709551616",
    "99999999999999999999999999",
    "1.5",
    "0x10",
    "abc",
    "\"",
    "$Nodes",
    "",
];

/// Reads `bytes` and, if that works, checks the mesh and inserts joints.
/// Panics (the failure proptest reports) only through the library; returns
/// the error line, if any, for the caller to check it lies in the file.
fn read_and_use(bytes: &[u8]) -> Option<usize> {
    match read_msh(bytes) {
        Ok(mesh) => {
            if check(&mesh).is_ok() {
                let jointed = insert_joints(&mesh).expect("a mesh that passes the check takes joints");
                assert_eq!(jointed.mesh.num_tets(), mesh.num_tets());
            }
            None
        }
        Err(MeshError::Msh { line, .. }) => Some(line),
        Err(other) => panic!("the reader gave a non-MSH error: {other:?}"),
    }
}

/// Asserts the error line, if any, is a line of `bytes` (the reader numbers
/// lines from 1; a file that ends without a final newline has as many lines
/// as it has `\n` plus one).
fn assert_line_in_file(bytes: &[u8], line: Option<usize>) -> Result<(), TestCaseError> {
    if let Some(line) = line {
        let lines = bytes.split(|&b| b == b'\n').count();
        prop_assert!((1..=lines.max(1)).contains(&line), "line {} of a {}-line file", line, lines);
    }
    Ok(())
}

/// One structural edit of a list of lines.
#[derive(Clone, Debug)]
enum LineEdit {
    Delete(prop::sample::Index),
    Duplicate(prop::sample::Index),
    Swap(prop::sample::Index, prop::sample::Index),
    /// Replace token `token` of line `line` by `NASTY[with]`.
    Token {
        line: prop::sample::Index,
        token: prop::sample::Index,
        with: usize,
    },
    /// Replace a whole line by a nasty token (a count, a tag, garbage).
    Line {
        line: prop::sample::Index,
        with: usize,
    },
}

fn line_edit() -> impl Strategy<Value = LineEdit> {
    let i = any::<prop::sample::Index>;
    prop_oneof![
        1 => i().prop_map(LineEdit::Delete),
        1 => i().prop_map(LineEdit::Duplicate),
        1 => (i(), i()).prop_map(|(a, b)| LineEdit::Swap(a, b)),
        3 => (i(), i(), 0..NASTY.len()).prop_map(|(line, token, with)| LineEdit::Token { line, token, with }),
        1 => (i(), 0..NASTY.len()).prop_map(|(line, with)| LineEdit::Line { line, with }),
    ]
}

fn apply(lines: &mut Vec<String>, edit: &LineEdit) {
    if lines.is_empty() {
        return;
    }
    match edit {
        LineEdit::Delete(i) => {
            lines.remove(i.index(lines.len()));
        }
        LineEdit::Duplicate(i) => {
            let k = i.index(lines.len());
            let l = lines[k].clone();
            lines.insert(k, l);
        }
        LineEdit::Swap(a, b) => {
            let (a, b) = (a.index(lines.len()), b.index(lines.len()));
            lines.swap(a, b);
        }
        LineEdit::Token { line, token, with } => {
            let k = line.index(lines.len());
            let mut tokens: Vec<&str> = lines[k].split_ascii_whitespace().collect();
            if tokens.is_empty() {
                lines[k] = NASTY[*with].to_owned();
            } else {
                let t = token.index(tokens.len());
                tokens[t] = NASTY[*with];
                lines[k] = tokens.join(" ");
            }
        }
        LineEdit::Line { line, with } => {
            let k = line.index(lines.len());
            lines[k] = NASTY[*with].to_owned();
        }
    }
}

fn fixture_lines() -> Vec<String> {
    FIXTURE.lines().map(str::to_owned).collect()
}

#[test]
fn the_unmutated_fixture_reads_and_takes_joints() {
    // The fuzzing below starts from a file that works end to end.
    assert_eq!(read_and_use(FIXTURE.as_bytes()), None);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4096, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..600)) {
        let line = read_and_use(&bytes);
        assert_line_in_file(&bytes, line)?;
    }

    /// Bytes after a valid head reach the section parsers; the tail is
    /// drawn from the characters an MSH file is made of, so that it often
    /// forms headers and numbers.
    #[test]
    fn arbitrary_sections_never_panic(tail in "(\\$(Nodes|Elements|Entities|PhysicalNames|End[A-Za-z]*)\n|[-0-9 .e\"\n]{1,12}){0,40}") {
        let text = format!("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n{tail}");
        let line = read_and_use(text.as_bytes());
        assert_line_in_file(text.as_bytes(), line)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4096, ..ProptestConfig::default() })]

    #[test]
    fn mutated_fixture_lines_never_panic(edits in prop::collection::vec(line_edit(), 1..5)) {
        let mut lines = fixture_lines();
        for e in &edits {
            apply(&mut lines, e);
        }
        let text = lines.join("\n") + "\n";
        let line = read_and_use(text.as_bytes());
        assert_line_in_file(text.as_bytes(), line)?;
    }

    /// Every number of one section replaced at random positions: the
    /// `$Nodes` header and node blocks (counts, tags, coordinates) and the
    /// `$Elements` records are where the counts that size allocations are.
    #[test]
    fn mutated_fixture_numbers_never_panic(
        section in prop::sample::select(vec!["$Entities", "$Nodes", "$Elements", "$PhysicalNames"]),
        at in prop::collection::vec((0usize..40, any::<prop::sample::Index>(), 0..NASTY.len()), 1..4),
    ) {
        let mut lines = fixture_lines();
        let start = lines.iter().position(|l| l == section).expect("the fixture has the section") + 1;
        for (offset, token, with) in at {
            let k = (start + offset).min(lines.len() - 1);
            let mut tokens: Vec<&str> = lines[k].split_ascii_whitespace().collect();
            if !tokens.is_empty() {
                let t = token.index(tokens.len());
                tokens[t] = NASTY[with];
                lines[k] = tokens.join(" ");
            }
        }
        let text = lines.join("\n") + "\n";
        let line = read_and_use(text.as_bytes());
        assert_line_in_file(text.as_bytes(), line)?;
    }
}
