//! The MSH 4.1 and MSH 2 (2.0–2.2) reader, ASCII and binary.
//!
//! `$MeshFormat` says which: [`read_msh_report`] reads it as text, then
//! hands the rest of the file to the section parsers below through a
//! [`Source`] — [`Ascii`], line by line (Gmsh writes one record per line,
//! so a record with too few or too many fields is reported on its own line
//! instead of shifting every later record), or [`Binary`], value by value
//! in the file's byte order. Counts given by headers are checked against
//! what follows, but never trusted for allocation. The sections MSH 2
//! writes differently are in `read/legacy.rs`.

use std::collections::hash_map::Entry;
use std::collections::{BTreeSet, HashMap};

mod assemble;
mod legacy;

use super::binary::{Binary, Endian};
use super::lex::{Ascii, Fields, Lines};
use super::report::MshReport;
use super::source::{At, Source};
use crate::{MeshError, TetMesh};

/// Gmsh element type of the 3-node triangle.
const TRIANGLE: u32 = 2;
/// Gmsh element type of the 4-node tetrahedron.
const TET: u32 = 4;
/// Name of the region that takes tets of volumes in no physical group.
const UNNAMED: &str = "unnamed";
/// The dimension of a physical name of MSH 2.0, which gives none: the name
/// of a physical group of any dimension with its tag.
const ANY_DIMENSION: i32 = -1;

/// Reads a Gmsh MSH 4.1 or 2 file, ASCII or binary (either byte order); see the
/// [module docs](super) for what is kept. Use [`read_msh_report`] to also
/// learn what was skipped.
///
/// # Errors
/// For any malformed input, a version other than 4.1 and 2.0–2.2, or a file with no
/// 4-node tets: [`MeshError::Msh`] with the 1-based line of the first
/// problem in an ASCII file (and in the `$MeshFormat` line of any file);
/// [`MeshError::MshBinary`] with its byte offset and section in a binary
/// one.
pub fn read_msh(bytes: &[u8]) -> Result<TetMesh, MeshError> {
    read_msh_report(bytes).map(|(mesh, _)| mesh)
}

/// Like [`read_msh`], and also reports the skipped elements, dropped nodes
/// and reoriented tets.
///
/// # Errors
/// As [`read_msh`].
pub fn read_msh_report(bytes: &[u8]) -> Result<(TetMesh, MshReport), MeshError> {
    let mut lines = Lines::new(bytes);
    let (legacy, binary) = mesh_format(&mut lines)?;
    match binary {
        None => Reader::new(Ascii::new(lines), bytes.len(), legacy).read(),
        Some((endian, size_t)) => Reader::new(Binary::new(lines, endian, size_t), bytes.len(), legacy).read(),
    }
}

/// Reads the `$MeshFormat` header and its line `version file-type
/// data-size`, and in a binary file the `int` 1 after it; stops before
/// `$EndMeshFormat`. Returns whether the file is MSH 2, and the byte order
/// and the size of a `size_t` of a binary file (`None` for an ASCII one).
fn mesh_format(lines: &mut Lines<'_>) -> Result<(bool, Option<(Endian, usize)>), MeshError> {
    const S: &str = "MeshFormat";
    let header = loop {
        match lines.next_line("")? {
            None => return Err(lines.err("", "empty file: no $MeshFormat section")),
            Some(l) if l.trim().is_empty() => {}
            Some(l) => break l.trim(),
        }
    };
    if header != "$MeshFormat" {
        return Err(
            lines.err("", format!("expected $MeshFormat first, found `{}` (not a Gmsh MSH file?)", shown(header)))
        );
    }
    let mut f = lines.record(S, || "`version file-type data-size`".into())?;
    let version = f.token("version")?;
    let legacy = matches!(version, "2" | "2.0" | "2.1" | "2.2");
    if version != "4.1" && !legacy {
        return Err(f.err(format!(
            "MSH version {version} is not supported: femdem reads MSH 4.1 and 2.2 \
             (in Gmsh, save with `Mesh.MshFileVersion = 4.1`)"
        )));
    }
    let file_type = f.count("file type")?;
    if file_type > 1 {
        return Err(f.err(format!("bad file type {file_type}: expected 0 (ASCII) or 1 (binary)")));
    }
    let data_size = f.count("data size")?;
    f.end("the data size")?;
    if file_type == 0 {
        return Ok((legacy, None));
    }
    if legacy && data_size != 8 {
        return Err(
            f.err(format!("bad data size {data_size} for a binary MSH 2 file: expected 8 (the bytes of a `double`)"))
        );
    }
    if data_size != 4 && data_size != 8 {
        return Err(f.err(format!(
            "bad data size {data_size} for a binary file: expected 4 or 8 (the bytes of a `size_t` on the \
             machine that wrote it)"
        )));
    }
    let at = At::Byte(lines.offset());
    let one = lines.take(4).ok_or_else(|| {
        at.err(S, "file ends inside $MeshFormat: expected the binary integer 1 that gives the byte order")
    })?;
    let one: [u8; 4] = one.try_into().expect("4 bytes");
    let endian = Endian::of_one(one).ok_or_else(|| {
        at.err(
            S,
            format!(
                "expected the binary integer 1 that gives the byte order, found the bytes {one:02x?} \
                 (is this an ASCII file with file type 1?)"
            ),
        )
    })?;
    Ok((legacy, Some((endian, data_size))))
}

/// At most 60 characters of `s`, escaped: a header in a message.
fn shown(s: &str) -> String {
    s.chars().take(60).collect::<String>().escape_debug().to_string()
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
/// and where it is.
struct RawTriangle {
    nodes: [u32; 3],
    entity: i32,
    at: At,
}

struct Reader<S> {
    src: S,
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
    /// Where each node's coordinates are.
    coord_at: Vec<At>,
    tags: Option<TagMap>,
    /// Tets in file node indices, with the physical tag of their volume.
    tets: Vec<[u32; 4]>,
    tet_phys: Vec<Option<i32>>,
    triangles: Vec<RawTriangle>,
    /// Where the `$Elements` header is, once read.
    elements_at: Option<At>,
    /// Whether the file is MSH 2 (`legacy.rs`).
    legacy: bool,
}

impl<'a, S: Source<'a>> Reader<S> {
    fn new(src: S, file_len: usize, legacy: bool) -> Self {
        Reader {
            src,
            file_len,
            report: MshReport::default(),
            names: HashMap::new(),
            volumes: None,
            surfaces: HashMap::new(),
            coords: Vec::new(),
            coord_at: Vec::new(),
            tags: None,
            tets: Vec::new(),
            tet_phys: Vec::new(),
            triangles: Vec::new(),
            elements_at: None,
            legacy,
        }
    }

    /// A capacity for `n` announced items that a malicious header cannot
    /// blow up: no item takes less than two bytes of file.
    fn capacity(&self, n: usize) -> usize {
        n.min(self.file_len / 2)
    }

    /// Reads the sections after `$MeshFormat`'s line, from its `$End`.
    fn read(mut self) -> Result<(TetMesh, MshReport), MeshError> {
        self.src.end_of("MeshFormat")?;
        let mut seen = BTreeSet::from(["MeshFormat".to_owned()]);
        while let Some(line) = self.src.lines().next_line("")? {
            let header = line.trim();
            if header.is_empty() {
                continue;
            }
            let at = self.src.lines().at();
            let Some(name) = header.strip_prefix('$') else {
                return Err(at.err("", format!("expected a section header such as $Nodes, found `{}`", shown(header))));
            };
            if name.starts_with("End") {
                return Err(at.err("", format!("`{}` closes no open section", shown(header))));
            }
            let known = matches!(name, "MeshFormat" | "PhysicalNames" | "Entities" | "Nodes" | "Elements");
            if known && !seen.insert(name.to_owned()) {
                return Err(at.err(name, format!("second ${name} section")));
            }
            match name {
                "PhysicalNames" => self.physical_names()?,
                // Gmsh writes one into MSH 2 with `Mesh.SaveTopology = 1`:
                // the elements' tags say all it would.
                "Entities" if self.legacy => self.src.lines().skip_section(name, at)?,
                "ParametricNodes" if self.legacy => {
                    return Err(at.err(
                        name,
                        "$ParametricNodes is not read: save the mesh without parametric coordinates \
                         (in Gmsh, `Mesh.SaveParametric = 0`)",
                    ));
                }
                "Nodes" if self.legacy => self.nodes_v2()?,
                "Elements" if self.legacy => self.elements_v2()?,
                "Entities" => {
                    if self.elements_at.is_some() {
                        return Err(at.err(name, "$Entities must come before $Elements"));
                    }
                    self.entities()?;
                }
                "Nodes" => self.nodes()?,
                "Elements" => self.elements()?,
                "PartitionedEntities" => {
                    return Err(at.err(name, "partitioned meshes are not supported: save without partitions"));
                }
                _ => self.src.lines().skip_section(name, at)?,
            }
        }
        if self.elements_at.is_none() {
            return Err(self.src.lines().err("", "file ends without an $Elements section"));
        }
        if self.legacy {
            self.groups_v2()?;
        }
        self.assemble()
    }

    /// `$PhysicalNames`: text in both encodings.
    fn physical_names(&mut self) -> Result<(), MeshError> {
        const S: &str = "PhysicalNames";
        let lines = self.src.lines();
        let mut f = lines.record(S, || "the number of physical names".into())?;
        let n = f.count("number of physical names")?;
        f.end("the number of physical names")?;
        for i in 0..n {
            let f = lines.record(S, || format!("physical name {} of {n}", i + 1))?;
            // `dim tag "name"`; the name may hold any run of spaces. MSH
            // 2.0 writes `tag "name"`, with no dimension.
            let raw = f.raw;
            let (head, quoted) = raw.split_at(raw.find('"').unwrap_or(raw.len()));
            let mut h = Fields { raw: head, it: head.split_ascii_whitespace(), at: f.at, section: S };
            let (dim, tag) = if self.legacy && head.split_ascii_whitespace().count() == 1 {
                (ANY_DIMENSION, h.int("physical tag")?)
            } else {
                let dim = h.int("dimension")?;
                if !(0..=3).contains(&dim) {
                    return Err(h.err(format!("bad dimension {dim}: expected 0 to 3")));
                }
                (dim, h.int("physical tag")?)
            };
            h.end("the physical tag")?;
            let quoted = quoted.trim_end();
            let name = quoted
                .strip_prefix('"')
                .and_then(|r| r.strip_suffix('"'))
                .ok_or_else(|| h.err(format!("expected a quoted name, found `{quoted}`")))?;
            self.names.insert((dim, tag), name.to_owned());
        }
        lines.end_of(S)
    }

    fn entities(&mut self) -> Result<(), MeshError> {
        const S: &str = "Entities";
        let src = &mut self.src;
        src.record(S, || "`numPoints numCurves numSurfaces numVolumes`".into())?;
        let mut counts = [0usize; 4];
        for (c, name) in counts.iter_mut().zip(["points", "curves", "surfaces", "volumes"]) {
            *c = src.count(&format!("number of {name}"))?;
        }
        src.end("the number of volumes")?;
        let mut volumes = HashMap::new();
        for (dim, &n) in counts.iter().enumerate() {
            let kind = ["point", "curve", "surface", "volume"][dim];
            let mut tags_seen = BTreeSet::new();
            for i in 0..n {
                src.record(S, || format!("{kind} entity {} of {n}", i + 1))?;
                let tag = src.int(&format!("{kind} tag"))?;
                if !tags_seen.insert(tag) {
                    return Err(src.err(format!("{kind} entity {tag} listed twice")));
                }
                let n_coords = if dim == 0 { 3 } else { 6 };
                for _ in 0..n_coords {
                    src.real("bounding-box coordinate")?;
                }
                let n_phys = src.count("number of physical tags")?;
                let mut phys = Vec::with_capacity(n_phys.min(16));
                for _ in 0..n_phys {
                    phys.push(src.int("physical tag")?);
                }
                if dim > 0 {
                    let n_bound = src.count("number of bounding entities")?;
                    for _ in 0..n_bound {
                        src.int("bounding entity tag")?;
                    }
                }
                src.end(&format!("the {kind} entity"))?;
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
        src.end_of(S)
    }

    fn nodes(&mut self) -> Result<(), MeshError> {
        const S: &str = "Nodes";
        self.src.record(S, || "`numEntityBlocks numNodes minNodeTag maxNodeTag`".into())?;
        let n_blocks = self.src.count("number of entity blocks")?;
        let n_nodes = self.src.count("number of nodes")?;
        let (min, max) = if n_nodes == 0 {
            (self.src.count("minimum node tag")? as u64, self.src.count("maximum node tag")? as u64)
        } else {
            (self.src.node_tag("minimum node tag")?, self.src.node_tag("maximum node tag")?)
        };
        self.src.end("the maximum node tag")?;
        if n_nodes > 0 && max < min {
            return Err(self.src.err(format!("maximum node tag {max} is below the minimum {min}")));
        }
        if u32::try_from(n_nodes).is_err() {
            return Err(self.src.err(format!("{n_nodes} nodes are more than femdem can index")));
        }
        let range = max.saturating_sub(min).saturating_add(1);
        let dense_limit = 2 * self.capacity(n_nodes) as u64 + 1024;
        let mut tags = if range <= dense_limit {
            TagMap::Dense { min, idx: vec![u32::MAX; range as usize] }
        } else {
            TagMap::Sparse(HashMap::with_capacity(self.capacity(n_nodes)))
        };
        self.coords = Vec::with_capacity(self.capacity(n_nodes));
        self.coord_at = Vec::with_capacity(self.capacity(n_nodes));
        for b in 0..n_blocks {
            self.src.record(S, || format!("entity block {} of {n_blocks}", b + 1))?;
            let dim = self.src.int("entity dimension")?;
            self.src.int("entity tag")?;
            let parametric = self.src.uint("parametric flag")?;
            let n = self.src.count("number of nodes in block")?;
            self.src.end("the number of nodes in the block")?;
            if !(0..=3).contains(&dim) {
                return Err(self.src.err(format!("bad entity dimension {dim}: expected 0 to 3")));
            }
            if parametric > 1 {
                return Err(self.src.err(format!("bad parametric flag {parametric}: expected 0 or 1")));
            }
            let base = self.coords.len();
            if n > n_nodes - base {
                return Err(self
                    .src
                    .err(format!("blocks hold more nodes than the {n_nodes} announced by the $Nodes header")));
            }
            let header_at = self.src.at();
            // A wrong count in the block header of an ASCII file shows as a
            // record of the wrong shape: say so, rather than what the
            // misread field is.
            let miscount = |src: &S, expected: &str, found: usize| {
                src.err(format!(
                    "{found} number(s) where {expected} was expected: does the block header on {} \
                     announce the right number of nodes ({n})?",
                    header_at.describe()
                ))
            };
            for i in 0..n {
                self.src.record(S, || format!("tag of node {} of block {}", i + 1, b + 1))?;
                if let Some(fields) = self.src.fields().filter(|&f| f != 1) {
                    return Err(miscount(&self.src, &format!("the tag of node {} of block {}", i + 1, b + 1), fields));
                }
                let tag = self.src.node_tag("node tag")?;
                self.src.end("the node tag")?;
                if !(min..=max).contains(&tag) {
                    return Err(self.src.err(format!("node tag {tag} is outside the header's range {min}..={max}")));
                }
                // `base + i < n_nodes`, which fits in u32 (checked above).
                if !tags.insert(tag, (base + i) as u32) {
                    return Err(self.src.err(format!("node tag {tag} appears twice")));
                }
            }
            let extra = if parametric == 1 { dim as usize } else { 0 };
            for i in 0..n {
                self.src.record(S, || format!("coordinates of node {} of block {}", i + 1, b + 1))?;
                if let Some(fields) = self.src.fields().filter(|&f| f < 3) {
                    let what = format!("the coordinates of node {} of block {}", i + 1, b + 1);
                    return Err(miscount(&self.src, &what, fields));
                }
                let x = self.src.real("x coordinate")?;
                let y = self.src.real("y coordinate")?;
                let z = self.src.real("z coordinate")?;
                for _ in 0..extra {
                    self.src.real("parametric coordinate")?;
                }
                self.src.end("the node coordinates")?;
                self.coords.push([x, y, z]);
                self.coord_at.push(self.src.at());
            }
        }
        if self.coords.len() != n_nodes {
            // Report where the next block header should have been.
            let at = self.src.next_at(S)?;
            return Err(at.err(
                S,
                format!("the $Nodes header announces {n_nodes} nodes, the blocks hold {}", self.coords.len()),
            ));
        }
        self.tags = Some(tags);
        self.src.end_of(S)
    }

    fn elements(&mut self) -> Result<(), MeshError> {
        const S: &str = "Elements";
        let header_at = self.src.lines().at();
        self.elements_at = Some(header_at);
        let Some(tags) = self.tags.take() else {
            return Err(header_at.err(S, "$Elements must come after $Nodes"));
        };
        self.src.record(S, || "`numEntityBlocks numElements minTag maxTag`".into())?;
        let n_blocks = self.src.count("number of entity blocks")?;
        let n_elements = self.src.count("number of elements")?;
        self.src.count("minimum element tag")?;
        self.src.count("maximum element tag")?;
        self.src.end("the maximum element tag")?;
        let mut total = 0usize;
        for b in 0..n_blocks {
            self.src.record(S, || format!("entity block {} of {n_blocks}", b + 1))?;
            let dim = self.src.int("entity dimension")?;
            let entity = self.src.int("entity tag")?;
            let ty = self.src.uint("element type")?;
            let n = self.src.count("number of elements in block")?;
            self.src.end("the number of elements in the block")?;
            total = total.saturating_add(n);
            if total > n_elements {
                return Err(self.src.err(format!(
                    "blocks hold more elements than the {n_elements} announced by the \
                     $Elements header"
                )));
            }
            let block_at = self.src.at();
            match ty {
                TET => self.tet_block(&tags, dim, entity, n, block_at)?,
                TRIANGLE => self.triangle_block(&tags, dim, entity, n, block_at)?,
                _ => {
                    *self.report.skipped_elements.entry(ty).or_insert(0) += n;
                    for i in 0..n {
                        self.src.record(S, || format!("element {} of block {}", i + 1, b + 1))?;
                        self.src.node_tag("element tag")?;
                        self.src.skip_element_nodes(ty)?;
                    }
                }
            }
        }
        if total != n_elements {
            let at = self.src.next_at(S)?;
            return Err(
                at.err(S, format!("the $Elements header announces {n_elements} elements, the blocks hold {total}"))
            );
        }
        self.tags = Some(tags);
        self.src.end_of(S)
    }

    /// Reads the `K` node tags of one element record as file node indices.
    fn element<const K: usize>(
        &mut self,
        tags: &TagMap,
        what: impl FnOnce() -> String,
    ) -> Result<([u32; K], At), MeshError> {
        self.src.record("Elements", what)?;
        self.src.node_tag("element tag")?;
        let mut nodes = [0u32; K];
        for v in &mut nodes {
            let tag = self.src.node_tag("node tag")?;
            *v = tags.get(tag).ok_or_else(|| self.src.err(format!("node tag {tag} is not in $Nodes")))?;
        }
        let at = self.src.at();
        self.src.end("the node tags")?;
        Ok((nodes, at))
    }

    fn tet_block(&mut self, tags: &TagMap, dim: i32, entity: i32, n: usize, at: At) -> Result<(), MeshError> {
        const S: &str = "Elements";
        if dim != 3 {
            return Err(at.err(S, format!("tets (type 4) on an entity of dimension {dim}")));
        }
        let phys = match &self.volumes {
            None => None,
            Some(v) => match v.get(&entity).map(Vec::as_slice) {
                None => {
                    return Err(at.err(S, format!("volume entity {entity} is not listed in $Entities")));
                }
                Some([]) => None,
                Some([p]) => Some(*p),
                Some(many) => {
                    return Err(at.err(
                        S,
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

    fn triangle_block(&mut self, tags: &TagMap, dim: i32, entity: i32, n: usize, at: At) -> Result<(), MeshError> {
        const S: &str = "Elements";
        if dim != 2 {
            return Err(at.err(S, format!("triangles (type 2) on an entity of dimension {dim}")));
        }
        let grouped = match &self.volumes {
            None => false,
            Some(_) => match self.surfaces.get(&entity) {
                None => {
                    return Err(at.err(S, format!("surface entity {entity} is not listed in $Entities")));
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
            let (nodes, at) = self.element::<3>(tags, || format!("triangle {} of {n} on surface {entity}", i + 1))?;
            if grouped {
                self.triangles.push(RawTriangle { nodes, entity, at });
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

    /// Volume elements, and elements of unknown type, are what a mesh read
    /// without them would miss; points, lines and faces are not.
    #[test]
    fn skipped_volumes_are_those_of_dimension_three_or_unknown() {
        use std::collections::BTreeMap;
        let report = MshReport {
            skipped_elements: BTreeMap::from([(1, 2), (3, 5), (6, 3), (11, 1), (15, 1), (99, 4)]),
            ..MshReport::default()
        };
        assert_eq!(report.skipped_volumes(), BTreeMap::from([(6, 3), (11, 1), (99, 4)]));
    }
}
