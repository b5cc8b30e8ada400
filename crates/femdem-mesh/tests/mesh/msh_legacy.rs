//! Gmsh MSH 2 (2.0–2.2, the "legacy" format) import, ASCII and binary.
//!
//! The files are written here by [`write_v2`], from the format's
//! specification in the Gmsh reference manual ("MSH file format version 2
//! (Legacy)"), independently of the reader: nodes renumbered sparsely,
//! every element with its physical group as first tag and an elementary
//! entity as second, an element in two physical groups written twice (as
//! Gmsh does). A mesh written so reads back as itself, random meshes and
//! the mesh Gmsh made for the MSH 4.1 tests alike, in ASCII and in binary
//! of either byte order; a small hand-written file covers what the writer
//! does not (skipped element types, partition tags, unknown sections);
//! malformed files name their line or byte.

use std::collections::BTreeMap;

use femdem_mesh::check::check;
use femdem_mesh::msh::{MshReport, read_msh, read_msh_report};
use femdem_mesh::{BoundaryGroup, FaceRef, MeshError, Region, TetMesh};
use proptest::prelude::*;

use crate::msh::{GMSH_TWO_VOLUMES, arb_mesh, assert_same_mesh, line_of, msh_error, two_cubes};

/// How [`write_v2`] encodes the file: ASCII, or binary in either byte
/// order with consecutive elements of one type in one block, or as Gmsh
/// writes them, each element in a block of its own (and with four tags:
/// a partition count and id after the physical and elementary tags).
#[derive(Clone, Copy, Debug)]
enum Encoding {
    Ascii,
    Binary { big_endian: bool },
    BinaryAsGmsh { big_endian: bool },
}

/// A node's number in the files written here: sparse and out of order.
fn number(v: usize) -> i32 {
    (7 * v + 1000) as i32
}

/// Physical tag of region `r` and of boundary group `g`.
fn region_tag(r: usize) -> i32 {
    r as i32 + 1
}
fn group_tag(g: usize) -> i32 {
    g as i32 + 101
}

/// One element record: `(type, tags, node numbers)`.
type Element = (i32, Vec<i32>, Vec<i32>);

/// The elements of `mesh`: a point and a line in no physical group (to be
/// skipped), its tets with their region's tag, then each boundary group's
/// faces as triangles (in the tet's outward order) with the group's tag —
/// a face in two groups twice. Elementary entities: 1 for every tet, 2 for
/// every triangle.
fn elements(mesh: &TetMesh) -> Vec<Element> {
    let mut out: Vec<Element> = vec![(15, vec![0, 3], vec![number(0)]), (1, vec![0, 4], vec![number(0), number(1)])];
    out.extend(
        mesh.tets
            .iter()
            .zip(&mesh.tet_region)
            .map(|(t, &r)| (4, vec![region_tag(r as usize), 1], t.iter().map(|&v| number(v as usize)).collect())),
    );
    for (g, group) in mesh.boundary.iter().enumerate() {
        for f in &group.faces {
            let nodes = f.nodes(&mesh.tets).iter().map(|&v| number(v as usize)).collect();
            out.push((2, vec![group_tag(g), 2], nodes));
        }
    }
    out
}

/// `mesh` as an MSH 2.2 file.
fn write_v2(mesh: &TetMesh, encoding: Encoding) -> Vec<u8> {
    let binary = !matches!(encoding, Encoding::Ascii);
    let big = matches!(encoding, Encoding::Binary { big_endian: true } | Encoding::BinaryAsGmsh { big_endian: true });
    let as_gmsh = matches!(encoding, Encoding::BinaryAsGmsh { .. });
    let int = |out: &mut Vec<u8>, v: i32| out.extend(if big { v.to_be_bytes() } else { v.to_le_bytes() });
    let real = |out: &mut Vec<u8>, x: f64| out.extend(if big { x.to_be_bytes() } else { x.to_le_bytes() });
    let mut out = Vec::new();
    out.extend(format!("$MeshFormat\n2.2 {} 8\n", u8::from(binary)).bytes());
    if binary {
        int(&mut out, 1);
        out.push(b'\n');
    }
    out.extend(b"$EndMeshFormat\n$PhysicalNames\n");
    let names: Vec<(i32, i32, &str)> = (mesh.regions.iter().enumerate().map(|(r, x)| (3, region_tag(r), &*x.name)))
        .chain(mesh.boundary.iter().enumerate().map(|(g, x)| (2, group_tag(g), &*x.name)))
        .collect();
    out.extend(format!("{}\n", names.len()).bytes());
    for (dim, tag, name) in names {
        out.extend(format!("{dim} {tag} \"{name}\"\n").bytes());
    }
    out.extend(format!("$EndPhysicalNames\n$Nodes\n{}\n", mesh.coords.len()).bytes());
    for (v, c) in mesh.coords.iter().enumerate() {
        if binary {
            int(&mut out, number(v));
            c.iter().for_each(|&x| real(&mut out, x));
        } else {
            out.extend(format!("{} {:e} {:e} {:e}\n", number(v), c[0], c[1], c[2]).bytes());
        }
    }
    if binary {
        out.push(b'\n');
    }
    let mut elements = elements(mesh);
    if as_gmsh {
        for (_, tags, _) in &mut elements {
            tags.extend([1, 2]);
        }
    }
    out.extend(format!("$EndNodes\n$Elements\n{}\n", elements.len()).bytes());
    if binary {
        // Consecutive elements of one type and tag count in one block.
        let mut i = 0;
        while i < elements.len() {
            let (ty, tags, _) = &elements[i];
            let n = if as_gmsh {
                1
            } else {
                elements[i..].iter().take_while(|e| e.0 == *ty && e.1.len() == tags.len()).count()
            };
            for v in [*ty, n as i32, tags.len() as i32] {
                int(&mut out, v);
            }
            for (k, (_, tags, nodes)) in elements[i..i + n].iter().enumerate() {
                int(&mut out, (i + k + 1) as i32);
                tags.iter().chain(nodes).for_each(|&v| int(&mut out, v));
            }
            i += n;
        }
        out.push(b'\n');
    } else {
        for (k, (ty, tags, nodes)) in elements.iter().enumerate() {
            let rest: Vec<String> = tags.iter().chain(nodes).map(i32::to_string).collect();
            out.extend(format!("{} {ty} {} {}\n", k + 1, tags.len(), rest.join(" ")).bytes());
        }
    }
    out.extend(b"$EndElements\n");
    out
}

const ENCODINGS: [Encoding; 5] = [
    Encoding::Ascii,
    Encoding::Binary { big_endian: false },
    Encoding::Binary { big_endian: true },
    Encoding::BinaryAsGmsh { big_endian: false },
    Encoding::BinaryAsGmsh { big_endian: true },
];

fn read_back(mesh: &TetMesh, encoding: Encoding) -> TetMesh {
    let bytes = write_v2(mesh, encoding);
    read_msh(&bytes).unwrap_or_else(|e| panic!("{encoding:?}: {e}\n{}", String::from_utf8_lossy(&bytes)))
}

// ------------------------------------------------------------ round trips

#[test]
fn two_cubes_read_back_in_every_encoding() {
    let mesh = two_cubes();
    for encoding in ENCODINGS {
        let back = read_back(&mesh, encoding);
        assert_same_mesh(&mesh, &back);
        assert_eq!(back, mesh, "{encoding:?}");
    }
}

/// The mesh Gmsh made (read from its MSH 4.1 file) written as MSH 2:
/// the same mesh, bit for bit (the ASCII file prints every coordinate with
/// all its digits).
#[test]
fn the_gmsh_fixture_reads_the_same_from_msh_2() {
    let mesh = read_msh(GMSH_TWO_VOLUMES).unwrap();
    for encoding in ENCODINGS {
        assert_same_mesh(&mesh, &read_back(&mesh, encoding));
    }
}

/// A face in two groups is written twice, once per group, and is in both;
/// a region and a group that hold nothing are kept from their names.
#[test]
fn a_face_in_two_groups_and_empty_groups() {
    let mut mesh = two_cubes();
    let shared = mesh.boundary[0].faces[0];
    mesh.boundary.push(BoundaryGroup { name: "both".into(), faces: vec![shared] });
    mesh.boundary.push(BoundaryGroup { name: "none".into(), faces: vec![] });
    mesh.regions.push(Region { name: "empty".into(), breakable: true });
    for encoding in ENCODINGS {
        let back = read_back(&mesh, encoding);
        assert_same_mesh(&mesh, &back);
        assert!(back.boundary[0].faces.contains(&shared) && back.boundary[2].faces == vec![shared]);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn random_meshes_read_back(mesh in arb_mesh(), pick in 0usize..5) {
        let back = read_back(&mesh, ENCODINGS[pick]);
        assert_same_mesh(&mesh, &back);
        check(&back).unwrap();
    }
}

// ------------------------------------------------------ a hand-written file

/// Two tets (the second in negative orientation) in physical volume 7
/// "rock" and in no physical volume, a triangle in physical surface 4
/// (unnamed) and in none, a point, a line, four tags (a partition count
/// and id) on one element, node numbers out of order with one unused, an
/// unknown section and an `$Entities` section (Gmsh's
/// `Mesh.SaveTopology = 1`).
const SMALL: &str = "\
$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
1
3 7 \"rock\"
$EndPhysicalNames
$Nodes
6
10 0 0 0
20 1 0 0
30 0 1 0
40 0 0 1
99 5 5 5
50 1 1 1
$EndNodes
$NodeData
1
\"a view\"
$EndNodeData
$Entities
0 0 0 1
1 0 0 0 1 1 1 1 7 0
$EndEntities
$Elements
6
1 15 2 0 1 99
2 1 2 0 1 10 20
3 2 2 4 1 10 20 30
4 2 2 0 1 20 30 40
5 4 4 7 1 1 2 10 20 30 40
6 4 2 0 2 30 20 40 50
$EndElements
";

#[test]
fn small_file_reads_as_expected() {
    let (mesh, report) = read_msh_report(SMALL.as_bytes()).unwrap();
    let expected = TetMesh {
        coords: vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.], [1., 1., 1.]],
        tets: vec![[0, 1, 2, 3], [2, 1, 4, 3]],
        tet_region: vec![0, 1],
        regions: vec![
            Region { name: "rock".into(), breakable: true },
            Region { name: "unnamed".into(), breakable: true },
        ],
        boundary: vec![BoundaryGroup { name: "surface_4".into(), faces: vec![FaceRef { tet: 0, local: 3 }] }],
        fracture_faces: vec![],
    };
    assert_eq!(mesh, expected);
    let expected = MshReport {
        skipped_elements: BTreeMap::from([(1, 1), (15, 1)]),
        ungrouped_triangles: 1,
        dropped_nodes: 1,
        reoriented_tets: 1,
    };
    assert_eq!(report, expected);
    check(&mesh).unwrap();
    assert_eq!(read_msh(SMALL.replace("2.2 0 8", "2.1 0 8").as_bytes()).unwrap(), mesh);
    // MSH 2.0's physical names have no dimension.
    for version in ["2", "2.0"] {
        let text = SMALL.replace("2.2 0 8", &format!("{version} 0 8")).replace("3 7 \"rock\"", "7 \"rock\"");
        assert_eq!(read_msh(text.as_bytes()).unwrap(), mesh, "version {version}");
    }
}

// -------------------------------------------------------- malformed files

#[test]
fn a_tet_in_two_physical_volumes_is_refused_with_both_numbers() {
    let text = SMALL
        .replace("6\n1 15", "7\n1 15")
        .replace("6 4 2 0 2 30 20 40 50\n", "6 4 2 0 2 30 20 40 50\n17 4 2 8 1 20 40 10 30\n");
    let (line, message) = msh_error(&text);
    assert_eq!(line, line_of(&text, "$Elements"));
    assert!(message.contains("elements 5 and 17 are tets on the same four nodes"), "{message}");
    assert!(message.contains("one region only"), "{message}");
    // The same in binary.
    let mut mesh = two_cubes();
    mesh.tets.push(mesh.tets[3]);
    mesh.tet_region.push(1 - mesh.tet_region[3]);
    match read_msh(&write_v2(&mesh, Encoding::BinaryAsGmsh { big_endian: true })) {
        Err(MeshError::MshBinary { section, message, .. }) => {
            // Elements 1 and 2 are the point and the line.
            assert_eq!(section, "Elements");
            assert!(message.contains("elements 6 and 15 are tets on the same four nodes"), "{message}");
        }
        other => panic!("{other:?}"),
    }
}

/// `Mesh.SaveAll = 1`: every element with physical tag 0, the groups
/// still named.
#[test]
fn a_file_saved_with_save_all_is_refused() {
    let text = SMALL.replace("5 4 4 7 1 1 2 ", "5 4 4 0 1 1 2 ").replace("3 2 2 4 1 ", "3 2 2 0 1 ");
    let (line, message) = msh_error(&text);
    assert_eq!(line, line_of(&text, "$Elements"));
    assert!(message.contains("Mesh.SaveAll = 0") && message.contains("physical tag 0"), "{message}");
    // With no physical names, the same elements are a mesh of one unnamed
    // region, as an MSH 4.1 file without physical groups is.
    let text = text.replace("$PhysicalNames\n1\n3 7 \"rock\"\n$EndPhysicalNames\n", "");
    let mesh = read_msh(text.as_bytes()).unwrap();
    assert_eq!((mesh.regions.len(), mesh.boundary.len()), (1, 0));
}

/// A file of triangles only, in named physical surfaces and volume (a
/// surface mesh saved where a volume mesh was meant): its trouble is that
/// it holds no tet, which is what the reader says — not that its elements
/// carry physical tag 0, which they do not.
#[test]
fn a_file_without_tets_says_so_though_its_groups_are_named() {
    let text = SMALL
        .replace("5 4 4 7 1 1 2 10 20 30 40\n6 4 2 0 2 30 20 40 50\n", "")
        .replace("$Elements\n6\n", "$Elements\n4\n");
    let (_, message) = msh_error(&text);
    assert!(message.contains("no 4-node tetrahedra (element type 4) in the file"), "{message}");
    assert!(!message.contains("physical tag 0"), "{message}");
}

#[test]
fn parametric_nodes_are_refused_by_name() {
    let text = SMALL.replace("$Nodes\n", "$ParametricNodes\n0\n$EndParametricNodes\n$Nodes\n");
    let (line, message) = msh_error(&text);
    assert_eq!(line, line_of(&text, "$ParametricNodes"));
    assert!(message.contains("Mesh.SaveParametric = 0"), "{message}");
}

#[test]
fn bad_records_name_their_line() {
    for (from, to, expected) in [
        ("20 1 0 0", "20 1 0", "missing z coordinate"),
        ("20 1 0 0", "20 1 0 0 0", "unexpected `0`"),
        ("20 1 0 0", "0 1 0 0", "numbers start at 1"),
        ("20 1 0 0", "10 1 0 0", "node number 10 appears twice (first on line 10)"),
        ("20 1 0 0", "20 1 nan 0", "bad y coordinate `nan`"),
        ("5 4 4 7 1 1 2 10 20 30 40", "5 4 4 7 1 1 2 10 20 30 41", "node number 41 is not in $Nodes"),
        ("5 4 4 7 1 1 2 10 20 30 40", "5 4 4 7 1 1 2 10 20 30", "missing node number"),
        ("3 2 2 4 1 10 20 30", "3 2 2 -4 1 10 20 30", "bad physical tag -4"),
    ] {
        let text = SMALL.replacen(from, to, 1);
        let (line, message) = msh_error(&text);
        assert_eq!(line, line_of(&text, to), "{to}: {message}");
        assert!(message.contains(expected), "{to}: {message}");
    }
}

#[test]
fn counts_that_disagree_with_the_records_are_refused() {
    let (line, message) = msh_error(&SMALL.replace("$Nodes\n6\n", "$Nodes\n7\n"));
    assert_eq!(line, line_of(SMALL, "$EndNodes"));
    assert!(message.contains("$Nodes ends early"), "{message}");
    let text = SMALL.replace("$Nodes\n6\n", "$Nodes\n5\n");
    let (line, message) = msh_error(&text);
    assert_eq!(line, line_of(&text, "50 1 1 1"));
    assert!(message.contains("expected $EndNodes"), "{message}");
}

#[test]
fn binary_data_sizes_other_than_a_double_are_refused() {
    let mut bytes = write_v2(&two_cubes(), Encoding::Binary { big_endian: false });
    bytes.splice(0..20, b"$MeshFormat\n2.2 1 4\n".iter().copied());
    match read_msh(&bytes) {
        Err(MeshError::Msh { line: 2, message }) => assert!(message.contains("expected 8"), "{message}"),
        other => panic!("{other:?}"),
    }
}

/// A binary file cut anywhere in its data, or with an element block that
/// claims more elements than the header, is refused with the byte offset
/// and the section.
#[test]
fn truncated_and_corrupt_binary_files_name_the_byte() {
    let mesh = two_cubes();
    let bytes = write_v2(&mesh, Encoding::Binary { big_endian: false });
    let find = |pat: &[u8]| bytes.windows(pat.len()).position(|w| w == pat).unwrap();
    let nodes = find(b"$Nodes\n") + 7;
    let elements_at = find(b"$Elements\n") + 10;
    for cut in [nodes + 5, nodes + 40, elements_at + 3, elements_at + 20, bytes.len() - 30] {
        match read_msh(&bytes[..cut]) {
            Err(MeshError::MshBinary { offset, section, message }) => {
                // At the value the cut falls in: at most 8 bytes before it.
                assert!(offset <= cut && cut - offset < 8, "cut at {cut}: {offset}: {message}");
                assert!(section == "Nodes" || section == "Elements", "{section}: {message}");
            }
            other => panic!("cut at {cut}: {other:?}"),
        }
    }
    // The first block header's count, raised by 1000.
    let n = elements(&mesh).len();
    let header = elements_at + format!("{n}\n").len();
    let mut corrupt = bytes.clone();
    let count = i32::from_le_bytes(corrupt[header + 4..header + 8].try_into().unwrap());
    corrupt[header + 4..header + 8].copy_from_slice(&(count + 1000).to_le_bytes());
    match read_msh(&corrupt) {
        Err(MeshError::MshBinary { offset, section, message }) => {
            assert_eq!((offset, section.as_str()), (header + 4, "Elements"), "{message}");
            assert!(message.contains(&format!("more than the {n} announced")), "{message}");
        }
        other => panic!("{other:?}"),
    }
}
