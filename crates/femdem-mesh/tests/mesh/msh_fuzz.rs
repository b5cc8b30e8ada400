//! Fuzzing the MSH 4.1 reader: no input makes it panic. Every input is
//! either read into a mesh or refused with [`MeshError::Msh`] naming a line
//! of the file or [`MeshError::MshBinary`] naming a byte of it; a mesh it
//! reads then goes through the same steps as in a run (`check`, and
//! `insert_joints` when the check passes), which must not panic either.
//!
//! Inputs: arbitrary bytes (with and without a valid `$MeshFormat` head,
//! ASCII and binary, so the section parsers are reached), structured
//! mutations of the Gmsh fixture `tests/data/gmsh_two_volumes.msh` (116
//! nodes, 2 volumes, 860 lines): lines deleted, duplicated or swapped, and
//! tokens replaced by huge, negative, non-finite or garbage ones; and
//! mutations of its binary twin `gmsh_two_volumes_binary.msh` in both byte
//! orders: bytes, `int`s and 8-byte words overwritten (at random or on the
//! counts and block headers of a section) by huge, negative, non-finite or
//! zero values, ranges deleted or repeated, the file cut. 4096 cases per
//! property (about 0.5 s each in release mode); a one-off run of 50,000
//! cases per property (200,000 inputs, 19 s) found no panic in the ASCII
//! reader; for the binary one, 50,000 cases of each of its three
//! properties found none either.

use femdem_mesh::MeshError;
use femdem_mesh::check::check;
use femdem_mesh::insert_joints;
use femdem_mesh::msh::read_msh;
use proptest::prelude::*;

use crate::msh_binary::{BINARY, binary_sections, reencode};

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

/// Where the error of a refused input points.
#[derive(Debug)]
enum Refused {
    Line(usize),
    Byte(usize),
}

/// Reads `bytes` and, if that works, checks the mesh and inserts joints.
/// Panics (the failure proptest reports) only through the library; returns
/// where the error points, if any, for the caller to check it lies in the
/// file.
fn read_and_use(bytes: &[u8]) -> Option<Refused> {
    match read_msh(bytes) {
        Ok(mesh) => {
            if check(&mesh).is_ok() {
                let jointed = insert_joints(&mesh).expect("a mesh that passes the check takes joints");
                assert_eq!(jointed.mesh.num_tets(), mesh.num_tets());
            }
            None
        }
        Err(MeshError::Msh { line, .. }) => Some(Refused::Line(line)),
        Err(MeshError::MshBinary { offset, .. }) => Some(Refused::Byte(offset)),
        Err(other) => panic!("the reader gave a non-MSH error: {other:?}"),
    }
}

/// Asserts the error's place, if any, is in `bytes`: a line (the reader
/// numbers lines from 1; a file that ends without a final newline has as
/// many lines as it has `\n` plus one) or a byte offset (at most the
/// length: the end of a truncated file).
fn assert_line_in_file(bytes: &[u8], refused: Option<Refused>) -> Result<(), TestCaseError> {
    match refused {
        None => {}
        Some(Refused::Line(line)) => {
            let lines = bytes.split(|&b| b == b'\n').count();
            prop_assert!((1..=lines.max(1)).contains(&line), "line {} of a {}-line file", line, lines);
        }
        Some(Refused::Byte(offset)) => {
            prop_assert!(offset <= bytes.len(), "byte {} of a {}-byte file", offset, bytes.len());
        }
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
fn the_unmutated_fixtures_read_and_take_joints() {
    // The fuzzing below starts from files that work end to end.
    assert!(read_and_use(FIXTURE.as_bytes()).is_none());
    assert!(read_and_use(BINARY).is_none());
    assert!(read_and_use(&reencode(BINARY, true, 8)).is_none());
}

/// 8-byte values that stress a binary reader: as a `size_t`, zero, one,
/// past `i32`, `u32` and `usize`-as-allocation ranges; as a `double`, NaN,
/// ±∞ and the largest finite numbers.
const NASTY_WORDS: [u64; 12] = [
    0,
    1,
    (1 << 31) - 1,
    1 << 31,
    u32::MAX as u64,
    1 << 32,
    1 << 62,
    u64::MAX,
    0x7ff8_0000_0000_0000, // NaN
    0x7ff0_0000_0000_0000, // +inf
    0xfff0_0000_0000_0000, // -inf
    0x7fef_ffff_ffff_ffff, // f64::MAX
];

/// 4-byte values that stress an `int` field: tags, dimensions, element
/// types, flags.
const NASTY_INTS: [i32; 8] = [0, -1, 1, 2, 4, 99, i32::MAX, i32::MIN];

/// One edit of a binary file.
#[derive(Clone, Debug)]
enum ByteEdit {
    Byte(prop::sample::Index, u8),
    Int(prop::sample::Index, usize),
    Word(prop::sample::Index, usize),
    Delete(prop::sample::Index, usize),
    Repeat(prop::sample::Index, usize),
    Cut(prop::sample::Index),
}

fn byte_edit() -> impl Strategy<Value = ByteEdit> {
    let i = any::<prop::sample::Index>;
    prop_oneof![
        2 => (i(), any::<u8>()).prop_map(|(a, b)| ByteEdit::Byte(a, b)),
        2 => (i(), 0..NASTY_INTS.len()).prop_map(|(a, w)| ByteEdit::Int(a, w)),
        2 => (i(), 0..NASTY_WORDS.len()).prop_map(|(a, w)| ByteEdit::Word(a, w)),
        1 => (i(), 1usize..24).prop_map(|(a, n)| ByteEdit::Delete(a, n)),
        1 => (i(), 1usize..24).prop_map(|(a, n)| ByteEdit::Repeat(a, n)),
        1 => i().prop_map(ByteEdit::Cut),
    ]
}

/// `value`'s bytes over `bytes` from `at` (as many as fit), in the byte
/// order of the file (`big`).
fn overwrite(bytes: &mut [u8], at: usize, value: &[u8], big: bool) {
    let mut v = value.to_vec();
    if big {
        v.reverse();
    }
    let n = v.len().min(bytes.len().saturating_sub(at));
    bytes[at..at + n].copy_from_slice(&v[..n]);
}

fn apply_bytes(bytes: &mut Vec<u8>, edit: &ByteEdit, big: bool) {
    if bytes.is_empty() {
        return;
    }
    match edit {
        ByteEdit::Byte(at, b) => {
            let k = at.index(bytes.len());
            bytes[k] = *b;
        }
        ByteEdit::Int(at, w) => {
            let k = at.index(bytes.len());
            overwrite(bytes, k, &NASTY_INTS[*w].to_le_bytes(), big);
        }
        ByteEdit::Word(at, w) => {
            let k = at.index(bytes.len());
            overwrite(bytes, k, &NASTY_WORDS[*w].to_le_bytes(), big);
        }
        ByteEdit::Delete(at, n) => {
            let k = at.index(bytes.len());
            bytes.drain(k..(k + n).min(bytes.len()));
        }
        ByteEdit::Repeat(at, n) => {
            let k = at.index(bytes.len());
            let piece = bytes[k..(k + n).min(bytes.len())].to_vec();
            bytes.splice(k..k, piece);
        }
        ByteEdit::Cut(at) => {
            let k = at.index(bytes.len());
            bytes.truncate(k);
        }
    }
}

/// The binary fixture, little- or big-endian.
fn binary_fixture(big: bool) -> Vec<u8> {
    if big { reencode(BINARY, true, 8) } else { BINARY.to_vec() }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4096, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..600)) {
        let line = read_and_use(&bytes);
        assert_line_in_file(&bytes, line)?;
    }

    /// Bytes after a valid head (MSH 4.1 or 2) reach the section parsers;
    /// the tail is drawn from the characters an MSH file is made of, so
    /// that it often forms headers and numbers.
    #[test]
    fn arbitrary_sections_never_panic(
        version in prop::sample::select(vec!["4.1", "2.2", "2.0"]),
        tail in "(\\$(Nodes|Elements|Entities|PhysicalNames|End[A-Za-z]*)\n|[-0-9 .e\"\n]{1,12}){0,40}",
    ) {
        let text = format!("$MeshFormat\n{version} 0 8\n$EndMeshFormat\n{tail}");
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

proptest! {
    #![proptest_config(ProptestConfig { cases: 4096, ..ProptestConfig::default() })]

    /// Arbitrary bytes after a valid binary head (MSH 4.1 in either byte
    /// order with either `size_t`, or MSH 2.2) reach the binary section
    /// parsers.
    #[test]
    fn arbitrary_binary_sections_never_panic(
        big in any::<bool>(),
        (version, size_t) in prop::sample::select(vec![("4.1", 4usize), ("4.1", 8), ("2.2", 8)]),
        section in prop::sample::select(vec!["$Entities", "$Nodes", "$Elements", "$Comments"]),
        data in prop::collection::vec(any::<u8>(), 0..400),
        close in any::<bool>(),
    ) {
        let one = if big { 1u32.to_be_bytes() } else { 1u32.to_le_bytes() };
        let mut bytes = format!("$MeshFormat\n{version} 1 {size_t}\n").into_bytes();
        bytes.extend_from_slice(&one);
        bytes.extend_from_slice(format!("\n$EndMeshFormat\n{section}\n").as_bytes());
        bytes.extend_from_slice(&data);
        if close {
            bytes.extend_from_slice(format!("\n$End{}\n", &section[1..]).as_bytes());
        }
        let refused = read_and_use(&bytes);
        assert_line_in_file(&bytes, refused)?;
    }

    #[test]
    fn mutated_binary_fixture_never_panics(big in any::<bool>(), edits in prop::collection::vec(byte_edit(), 1..5)) {
        let mut bytes = binary_fixture(big);
        for e in &edits {
            apply_bytes(&mut bytes, e, big);
        }
        let refused = read_and_use(&bytes);
        assert_line_in_file(&bytes, refused)?;
    }

    /// The counts of a section's header and of its first block's header,
    /// where the values that size allocations and loops are, overwritten
    /// by nasty words and ints.
    #[test]
    fn mutated_binary_counts_never_panic(
        big in any::<bool>(),
        section in 0usize..3,
        at in prop::collection::vec((0usize..8, any::<bool>(), 0..NASTY_WORDS.len()), 1..4),
    ) {
        let mut bytes = binary_fixture(big);
        let start = binary_sections(&bytes)[section].1.start;
        for (field, word, with) in at {
            // Fields 0–3: the section header's four size_t; 4–7: the first
            // block's (or entity's) three ints and a size_t.
            let offset = if field < 4 { start + 8 * field } else { start + 32 + 4 * (field - 4) };
            if word {
                overwrite(&mut bytes, offset, &NASTY_WORDS[with].to_le_bytes(), big);
            } else {
                overwrite(&mut bytes, offset, &NASTY_INTS[with % NASTY_INTS.len()].to_le_bytes(), big);
            }
        }
        let refused = read_and_use(&bytes);
        assert_line_in_file(&bytes, refused)?;
    }
}
