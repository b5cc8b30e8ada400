//! Choosing nodes and faces of a jointed mesh for loads and constraints.

use femdem_core::Real;
use femdem_mesh::JointedMesh;

/// A selection of nodes: the intersection of the criteria given (an empty
/// selection selects every node).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NodeSelection {
    /// Nodes on the faces of this boundary group.
    pub group: Option<String>,
    /// Nodes of the tets of this region.
    pub region: Option<String>,
    /// Nodes whose initial position lies in this box `(min, max)`.
    pub within: Option<([Real; 3], [Real; 3])>,
}

/// A selection that names something the mesh does not have.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownName {
    /// `"group"` or `"region"`.
    pub kind: &'static str,
    /// The name asked for.
    pub name: String,
    /// The names available.
    pub available: Vec<String>,
}

/// The boundary group called `name`.
fn group<'a>(mesh: &'a JointedMesh, name: &str) -> Result<&'a femdem_mesh::BoundaryGroup, UnknownName> {
    let m = &mesh.mesh;
    m.boundary_group(name).ok_or_else(|| UnknownName {
        kind: "group",
        name: name.to_string(),
        available: m.boundary.iter().map(|g| g.name.clone()).collect(),
    })
}

/// The selected node ids, sorted.
///
/// # Errors
/// [`UnknownName`] for a group or region the mesh lacks.
pub fn select_nodes(mesh: &JointedMesh, s: &NodeSelection) -> Result<Vec<u32>, UnknownName> {
    let m = &mesh.mesh;
    let mut keep = vec![true; m.num_nodes()];
    if let Some(name) = &s.group {
        let g = group(mesh, name)?;
        let mut on = vec![false; m.num_nodes()];
        for f in &g.faces {
            for n in f.nodes(&m.tets) {
                on[n as usize] = true;
            }
        }
        keep.iter_mut().zip(&on).for_each(|(k, o)| *k &= o);
    }
    if let Some(name) = &s.region {
        let r = m.region_index(name).ok_or_else(|| UnknownName {
            kind: "region",
            name: name.clone(),
            available: m.regions.iter().map(|r| r.name.clone()).collect(),
        })?;
        let mut on = vec![false; m.num_nodes()];
        for (t, tet) in m.tets.iter().enumerate() {
            if m.tet_region[t] == r {
                for &n in tet {
                    on[n as usize] = true;
                }
            }
        }
        keep.iter_mut().zip(&on).for_each(|(k, o)| *k &= o);
    }
    if let Some((lo, hi)) = s.within {
        for (k, c) in keep.iter_mut().zip(&m.coords) {
            *k &= (0..3).all(|a| c[a] >= lo[a] && c[a] <= hi[a]);
        }
    }
    Ok((0..m.num_nodes() as u32).filter(|&i| keep[i as usize]).collect())
}

/// The faces of a boundary group as outward node triples of the jointed
/// mesh.
///
/// # Errors
/// [`UnknownName`] for a group the mesh lacks.
pub fn group_faces(mesh: &JointedMesh, name: &str) -> Result<Vec<[u32; 3]>, UnknownName> {
    let g = group(mesh, name)?;
    Ok(g.faces.iter().map(|f| f.nodes(&mesh.mesh.tets)).collect())
}
