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
//! is refused with both element numbers, as 4.1 refuses a volume in two
//! physical volumes.
//!
//! With `Mesh.SaveAll = 1` Gmsh writes every element with physical tag 0
//! and still names the physical groups: read as it stands, such a file
//! would put every tet in one unnamed region and every named group would
//! be empty, so it is refused. The other sections Gmsh may add to MSH 2 are
//! skipped (`$Entities`, which `Mesh.SaveTopology = 1` writes) or refused
//! with what to change (`$ParametricNodes`).

use std::collections::HashMap;

use super::super::report::{element_type_name, element_type_nodes};
use super::super::source::{At, Source};
use super::{ANY_DIMENSION, RawTriangle, Reader, TET, TRIANGLE, TagMap};
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
        // The tets' element numbers, for an error about two of them.
        let mut numbers = Vec::new();
        if self.src.fields().is_some() {
            for i in 0..n {
                self.src.record(S, || format!("element {} of {n}", i + 1))?;
                let number = self.number("element number")?;
                let ty = self.src.uint("element type")?;
                let n_tags = self.src.count("number of tags")?;
                self.element_v2(&tags, &mut numbers, (number, ty), n_tags)?;
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
                    let number = self.number("element number")?;
                    self.element_v2(&tags, &mut numbers, (number, ty), n_tags)?;
                }
                done += follow;
            }
        }
        self.refuse_repeated_tets(&numbers, header_at)?;
        self.tags = Some(tags);
        self.src.end_of(S)
    }

    /// Refuses two tets of this `$Elements` (`numbers`: their element
    /// numbers, in the order read) with the same four nodes (the module
    /// documentation), naming both. A sort of the tets' node sets, not a
    /// map: a few bytes a tet beside what is read anyway.
    fn refuse_repeated_tets(&self, numbers: &[u64], at: At) -> Result<(), MeshError> {
        let first = self.tets.len() - numbers.len();
        let mut keys: Vec<([u32; 4], u32)> = (first..self.tets.len())
            .map(|t| {
                let mut k = self.tets[t];
                k.sort_unstable();
                (k, (t - first) as u32)
            })
            .collect();
        keys.sort_unstable();
        match keys.windows(2).find(|w| w[0].0 == w[1].0) {
            None => Ok(()),
            Some(w) => Err(at.err(
                "Elements",
                format!(
                    "elements {} and {} are tets on the same four nodes: a tet can belong to one region only \
                     (MSH 2 writes an element once for each physical group it is in: put each volume in one \
                     physical volume)",
                    numbers[w[0].1 as usize], numbers[w[1].1 as usize]
                ),
            )),
        }
    }

    /// The physical groups as `assemble` reads them, each its own
    /// "entity": those of the tets and triangles read, and every physical
    /// volume and surface `$PhysicalNames` names, even one that holds no
    /// element (MSH 2 has no entities to say more). A file whose named
    /// physical groups hold no element at all, as `Mesh.SaveAll = 1` writes
    /// it, is refused (the module documentation).
    pub(super) fn groups_v2(&mut self) -> Result<(), MeshError> {
        let named = |d: i32| self.names.keys().any(|&(dim, _)| dim == d);
        // A file without tets is not refused here: `assemble` says that it
        // has none, which is the trouble then.
        let tets_grouped = self.tet_phys.is_empty() || self.tet_phys.iter().any(Option::is_some);
        let triangles_grouped = !self.triangles.is_empty();
        let ungrouped = self.report.ungrouped_triangles > 0;
        if (named(3) && !tets_grouped)
            || (named(2) && ungrouped && !triangles_grouped)
            || (named(ANY_DIMENSION) && !tets_grouped && !triangles_grouped)
        {
            let at = self.elements_at.unwrap_or(At::Line(1));
            return Err(at.err(
                "Elements",
                "$PhysicalNames names physical groups, but every element has physical tag 0: Gmsh writes MSH 2 \
                 so with `Mesh.SaveAll = 1`, which would leave every tet in one unnamed region and every \
                 named group empty; save with `Mesh.SaveAll = 0`, or as MSH 4.1 (`Mesh.MshFileVersion = 4.1`)",
            ));
        }
        let volumes = self.volumes.get_or_insert_with(HashMap::new);
        for &p in self.tet_phys.iter().flatten() {
            volumes.entry(p).or_insert_with(|| vec![p]);
        }
        for t in &self.triangles {
            self.surfaces.entry(t.entity).or_insert_with(|| vec![t.entity]);
        }
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
        Ok(())
    }

    /// The rest of one element record after its number and type and its
    /// number of tags `n_tags`: the tags and the node numbers.
    fn element_v2(
        &mut self,
        tags: &TagMap,
        tet_numbers: &mut Vec<u64>,
        (number, ty): (u64, u32),
        n_tags: usize,
    ) -> Result<(), MeshError> {
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
                tet_numbers.push(number);
                self.tets.push(nodes);
                self.tet_phys.push((physical > 0).then_some(physical));
            }
            TRIANGLE => {
                let nodes = self.element_nodes::<3>(tags)?;
                if physical > 0 {
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
