//! Building the mesh a case describes, part by part.

use femdem_mesh::generate::{
    BoxSpec, ExtrusionSpec, Outline, PlatenSpec, Side, generate_box, generate_extrusion, generate_platen,
};
use femdem_mesh::trace_file::{TracePolyline, parse_traces};
use femdem_mesh::{Region, TetMesh};

use super::format::PartSpec;
use super::{CaseError, LoadedCase};

/// Default `jitter` of box parts (fraction of the element size).
pub const DEFAULT_JITTER: f64 = 0.1;

/// Builds the case's mesh: every part meshed in order and appended as a
/// separate body, boundary groups renamed `<part>.<group>`, then checked.
///
/// # Errors
/// A [`CaseError`] located at the offending part or region.
pub fn build_mesh(case: &LoadedCase) -> Result<TetMesh, CaseError> {
    build_mesh_noting(case, &mut Vec::new())
}

/// [`build_mesh`], pushing onto `warnings` what is legal but probably not
/// meant, one located sentence each: an extrusion meshed far finer than
/// its `element_size` because features of its outline or traces crowd
/// ([`crate::refinement`]); parts whose tets coincide exactly
/// ([`crate::coincident`]).
///
/// # Errors
/// As [`build_mesh`].
pub fn build_mesh_noting(case: &LoadedCase, warnings: &mut Vec<String>) -> Result<TetMesh, CaseError> {
    let section = &case.case.mesh;
    let mut regions: Vec<Region> = Vec::new();
    for (i, r) in section.regions.iter().enumerate() {
        if regions.iter().any(|q| q.name == r.get_ref().name) {
            return Err(
                case.error_at(r.span(), format!("mesh.regions[{i}]: region `{}` is declared twice", r.get_ref().name))
            );
        }
        regions.push(Region { name: r.get_ref().name.clone(), breakable: r.get_ref().breakable });
    }
    if section.parts.is_empty() {
        return Err(CaseError {
            path: case.path.clone(),
            at: None,
            message: "mesh.parts: at least one part is needed".into(),
        });
    }
    let mut mesh = TetMesh::default();
    let mut names: Vec<String> = Vec::new();
    // Each part's tets in the assembled mesh.
    let mut ranges: Vec<std::ops::Range<usize>> = Vec::new();
    for (i, part) in section.parts.iter().enumerate() {
        let span = part.span();
        let key = format!("mesh.parts[{i}]");
        let region = |name: &str| -> Result<Region, CaseError> {
            regions.iter().find(|r| r.name == name).cloned().ok_or_else(|| {
                case.error_at(span.clone(), format!("{key}.region: `{name}` is not declared in [[mesh.regions]]"))
            })
        };
        let fail = |e: femdem_mesh::MeshError| case.error_at(span.clone(), format!("{key}: {e}"));
        let (name, mut body) = match part.get_ref() {
            PartSpec::Box { name, region: r, min, max, element_size, jitter } => {
                let spec = BoxSpec {
                    min: *min,
                    max: *max,
                    element_size: *element_size,
                    jitter: jitter.unwrap_or(DEFAULT_JITTER),
                    seed: section.seed.wrapping_add(i as u64),
                    region: region(r)?,
                };
                (name.clone().unwrap_or_else(|| r.clone()), generate_box(&spec).map_err(fail)?)
            }
            PartSpec::Extrusion {
                name,
                region: r,
                circle,
                polygon,
                traces,
                traces_file,
                z0,
                thickness,
                element_size,
                layers,
            } => {
                let outline = match (circle, polygon) {
                    (Some(c), None) => Outline::Circle { center: c.center, radius: c.radius },
                    (None, Some(p)) => Outline::Polygon(p.clone()),
                    _ => {
                        return Err(case.error_at(span, format!("{key}: give exactly one of `circle` and `polygon`")));
                    }
                };
                let file = match traces_file {
                    Some(_) if !traces.is_empty() => {
                        return Err(case.error_at(span, format!("{key}: give `traces` or `traces_file`, not both")));
                    }
                    Some(f) => Some(read_trace_file(case, &span, &key, f)?),
                    None => None,
                };
                let spec = ExtrusionSpec {
                    outline,
                    traces: file
                        .as_ref()
                        .map_or_else(|| traces.clone(), |(_, t)| t.iter().map(|p| p.points.clone()).collect()),
                    z0: *z0,
                    thickness: *thickness,
                    element_size: *element_size,
                    layers: *layers,
                    region: region(r)?,
                };
                let body = generate_extrusion(&spec).map_err(|e| match (&e, &file) {
                    // A trace of the file: point at the line where it is written.
                    (femdem_mesh::MeshError::Trace { trace, point, reason }, Some((path, t))) => {
                        trace_file_error(case, &span, &key, path, t[*trace].at[*point], reason)
                    }
                    (femdem_mesh::MeshError::Trace { trace, point, reason }, None) => {
                        case.error_at(span.clone(), format!("{key}.traces[{trace}], point {point}: {reason}"))
                    }
                    _ => fail(e),
                })?;
                if let Outline::Circle { radius, .. } = spec.outline
                    && let Some(w) = crate::outline::circle_warning(&key, radius, spec.element_size)
                {
                    warnings.push(case.error_at(span.clone(), w).to_string());
                }
                let layers = spec.layer_count();
                if let Some(w) = crate::refinement::warning(&key, &body, spec.element_size, layers, spec.thickness) {
                    warnings.push(case.error_at(span.clone(), w).to_string());
                }
                (name.clone().unwrap_or_else(|| r.clone()), body)
            }
            PartSpec::Platen { name, region: r, side, thickness, extent, element_size } => {
                let Some((lo, hi)) = mesh.bounding_box() else {
                    return Err(case.error_at(span, format!("{key}: a platen needs a specimen part before it")));
                };
                let side = parse_side(side).ok_or_else(|| {
                    case.error_at(span.clone(), format!("{key}.side: `{side}` is not one of +x, -x, +y, -y, +z, -z"))
                })?;
                let spec = PlatenSpec {
                    side,
                    thickness: *thickness,
                    extent: extent.map_or([None, None], |e| [Some(e[0]), Some(e[1])]),
                    element_size: *element_size,
                    region: region(r)?,
                };
                (name.clone().unwrap_or_else(|| r.clone()), generate_platen(&spec, lo, hi).map_err(fail)?)
            }
            PartSpec::Msh { name, path, scale, translate } => {
                let file = case.dir().join(path);
                let bytes = std::fs::read(&file).map_err(|e| {
                    case.error_at(span.clone(), format!("{key}.path: cannot read {}: {e}", file.display()))
                })?;
                let (mut m, report) = femdem_mesh::msh::read_msh_report(&bytes)
                    .map_err(|e| case.error_at(span.clone(), format!("{key}.path: {}: {e}", file.display())))?;
                place(&mut m, *scale, *translate).map_err(|e| case.error_at(span.clone(), format!("{key}.{e}")))?;
                // Volume elements other than linear tets would leave their
                // part of the body out of the model, silently.
                let volumes = report.skipped_volumes();
                if !volumes.is_empty() {
                    let what: Vec<String> = volumes
                        .iter()
                        .map(|(&ty, &n)| match femdem_mesh::msh::element_type_name(ty) {
                            Some(name) => format!("{n} {name} (type {ty})"),
                            None => format!("{n} element(s) of type {ty}, which femdem does not know"),
                        })
                        .collect();
                    return Err(case.error_at(
                        span.clone(),
                        format!(
                            "{key}.path: {} holds {} besides its 4-node tets: femdem's bodies are linear tets \
                             only, and the part of the body meshed otherwise would be missing from the model; \
                             mesh every volume with 4-node tets (in Gmsh, `Mesh.ElementOrder = 1` and no \
                             recombination)",
                            file.display(),
                            what.join(", ")
                        ),
                    ));
                }
                for (k, r) in m.regions.iter_mut().enumerate() {
                    // The reader's name for tets in no physical volume.
                    let unnamed = r.name == "unnamed";
                    let tets = m.tet_region.iter().filter(|&&t| t as usize == k).count();
                    r.breakable = region(&r.name)
                        .map_err(|_| {
                            let message = if unnamed {
                                format!(
                                    "{key}: {tets} tets of {} belong to no physical volume (the file has no \
                                     $Entities section, or their volumes are in no physical group), and femdem \
                                     puts such tets in a region called `unnamed`; declare a [[mesh.regions]] \
                                     named `unnamed`, or give the volumes a physical group in Gmsh (Physical \
                                     Volume) and declare its name",
                                    file.display()
                                )
                            } else {
                                format!(
                                    "{key}: {} has physical volume `{}` ({tets} tets), which is not declared in \
                                     [[mesh.regions]]",
                                    file.display(),
                                    r.name
                                )
                            };
                            case.error_at(span.clone(), message)
                        })?
                        .breakable;
                }
                let stem =
                    std::path::Path::new(path).file_stem().map_or("msh".into(), |s| s.to_string_lossy().into_owned());
                (name.clone().unwrap_or(stem), m)
            }
        };
        let msh = matches!(part.get_ref(), PartSpec::Msh { .. });
        let meshed = msh || matches!(part.get_ref(), PartSpec::Extrusion { .. });
        femdem_mesh::check::check(&body)
            .map_err(|e| case.error_at(span.clone(), format!("{key}: {}", located(&e, &body, msh))))?;
        if meshed {
            // A mesher's order is often far from spatial: Gmsh's, and the
            // order in which spade's refinement leaves the extrusion's
            // triangles (the box and platen generators write theirs cell by
            // cell). Checked first, so that errors count an MSH part's tets
            // in the file's order.
            body = femdem_mesh::order::spatially_ordered(&body);
        }
        if names.contains(&name) {
            return Err(
                case.error_at(span, format!("{key}: part name `{name}` is used twice; set `name` to tell them apart"))
            );
        }
        for g in &mut body.boundary {
            g.name = format!("{name}.{}", g.name);
            // Dots in part or group names can make one name of two (part
            // `a` with group `b.c`, part `a.b` with group `c`): appending
            // would merge them into one group spanning both bodies.
            if mesh.boundary_group(&g.name).is_some() {
                return Err(case.error_at(
                    span.clone(),
                    format!(
                        "{key}: its boundary group `{}` has the name of a group of an earlier part (part and group \
                         names joined by a dot); rename the part (`name`) so that no two groups share a name",
                        g.name
                    ),
                ));
            }
        }
        names.push(name);
        let first = mesh.num_tets();
        mesh.append(&body);
        ranges.push(first..mesh.num_tets());
    }
    for (earlier, later, tets) in crate::coincident::coinciding_parts(&mesh, &ranges) {
        let (a, b) = (&names[earlier], &names[later]);
        let total = ranges[later].len();
        warnings.push(
            case.error_at(
                section.parts[later].span(),
                format!(
                    "mesh.parts[{later}] (`{b}`): {tets} of its {total} tets coincide exactly with tets of \
                     mesh.parts[{earlier}] (`{a}`), two bodies in one place (a part given twice?): their mass \
                     counts twice, and contact feels no force between coinciding tets (Eq. 17's potential is \
                     zero on a tet's own faces); remove the copy, or move it"
                ),
            )
            .to_string(),
        );
    }
    // Keep the declared region order, including regions no part uses.
    reorder_regions(&mut mesh, &regions);
    // Each part passed the full check above; appending changes no tet's
    // shape or neighbours, so only the bookkeeping is checked again.
    femdem_mesh::check::consistent(&mesh).map_err(|e| CaseError {
        path: case.path.clone(),
        at: None,
        message: format!("mesh check failed: {e}"),
    })?;
    Ok(mesh)
}

/// Brings an MSH part's coordinates into the case's: `x ← scale x +
/// translate`, rounded once (a fused multiply–add: a file in site
/// coordinates keeps every digit it holds of its edges, since the shift of
/// `x` by a nearby `−x₀` is exact). Refuses a `scale` that is not finite
/// and positive (a negative one would turn every tet inside out), a
/// `translate` that is not finite, and a placement that takes a
/// coordinate out of the finite numbers, naming the key (without the
/// part's, which the caller adds).
pub(crate) fn place(m: &mut TetMesh, scale: Option<f64>, translate: Option<[f64; 3]>) -> Result<(), String> {
    if let Some(s) = scale
        && !(s.is_finite() && s > 0.0)
    {
        return Err(format!(
            "scale: the factor on the file's coordinates must be finite and > 0 (1e-3 for a file in millimetres), \
             got {s}"
        ));
    }
    if let Some(t) = translate
        && !t.iter().all(|c| c.is_finite())
    {
        return Err(format!("translate: every component must be finite (m), got {t:?}"));
    }
    let (s, t) = (scale.unwrap_or(1.0), translate.unwrap_or([0.0; 3]));
    if s != 1.0 || t != [0.0; 3] {
        for x in &mut m.coords {
            *x = [0, 1, 2].map(|k| s.mul_add(x[k], t[k]));
        }
        if let Some(x) = m.coords.iter().find(|x| !x.iter().all(|c| c.is_finite())) {
            let key = if scale.is_some() { "scale" } else { "translate" };
            return Err(format!(
                "{key}: the placed mesh has a coordinate that is not a finite number ({x:?}): the scale or the \
                 shift is too large"
            ));
        }
    }
    Ok(())
}

/// `e`, a check of one part's mesh `body`, with where its tets are: their
/// centroids (in m), and for an MSH part (`msh`) how they are counted.
fn located(e: &femdem_mesh::MeshError, body: &TetMesh, msh: bool) -> String {
    use femdem_mesh::MeshError::{BadTet, TangledFace};
    let at = |t: usize| {
        let c = body.tet_points(t).iter().fold([0.0; 3], |s, p| [s[0] + p[0], s[1] + p[1], s[2] + p[2]]);
        format!("tet {t} has its centroid at ({:e}, {:e}, {:e}) m", c[0] / 4.0, c[1] / 4.0, c[2] / 4.0)
    };
    let counted = if msh { "; the part's tets counted from 0 in the order the file lists them" } else { "" };
    match *e {
        BadTet { tet, .. } => format!("{e} ({}{counted})", at(tet)),
        TangledFace { a, b, .. } => format!("{e} ({}, {}{counted})", at(a), at(b)),
        _ => e.to_string(),
    }
}

/// Reads and parses the trace file `file` (relative to the case) of part
/// `key`, whose table is at `span`.
fn read_trace_file(
    case: &LoadedCase,
    span: &std::ops::Range<usize>,
    key: &str,
    file: &str,
) -> Result<(std::path::PathBuf, Vec<TracePolyline>), CaseError> {
    let path = case.dir().join(file);
    let text = std::fs::read_to_string(&path)
        .map_err(|e| case.error_at(span.clone(), format!("{key}.traces_file: cannot read {}: {e}", path.display())))?;
    let traces =
        parse_traces(&text).map_err(|e| trace_file_error(case, span, key, &path, (e.line, e.column), &e.message))?;
    Ok((path, traces))
}

/// An error at line and column `at` of trace file `path`, naming the case
/// key that reads it and where.
fn trace_file_error(
    case: &LoadedCase,
    span: &std::ops::Range<usize>,
    key: &str,
    path: &std::path::Path,
    at: (usize, usize),
    message: &str,
) -> CaseError {
    // Point at the `traces_file` key of the part where it can be found.
    // (The part's span may be its header only: look on to the next table.)
    let mut offset = span.start;
    let mut pos = span.start;
    for (i, l) in case.source.get(span.start..).unwrap_or("").split_inclusive('\n').enumerate() {
        if i > 0 && l.trim_start().starts_with('[') {
            break;
        }
        if l.trim_start().starts_with("traces_file") {
            offset = pos + l.len() - l.trim_start().len();
            break;
        }
        pos += l.len();
    }
    let (line, column) = super::line_col(&case.source, offset);
    CaseError {
        path: path.to_path_buf(),
        at: Some(at),
        message: format!("{message} (the trace file of {key}.traces_file, {}:{line}:{column})", case.path.display()),
    }
}

/// The `side` of a platen part (`+x` … `-z`); `None` for anything else.
pub(crate) fn parse_side(s: &str) -> Option<Side> {
    Some(match s {
        "+x" => Side::XMax,
        "-x" => Side::XMin,
        "+y" => Side::YMax,
        "-y" => Side::YMin,
        "+z" => Side::ZMax,
        "-z" => Side::ZMin,
        _ => return None,
    })
}

fn reorder_regions(mesh: &mut TetMesh, declared: &[Region]) {
    let map: Vec<u16> =
        mesh.regions.iter().map(|r| declared.iter().position(|d| d.name == r.name).unwrap_or(0) as u16).collect();
    for r in &mut mesh.tet_region {
        *r = map[*r as usize];
    }
    mesh.regions = declared.to_vec();
}
