//! The sections of MSH 2 (versions 2.0 to 2.2, Gmsh's "legacy" format,
//! ASCII and binary) that differ from MSH 4.1: `$Nodes` and `$Elements`.
//! `$MeshFormat` and `$PhysicalNames` are read as in 4.1, and the mesh is
//! assembled by the same code (`assemble.rs`).
//!
//! In MSH 2 there are no entity blocks: `$Nodes` is a count, then one
//! record `node-number x y z` per node; `$Elements` is a count, then one
//! record `elm-number elm-type number-of-tags tag… node-number…` per
//! element, whose first tag is its physical group (0: none) and second its
//! elementary entity. A binary file writes the counts as text lines and
//! the records in binary: a node as an `int` and three `double`s; the
//! elements in blocks, each an `int` header `elm-type
//! number-of-elements-following number-of-tags`, then per element `int`s
//! only (number, tags, nodes).
//!
//! An element in several physical groups is written once per group. For
//! triangles that puts the face in each boundary group, as in 4.1; a tet
//! can be in one region only, so a tet written twice (the same four nodes)
//! is refused with both places, as 4.1 refuses a volume in two physical
//! volumes.

use std::collections::{BTreeSet, HashMap};

use super::super::report::{element_type_name, element_type_nodes};
use super::super::source::{At, Source};
use super::{RawTriangle, Reader, TET, TRIANGLE, TagMap};
use crate::MeshError;

impl<'a, S: Source<'a>> Reader<S> {
    /// `$Nodes` of MSH 2.
    pub(super) fn nodes_v2(&mut self) -> Result<(), MeshError> {
        const S: &str = "Nodes";
        let lines = self.src.lines();
        let mut f = lines.record(S, || "the number of nodes".into())?;
        let n = f.count("number of nodes")?;
        f.end("the number of nodes")?;
        if u32::try_from(n).is_err() {
            return Err(f.err(format!("{n} nodes are more than femdem can index")));
        }
        let mut numbers = Vec::with_capacity(self.capacity(n));
        self.coords = Vec::with_capacity(self.capacity(n));
        self.coord_at = Vec::with_capacity(self.capacity(n));
        for i in 0..n {
            self.src.record(S, || format!("node {} of {n}", i + 1))?;
            let number = self.number("node number")?;
            let x = self.src.real("x coordinate")?;
            let y = self.src.real("y coordinate")?;
            let z = self.src.real("z coordinate")?;
            self.src.end("the node coordinates")?;
            numbers.push(number);
            self.coords.push([x, y, z]);
            self.coord_at.push(self.src.at());
        }
        let (min, max) = numbers.iter().fold((u64::MAX, 0), |(lo, hi), &t| (lo.min(t), hi.max(t)));
        let dense_limit = 2 * self.capacity(n) as u64 + 1024;
        let mut tags = if n > 0 && max - min < dense_limit {
            TagMap::Dense { min, idx: vec![u32::MAX; (max - min + 1) as usize] }
        } else {
            TagMap::Sparse(HashMap::with_capacity(self.capacity(n)))
        };
        for (i, &number) in numbers.iter().enumerate() {
            // `i < n`, which fits in u32 (checked above).
            if !tags.insert(number, i as u32) {
                let first = numbers.iter().position(|&t| t == number).expect("inserted before");
                return Err(self.coord_at[i].err(
                    S,
                    format!("node number {number} appears twice (first on {})", self.coord_at[first].describe()),
                ));
            }
        }
        self.tags = Some(tags);
        self.src.end_of(S)
    }

    /// `$Elements` of MSH 2.
    pub(super) fn elements_v2(&mut self) -> Result<(), MeshError> {
        const S: &str = "Elements";
        let header_at = self.src.lines().at();
        self.elements_at = Some(header_at);
        let Some(tags) = self.tags.take() else {
            return Err(header_at.err(S, "$Elements must come after $Nodes"));
        };
        let lines = self.src.lines();
        let mut f = lines.record(S, || "the number of elements".into())?;
        let n = f.count("number of elements")?;
        f.end("the number of elements")?;
        let mut seen = Seen::default();
        if self.src.fields().is_some() {
            for i in 0..n {
                self.src.record(S, || format!("element {} of {n}", i + 1))?;
                self.number("element number")?;
                let ty = self.src.uint("element type")?;
                let n_tags = self.src.count("number of tags")?;
                self.element_v2(&tags, &mut seen, ty, n_tags)?;
                self.src.end("the node numbers")?;
            }
        } else {
            let mut done = 0usize;
            while done < n {
                self.src.record(S, || "an element block header".into())?;
                let ty = self.src.uint("element type")?;
                let follow = self.src.uint("number of elements following")? as usize;
                if follow > n - done {
                    return Err(self.src.err(format!(
                        "a block of {follow} elements after {done}: more than the {n} announced by the \
                         $Elements header"
                    )));
                }
                if follow == 0 {
                    return Err(self.src.err("an element block of no elements (a corrupt file?)"));
                }
                let n_tags = self.src.uint("number of tags")? as usize;
                for _ in 0..follow {
                    self.src.record(S, || "an element".into())?;
                    self.number("element number")?;
                    self.element_v2(&tags, &mut seen, ty, n_tags)?;
                }
                done += follow;
            }
        }
        // Each physical volume is its own "entity", as `assemble` reads them.
        let volumes = self.volumes.get_or_insert_with(HashMap::new);
        volumes.extend(seen.volumes.into_iter().map(|p| (p, vec![p])));
        self.tags = Some(tags);
        self.src.end_of(S)
    }

    /// Every physical volume and surface `$PhysicalNames` names is a
    /// region or a boundary group, even one that holds no element (as an
    /// MSH 4.1 file's physical groups of entities that hold none are).
    pub(super) fn named_groups_v2(&mut self) {
        let volumes = self.volumes.get_or_insert_with(HashMap::new);
        for &(dim, p) in self.names.keys() {
            match dim {
                3 => {
                    volumes.entry(p).or_insert_with(|| vec![p]);
                }
                2 => {
                    self.surfaces.entry(p).or_insert_with(|| vec![p]);
                }
                _ => {}
            }
        }
    }

    /// The rest of one element record after its type `ty` and number of
    /// tags `n_tags`: the tags and the node numbers.
    fn element_v2(&mut self, tags: &TagMap, seen: &mut Seen, ty: u32, n_tags: usize) -> Result<(), MeshError> {
        let mut physical = 0;
        for k in 0..n_tags {
            let t = self.src.int("tag")?;
            if k == 0 {
                physical = t;
            }
        }
        if physical < 0 {
            return Err(self.src.err(format!("bad physical tag {physical}: expected 0 (none) or a positive tag")));
        }
        match ty {
            TET => {
                let nodes = self.element_nodes::<4>(tags)?;
                let mut key = nodes;
                key.sort_unstable();
                let at = self.src.at();
                if let Some(first) = seen.tets.insert(key, at) {
                    return Err(at.err(
                        "Elements",
                        format!(
                            "this tet has the four nodes of the tet on {}: a tet can belong to one region only \
                             (MSH 2 writes an element once for each physical group it is in: put each volume \
                             in one physical volume)",
                            first.describe()
                        ),
                    ));
                }
                let phys = (physical > 0).then_some(physical);
                if let Some(p) = phys {
                    seen.volumes.insert(p);
                }
                self.tets.push(nodes);
                self.tet_phys.push(phys);
            }
            TRIANGLE => {
                let nodes = self.element_nodes::<3>(tags)?;
                if physical > 0 {
                    self.surfaces.insert(physical, vec![physical]);
                    self.triangles.push(RawTriangle { nodes, entity: physical, at: self.src.at() });
                } else {
                    self.report.ungrouped_triangles += 1;
                }
            }
            _ => {
                *self.report.skipped_elements.entry(ty).or_insert(0) += 1;
                if self.src.fields().is_some() {
                    self.src.skip_element_nodes(ty)?;
                } else {
                    let Some(k) = element_type_nodes(ty) else {
                        return Err(self.src.err(format!(
                            "element type {ty} is not one femdem knows, so its node numbers cannot be skipped \
                             in a binary file; save the mesh as ASCII (in Gmsh, `Mesh.Binary = 0`) or without \
                             these elements"
                        )));
                    };
                    let name = format!("node number of a {}", element_type_name(ty).unwrap_or("element"));
                    for _ in 0..k {
                        self.number(&name)?;
                    }
                }
            }
        }
        Ok(())
    }

    /// The `K` node numbers of an element as file node indices.
    fn element_nodes<const K: usize>(&mut self, tags: &TagMap) -> Result<[u32; K], MeshError> {
        let mut nodes = [0u32; K];
        for v in &mut nodes {
            let number = self.number("node number")?;
            *v = tags.get(number).ok_or_else(|| self.src.err(format!("node number {number} is not in $Nodes")))?;
        }
        Ok(nodes)
    }

    /// A node or element number of MSH 2: an `int`, at least 1.
    fn number(&mut self, name: &str) -> Result<u64, MeshError> {
        let v = self.src.int(name)?;
        u64::try_from(v)
            .ok()
            .filter(|&v| v > 0)
            .ok_or_else(|| self.src.err(format!("bad {name} {v}: numbers start at 1")))
    }
}

/// What `$Elements` of MSH 2 has read so far: each tet's sorted nodes and
/// where it is, and the physical volumes that hold tets.
#[derive(Default)]
struct Seen {
    tets: HashMap<[u32; 4], At>,
    volumes: BTreeSet<i32>,
}
