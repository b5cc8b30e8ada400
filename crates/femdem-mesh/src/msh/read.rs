//! The ASCII MSH 4.1 reader.
//!
//! The file is read line by line: Gmsh writes one record per line, so a
//! record with too few or too many fields is reported on its own line
//! instead of shifting every later record. Counts given by headers are
//! checked against what follows, but never trusted for allocation.

use std::collections::hash_map::Entry;
use std::collections::{BTreeSet, HashMap};

mod assemble;

use super::lex::{Fields, Lines, err_at};
use super::report::MshReport;
use super::report::element_type_nodes;
use crate::{MeshError, TetMesh};

/// Gmsh element type of the 3-node triangle.
const TRIANGLE: u32 = 2;
/// Gmsh element type of the 4-node tetrahedron.
const TET: u32 = 4;
/// Name of the region that takes tets of volumes in no physical group.
const UNNAMED: &str = "unnamed";

/// Reads an ASCII Gmsh MSH 4.1 file; see the [module docs](super) for what
/// is kept. Use [`read_msh_report`] to also learn what was skipped.
///
/// # Errors
/// [`MeshError::Msh`] with the 1-based line of the first problem, for any
/// malformed input, a binary file, a version other than 4.1, or a file with
/// no 4-node tets.
pub fn read_msh(bytes: &[u8]) -> Result<TetMesh, MeshError> {
    read_msh_report(bytes).map(|(mesh, _)| mesh)
}

/// Like [`read_msh`], and also reports the skipped elements, dropped nodes
/// and reoriented tets.
///
/// # Errors
/// As [`read_msh`].
pub fn read_msh_report(bytes: &[u8]) -> Result<(TetMesh, MshReport), MeshError> {
    Reader::new(bytes).read()
}

/// Node tag → index into the file's node list.
enum TagMap {
    /// Tags in `min..min + idx.len()`; `u32::MAX` marks a missing tag.
    Dense {
        min: u64,
        idx: Vec<u32>,
    },
    Sparse(HashMap<u64, u32>),
}

impl TagMap {
    fn get(&self, tag: u64) -> Option<u32> {
        match self {
            TagMap::Dense { min, idx } => {
                let i = usize::try_from(tag.checked_sub(*min)?).ok()?;
                idx.get(i).copied().filter(|&v| v != u32::MAX)
            }
            TagMap::Sparse(m) => m.get(&tag).copied(),
        }
    }

    /// Inserts; `false` if the tag was already there.
    fn insert(&mut self, tag: u64, index: u32) -> bool {
        match self {
            TagMap::Dense { min, idx } => {
                let slot = tag.checked_sub(*min).and_then(|i| usize::try_from(i).ok()).and_then(|i| idx.get_mut(i));
                match slot {
                    Some(s) if *s == u32::MAX => {
                        *s = index;
                        true
                    }
                    _ => false,
                }
            }
            TagMap::Sparse(m) => match m.entry(tag) {
                Entry::Occupied(_) => false,
                Entry::Vacant(e) => {
                    e.insert(index);
                    true
                }
            },
        }
    }
}

/// A triangle waiting for the tets: file node indices, its surface entity,
/// and its line.
struct RawTriangle {
    nodes: [u32; 3],
    entity: i32,
    line: usize,
}

struct Reader<'a> {
    lines: Lines<'a>,
    /// Bound on any count worth allocating for: the file's size.
    file_len: usize,
    report: MshReport,
    /// `(dim, tag)` → physical name.
    names: HashMap<(i32, i32), String>,
    /// Volume entity → physical tags; `None` until `$Entities` is read.
    volumes: Option<HashMap<i32, Vec<i32>>>,
    /// Surface entity → physical tags.
    surfaces: HashMap<i32, Vec<i32>>,
    coords: Vec<[f64; 3]>,
    /// Line of each node's coordinates.
    coord_lines: Vec<usize>,
    tags: Option<TagMap>,
    /// Tets in file node indices, with the physical tag of their volume.
    tets: Vec<[u32; 4]>,
    tet_phys: Vec<Option<i32>>,
    triangles: Vec<RawTriangle>,
    /// Line of the `$Elements` header, once read.
    elements_line: Option<usize>,
}

impl<'a> Reader<'a> {
    fn new(bytes: &'a [u8]) -> Self {
        Reader {
            lines: Lines { rest: bytes, line: 0 },
            file_len: bytes.len(),
            report: MshReport::default(),
            names: HashMap::new(),
            volumes: None,
            surfaces: HashMap::new(),
            coords: Vec::new(),
            coord_lines: Vec::new(),
            tags: None,
            tets: Vec::new(),
            tet_phys: Vec::new(),
            triangles: Vec::new(),
            elements_line: None,
        }
    }

    /// A capacity for `n` announced items that a malicious header cannot
    /// blow up: no item takes less than two bytes of file.
    fn capacity(&self, n: usize) -> usize {
        n.min(self.file_len / 2)
    }

    fn read(mut self) -> Result<(TetMesh, MshReport), MeshError> {
        let mut seen_format = false;
        let mut seen = BTreeSet::new();
        while let Some(line) = self.lines.next_line()? {
            let header = line.trim();
            if header.is_empty() {
                continue;
            }
            let Some(name) = header.strip_prefix('$') else {
                return Err(self.lines.err(format!("expected a section header such as $Nodes, found `{header}`")));
            };
            if name.starts_with("End") {
                return Err(self.lines.err(format!("`{header}` closes no open section")));
            }
            if !seen_format && name != "MeshFormat" {
                return Err(self
                    .lines
                    .err(format!("expected $MeshFormat first, found `{header}` (not a Gmsh MSH file?)")));
            }
            let known = matches!(name, "MeshFormat" | "PhysicalNames" | "Entities" | "Nodes" | "Elements");
            if known && !seen.insert(name.to_owned()) {
                return Err(self.lines.err(format!("second ${name} section")));
            }
            match name {
                "MeshFormat" => {
                    self.mesh_format()?;
                    seen_format = true;
                }
                "PhysicalNames" => self.physical_names()?,
                "Entities" => {
                    if self.elements_line.is_some() {
                        return Err(self.lines.err("$Entities must come before $Elements"));
                    }
                    self.entities()?;
                }
                "Nodes" => self.nodes()?,
                "Elements" => self.elements()?,
                "PartitionedEntities" => {
                    return Err(self.lines.err("partitioned meshes are not supported: save without partitions"));
                }
                _ => self.skip_section(name)?,
            }
        }
        if !seen_format {
            return Err(self.lines.err("empty file: no $MeshFormat section"));
        }
        if self.elements_line.is_none() {
            return Err(self.lines.err("file ends without an $Elements section"));
        }
        self.assemble()
    }

    fn skip_section(&mut self, name: &str) -> Result<(), MeshError> {
        let start = self.lines.line;
        let end = format!("$End{name}");
        while let Some(l) = self.lines.next_line()? {
            if l.trim() == end {
                return Ok(());
            }
        }
        Err(err_at(start, format!("section ${name} is never closed by {end}")))
    }

    fn mesh_format(&mut self) -> Result<(), MeshError> {
        let mut f = self.lines.record("MeshFormat", || "`version file-type data-size`".into())?;
        let version = f.token("version")?;
        if version != "4.1" {
            return Err(f.err(format!(
                "MSH version {version} is not supported: femdem reads MSH 4.1 \
                 (in Gmsh, save with `Mesh.MshFileVersion = 4.1`)"
            )));
        }
        let file_type = f.count("file type")?;
        match file_type {
            0 => {}
            1 => {
                return Err(f.err(
                    "binary MSH files are not supported: save as ASCII \
                     (in Gmsh, `Mesh.Binary = 0`)",
                ));
            }
            other => return Err(f.err(format!("bad file type {other}: expected 0 (ASCII)"))),
        }
        f.count("data size")?;
        f.end("the data size")?;
        self.lines.end_of("MeshFormat")
    }

    fn physical_names(&mut self) -> Result<(), MeshError> {
        const S: &str = "PhysicalNames";
        let mut f = self.lines.record(S, || "the number of physical names".into())?;
        let n = f.count("number of physical names")?;
        f.end("the number of physical names")?;
        for i in 0..n {
            let f = self.lines.record(S, || format!("physical name {} of {n}", i + 1))?;
            // `dim tag "name"`; the name may hold any run of spaces.
            let raw = f.raw;
            let (head, quoted) = raw.split_at(raw.find('"').unwrap_or(raw.len()));
            let mut h = Fields { raw: head, it: head.split_ascii_whitespace(), line: f.line };
            let dim = h.int("dimension")?;
            let tag = h.int("physical tag")?;
            h.end("the physical tag")?;
            let quoted = quoted.trim_end();
            let name = quoted
                .strip_prefix('"')
                .and_then(|r| r.strip_suffix('"'))
                .ok_or_else(|| h.err(format!("expected a quoted name, found `{quoted}`")))?;
            if !(0..=3).contains(&dim) {
                return Err(h.err(format!("bad dimension {dim}: expected 0 to 3")));
            }
            self.names.insert((dim, tag), name.to_owned());
        }
        self.lines.end_of(S)
    }

    fn entities(&mut self) -> Result<(), MeshError> {
        const S: &str = "Entities";
        let mut f = self.lines.record(S, || "`numPoints numCurves numSurfaces numVolumes`".into())?;
        let mut counts = [0usize; 4];
        for (c, name) in counts.iter_mut().zip(["points", "curves", "surfaces", "volumes"]) {
            *c = f.count(&format!("number of {name}"))?;
        }
        f.end("the number of volumes")?;
        let mut volumes = HashMap::new();
        for (dim, &n) in counts.iter().enumerate() {
            let kind = ["point", "curve", "surface", "volume"][dim];
            let mut tags_seen = BTreeSet::new();
            for i in 0..n {
                let mut f = self.lines.record(S, || format!("{kind} entity {} of {n}", i + 1))?;
                let tag = f.int(&format!("{kind} tag"))?;
                if !tags_seen.insert(tag) {
                    return Err(f.err(format!("{kind} entity {tag} listed twice")));
                }
                let n_coords = if dim == 0 { 3 } else { 6 };
                for _ in 0..n_coords {
                    f.real("bounding-box coordinate")?;
                }
                let n_phys = f.count("number of physical tags")?;
                let mut phys = Vec::with_capacity(n_phys.min(16));
                for _ in 0..n_phys {
                    phys.push(f.int("physical tag")?);
                }
                if dim > 0 {
                    let n_bound = f.count("number of bounding entities")?;
                    for _ in 0..n_bound {
                        f.int("bounding entity tag")?;
                    }
                }
                f.end(&format!("the {kind} entity"))?;
                match dim {
                    2 => {
                        self.surfaces.insert(tag, phys);
                    }
                    3 => {
                        volumes.insert(tag, phys);
                    }
                    _ => {}
                }
            }
        }
        self.volumes = Some(volumes);
        self.lines.end_of(S)
    }

    fn nodes(&mut self) -> Result<(), MeshError> {
        const S: &str = "Nodes";
        let mut f = self.lines.record(S, || "`numEntityBlocks numNodes minNodeTag maxNodeTag`".into())?;
        let n_blocks = f.count("number of entity blocks")?;
        let n_nodes = f.count("number of nodes")?;
        let (min, max) = if n_nodes == 0 {
            (f.count("minimum node tag")? as u64, f.count("maximum node tag")? as u64)
        } else {
            (f.node_tag("minimum node tag")?, f.node_tag("maximum node tag")?)
        };
        f.end("the maximum node tag")?;
        if n_nodes > 0 && max < min {
            return Err(f.err(format!("maximum node tag {max} is below the minimum {min}")));
        }
        if u32::try_from(n_nodes).is_err() {
            return Err(f.err(format!("{n_nodes} nodes are more than femdem can index")));
        }
        let range = max.saturating_sub(min).saturating_add(1);
        let dense_limit = 2 * self.capacity(n_nodes) as u64 + 1024;
        let mut tags = if range <= dense_limit {
            TagMap::Dense { min, idx: vec![u32::MAX; range as usize] }
        } else {
            TagMap::Sparse(HashMap::with_capacity(self.capacity(n_nodes)))
        };
        self.coords = Vec::with_capacity(self.capacity(n_nodes));
        for b in 0..n_blocks {
            let mut f = self.lines.record(S, || format!("entity block {} of {n_blocks}", b + 1))?;
            let dim = f.int("entity dimension")?;
            f.int("entity tag")?;
            let parametric = f.count("parametric flag")?;
            let n = f.count("number of nodes in block")?;
            f.end("the number of nodes in the block")?;
            if !(0..=3).contains(&dim) {
                return Err(f.err(format!("bad entity dimension {dim}: expected 0 to 3")));
            }
            if parametric > 1 {
                return Err(f.err(format!("bad parametric flag {parametric}: expected 0 or 1")));
            }
            let base = self.coords.len();
            if n > n_nodes - base {
                return Err(f.err(format!("blocks hold more nodes than the {n_nodes} announced by the $Nodes header")));
            }
            let header_line = self.lines.line;
            // A wrong count in the block header shows as a record of the
            // wrong shape: say so, rather than what the misread field is.
            let miscount = |f: &super::lex::Fields<'_>, expected: &str, found: usize| {
                f.err(format!(
                    "{found} number(s) where {expected} was expected: does the block header on line {header_line} \
                     announce the right number of nodes ({n})?"
                ))
            };
            for i in 0..n {
                let mut f = self.lines.record(S, || format!("tag of node {} of block {}", i + 1, b + 1))?;
                let fields = f.raw.split_ascii_whitespace().count();
                if fields != 1 {
                    return Err(miscount(&f, &format!("the tag of node {} of block {}", i + 1, b + 1), fields));
                }
                let tag = f.node_tag("node tag")?;
                f.end("the node tag")?;
                if !(min..=max).contains(&tag) {
                    return Err(f.err(format!("node tag {tag} is outside the header's range {min}..={max}")));
                }
                // `base + i < n_nodes`, which fits in u32 (checked above).
                if !tags.insert(tag, (base + i) as u32) {
                    return Err(f.err(format!("node tag {tag} appears twice")));
                }
            }
            let extra = if parametric == 1 { dim as usize } else { 0 };
            for i in 0..n {
                let mut f = self.lines.record(S, || format!("coordinates of node {} of block {}", i + 1, b + 1))?;
                let fields = f.raw.split_ascii_whitespace().count();
                if fields < 3 {
                    let what = format!("the coordinates of node {} of block {}", i + 1, b + 1);
                    return Err(miscount(&f, &what, fields));
                }
                let x = f.real("x coordinate")?;
                let y = f.real("y coordinate")?;
                let z = f.real("z coordinate")?;
                for _ in 0..extra {
                    f.real("parametric coordinate")?;
                }
                f.end("the node coordinates")?;
                self.coords.push([x, y, z]);
                self.coord_lines.push(self.lines.line);
            }
        }
        if self.coords.len() != n_nodes {
            // Report on the line that should have been a block header.
            self.lines.next_line()?;
            return Err(self
                .lines
                .err(format!("the $Nodes header announces {n_nodes} nodes, the blocks hold {}", self.coords.len())));
        }
        self.tags = Some(tags);
        self.lines.end_of(S)
    }

    fn elements(&mut self) -> Result<(), MeshError> {
        const S: &str = "Elements";
        self.elements_line = Some(self.lines.line);
        let Some(tags) = self.tags.take() else {
            return Err(self.lines.err("$Elements must come after $Nodes"));
        };
        let mut f = self.lines.record(S, || "`numEntityBlocks numElements minTag maxTag`".into())?;
        let n_blocks = f.count("number of entity blocks")?;
        let n_elements = f.count("number of elements")?;
        f.count("minimum element tag")?;
        f.count("maximum element tag")?;
        f.end("the maximum element tag")?;
        let mut total = 0usize;
        for b in 0..n_blocks {
            let mut f = self.lines.record(S, || format!("entity block {} of {n_blocks}", b + 1))?;
            let dim = f.int("entity dimension")?;
            let entity = f.int("entity tag")?;
            let ty: u32 = f.parse("element type", "a positive integer")?;
            let n = f.count("number of elements in block")?;
            f.end("the number of elements in the block")?;
            total = total.saturating_add(n);
            if total > n_elements {
                return Err(f.err(format!(
                    "blocks hold more elements than the {n_elements} announced by the \
                     $Elements header"
                )));
            }
            match ty {
                TET => self.tet_block(&tags, dim, entity, n, f.line)?,
                TRIANGLE => self.triangle_block(&tags, dim, entity, n, f.line)?,
                _ => {
                    *self.report.skipped_elements.entry(ty).or_insert(0) += n;
                    for i in 0..n {
                        let mut f = self.lines.record(S, || format!("element {} of block {}", i + 1, b + 1))?;
                        f.node_tag("element tag")?;
                        let nodes = f.it.by_ref().count();
                        let ok = match element_type_nodes(ty) {
                            Some(k) => nodes == k,
                            None => nodes > 0,
                        };
                        if !ok {
                            let k = element_type_nodes(ty).unwrap_or(0);
                            return Err(f.err(format!("element of type {ty} has {nodes} node tags, expected {k}")));
                        }
                    }
                }
            }
        }
        if total != n_elements {
            self.lines.next_line()?;
            return Err(self
                .lines
                .err(format!("the $Elements header announces {n_elements} elements, the blocks hold {total}")));
        }
        self.tags = Some(tags);
        self.lines.end_of(S)
    }

    /// Reads the `K` node tags of one element line as file node indices.
    fn element<const K: usize>(
        &mut self,
        tags: &TagMap,
        what: impl FnOnce() -> String,
    ) -> Result<([u32; K], usize), MeshError> {
        let mut f = self.lines.record("Elements", what)?;
        f.node_tag("element tag")?;
        let mut nodes = [0u32; K];
        for v in &mut nodes {
            let tag = f.node_tag("node tag")?;
            *v = tags.get(tag).ok_or_else(|| f.err(format!("node tag {tag} is not in $Nodes")))?;
        }
        let line = f.line;
        f.end("the node tags")?;
        Ok((nodes, line))
    }

    fn tet_block(&mut self, tags: &TagMap, dim: i32, entity: i32, n: usize, line: usize) -> Result<(), MeshError> {
        if dim != 3 {
            return Err(err_at(line, format!("tets (type 4) on an entity of dimension {dim}")));
        }
        let phys = match &self.volumes {
            None => None,
            Some(v) => match v.get(&entity).map(Vec::as_slice) {
                None => {
                    return Err(err_at(line, format!("volume entity {entity} is not listed in $Entities")));
                }
                Some([]) => None,
                Some([p]) => Some(*p),
                Some(many) => {
                    return Err(err_at(
                        line,
                        format!(
                            "volume entity {entity} is in {} physical volumes {many:?}; \
                             a tet can belong to one region only",
                            many.len()
                        ),
                    ));
                }
            },
        };
        let cap = self.capacity(n);
        self.tets.reserve(cap);
        self.tet_phys.reserve(cap);
        for i in 0..n {
            let (t, _) = self.element::<4>(tags, || format!("tet {} of {n} on volume {entity}", i + 1))?;
            self.tets.push(t);
            self.tet_phys.push(phys);
        }
        Ok(())
    }

    fn triangle_block(&mut self, tags: &TagMap, dim: i32, entity: i32, n: usize, line: usize) -> Result<(), MeshError> {
        if dim != 2 {
            return Err(err_at(line, format!("triangles (type 2) on an entity of dimension {dim}")));
        }
        let grouped = match &self.volumes {
            None => false,
            Some(_) => match self.surfaces.get(&entity) {
                None => {
                    return Err(err_at(line, format!("surface entity {entity} is not listed in $Entities")));
                }
                Some(p) => !p.is_empty(),
            },
        };
        if grouped {
            self.triangles.reserve(self.capacity(n));
        } else {
            self.report.ungrouped_triangles += n;
        }
        for i in 0..n {
            let (nodes, line) = self.element::<3>(tags, || format!("triangle {} of {n} on surface {entity}", i + 1))?;
            if grouped {
                self.triangles.push(RawTriangle { nodes, entity, line });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::report::element_type_name;
    use super::*;

    #[test]
    fn dense_and_sparse_tag_maps_agree() {
        let mut dense = TagMap::Dense { min: 5, idx: vec![u32::MAX; 10] };
        let mut sparse = TagMap::Sparse(HashMap::new());
        for m in [&mut dense, &mut sparse] {
            assert!(m.insert(7, 0));
            assert!(m.insert(14, 1));
            assert!(!m.insert(7, 2), "a tag given twice");
            assert_eq!((m.get(7), m.get(14), m.get(8)), (Some(0), Some(1), None));
            assert_eq!((m.get(0), m.get(u64::MAX)), (None, None));
        }
        assert!(!dense.insert(15, 3), "outside the dense range");
    }

    #[test]
    fn element_types_have_gmsh_names() {
        assert_eq!(element_type_name(TET), Some("4-node tetrahedron"));
        assert_eq!(element_type_name(15), Some("point"));
        assert_eq!(element_type_name(99), None);
    }
}
