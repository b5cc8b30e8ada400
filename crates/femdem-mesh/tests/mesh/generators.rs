//! Properties of the mesh generators, over random parameters: every tet is
//! positive and the mesh passes `check`; volumes sum to the geometry's
//! volume (for a circle, to the inscribed polygon's area times the
//! thickness: `A_n = (n/2) r² sin(2π/n)`); boundary groups cover the sides;
//! the same parameters give the same mesh.

use femdem_core::tet::triangle_area;
use femdem_mesh::check::check;
use femdem_mesh::generate::{
    BoxSpec, ExtrusionSpec, Outline, PlatenSpec, Side, generate_box, generate_extrusion, generate_platen,
};
use femdem_mesh::{Region, TetMesh, stats};
use proptest::prelude::*;

fn region() -> Region {
    Region { name: "rock".into(), breakable: true }
}

fn group_area(mesh: &TetMesh, name: &str) -> f64 {
    mesh.boundary_group(name)
        .unwrap_or_else(|| panic!("no group {name}"))
        .faces
        .iter()
        .map(|f| {
            let [a, b, c] = f.nodes(&mesh.tets).map(|n| mesh.point(n));
            triangle_area(&a, &b, &c)
        })
        .sum()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn box_is_positive_and_fills_its_volume(
        lx in 0.2f64..2.0, ly in 0.2f64..2.0, lz in 0.2f64..2.0,
        h in 0.12f64..0.5, jitter in 0.0f64..=0.15, seed in any::<u64>(),
    ) {
        let spec = BoxSpec { min: [-0.3, 0.1, 1.0], max: [-0.3 + lx, 0.1 + ly, 1.0 + lz], element_size: h, jitter, seed, region: region() };
        let mesh = generate_box(&spec).unwrap();
        prop_assert_eq!(check(&mesh), Ok(()));
        let s = stats(&mesh);
        // Round-off only: each tet volume carries ~1e-16 relative error.
        prop_assert!(rel(s.volume, lx * ly * lz) < 1e-12, "volume {} vs {}", s.volume, lx * ly * lz);
        prop_assert!(rel(group_area(&mesh, "xmin"), ly * lz) < 1e-12);
        prop_assert!(rel(group_area(&mesh, "zmax"), lx * ly) < 1e-12);
        prop_assert_eq!(&generate_box(&spec).unwrap(), &mesh);
    }

    #[test]
    fn extruded_polygon_fills_its_prism(
        w in 0.5f64..2.0, hgt in 0.5f64..2.0, notch in 0.1f64..0.4, t in 0.1f64..0.6,
        h in 0.1f64..0.3, layers in proptest::option::of(1usize..5),
    ) {
        // An L-shaped (non-convex) outline: area w·hgt − (notch·w)(notch·hgt).
        let poly = vec![[0.0, 0.0], [w, 0.0], [w, hgt * (1.0 - notch)], [w * (1.0 - notch), hgt * (1.0 - notch)], [w * (1.0 - notch), hgt], [0.0, hgt]];
        let area = w * hgt - notch * w * notch * hgt;
        let spec = ExtrusionSpec { outline: Outline::Polygon(poly), traces: vec![], z0: -0.2, thickness: t, element_size: h, layers, region: region() };
        let mesh = generate_extrusion(&spec).unwrap();
        prop_assert_eq!(check(&mesh), Ok(()));
        prop_assert!(rel(stats(&mesh).volume, area * t) < 1e-12);
        prop_assert!(rel(group_area(&mesh, "bottom"), area) < 1e-12);
        prop_assert!(rel(group_area(&mesh, "top"), area) < 1e-12);
        let perimeter = 2.0 * (w + hgt);
        prop_assert!(rel(group_area(&mesh, "side"), perimeter * t) < 1e-12);
        prop_assert!(mesh.fracture_faces.is_empty());
    }

    #[test]
    fn extruded_circle_fills_its_inscribed_polygon(r in 0.01f64..0.05, t in 0.005f64..0.02, frac in 0.08f64..0.25) {
        let h = r * frac;
        let spec = ExtrusionSpec { outline: Outline::Circle { center: [0.01, -0.02], radius: r }, traces: vec![], z0: 0.0, thickness: t, element_size: h, layers: None, region: region() };
        let mesh = generate_extrusion(&spec).unwrap();
        prop_assert_eq!(check(&mesh), Ok(()));
        let n = femdem_mesh::generate::circle_segments(r, h) as f64;
        let polygon = 0.5 * n * r * r * (std::f64::consts::TAU / n).sin();
        prop_assert!(rel(stats(&mesh).volume, polygon * t) < 1e-12);
        // The inscribed polygon is within (2π/n)²/6 of the circle.
        prop_assert!(rel(polygon, std::f64::consts::PI * r * r) < (std::f64::consts::TAU / n).powi(2) / 6.0 * 1.01);
    }

    #[test]
    fn trace_faces_cover_the_trace(y in -0.3f64..0.3, x0 in -0.8f64..-0.2, x1 in 0.2f64..0.8, kink in -0.2f64..0.2) {
        let trace = vec![[x0, y], [0.0, y + kink], [x1, y]];
        let length = (x0.powi(2) + kink.powi(2)).sqrt() + (x1.powi(2) + kink.powi(2)).sqrt();
        let t = 0.3;
        let spec = ExtrusionSpec {
            outline: Outline::Polygon(vec![[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]),
            traces: vec![trace], z0: 0.0, thickness: t, element_size: 0.2, layers: Some(2), region: region(),
        };
        let mesh = generate_extrusion(&spec).unwrap();
        prop_assert_eq!(check(&mesh), Ok(()));
        let area: f64 = mesh.fracture_faces.iter().map(|f| {
            let [a, b, c] = f.nodes(&mesh.tets).map(|n| mesh.point(n));
            triangle_area(&a, &b, &c)
        }).sum();
        prop_assert!(rel(area, length * t) < 1e-12, "fracture area {} vs {}", area, length * t);
    }
}

#[test]
fn platen_touches_the_specimen_without_sharing_nodes() {
    let spec = ExtrusionSpec {
        outline: Outline::Circle { center: [0.0, 0.0], radius: 0.02 },
        traces: vec![],
        z0: 0.0,
        thickness: 0.01,
        element_size: 0.004,
        layers: None,
        region: region(),
    };
    let mut mesh = generate_extrusion(&spec).unwrap();
    let (lo, hi) = mesh.bounding_box().unwrap();
    let platen = PlatenSpec {
        side: Side::YMax,
        thickness: 0.005,
        extent: [Some(0.01), None],
        element_size: 0.0025,
        region: Region { name: "platen".into(), breakable: false },
    };
    let p = generate_platen(&platen, lo, hi).unwrap();
    let (plo, phi) = p.bounding_box().unwrap();
    assert_eq!(plo[1], hi[1], "contact face in the plane of the disc's top");
    assert!((phi[1] - hi[1] - 0.005).abs() < 1e-15);
    assert!((phi[0] - plo[0] - 0.01).abs() < 1e-15);
    assert_eq!((plo[2], phi[2]), (lo[2], hi[2]));
    let before = mesh.num_nodes();
    mesh.append(&p);
    assert_eq!(check(&mesh), Ok(()));
    assert_eq!(mesh.regions.len(), 2);
    assert_eq!(mesh.num_nodes(), before + p.num_nodes());
}

#[test]
fn bad_parameters_are_rejected_with_their_name() {
    let mut spec = BoxSpec { min: [0.0; 3], max: [1.0; 3], element_size: 0.0, jitter: 0.1, seed: 0, region: region() };
    let e = generate_box(&spec).unwrap_err().to_string();
    assert!(e.contains("element_size"), "{e}");
    spec.element_size = 0.5;
    spec.jitter = 0.3;
    assert!(generate_box(&spec).unwrap_err().to_string().contains("jitter"));
    spec.jitter = 0.0;
    spec.max[1] = -1.0;
    assert!(generate_box(&spec).unwrap_err().to_string().contains("max"));
    let crossing = ExtrusionSpec {
        outline: Outline::Polygon(vec![[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]),
        traces: vec![],
        z0: 0.0,
        thickness: 1.0,
        element_size: 0.3,
        layers: None,
        region: region(),
    };
    let e = generate_extrusion(&crossing).unwrap_err().to_string();
    assert!(e.contains("or it crosses itself"), "a self-intersecting outline must be refused: {e}");
    let nan =
        ExtrusionSpec { outline: Outline::Polygon(vec![[0.0, 0.0], [1.0, f64::NAN], [1.0, 1.0]]), ..crossing.clone() };
    let e = generate_extrusion(&nan).unwrap_err().to_string();
    assert!(e.contains("has a point that is not finite: [1.0, NaN]"), "{e}");
    let infinite = BoxSpec {
        min: [f64::NEG_INFINITY, 0.0, 0.0],
        max: [1.0; 3],
        element_size: 0.5,
        jitter: 0.0,
        seed: 0,
        region: region(),
    };
    let e = generate_box(&infinite).unwrap_err().to_string();
    assert!(e.contains("`min`: must be finite on every axis, got -inf on axis 0"), "{e}");
}

/// The element size of an extrusion is the in-plane edge length: the mean
/// edge of the bottom triangles lies within 15% of it (Delaunay refinement
/// makes sizes vary; the bound says the knob means what it says).
#[test]
fn extruded_mean_edge_is_close_to_the_element_size() {
    for (r, h) in [(0.02, 1.2e-3), (1.0, 0.05), (1.0, 0.2)] {
        let spec = ExtrusionSpec {
            outline: Outline::Circle { center: [0.0, 0.0], radius: r },
            traces: vec![],
            z0: 0.0,
            thickness: h,
            element_size: h,
            layers: Some(1),
            region: region(),
        };
        let mesh = generate_extrusion(&spec).unwrap();
        let faces = &mesh.boundary_group("bottom").unwrap().faces;
        let mut sum = 0.0;
        for f in faces {
            let [a, b, c] = f.nodes(&mesh.tets).map(|n| mesh.point(n));
            sum += (b - a).norm() + (c - b).norm() + (a - c).norm();
        }
        let mean = sum / (3 * faces.len()) as f64;
        assert!(rel(mean, h) < 0.15, "r = {r}, h = {h}: mean in-plane edge {mean}");
    }
}

/// A tiny element size is refused from an estimate made before the 2D
/// triangulation (which would otherwise exhaust memory first): the paper's
/// disc at 1 µm would be about 8.7e10 tets.
#[test]
fn a_tiny_extrusion_element_size_is_refused_before_meshing() {
    let spec = ExtrusionSpec {
        outline: Outline::Circle { center: [0.0, 0.0], radius: 0.02 },
        traces: vec![],
        z0: 0.0,
        thickness: 0.015,
        element_size: 1e-6,
        layers: Some(10),
        region: region(),
    };
    // "about" is the wording of the estimate made before triangulating.
    match generate_extrusion(&spec) {
        Err(femdem_mesh::MeshError::InvalidParameter { name: "element_size", reason }) => {
            assert!(reason.contains("would make about 8.7"), "{reason}");
        }
        other => panic!("expected a refusal, got {:?}", other.map(|m| m.tets.len())),
    }
}

/// A rectangular outline gets a group per side (issue 11: a pressure per
/// face of the multi-layer block): together they are `side`, face for face,
/// each lies in its plane, and its area is that side's length times the
/// thickness. A trace ending on the outline (which puts a vertex on a side)
/// keeps the outline a rectangle. A non-rectangular outline has `side` only.
#[test]
fn a_rectangular_outline_has_a_group_per_side() {
    let (w, hgt, t) = (1.5, 1.2, 0.5);
    let spec = ExtrusionSpec {
        outline: Outline::Polygon(vec![[0.0, 0.0], [w, 0.0], [w, hgt], [0.0, hgt]]),
        traces: vec![vec![[0.0, 0.4], [w, 0.5]]],
        z0: 0.0,
        thickness: t,
        element_size: 0.15,
        layers: None,
        region: region(),
    };
    let mesh = generate_extrusion(&spec).unwrap();
    let side = &mesh.boundary_group("side").unwrap().faces;
    let mut union = Vec::new();
    for (name, k, v, length) in [("xmin", 0, 0.0, hgt), ("xmax", 0, w, hgt), ("ymin", 1, 0.0, w), ("ymax", 1, hgt, w)] {
        let faces = &mesh.boundary_group(name).unwrap().faces;
        assert!(!faces.is_empty(), "{name}");
        for f in faces {
            assert!(f.nodes(&mesh.tets).iter().all(|&n| mesh.point(n)[k] == v), "{name}: a face off its plane");
        }
        assert!(rel(group_area(&mesh, name), length * t) < 1e-12, "{name} area");
        union.extend(faces.iter().copied());
    }
    let key = |f: &femdem_mesh::FaceRef| (f.tet, f.local);
    union.sort_by_key(key);
    let mut all = side.clone();
    all.sort_by_key(key);
    assert_eq!(union, all, "xmin + xmax + ymin + ymax must be `side`, face for face");

    let quad = ExtrusionSpec { outline: Outline::Polygon(vec![[0.0, 0.0], [w, 0.1], [w, hgt], [0.0, hgt]]), ..spec };
    let mesh = generate_extrusion(&quad).unwrap();
    assert!(mesh.boundary_group("xmin").is_none() && mesh.boundary_group("side").is_some());
}

/// Regression (found by fuzzing the case loader): a trace point outside the
/// outline widened the region the 2D mesher refines far past the area the
/// size check estimates; a circle moved to x = 9.2e18 m with its trace
/// left near the origin refined for over ten minutes. Such a point is now
/// refused by the trace network before any refinement, naming the trace
/// and the point.
#[test]
fn a_trace_point_outside_the_outline_is_refused() {
    let spec = ExtrusionSpec {
        outline: Outline::Circle { center: [9.223372036854776e18, 0.0], radius: 0.01 },
        traces: vec![vec![[-0.004, 0.0], [0.004, 0.001]]],
        z0: 0.0,
        thickness: 0.004,
        element_size: 0.005,
        layers: Some(1),
        region: region(),
    };
    match generate_extrusion(&spec) {
        Err(femdem_mesh::MeshError::Trace { trace: 0, point: 0, reason }) => {
            assert!(reason.contains("outside the outline"), "{reason}");
        }
        other => panic!("expected a refusal, got {:?}", other.map(|m| m.tets.len())),
    }
    // A trace inside the same circle at the origin still meshes.
    let inside = ExtrusionSpec { outline: Outline::Circle { center: [0.0, 0.0], radius: 0.01 }, ..spec };
    assert!(generate_extrusion(&inside).is_ok());
}

/// Regression (found reading the generators while fuzzing): the box's cell counts saturate at `usize::MAX` for a huge
/// extent, and their integer product wrapped (`MAX × MAX = 1`), so a box of
/// `max = [1e300, 1e300, 1]` passed the tet-count cap as 6 tets and then
/// pushed vertices until memory ran out (in a debug build, an overflow
/// panic). The count is now
/// a floating-point product, and the box is refused.
#[test]
fn a_box_huge_on_two_axes_is_refused_not_wrapped() {
    let spec =
        BoxSpec { min: [0.0; 3], max: [1e300, 1e300, 1.0], element_size: 1.0, jitter: 0.0, seed: 0, region: region() };
    match generate_box(&spec) {
        Err(femdem_mesh::MeshError::InvalidParameter { name: "element_size", reason }) => {
            assert!(reason.contains("refuse above"), "{reason}");
            // The counts as they are (their product overflows an f64).
            assert!(reason.contains("would make about 1e601 tets (1.000e300×1.000e300×1 cells of 6)"), "{reason}");
        }
        other => panic!("expected a refusal, got {:?}", other.map(|m| m.tets.len())),
    }
    let fine = BoxSpec { max: [1.0, 1.0, 1.0], element_size: 1e-3, ..spec };
    let reason = generate_box(&fine).unwrap_err().to_string();
    assert!(reason.contains("1e-3 m would make 6000000000 tets (1000×1000×1000 cells of 6)"), "{reason}");
}

/// Regressions (found probing bad inputs): `z0 = NaN` meshed, and `femdem
/// check` printed a volume of NaN m³ (the run then stopped at "tet 0 has
/// non-positive volume"); a polygon whose vertices lie on one line meshed
/// no tets and `femdem check` passed it. Both are refused by name.
#[test]
fn a_non_finite_z0_and_a_flat_outline_are_refused() {
    let spec = ExtrusionSpec {
        outline: Outline::Polygon(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]),
        traces: vec![],
        z0: 0.0,
        thickness: 0.2,
        element_size: 0.25,
        layers: None,
        region: region(),
    };
    assert!(generate_extrusion(&spec).is_ok());
    for z0 in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        match generate_extrusion(&ExtrusionSpec { z0, ..spec.clone() }) {
            Err(femdem_mesh::MeshError::InvalidParameter { name: "z0", reason }) => {
                assert!(reason.contains("must be finite"), "{reason}");
            }
            other => panic!("z0 = {z0}: expected a refusal, got {:?}", other.map(|m| m.tets.len())),
        }
    }
    let flat = ExtrusionSpec { outline: Outline::Polygon(vec![[0.0, 0.0], [0.5, 0.0], [1.0, 0.0]]), ..spec };
    match generate_extrusion(&flat) {
        Err(femdem_mesh::MeshError::InvalidParameter { name: "outline", reason }) => {
            assert!(reason.contains("encloses no area"), "{reason}");
        }
        other => panic!("expected a refusal, got {:?}", other.map(|m| m.tets.len())),
    }
    // And a mesh of no tets fails the check, whatever made it.
    let empty = femdem_mesh::TetMesh { regions: vec![region()], ..Default::default() };
    assert!(
        matches!(femdem_mesh::check::check(&empty), Err(femdem_mesh::MeshError::Inconsistent(m)) if m.contains("no tets"))
    );
}

/// Two traces 2·10⁻⁵ m apart in an outline meshed at 0.05 m (above the
/// clearance refused before meshing, 5·10⁻⁶ m): the refinement would fill
/// the gap down to edges of its width, some 10⁵ vertices along it. It may
/// add at most twice the vertices whose triangles make the 2e8-tet limit in
/// the extrusion's layers (here 2,000 layers, so some 33k vertices and a
/// quick refusal), and its refusal names the place of the shortest edge:
/// on the gap, between x = 0.2 and 0.8 at y = 0.3.
#[test]
fn crowded_traces_are_refused_at_the_tet_limit_naming_the_gap() {
    let spec = ExtrusionSpec {
        outline: Outline::Polygon(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 0.6], [0.0, 0.6]]),
        traces: vec![vec![[0.2, 0.3], [0.8, 0.3]], vec![[0.2, 0.3 + 2e-5], [0.8, 0.3 + 2e-5]]],
        z0: 0.0,
        thickness: 1.0,
        element_size: 0.05,
        layers: Some(2000),
        region: region(),
    };
    let e = generate_extrusion(&spec).unwrap_err().to_string();
    assert!(e.contains("the mesh would exceed 2e8 tets: the refinement has to fill gaps far narrower"), "{e}");
    let at = |name: &str| -> f64 {
        let from = e.find(&format!("{name} = ")).unwrap() + name.len() + 3;
        e[from..].split([',', ' ']).next().unwrap().parse().unwrap()
    };
    assert!((0.2..=0.8).contains(&at("x")) && (at("y") - 0.3).abs() < 1e-4, "{e}");
}

/// A trace 10⁻⁷ m from the outline along 0.6 m of it, at 0.05 m in 4
/// layers: meshing it took three minutes and 5.6 GB and ended in a
/// degenerate tet. It is refused before the refinement, naming the point
/// and the gap; a trace 10⁻⁵ m off (above 10⁻⁴ × 0.05 m; 5 cm long, to
/// keep the test quick) meshes.
#[test]
fn features_closer_than_the_clearance_are_refused_before_meshing() {
    let spec = |gap: f64, end: f64| ExtrusionSpec {
        outline: Outline::Polygon(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 0.6], [0.0, 0.6]]),
        traces: vec![vec![[0.2, gap], [end, gap]]],
        z0: 0.0,
        thickness: 0.2,
        element_size: 0.05,
        layers: None,
        region: region(),
    };
    let e = generate_extrusion(&spec(1e-7, 0.8)).unwrap_err().to_string();
    assert!(
        e.contains("a point of a trace at (0.200000000, 0.000000100) m lies 1.000e-7 m from a segment of the outline"),
        "{e}"
    );
    assert!(e.contains("closer than 1e-4 of the element size or layer height (5.000e-6 m)"), "{e}");
    let mesh = generate_extrusion(&spec(1e-5, 0.25)).unwrap();
    femdem_mesh::check::check(&mesh).unwrap();
}
