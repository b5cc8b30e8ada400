//! Properties of joint insertion (reference paper §2.1, Fig. 2):
//! every interior face of a breakable region gets exactly one joint; the
//! joint's node pairs N1–N6, N2–N5, N3–N4 start at the same point; every
//! split node maps back to the vertex it came from; unbreakable regions keep
//! shared nodes; faces on pre-existing fractures get no joint and become
//! initial contacts; with a joint zone, only the zone's breakable tets are
//! split and the rest of the region keeps shared nodes.

use std::collections::{HashMap, HashSet};

use femdem_core::tet::centroid;
use femdem_mesh::check::check;
use femdem_mesh::faces::face_key;
use femdem_mesh::generate::{BoxSpec, ExtrusionSpec, Outline, generate_box, generate_extrusion};
use femdem_mesh::{JointedMesh, Region, TetMesh, face_adjacency, insert_joints, insert_joints_within};
use proptest::prelude::*;

/// A jittered box whose tets left of `split` form an unbreakable region.
fn two_region_box(h: f64, jitter: f64, seed: u64, split: f64) -> TetMesh {
    let spec = BoxSpec {
        min: [0.0; 3],
        max: [1.0, 0.6, 0.5],
        element_size: h,
        jitter,
        seed,
        region: Region { name: "rock".into(), breakable: true },
    };
    let mut mesh = generate_box(&spec).unwrap();
    mesh.regions.push(Region { name: "steel".into(), breakable: false });
    for t in 0..mesh.num_tets() {
        if centroid(&mesh.tet_points(t))[0] < split {
            mesh.tet_region[t] = 1;
        }
    }
    mesh
}

fn breakable(mesh: &TetMesh, t: u32) -> bool {
    mesh.regions[mesh.tet_region[t as usize] as usize].breakable
}

/// Checks every invariant of `j` against its source `mesh`.
fn assert_joint_invariants(mesh: &TetMesh, j: &JointedMesh) {
    assert_zone_invariants(mesh, &vec![true; mesh.num_tets()], j);
}

/// Checks every invariant of `j`, made with the joint zone `zone`, against
/// its source `mesh`: a tet is split when it is breakable and in the zone.
fn assert_zone_invariants(mesh: &TetMesh, zone: &[bool], j: &JointedMesh) {
    let split = |t: u32| breakable(mesh, t) && zone[t as usize];
    assert_eq!(check(&j.mesh), Ok(()), "the split mesh is valid");
    assert_eq!(j.mesh.tets.len(), mesh.tets.len());
    // Split nodes map back to their vertex, at the same position.
    for (t, tet) in j.mesh.tets.iter().enumerate() {
        for (k, &n) in tet.iter().enumerate() {
            assert_eq!(j.origin[n as usize], mesh.tets[t][k], "tet {t} node {k}");
            assert_eq!(j.mesh.coords[n as usize], mesh.coords[mesh.tets[t][k] as usize]);
        }
    }
    // Split tets own their nodes; the others share theirs.
    let mut users: HashMap<u32, usize> = HashMap::new();
    for (t, tet) in j.mesh.tets.iter().enumerate() {
        if split(t as u32) {
            for &n in tet {
                *users.entry(n).or_default() += 1;
            }
        }
    }
    assert!(users.values().all(|&c| c == 1), "a split tet's node is used by another tet");
    let unbreakable_vertices: HashSet<u32> = mesh
        .tets
        .iter()
        .enumerate()
        .filter(|(t, _)| !split(*t as u32))
        .flat_map(|(_, tet)| tet.iter().copied())
        .collect();
    let n_breakable = (0..mesh.num_tets()).filter(|&t| split(t as u32)).count();
    assert_eq!(j.mesh.num_nodes(), 4 * n_breakable + unbreakable_vertices.len());

    // Exactly one joint per interior face that touches a breakable tet and is
    // not a fracture face; none elsewhere.
    let fracture: HashSet<u128> = mesh.fracture_faces.iter().map(|f| face_key(f.nodes(&mesh.tets))).collect();
    let mut expected = HashSet::new();
    let mut interface = 0;
    for (a, b) in face_adjacency(mesh).unwrap().interior {
        let key = face_key(a.nodes(&mesh.tets));
        let (ba, bb) = (split(a.tet), split(b.tet));
        if (ba || bb) && !fracture.contains(&key) {
            expected.insert(key);
            interface += usize::from(ba != bb);
        }
    }
    let got: Vec<u128> =
        j.joints.iter().map(|jn| face_key([jn[0], jn[1], jn[2]].map(|n| j.origin[n as usize]))).collect();
    let got_set: HashSet<u128> = got.iter().copied().collect();
    assert_eq!(got.len(), got_set.len(), "a face has two joints");
    assert_eq!(got_set, expected);
    assert_eq!(j.interface_joints, interface);
    assert_eq!(j.initial_contacts.len(), fracture.len());

    for (jn, &(fa, fb)) in j.joints.iter().zip(&j.joint_faces) {
        // N1–N6, N2–N5, N3–N4 coincide initially and share their origin.
        for (p, q) in [(0, 5), (1, 4), (2, 3)] {
            assert_eq!(j.mesh.coords[jn[p] as usize], j.mesh.coords[jn[q] as usize]);
            assert_eq!(j.origin[jn[p] as usize], j.origin[jn[q] as usize]);
        }
        // N1N2N3 is face fa of tet a; N4N5N6 is face fb of tet b.
        let ta = j.mesh.tets[fa.tet as usize];
        let tb = j.mesh.tets[fb.tet as usize];
        assert!(jn[..3].iter().all(|n| ta.contains(n)));
        assert!(jn[3..].iter().all(|n| tb.contains(n)));
        // The normal of N1N2N3 points from a to b.
        let p = |n: u32| j.mesh.point(n);
        let normal = (p(jn[1]) - p(jn[0])).cross(&(p(jn[2]) - p(jn[0])));
        let ab = centroid(&j.mesh.tet_points(fb.tet as usize)) - centroid(&j.mesh.tet_points(fa.tet as usize));
        assert!(normal.dot(&ab) > 0.0, "N1N2N3 must face tet b");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    #[test]
    fn joints_are_inserted_on_every_breakable_interior_face(
        h in 0.12f64..0.3, jitter in 0.0f64..=0.15, seed in any::<u64>(), split in -0.1f64..1.1,
    ) {
        let mesh = two_region_box(h, jitter, seed, split);
        let j = insert_joints(&mesh).unwrap();
        assert_joint_invariants(&mesh, &j);
    }

    /// A joint zone (tets with centroid x in `[lo, lo + width]`) on the
    /// two-region box: zone tets of the breakable region own their nodes,
    /// the rest share them, and joints sit exactly on the faces with a
    /// split tet on either side (the zone's edge counted as interface).
    #[test]
    fn joints_are_confined_to_the_zone(
        h in 0.12f64..0.3, seed in any::<u64>(), split in -0.1f64..1.1, lo in -0.1f64..1.0, width in 0.0f64..0.8,
    ) {
        let mesh = two_region_box(h, 0.1, seed, split);
        let zone: Vec<bool> = (0..mesh.num_tets())
            .map(|t| (lo..=lo + width).contains(&centroid(&mesh.tet_points(t))[0]))
            .collect();
        let j = insert_joints_within(&mesh, &zone).unwrap();
        assert_zone_invariants(&mesh, &zone, &j);
    }

    #[test]
    fn fracture_traces_become_initial_contacts(y in -0.5f64..0.5, layers in 1usize..4) {
        let spec = ExtrusionSpec {
            outline: Outline::Polygon(vec![[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]),
            traces: vec![vec![[-0.6, y], [0.7, y + 0.2]]],
            z0: 0.0, thickness: 0.4, element_size: 0.25, layers: Some(layers),
            region: Region { name: "rock".into(), breakable: true },
        };
        let mesh = generate_extrusion(&spec).unwrap();
        let j = insert_joints(&mesh).unwrap();
        prop_assert!(!j.initial_contacts.is_empty());
        assert_joint_invariants(&mesh, &j);
    }
}

#[test]
fn all_unbreakable_mesh_has_no_joints_and_keeps_its_nodes() {
    let mesh = two_region_box(0.2, 0.1, 7, 2.0);
    let j = insert_joints(&mesh).unwrap();
    assert!(j.joints.is_empty());
    assert_eq!(j.mesh.num_nodes(), mesh.num_nodes());
}

#[test]
fn fracture_face_inside_an_unbreakable_region_is_refused() {
    let spec = ExtrusionSpec {
        outline: Outline::Polygon(vec![[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]),
        traces: vec![vec![[-0.5, 0.0], [0.5, 0.0]]],
        z0: 0.0,
        thickness: 0.4,
        element_size: 0.3,
        layers: Some(1),
        region: Region { name: "steel".into(), breakable: false },
    };
    let mesh = generate_extrusion(&spec).unwrap();
    let e = insert_joints(&mesh).unwrap_err().to_string();
    assert!(e.contains("unbreakable"), "{e}");
}

#[test]
fn a_zone_of_every_tet_is_plain_joint_insertion() {
    let mesh = two_region_box(0.2, 0.1, 3, 0.4);
    let all = insert_joints_within(&mesh, &vec![true; mesh.num_tets()]).unwrap();
    assert_eq!(all, insert_joints(&mesh).unwrap());
    let none = insert_joints_within(&mesh, &vec![false; mesh.num_tets()]).unwrap();
    assert!(none.joints.is_empty());
    assert_eq!(none.mesh.num_nodes(), mesh.num_nodes());
    let e = insert_joints_within(&mesh, &[true]).unwrap_err().to_string();
    assert!(e.contains("1 entries for"), "{e}");
}

/// A pre-existing fracture needs a split tet on one side at least: one
/// wholly outside the joint zone of a breakable region is refused, naming
/// the zone; one with the zone on one side becomes an initial contact.
#[test]
fn fracture_face_outside_the_joint_zone_is_refused() {
    let spec = ExtrusionSpec {
        outline: Outline::Polygon(vec![[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]),
        traces: vec![vec![[-0.5, 0.0], [0.5, 0.0]]],
        z0: 0.0,
        thickness: 0.4,
        element_size: 0.3,
        layers: Some(1),
        region: Region { name: "rock".into(), breakable: true },
    };
    let mesh = generate_extrusion(&spec).unwrap();
    let far: Vec<bool> = (0..mesh.num_tets()).map(|t| centroid(&mesh.tet_points(t))[1] > 0.7).collect();
    let e = insert_joints_within(&mesh, &far).unwrap_err().to_string();
    assert!(e.contains("outside the joint zone"), "{e}");
    let above: Vec<bool> = (0..mesh.num_tets()).map(|t| centroid(&mesh.tet_points(t))[1] > 0.0).collect();
    let j = insert_joints_within(&mesh, &above).unwrap();
    assert_eq!(j.initial_contacts.len(), mesh.fracture_faces.len());
    assert_zone_invariants(&mesh, &above, &j);
}

/// A fracture map with both kinds of junction (issue 11): a persistent
/// trace across the whole square (a layer boundary, ending on the outline
/// at both ends), a trace crossing it (X-junction) and a trace ending on
/// it from below (T-junction, a non-persistent fracture ending inside the
/// domain at its other end). The mesh is valid, and the initial contact
/// faces cover each trace, whole: the area of the faces on each trace is
/// its length times the thickness (to round-off: the faces tile it).
#[test]
fn crossing_traces_become_initial_contacts_on_every_trace() {
    let traces = vec![vec![[-1.0, 0.0], [1.0, 0.0]], vec![[-0.7, -0.5], [0.5, 0.7]], vec![[0.5, -0.6], [0.5, 0.0]]];
    let t = 0.3;
    let spec = ExtrusionSpec {
        outline: Outline::Polygon(vec![[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]),
        traces: traces.clone(),
        z0: 0.0,
        thickness: t,
        element_size: 0.2,
        layers: Some(2),
        region: Region { name: "rock".into(), breakable: true },
    };
    let mesh = generate_extrusion(&spec).unwrap();
    assert_eq!(check(&mesh), Ok(()));
    let j = insert_joints(&mesh).unwrap();
    assert_joint_invariants(&mesh, &j);
    assert_eq!(j.initial_contacts.len(), mesh.fracture_faces.len());
    for trace in &traces {
        let (p, q) = (trace[0], trace[1]);
        let length = ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2)).sqrt();
        let on_trace = |x: [f64; 2]| {
            let s = ((x[0] - p[0]) * (q[0] - p[0]) + (x[1] - p[1]) * (q[1] - p[1])) / (length * length);
            let c = [p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])];
            (0.0..=1.0).contains(&s) && ((c[0] - x[0]).powi(2) + (c[1] - x[1]).powi(2)).sqrt() < 1e-12
        };
        let area: f64 = j
            .initial_contacts
            .iter()
            .map(|(f, _)| f.nodes(&j.mesh.tets).map(|n| j.mesh.point(n)))
            .filter(|[a, b, c]| [a, b, c].iter().all(|v| on_trace([v[0], v[1]])))
            .map(|[a, b, c]| femdem_core::tet::triangle_area(&a, &b, &c))
            .sum();
        assert!((area / (length * t) - 1.0).abs() < 1e-12, "trace {trace:?}: contact area {area} vs {}", length * t);
    }
}
