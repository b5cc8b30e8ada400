//! Gmsh MSH 4.1 import and export (MSH 2 import: `msh_legacy.rs`): round trips, a mesh written by Gmsh
//! itself, and malformed files, each with the line its error must name.

use std::collections::BTreeMap;

use femdem_core::tet::signed_volume;
use femdem_core::{Real, Vec3};
use femdem_mesh::check::check;
use femdem_mesh::msh::{MshReport, read_msh, read_msh_report, write_msh};
use femdem_mesh::{BoundaryGroup, FaceRef, MeshError, Region, TetMesh, face_adjacency};
use proptest::prelude::*;

// ---------------------------------------------------------------- helpers

/// The six tets of the Kuhn subdivision of every cell of an `n[0] × n[1] ×
/// n[2]` grid of cubes of edge `h` from `origin`, each grid point moved by
/// `jitter(i)` cube edges (keep it under 0.05 so no tet inverts). One region.
fn kuhn_grid(n: [usize; 3], h: Real, origin: [Real; 3], jitter: impl Fn(usize) -> [Real; 3]) -> TetMesh {
    let id = |i: usize, j: usize, k: usize| ((k * (n[1] + 1) + j) * (n[0] + 1) + i) as u32;
    let mut coords = Vec::new();
    for k in 0..=n[2] {
        for j in 0..=n[1] {
            for i in 0..=n[0] {
                let d = jitter(coords.len());
                let ijk = [i, j, k];
                coords.push(std::array::from_fn(|a| origin[a] + h * (ijk[a] as Real + d[a])));
            }
        }
    }
    let mut mesh = TetMesh { coords, ..Default::default() };
    let axes = [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]];
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                for p in axes {
                    let mut c = [i, j, k];
                    let mut t = [id(c[0], c[1], c[2]); 4];
                    for (s, &a) in p.iter().enumerate() {
                        c[a] += 1;
                        t[s + 1] = id(c[0], c[1], c[2]);
                    }
                    mesh.tets.push(t);
                }
            }
        }
    }
    for t in 0..mesh.tets.len() {
        if signed_volume(&mesh.tet_points(t)) < 0.0 {
            mesh.tets[t].swap(2, 3);
        }
    }
    mesh.tet_region = vec![0; mesh.tets.len()];
    mesh.regions = vec![Region { name: "r".into(), breakable: true }];
    mesh
}

/// Keeps the tets `keep` (in that order) and the nodes they use (in index
/// order); regions, groups and fracture faces are cleared.
fn sub_mesh(mesh: &TetMesh, keep: &[usize]) -> TetMesh {
    let mut used = vec![false; mesh.coords.len()];
    for &t in keep {
        for v in mesh.tets[t] {
            used[v as usize] = true;
        }
    }
    let mut index = vec![u32::MAX; used.len()];
    let mut coords = Vec::new();
    for (i, &u) in used.iter().enumerate() {
        if u {
            index[i] = coords.len() as u32;
            coords.push(mesh.coords[i]);
        }
    }
    TetMesh {
        coords,
        tets: keep.iter().map(|&t| mesh.tets[t].map(|v| index[v as usize])).collect(),
        ..Default::default()
    }
}

/// Boundary groups as `name → sorted faces`, for comparing them as sets.
fn groups(mesh: &TetMesh) -> BTreeMap<String, Vec<FaceRef>> {
    mesh.boundary
        .iter()
        .map(|g| {
            let mut f = g.faces.clone();
            f.sort_unstable();
            (g.name.clone(), f)
        })
        .collect()
}

fn region_names(mesh: &TetMesh) -> Vec<&str> {
    mesh.regions.iter().map(|r| r.name.as_str()).collect()
}

/// Asserts that `back` holds what MSH stores of `mesh`.
pub(crate) fn assert_same_mesh(mesh: &TetMesh, back: &TetMesh) {
    assert_eq!(back.coords, mesh.coords);
    assert_eq!(back.tets, mesh.tets);
    assert_eq!(back.tet_region, mesh.tet_region);
    assert_eq!(region_names(back), region_names(mesh));
    assert_eq!(groups(back), groups(mesh));
}

fn round_trip(mesh: &TetMesh) -> TetMesh {
    let text = write_msh(mesh);
    read_msh(text.as_bytes()).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn face_normal(mesh: &TetMesh, f: FaceRef) -> Vec3 {
    let [a, b, c] = f.nodes(&mesh.tets).map(|v| mesh.point(v));
    (b - a).cross(&(c - a))
}

fn total_volume(mesh: &TetMesh, region: Option<u16>) -> Real {
    (0..mesh.num_tets())
        .filter(|&t| region.is_none_or(|r| mesh.tet_region[t] == r))
        .map(|t| signed_volume(&mesh.tet_points(t)))
        .sum()
}

// ------------------------------------------------------------ round trips

/// Two unit cubes side by side, "left" and "right", with their outer end
/// faces in groups "xmin" and "xmax".
pub(crate) fn two_cubes() -> TetMesh {
    let mut mesh = kuhn_grid([2, 1, 1], 1.0, [0.0; 3], |_| [0.0; 3]);
    mesh.regions =
        vec![Region { name: "left".into(), breakable: true }, Region { name: "right".into(), breakable: true }];
    mesh.tet_region = (0..12).map(|t| u16::from(t >= 6)).collect();
    let adj = face_adjacency(&mesh).unwrap();
    let on_plane = |f: &FaceRef, x: Real| f.nodes(&mesh.tets).iter().all(|&v| mesh.coords[v as usize][0] == x);
    let xmin = adj.boundary.iter().copied().filter(|f| on_plane(f, 0.0)).collect();
    let xmax = adj.boundary.iter().copied().filter(|f| on_plane(f, 2.0)).collect();
    mesh.boundary =
        vec![BoundaryGroup { name: "xmin".into(), faces: xmin }, BoundaryGroup { name: "xmax".into(), faces: xmax }];
    mesh
}

#[test]
fn two_cubes_survive_a_round_trip() {
    let mesh = two_cubes();
    check(&mesh).unwrap();
    assert_eq!(mesh.boundary[0].faces.len(), 2);
    assert_eq!(mesh.boundary[1].faces.len(), 2);
    let back = round_trip(&mesh);
    assert_same_mesh(&mesh, &back);
    assert!(back.regions.iter().all(|r| r.breakable));
    check(&back).unwrap();
}

#[test]
fn breakable_flag_is_not_stored_and_reads_as_true() {
    let mut mesh = two_cubes();
    mesh.regions[1].breakable = false;
    let back = round_trip(&mesh);
    assert!(back.regions[1].breakable);
}

#[test]
fn interleaved_regions_keep_their_tet_order() {
    let mut mesh = two_cubes();
    mesh.tet_region = (0..12).map(|t| (t % 2) as u16).collect();
    assert_same_mesh(&mesh, &round_trip(&mesh));
}

#[test]
fn interior_faces_in_a_group_keep_their_side() {
    // Both sides of every interior face, each in its own group: the reader
    // must pick the tet by the triangle's orientation.
    let mut mesh = two_cubes();
    let adj = face_adjacency(&mesh).unwrap();
    mesh.boundary = vec![
        BoundaryGroup { name: "a".into(), faces: adj.interior.iter().map(|p| p.0).collect() },
        BoundaryGroup { name: "b".into(), faces: adj.interior.iter().map(|p| p.1).collect() },
    ];
    assert_same_mesh(&mesh, &round_trip(&mesh));
}

#[test]
fn empty_regions_and_groups_survive_a_round_trip() {
    let mut mesh = two_cubes();
    mesh.tet_region = vec![0; 12];
    mesh.boundary.push(BoundaryGroup { name: "nothing".into(), faces: vec![] });
    let back = round_trip(&mesh);
    assert_same_mesh(&mesh, &back);
    assert_eq!(region_names(&back), ["left", "right"]);
}

#[test]
fn extreme_coordinates_are_written_exactly() {
    let mut mesh = two_cubes();
    mesh.coords[0] = [1e-300, -0.0, 1.234_567_891_234_568e18];
    mesh.coords[1][1] = 1e-7;
    let text = write_msh(&mesh);
    assert!(!text.contains("0000000000000000000"), "positional notation for tiny numbers");
    assert_eq!(read_msh(text.as_bytes()).unwrap().coords, mesh.coords);
}

pub(crate) fn arb_mesh() -> impl Strategy<Value = TetMesh> {
    (
        prop::array::uniform3(1usize..=2),
        1e-3..10.0f64,
        prop::array::uniform3(-5.0..5.0f64),
        prop::collection::vec(prop::array::uniform3(-0.05..0.05f64), 27),
        prop::collection::vec(any::<bool>(), 48),
        1usize..=3,
        prop::collection::vec(0u16..3, 48),
        prop::collection::vec(prop::collection::vec((0usize..48, 0u8..4), 0..8), 0..=3),
    )
        .prop_map(|(n, h, origin, jitter, keep, num_regions, region, faces)| {
            let grid = kuhn_grid(n, h, origin, |i| jitter[i]);
            let mut keep: Vec<usize> = (0..grid.num_tets()).filter(|&t| keep[t]).collect();
            if keep.is_empty() {
                keep.push(0);
            }
            let mut mesh = sub_mesh(&grid, &keep);
            let nt = mesh.num_tets();
            mesh.regions = (0..num_regions).map(|r| Region { name: format!("region {r}"), breakable: true }).collect();
            mesh.tet_region = (0..nt).map(|t| region[t] % num_regions as u16).collect();
            mesh.boundary = faces
                .iter()
                .enumerate()
                .map(|(g, fs)| BoundaryGroup {
                    name: format!("group_{g}"),
                    faces: fs.iter().map(|&(t, l)| FaceRef { tet: (t % nt) as u32, local: l }).collect(),
                })
                .collect();
            mesh
        })
}

proptest! {
    #[test]
    fn random_meshes_survive_a_round_trip(mesh in arb_mesh()) {
        check(&mesh).unwrap();
        let back = round_trip(&mesh);
        assert_same_mesh(&mesh, &back);
        check(&back).unwrap();
    }
}

// --------------------------------------------------- the Gmsh-made fixture

/// Written by Gmsh 4.15.2 from `data/gmsh_two_volumes.geo` (see
/// `data/regenerate.py`): a 10 mm cube ("matrix") with a cylindrical
/// inclusion of radius 2.5 mm and height 6 mm ("inclusion").
pub(crate) const GMSH_TWO_VOLUMES: &[u8] = include_bytes!("../data/gmsh_two_volumes.msh");
const CUBE: Real = 0.01;
const RADIUS: Real = 0.0025;
const HEIGHT: Real = 0.006;
const Z0: Real = 0.002;

#[test]
fn gmsh_fixture_counts_match_what_gmsh_reported() {
    let (mesh, report) = read_msh_report(GMSH_TWO_VOLUMES).unwrap();
    // Counts printed by regenerate.py through the Gmsh API.
    assert_eq!(mesh.num_nodes(), 116);
    assert_eq!(region_names(&mesh), ["matrix", "inclusion"]);
    assert!(mesh.regions.iter().all(|r| r.breakable));
    assert_eq!(mesh.num_tets(), 335 + 68);
    assert_eq!(mesh.tet_region.iter().filter(|&&r| r == 0).count(), 335);
    assert_eq!(mesh.tet_region.iter().filter(|&&r| r == 1).count(), 68);
    let sizes: Vec<(&str, usize)> = mesh.boundary.iter().map(|g| (g.name.as_str(), g.faces.len())).collect();
    assert_eq!(sizes, [("bottom", 26), ("top", 26), ("inclusion_boundary", 66)]);
    // Physical curve "z_axis_edge": 3 lines; physical point "origin": 1.
    let expected = MshReport { skipped_elements: BTreeMap::from([(1, 3), (15, 1)]), ..Default::default() };
    assert_eq!(report, expected);
    check(&mesh).unwrap();
}

#[test]
fn gmsh_fixture_tets_are_positive_and_fill_the_cube() {
    let mesh = read_msh(GMSH_TWO_VOLUMES).unwrap();
    assert!((0..mesh.num_tets()).all(|t| signed_volume(&mesh.tet_points(t)) > 0.0));
    // The cube's faces are planar, so faceting loses nothing: only the
    // round-off of ~400 determinants (and of 16-digit coordinates) remains.
    let total = total_volume(&mesh, None);
    assert!((total - CUBE.powi(3)).abs() <= 1e-12 * CUBE.powi(3), "total volume {total:e}");
}

#[test]
fn gmsh_fixture_inclusion_volume_is_bounded_by_its_faceting() {
    let mesh = read_msh(GMSH_TWO_VOLUMES).unwrap();
    let inclusion = total_volume(&mesh, mesh.region_index("inclusion"));
    // The value Gmsh's own node coordinates give (regenerate.py).
    assert!((inclusion - 1.074653910360876e-7).abs() <= 1e-12 * inclusion);
    // The faceted side has its nodes on the cylinder and facets with edges
    // at most `l` long, so it lies between radii sqrt(R² − l²/4) and R; the
    // caps are planar. Hence π(R² − l²/4)H ≤ V ≤ πR²H.
    let group = mesh.boundary_group("inclusion_boundary").unwrap();
    let l = group
        .faces
        .iter()
        .flat_map(|f| {
            let p = f.nodes(&mesh.tets).map(|v| mesh.point(v));
            [(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()]
        })
        .fold(0.0, Real::max);
    let pi = std::f64::consts::PI;
    let (lo, hi) = (pi * (RADIUS.powi(2) - l * l / 4.0) * HEIGHT, pi * RADIUS.powi(2) * HEIGHT);
    assert!(lo <= inclusion && inclusion <= hi * (1.0 + 1e-12), "{lo:e} <= {inclusion:e} <= {hi:e}");
}

#[test]
fn gmsh_fixture_groups_lie_where_the_geometry_puts_them() {
    let mesh = read_msh(GMSH_TWO_VOLUMES).unwrap();
    let z_of = |g: &str| -> Vec<Real> {
        let group = mesh.boundary_group(g).unwrap();
        group.faces.iter().flat_map(|f| f.nodes(&mesh.tets)).map(|v| mesh.coords[v as usize][2]).collect()
    };
    assert!(z_of("bottom").iter().all(|&z| z == 0.0));
    assert!(z_of("top").iter().all(|&z| (z - CUBE).abs() < 1e-15));
    // Outer faces are named from their only tet, so they point outwards.
    for (g, dir) in [("bottom", -1.0), ("top", 1.0)] {
        let group = mesh.boundary_group(g).unwrap();
        assert!(group.faces.iter().all(|&f| face_normal(&mesh, f).z * dir > 0.0));
    }
    // The inclusion boundary is interior: each triangle is shared by a
    // matrix tet and an inclusion tet, and lies on the cylinder or a cap.
    let adj = face_adjacency(&mesh).unwrap();
    let interior: std::collections::HashSet<FaceRef> = adj.interior.iter().flat_map(|&(a, b)| [a, b]).collect();
    let group = mesh.boundary_group("inclusion_boundary").unwrap();
    for f in &group.faces {
        assert!(interior.contains(f));
        for v in f.nodes(&mesh.tets) {
            let [x, y, z] = mesh.coords[v as usize];
            let r = ((x - CUBE / 2.0).powi(2) + (y - CUBE / 2.0).powi(2)).sqrt();
            let on_cap = (z - Z0).abs() < 1e-12 || (z - Z0 - HEIGHT).abs() < 1e-12;
            assert!(on_cap || (r - RADIUS).abs() < 1e-12, "node {v} at r = {r}, z = {z}");
        }
    }
}

#[test]
fn gmsh_fixture_survives_a_round_trip() {
    let mesh = read_msh(GMSH_TWO_VOLUMES).unwrap();
    assert_same_mesh(&mesh, &round_trip(&mesh));
}

// ------------------------------------------------- a small hand-made file

/// Non-contiguous node tags, an unused node (on a geometry point), a
/// parametric node block, a tet in negative orientation, a volume and a
/// surface in no physical group, an unnamed physical surface, a point
/// element and an unknown section.
const SMALL: &str = "\
$MeshFormat
4.1 0 8
$EndMeshFormat
$Comments
free text, even $Nodes-like words
$EndComments
$PhysicalNames
1
3 7 \"rock  mass\"
$EndPhysicalNames
$Entities
1 0 2 2
1 5 5 5 0
1 0 0 0 1 1 0 1 4 0
2 0 0 0 1 1 1 0 0
1 0 0 0 1 1 1 1 7 0
2 0 0 0 1 1 1 0 0
$EndEntities
$Nodes
3 6 10 99
0 1 0 1
99
5 5 5
3 1 0 4
10
20
30
40
0 0 0
1 0 0
0 1 0
0 0 1
3 2 1 1
50
1 1 1 0.1 0.2 0.3
$EndNodes
$Elements
5 5 1 5
0 1 15 1
1 99
2 1 2 1
2 10 20 30
2 2 2 1
3 20 30 40
3 1 4 1
4 10 20 30 40
3 2 4 1
5 30 20 40 50
$EndElements
";

fn expected_small() -> TetMesh {
    TetMesh {
        coords: vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.], [1., 1., 1.]],
        tets: vec![[0, 1, 2, 3], [2, 1, 4, 3]],
        tet_region: vec![0, 1],
        regions: vec![
            Region { name: "rock  mass".into(), breakable: true },
            Region { name: "unnamed".into(), breakable: true },
        ],
        boundary: vec![BoundaryGroup { name: "surface_4".into(), faces: vec![FaceRef { tet: 0, local: 3 }] }],
        fracture_faces: vec![],
    }
}

#[test]
fn small_file_reads_as_expected() {
    let (mesh, report) = read_msh_report(SMALL.as_bytes()).unwrap();
    assert_eq!(mesh, expected_small());
    let expected = MshReport {
        skipped_elements: BTreeMap::from([(15, 1)]),
        ungrouped_triangles: 1,
        dropped_nodes: 1,
        reoriented_tets: 1,
    };
    assert_eq!(report, expected);
    assert_eq!(
        report.to_string(),
        "skipped elements: 1 point (type 15); 1 triangle(s) in no physical surface ignored; \
         1 node(s) used by no tet dropped; 1 tet(s) reoriented"
    );
    check(&mesh).unwrap();
}

#[test]
fn sparse_node_tags_are_mapped() {
    let far = "1000000000000";
    let text = SMALL
        .replace("3 6 10 99", &format!("3 6 10 {far}"))
        .replace("\n99\n", &format!("\n{far}\n"))
        .replace("1 99\n", &format!("1 {far}\n"));
    assert_eq!(read_msh(text.as_bytes()).unwrap(), expected_small());
}

#[test]
fn crlf_line_ends_are_accepted() {
    let crlf = SMALL.replace('\n', "\r\n");
    assert_eq!(read_msh(crlf.as_bytes()).unwrap(), expected_small());
}

#[test]
fn a_byte_order_mark_an_editor_wrote_is_skipped() {
    let bom = format!("\u{feff}{SMALL}");
    assert_eq!(read_msh(bom.as_bytes()).unwrap(), expected_small());
    // Lines are still counted from the file's first.
    let (bad, n) = small_with("0 1 0", Some("0 x 0"));
    let plain = read_msh(bad.as_bytes()).unwrap_err().to_string();
    let marked = read_msh(format!("\u{feff}{bad}").as_bytes()).unwrap_err().to_string();
    assert_eq!(plain, marked);
    assert!(plain.contains(&format!("line {n}")), "{plain}");
}

// -------------------------------------------------------- malformed files

/// 1-based number of the first line of `text` equal to `line`.
pub(crate) fn line_of(text: &str, line: &str) -> usize {
    1 + text.lines().position(|l| l == line).unwrap_or_else(|| panic!("no line `{line}`"))
}

/// `SMALL` with its first line equal to `from` replaced by `to` (removed if
/// `to` is `None`), and that line's number.
fn small_with(from: &str, to: Option<&str>) -> (String, usize) {
    let n = line_of(SMALL, from);
    let lines = SMALL.lines().enumerate().filter_map(|(i, l)| if i + 1 == n { to } else { Some(l) });
    (lines.map(|l| format!("{l}\n")).collect(), n)
}

/// The line and message of the error that reading `text` gives.
pub(crate) fn msh_error(text: &str) -> (usize, String) {
    match read_msh(text.as_bytes()) {
        Err(MeshError::Msh { line, message }) => (line, message),
        other => panic!("expected an MSH error, got {other:?}"),
    }
}

#[test]
fn truncated_nodes_section_names_the_last_line() {
    let n = line_of(SMALL, "0 1 0");
    let text: String = SMALL.lines().take(n).map(|l| format!("{l}\n")).collect();
    let (line, message) = msh_error(&text);
    assert_eq!(line, n);
    assert!(message.contains("file ends inside $Nodes"), "{message}");
}

#[test]
fn nodes_section_ending_early_names_the_end_line() {
    // Node 50's coordinates are missing: `$EndNodes` moves up to its line.
    let (text, n) = small_with("1 1 1 0.1 0.2 0.3", None);
    let (line, message) = msh_error(&text);
    assert_eq!(line, n);
    assert!(message.contains("$Nodes ends early") && message.contains("$EndNodes"), "{message}");
}

#[test]
fn bad_float_names_its_line() {
    let (text, n) = small_with("1 0 0", Some("1 0x 0"));
    let (line, message) = msh_error(&text);
    assert_eq!(line, n);
    assert!(message.contains("`0x`"), "{message}");
}

#[test]
fn unknown_node_tag_in_an_element_names_its_line() {
    let (text, n) = small_with("4 10 20 30 40", Some("4 10 20 30 41"));
    let (line, message) = msh_error(&text);
    assert_eq!(line, n);
    assert!(message.contains("node tag 41"), "{message}");
}

/// An ASCII file whose header says binary (file type 1): the reader looks
/// for the binary integer 1 after the header line and finds `$End`. (Binary
/// files themselves are read: `msh_binary.rs`.)
#[test]
fn an_ascii_file_that_says_binary_is_refused_at_the_byte_order_check() {
    let (text, _) = small_with("4.1 0 8", Some("4.1 1 8"));
    match read_msh(text.as_bytes()) {
        Err(MeshError::MshBinary { offset, section, message }) => {
            assert_eq!((offset, section.as_str()), ("$MeshFormat\n4.1 1 8\n".len(), "MeshFormat"));
            assert!(message.contains("byte order") && message.contains("ASCII file with file type 1"), "{message}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn bad_file_type_and_binary_data_size_name_the_format_line() {
    for (format, expected) in [("4.1 2 8", "bad file type 2"), ("4.1 1 2", "bad data size 2")] {
        let (text, _) = small_with("4.1 0 8", Some(format));
        let (line, message) = msh_error(&text);
        assert_eq!(line, 2, "{format}");
        assert!(message.contains(expected), "{message}");
    }
}

#[test]
fn other_versions_are_refused_by_name() {
    for version in ["3.0", "4.0", "4", "1.0", "2.3"] {
        let (text, _) = small_with("4.1 0 8", Some(&format!("{version} 0 8")));
        let (line, message) = msh_error(&text);
        assert_eq!(line, 2);
        assert!(
            message.contains(&format!("version {version} ")) && message.contains("Mesh.MshFileVersion = 4.1"),
            "{message}"
        );
    }
}

#[test]
fn missing_end_of_section_names_the_last_line() {
    let (text, n) = small_with("$EndElements", None);
    let (line, message) = msh_error(&text);
    assert_eq!(line, n - 1);
    assert!(message.contains("$EndElements"), "{message}");
}

#[test]
fn unclosed_unknown_section_names_its_header() {
    let (text, _) = small_with("$EndComments", None);
    assert_eq!(msh_error(&text).0, line_of(SMALL, "$Comments"));
}

#[test]
fn wrong_element_count_names_the_line_after_the_blocks() {
    let (text, _) = small_with("5 5 1 5", Some("5 6 1 6"));
    let (line, message) = msh_error(&text);
    assert_eq!(line, line_of(SMALL, "$EndElements"));
    assert!(message.contains("announces 6 elements"), "{message}");
}

#[test]
fn extra_node_tag_on_a_tet_names_its_line() {
    let (text, n) = small_with("4 10 20 30 40", Some("4 10 20 30 40 50"));
    assert_eq!(msh_error(&text).0, n);
}

#[test]
fn triangle_on_no_tet_face_names_its_line() {
    let (text, n) = small_with("2 10 20 30", Some("2 10 20 50"));
    let (line, message) = msh_error(&text);
    assert_eq!(line, n);
    assert!(message.contains("not a face of any tet"), "{message}");
}

#[test]
fn file_without_tets_says_what_it_found() {
    let text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n0 1 0 1\n1\n0 0 0\n$EndNodes\n\
                $Elements\n1 1 1 1\n0 1 15 1\n1 1\n$EndElements\n";
    let (line, message) = msh_error(text);
    assert_eq!(line, 10);
    assert!(message.contains("no 4-node tetrahedra") && message.contains("1 point (type 15)"), "{message}");
}

#[test]
fn every_truncation_is_an_error_not_a_panic() {
    let lines = SMALL.lines().count();
    for cut in 0..SMALL.len() - 1 {
        match read_msh(&SMALL.as_bytes()[..cut]) {
            Err(MeshError::Msh { line, .. }) => {
                assert!((1..=lines).contains(&line), "cut {cut}: line {line}")
            }
            other => panic!("cut at byte {cut}: {other:?}"),
        }
    }
}

proptest! {
    #[test]
    fn mangled_files_never_panic(edits in prop::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..6)) {
        let mut bytes = SMALL.as_bytes().to_vec();
        for (at, b) in edits {
            let i = at.index(bytes.len());
            bytes[i] = b;
        }
        let lines = bytes.split(|&b| b == b'\n').count();
        if let Err(MeshError::Msh { line, .. }) = read_msh(&bytes) {
            prop_assert!((1..=lines).contains(&line));
        }
    }
}

/// Two nodes at one point (node 60 duplicates node 20, and the second tet
/// uses it instead of 20) would split the two tets with no joint between
/// them: a hidden crack. It is refused on the duplicate's coordinate line,
/// naming the line of the first.
#[test]
fn coincident_nodes_are_refused_with_both_lines() {
    let text = SMALL
        .replace("3 6 10 99\n", "3 7 10 99\n")
        .replace("3 2 1 1\n50\n1 1 1 0.1 0.2 0.3\n", "3 2 1 2\n50\n60\n1 1 1 0.1 0.2 0.3\n1 0 0 0.1 0.2 0.3\n")
        .replace("5 30 20 40 50\n", "5 30 60 40 50\n");
    let first = line_of(&text, "1 0 0");
    let second = line_of(&text, "1 0 0 0.1 0.2 0.3");
    let (line, message) = msh_error(&text);
    assert_eq!(line, second, "{message}");
    assert!(message.contains(&format!("coincides with the node on line {first}")), "{message}");
}

/// A wrong node count in an entity block's header shows as a record of the
/// wrong shape; the message says so and names the header's line (it used
/// to report the misread field: "bad node tag `0`", "missing y coordinate").
#[test]
fn a_wrong_block_node_count_is_reported_as_such() {
    let header = line_of(SMALL, "3 1 0 4");
    for (count, found) in [("5", "3 number(s) where the tag of node 5"), ("3", "1 number(s) where the coordinates")] {
        let (text, _) = small_with("3 1 0 4", Some(&format!("3 1 0 {count}")));
        let (_, message) = msh_error(&text);
        assert!(message.contains(found), "{message}");
        assert!(message.contains(&format!("the block header on line {header}")), "{message}");
    }
}
