//! Binary MSH 4.1: the fixture Gmsh wrote in binary reads into the same
//! mesh as its ASCII twin (coordinates to the 16 digits Gmsh prints in
//! ASCII: the binary file has the exact doubles), and bit for bit the same
//! in both byte orders and with 4- and 8-byte `size_t`; truncated and
//! corrupt files are refused with the byte offset and the section of the
//! problem.
//!
//! Gmsh writes binary files in the byte order of the machine it runs on,
//! so the committed fixture (`data/gmsh_two_volumes_binary.msh`, written
//! by `data/regenerate.py` on x86) is little-endian with 8-byte `size_t`.
//! The big-endian and 4-byte twins are made from it by [`reencode`], a
//! walker written here from the MSH 4.1 specification, independently of
//! the reader: it swaps the bytes of every value and resizes every
//! `size_t`, as Gmsh on such a machine would have written them.

use std::collections::BTreeMap;

use femdem_mesh::msh::{MshReport, read_msh, read_msh_report};
use femdem_mesh::{MeshError, TetMesh};

/// Written by Gmsh 4.15.2 with `Mesh.Binary = 1` from the same mesh as
/// `data/gmsh_two_volumes.msh` (see `data/regenerate.py`).
pub const BINARY: &[u8] = include_bytes!("../data/gmsh_two_volumes_binary.msh");
const ASCII: &[u8] = include_bytes!("../data/gmsh_two_volumes.msh");

// -------------------------------------------------------- re-encoding

/// Node count of the element types in the fixture.
fn element_nodes(ty: i32) -> usize {
    match ty {
        1 => 2,
        2 => 3,
        4 => 4,
        15 => 1,
        _ => panic!("element type {ty} is not in the fixture"),
    }
}

/// Copies a binary MSH file value by value into another byte order and
/// `size_t` width.
struct Recoder<'a> {
    input: &'a [u8],
    at: usize,
    out: Vec<u8>,
    big: bool,
    size_t: usize,
}

impl Recoder<'_> {
    /// Copies one text line, line break included.
    fn line(&mut self) -> String {
        let end = self.input[self.at..].iter().position(|&b| b == b'\n').expect("a line break") + self.at + 1;
        let line = String::from_utf8(self.input[self.at..end].to_vec()).expect("text");
        self.out.extend_from_slice(line.as_bytes());
        self.at = end;
        line.trim().to_owned()
    }

    fn raw<const N: usize>(&mut self) -> [u8; N] {
        let b: [u8; N] = self.input[self.at..self.at + N].try_into().unwrap();
        self.at += N;
        b
    }

    /// An `int` or a `double`: `N` bytes, reversed for big-endian.
    fn fixed<const N: usize>(&mut self) -> [u8; N] {
        let b = self.raw::<N>();
        let mut o = b;
        if self.big {
            o.reverse();
        }
        self.out.extend_from_slice(&o);
        b
    }

    fn int(&mut self) -> i32 {
        i32::from_le_bytes(self.fixed::<4>())
    }

    fn double(&mut self) {
        self.fixed::<8>();
    }

    /// A `size_t`, 8 bytes in, `size_t` bytes out.
    fn size(&mut self) -> usize {
        let v = u64::from_le_bytes(self.raw::<8>());
        match (self.size_t, self.big) {
            (8, false) => self.out.extend_from_slice(&v.to_le_bytes()),
            (8, true) => self.out.extend_from_slice(&v.to_be_bytes()),
            (4, false) => self.out.extend_from_slice(&u32::try_from(v).unwrap().to_le_bytes()),
            (4, true) => self.out.extend_from_slice(&u32::try_from(v).unwrap().to_be_bytes()),
            _ => unreachable!(),
        }
        v as usize
    }

    fn entities(&mut self) {
        let counts: Vec<usize> = (0..4).map(|_| self.size()).collect();
        for (dim, &n) in counts.iter().enumerate() {
            for _ in 0..n {
                self.int();
                for _ in 0..if dim == 0 { 3 } else { 6 } {
                    self.double();
                }
                let phys = self.size();
                (0..phys).for_each(|_| {
                    self.int();
                });
                if dim > 0 {
                    let bounds = self.size();
                    (0..bounds).for_each(|_| {
                        self.int();
                    });
                }
            }
        }
    }

    fn nodes(&mut self) {
        let blocks = self.size();
        (0..3).for_each(|_| {
            self.size();
        });
        for _ in 0..blocks {
            let dim = self.int() as usize;
            self.int();
            let parametric = self.int() as usize;
            let n = self.size();
            (0..n).for_each(|_| {
                self.size();
            });
            (0..n * (3 + parametric * dim)).for_each(|_| self.double());
        }
    }

    fn elements(&mut self) {
        let blocks = self.size();
        (0..3).for_each(|_| {
            self.size();
        });
        for _ in 0..blocks {
            self.int();
            self.int();
            let ty = self.int();
            let n = self.size();
            (0..n * (1 + element_nodes(ty))).for_each(|_| {
                self.size();
            });
        }
    }
}

/// The little-endian, 8-byte-`size_t` binary MSH file `le` in big-endian
/// order (`big`) and with `size_t` of `size_t` bytes.
pub fn reencode(le: &[u8], big: bool, size_t: usize) -> Vec<u8> {
    let mut r = Recoder { input: le, at: 0, out: Vec::with_capacity(le.len()), big, size_t };
    assert_eq!(r.line(), "$MeshFormat");
    let format = r.line();
    assert_eq!(format, "4.1 1 8", "a little-endian fixture with 8-byte size_t");
    r.out.truncate(r.out.len() - "4.1 1 8\n".len());
    r.out.extend_from_slice(format!("4.1 1 {size_t}\n").as_bytes());
    assert_eq!(r.int(), 1);
    loop {
        while r.at < le.len() && le[r.at].is_ascii_whitespace() {
            r.out.push(le[r.at]);
            r.at += 1;
        }
        if r.at == le.len() {
            return r.out;
        }
        let header = r.line();
        let name = header.strip_prefix('$').expect("a header").to_owned();
        match name.as_str() {
            "EndMeshFormat" => continue,
            "Entities" => r.entities(),
            "Nodes" => r.nodes(),
            "Elements" => r.elements(),
            _ => {
                while r.line() != format!("$End{name}") {}
                continue;
            }
        }
        let rest = r.line();
        assert!(rest.is_empty(), "a line break after the data of ${name}");
        assert_eq!(r.line(), format!("$End{name}"));
    }
}

/// Where each binary section's data lies in `bytes`: from after its header
/// line to the end of its `$End` word.
pub fn binary_sections(bytes: &[u8]) -> Vec<(&'static str, std::ops::Range<usize>)> {
    let find = |needle: &str| bytes.windows(needle.len()).position(|w| w == needle.as_bytes()).unwrap();
    ["Entities", "Nodes", "Elements"]
        .into_iter()
        .map(|s| (s, find(&format!("\n${s}\n")) + s.len() + 3..find(&format!("\n$End{s}\n")) + s.len() + 5))
        .collect()
}

/// The byte offset, section and message of the error reading `bytes` gives.
fn binary_error(bytes: &[u8]) -> (usize, String, String) {
    match read_msh(bytes) {
        Err(MeshError::MshBinary { offset, section, message }) => (offset, section, message),
        other => panic!("expected a binary MSH error, got {other:?}"),
    }
}

// ------------------------------------------------------ the same mesh

/// Asserts that binary-read `a` and ASCII-read `b` are the same mesh and
/// report, field by field (a mesh's debug print is too long to compare by
/// eye): the same tets, regions, groups and report, and the same
/// coordinates up to the rounding of the ASCII file, where Gmsh prints 16
/// significant digits (`%.16g`) of each double: a relative difference of
/// at most 5e-16 (half a unit in the 16th digit), where the binary file
/// holds the doubles themselves.
fn assert_same(a: &(TetMesh, MshReport), b: &(TetMesh, MshReport), what: &str) {
    let ((m, r), (n, s)) = (a, b);
    assert_eq!(m.coords.len(), n.coords.len(), "{what}: node count");
    for (i, (p, q)) in m.coords.iter().zip(&n.coords).enumerate() {
        for k in 0..3 {
            assert!((p[k] - q[k]).abs() <= 5e-16 * q[k].abs(), "{what}: node {i} at {p:?}, not {q:?}");
        }
    }
    assert!(m.tets == n.tets, "{what}: tets differ");
    assert!(m.tet_region == n.tet_region, "{what}: tet regions differ");
    assert_eq!(m.regions, n.regions, "{what}: regions");
    assert!(m.boundary == n.boundary, "{what}: boundary groups differ");
    assert_eq!(m.fracture_faces, n.fracture_faces, "{what}: fracture faces");
    assert_eq!(r, s, "{what}: report");
}

#[test]
fn gmsh_binary_fixture_reads_as_its_ascii_twin() {
    let ascii = read_msh_report(ASCII).unwrap();
    let binary = read_msh_report(BINARY).unwrap();
    assert_same(&binary, &ascii, "binary vs ASCII");
    // The counts Gmsh printed (regenerate.py), as for the ASCII file.
    let (mesh, report) = binary;
    assert_eq!((mesh.num_nodes(), mesh.num_tets()), (116, 335 + 68));
    let expected = MshReport { skipped_elements: BTreeMap::from([(1, 3), (15, 1)]), ..Default::default() };
    assert_eq!(report, expected);
}

#[test]
fn big_endian_and_four_byte_size_t_twins_read_the_same_mesh() {
    let little = read_msh_report(BINARY).unwrap();
    assert_eq!(reencode(BINARY, false, 8), BINARY, "the walker copies the fixture unchanged");
    for (big, size_t) in [(true, 8), (false, 4), (true, 4)] {
        let twin = reencode(BINARY, big, size_t);
        assert_ne!(twin, BINARY);
        let read = read_msh_report(&twin).unwrap();
        assert!(read == little, "big-endian {big}, size_t {size_t}: not the same mesh, bit for bit");
    }
}

// -------------------------------------------------- truncated files

/// Every prefix of the binary file is refused, none panics; a cut inside a
/// section's data (or its `$End` line) is reported in that section, at or
/// before the cut. In both byte orders.
#[test]
fn every_truncation_of_a_binary_file_names_its_section() {
    for bytes in [BINARY.to_vec(), reencode(BINARY, true, 8)] {
        let sections = binary_sections(&bytes);
        for cut in 0..bytes.len() - 1 {
            let err = read_msh(&bytes[..cut]).expect_err("a truncated file is refused");
            let Some((name, _)) = sections.iter().find(|(_, r)| r.contains(&cut)) else {
                continue;
            };
            match err {
                MeshError::MshBinary { offset, section, message } => {
                    assert_eq!(section, *name, "cut at {cut}: {message}");
                    assert!(offset <= cut, "cut at {cut}: offset {offset}");
                }
                other => panic!("cut at {cut}: {other:?}"),
            }
        }
    }
}

#[test]
fn a_cut_inside_the_node_coordinates_says_what_is_missing() {
    let (_, nodes) = binary_sections(BINARY).into_iter().find(|s| s.0 == "Nodes").unwrap();
    let cut = nodes.end - 100;
    let (offset, section, message) = binary_error(&BINARY[..cut]);
    assert_eq!(section, "Nodes");
    assert!(cut - offset < 8, "the value the cut falls in: offset {offset}, cut {cut}");
    assert!(message.contains("file ends inside $Nodes") && message.contains("coordinate"), "{message}");
    let shown = MeshError::MshBinary { offset, section, message }.to_string();
    assert!(shown.starts_with(&format!("MSH binary file, byte {offset} in $Nodes: ")), "{shown}");
}

// ---------------------------------------------------- corrupt values

/// Offset of the first `$Nodes` header's data, and of its first block's
/// first node tag (after 4 `size_t` and the block header).
fn first_node_tag() -> usize {
    let (_, nodes) = binary_sections(BINARY).into_iter().find(|s| s.0 == "Nodes").unwrap();
    nodes.start + 4 * 8 + 3 * 4 + 8
}

fn with(at: usize, bytes: &[u8]) -> Vec<u8> {
    let mut v = BINARY.to_vec();
    v[at..at + bytes.len()].copy_from_slice(bytes);
    v
}

#[test]
fn a_zero_node_tag_is_refused_at_its_offset() {
    let at = first_node_tag();
    let (offset, section, message) = binary_error(&with(at, &0u64.to_le_bytes()));
    assert_eq!((offset, section.as_str()), (at, "Nodes"));
    assert!(message.contains("tags start at 1"), "{message}");
}

#[test]
fn a_non_finite_coordinate_is_refused_at_its_offset() {
    // The first block is on a geometry point: one node, then its x.
    let at = first_node_tag() + 8;
    let (offset, section, message) = binary_error(&with(at, &f64::NAN.to_le_bytes()));
    assert_eq!((offset, section.as_str()), (at, "Nodes"));
    assert!(message.contains("bad x coordinate NaN"), "{message}");
}

#[test]
fn a_huge_node_count_is_refused_without_allocating_it() {
    let (_, nodes) = binary_sections(BINARY).into_iter().find(|s| s.0 == "Nodes").unwrap();
    // numNodes, then maxNodeTag, each set to 2⁶² − 1.
    let huge = ((1u64 << 62) - 1).to_le_bytes();
    let mut bytes = with(nodes.start + 8, &huge);
    bytes[nodes.start + 24..nodes.start + 32].copy_from_slice(&huge);
    let (_, section, message) = binary_error(&bytes);
    assert_eq!(section, "Nodes");
    assert!(message.contains("more than femdem can index"), "{message}");
}

#[test]
fn a_wrong_element_count_is_reported_at_the_end_of_the_data() {
    // One element fewer in the header and in the last block: the data of
    // the last element is left over where `$EndElements` should be.
    let (_, elements) = binary_sections(BINARY).into_iter().find(|s| s.0 == "Elements").unwrap();
    let total = u64::from_le_bytes(BINARY[elements.start + 8..elements.start + 16].try_into().unwrap());
    let mut bytes = with(elements.start + 8, &(total - 1).to_le_bytes());
    // The last block's count: the last block holds the 335 matrix tets,
    // of 5 size_t each.
    let last_block_count = elements.end - "\n$EndElements".len() - 335 * 5 * 8 - 8;
    assert_eq!(u64::from_le_bytes(bytes[last_block_count..last_block_count + 8].try_into().unwrap()), 335);
    bytes[last_block_count..last_block_count + 8].copy_from_slice(&334u64.to_le_bytes());
    let (_, section, message) = binary_error(&bytes);
    assert_eq!(section, "Elements");
    assert!(message.contains("expected $EndElements after the data"), "{message}");
}

#[test]
fn a_bad_byte_order_mark_is_refused() {
    let at = "$MeshFormat\n4.1 1 8\n".len();
    let (offset, section, message) = binary_error(&with(at, &[2, 0, 0, 0]));
    assert_eq!((offset, section.as_str()), (at, "MeshFormat"));
    assert!(message.contains("byte order"), "{message}");
}

#[test]
fn an_unknown_element_type_cannot_be_skipped_in_binary() {
    // The first element block is the point element (type 15) of the
    // physical point "origin": make it type 99.
    let (_, elements) = binary_sections(BINARY).into_iter().find(|s| s.0 == "Elements").unwrap();
    let ty = elements.start + 4 * 8 + 2 * 4;
    assert_eq!(i32::from_le_bytes(BINARY[ty..ty + 4].try_into().unwrap()), 15);
    let (_, section, message) = binary_error(&with(ty, &99i32.to_le_bytes()));
    assert_eq!(section, "Elements");
    assert!(message.contains("element type 99") && message.contains("Mesh.Binary = 0"), "{message}");
}
