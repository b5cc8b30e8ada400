//! The ASCII MSH 4.1 writer.

use std::fmt::Write as _;

use crate::TetMesh;

/// Writes `mesh` as an ASCII Gmsh MSH 4.1 file that Gmsh and
/// [`read_msh`](super::read_msh) accept.
///
/// Region `r` becomes volume entity `r + 1` in physical volume `r + 1`,
/// named after the region; boundary group `g` becomes surface entity
/// `g + 1` in physical surface `g + 1`, named after the group, holding one
/// triangle per face in the face's outward node order. All nodes are
/// written, with tags `1..=n` in index order, on the first volume entity.
/// Tets keep their order (one element block per run of tets of the same
/// region), so that reading the file back gives the same tet indices.
///
/// Not stored: [`Region::breakable`](crate::Region::breakable) (MSH has no
/// such notion; the case file says which regions may fracture) and
/// [`TetMesh::fracture_faces`]. A `"` in a name, which MSH cannot quote,
/// is written as `'`, and line breaks as spaces. Coordinates are written in
/// shortest round-trip form, so reading them back gives the same `f64`s.
///
/// # Panics
/// If `tets` and `tet_region` differ in length, or a boundary face names a
/// tet that does not exist (a mesh that fails [`check`](crate::check::check)
/// or has stale groups).
pub fn write_msh(mesh: &TetMesh) -> String {
    let num_volumes = mesh.tet_region.iter().map(|&r| usize::from(r) + 1).max().unwrap_or(0).max(mesh.regions.len());
    // Nodes need an entity to live on, even in a mesh with no regions.
    let num_volume_entities = num_volumes.max(usize::from(!mesh.coords.is_empty()));
    let num_groups = mesh.boundary.len();

    let mut out = String::with_capacity(64 * (mesh.coords.len() + mesh.tets.len()) + 1024);
    out.push_str("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");

    // Regions beyond `mesh.regions` (only in a mesh whose region ids are out
    // of range) get a physical tag but no name.
    out.push_str("$PhysicalNames\n");
    let _ = writeln!(out, "{}", num_groups + mesh.regions.len());
    for (g, group) in mesh.boundary.iter().enumerate() {
        let _ = writeln!(out, "2 {} \"{}\"", g + 1, quotable(&group.name));
    }
    for (r, region) in mesh.regions.iter().enumerate() {
        let _ = writeln!(out, "3 {} \"{}\"", r + 1, quotable(&region.name));
    }
    out.push_str("$EndPhysicalNames\n");

    // Entity bounding boxes, from the nodes of their elements.
    let mut volume_box = vec![EMPTY_BOX; num_volume_entities];
    for (t, &r) in mesh.tets.iter().zip(&mesh.tet_region) {
        for &v in t {
            grow(&mut volume_box[usize::from(r)], mesh.coords[v as usize]);
        }
    }
    let mut surface_box = vec![EMPTY_BOX; num_groups];
    for (g, group) in mesh.boundary.iter().enumerate() {
        for f in &group.faces {
            for v in f.nodes(&mesh.tets) {
                grow(&mut surface_box[g], mesh.coords[v as usize]);
            }
        }
    }

    out.push_str("$Entities\n");
    let _ = writeln!(out, "0 0 {num_groups} {num_volume_entities}");
    for (g, b) in surface_box.iter().enumerate() {
        let _ = write!(out, "{}", g + 1);
        push_box(&mut out, b);
        let _ = writeln!(out, " 1 {} 0", g + 1);
    }
    for (r, b) in volume_box.iter().enumerate() {
        let _ = write!(out, "{}", r + 1);
        push_box(&mut out, b);
        if r < num_volumes {
            let _ = writeln!(out, " 1 {} 0", r + 1);
        } else {
            out.push_str(" 0 0\n");
        }
    }
    out.push_str("$EndEntities\n");

    let n = mesh.coords.len();
    out.push_str("$Nodes\n");
    if n == 0 {
        out.push_str("0 0 0 0\n");
    } else {
        let _ = writeln!(out, "1 {n} 1 {n}\n3 1 0 {n}");
        for i in 1..=n {
            let _ = writeln!(out, "{i}");
        }
        for c in &mesh.coords {
            push_real(&mut out, c[0]);
            out.push(' ');
            push_real(&mut out, c[1]);
            out.push(' ');
            push_real(&mut out, c[2]);
            out.push('\n');
        }
    }
    out.push_str("$EndNodes\n");

    // Element blocks: one per non-empty group, then one per run of tets of
    // the same region.
    let mut runs: Vec<(u16, &[[u32; 4]])> = Vec::new();
    let mut start = 0;
    for t in 1..=mesh.tets.len() {
        if t == mesh.tets.len() || mesh.tet_region[t] != mesh.tet_region[start] {
            runs.push((mesh.tet_region[start], &mesh.tets[start..t]));
            start = t;
        }
    }
    let num_faces: usize = mesh.boundary.iter().map(|g| g.faces.len()).sum();
    let num_elements = num_faces + mesh.tets.len();
    let num_blocks = mesh.boundary.iter().filter(|g| !g.faces.is_empty()).count() + runs.len();
    out.push_str("$Elements\n");
    let _ = writeln!(out, "{num_blocks} {num_elements} {} {num_elements}", usize::from(num_elements > 0));
    let mut tag = 0usize;
    for (g, group) in mesh.boundary.iter().enumerate() {
        if group.faces.is_empty() {
            continue;
        }
        let _ = writeln!(out, "2 {} 2 {}", g + 1, group.faces.len());
        for f in &group.faces {
            let [a, b, c] = f.nodes(&mesh.tets);
            tag += 1;
            let _ = writeln!(out, "{tag} {} {} {}", a + 1, b + 1, c + 1);
        }
    }
    for (r, tets) in runs {
        let _ = writeln!(out, "3 {} 4 {}", usize::from(r) + 1, tets.len());
        for [a, b, c, d] in tets {
            tag += 1;
            let _ = writeln!(out, "{tag} {} {} {} {}", a + 1, b + 1, c + 1, d + 1);
        }
    }
    out.push_str("$EndElements\n");
    out
}

const EMPTY_BOX: [[f64; 3]; 2] = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];

fn grow(b: &mut [[f64; 3]; 2], p: [f64; 3]) {
    for k in 0..3 {
        b[0][k] = b[0][k].min(p[k]);
        b[1][k] = b[1][k].max(p[k]);
    }
}

/// Writes ` minX minY minZ maxX maxY maxZ`; an empty box as zeros.
fn push_box(out: &mut String, b: &[[f64; 3]; 2]) {
    let b = if b[0][0] <= b[1][0] { *b } else { [[0.0; 3]; 2] };
    for x in b.iter().flatten() {
        out.push(' ');
        push_real(out, *x);
    }
}

/// Shortest decimal form that reads back as the same `f64`, in positional
/// notation for ordinary magnitudes and in exponent notation otherwise
/// (Rust's `{}` would spell 1e-300 with 300 zeros).
fn push_real(out: &mut String, x: f64) {
    let _ = if x == 0.0 || (1e-5..1e16).contains(&x.abs()) { write!(out, "{x}") } else { write!(out, "{x:e}") };
}

/// `name` with the characters MSH cannot hold in a quoted name replaced.
fn quotable(name: &str) -> String {
    name.replace('"', "'").replace(['\n', '\r'], " ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn real(x: f64) -> String {
        let mut s = String::new();
        push_real(&mut s, x);
        s
    }

    #[test]
    fn reals_are_short_and_exact() {
        assert_eq!(real(0.01), "0.01");
        assert_eq!(real(-0.0), "-0");
        assert_eq!(real(1e-300), "1e-300");
        assert_eq!(real(2.5e20), "2.5e20");
        assert_eq!(real(0.1 + 0.2), "0.30000000000000004");
        for x in [1e-300, 3e-6, 0.1 + 0.2, 1e15 + 1.0, 1.7976931348623157e308] {
            assert_eq!(real(x).parse::<f64>().unwrap(), x);
        }
    }

    #[test]
    fn quotes_in_names_are_replaced() {
        assert_eq!(quotable("a \"b\"\nc"), "a 'b' c");
    }
}
