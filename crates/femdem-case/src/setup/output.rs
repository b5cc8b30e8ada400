//! `[output]`: frames, history, checkpoints and the load–strain columns.

use femdem_core::Vec3;
use femdem_solver::Loads;
use femdem_vtk::Compression;

use crate::format::OutputSpec;
use crate::{CaseError, LoadedCase};

/// The fields `[output] fields` may name (written into every VTU frame
/// by the run driver).
pub const FIELDS: [&str; 6] = ["displacement", "velocity", "stress", "principal_stress", "von_mises", "region"];

/// The load–strain columns of `[output.load_strain]`, resolved against the
/// drives of `loads`.
#[derive(Clone, Copy, Debug)]
pub struct LoadStrain {
    /// Index of the upper platen's drive.
    pub upper: usize,
    /// Index of the lower platen's drive.
    pub lower: usize,
    /// Specimen length `d`, m.
    pub length: f64,
    /// Unit loading axis.
    pub axis: Vec3,
    /// `stop_below_peak`: the fraction of the peak load below which a run
    /// with failed joints ends.
    pub stop_below_peak: Option<f64>,
}

impl LoadStrain {
    /// `(F, ε)` of Eq. 21–22 from the drives' reaction forces `forces` (the
    /// force each drive applies to its platen) and mean displacements `u`:
    /// the specimen pushes the upper platen along `+axis`, so
    /// `F_upper = −f_upper·axis` and `F_lower = f_lower·axis`, and
    /// `Δa = (u_lower − u_upper)·axis` is the shortening.
    pub fn evaluate(&self, forces: &[Vec3], u: &[Vec3]) -> (f64, f64) {
        let f_upper = -forces[self.upper].dot(&self.axis);
        let f_lower = forces[self.lower].dot(&self.axis);
        let shortening = (u[self.lower] - u[self.upper]).dot(&self.axis);
        (0.5 * (f_upper + f_lower), shortening / self.length)
    }
}

/// Resolves `[output.load_strain]`, if any, and checks it against where
/// the platens are: the centres `c_u`, `c_l` of the upper and lower
/// drives' nodes at `x0` (the reference positions). With `a` the unit
/// axis and `D = (c_u − c_l)·a`, the upper platen must lie on the +axis
/// side (`D > 10⁻³ |c_u − c_l|`), else `F` and `ε` would both come out with the wrong
/// sign and `stop_below_peak` would never fire; an axis more than 30°
/// from `c_u − c_l`, or a `length` above 1.5 `D` (the specimen lies
/// between the platens' faces, inside their centres) or below `D / 10`
/// (a length in mm, or a platen far thicker than the specimen) is
/// pushed onto `warnings`.
///
/// # Errors
/// A located [`CaseError`] when a name is not a platen of the case, the two
/// are the same, the length is not positive, the axis is zero or the
/// upper platen does not lie on the axis' side of the lower.
pub fn load_strain(
    case: &LoadedCase,
    loads: &Loads,
    x0: &[Vec3],
    warnings: &mut Vec<String>,
) -> Result<Option<LoadStrain>, CaseError> {
    let Some(spec) = case.case.output.as_ref().and_then(|o| o.get_ref().load_strain.as_ref()) else {
        return Ok(None);
    };
    let s = spec.get_ref();
    let at = |msg: String| case.error_at(spec.span(), format!("output.load_strain.{msg}"));
    let find = |key: &str, name: &str| {
        loads
            .drives
            .iter()
            .position(|d| d.name == name)
            .ok_or_else(|| at(format!("{key}: `{name}` is not a platen of the case")))
    };
    let (upper, lower) = (find("upper", &s.upper)?, find("lower", &s.lower)?);
    if upper == lower {
        return Err(at("lower: must differ from upper".into()));
    }
    if !(s.length.is_finite() && s.length > 0.0) {
        return Err(at(format!("length must be > 0 m, got {}", s.length)));
    }
    let axis = Vec3::from(s.axis);
    if !(axis.norm().is_finite() && axis.norm() > 0.0) {
        return Err(at("axis must be a non-zero vector".into()));
    }
    if let Some(f) = s.stop_below_peak
        && !(f > 0.0 && f < 1.0)
    {
        return Err(at(format!("stop_below_peak must be a fraction in (0, 1), got {f}")));
    }
    let axis = axis.normalize();
    let centre = |d: usize| {
        let nodes = &loads.drives[d].nodes;
        nodes.iter().fold(Vec3::zeros(), |c, &n| c + x0[n as usize]) / nodes.len().max(1) as f64
    };
    let (c_u, c_l) = (centre(upper), centre(lower));
    let gap = c_u - c_l;
    let along = gap.dot(&axis);
    let show = |v: Vec3| format!("[{:.4e}, {:.4e}, {:.4e}]", v.x, v.y, v.z);
    // Refused at or below round-off of perpendicular too (1e-3 of the
    // centres' distance: within 0.06° of it), where the sign is chance.
    if along.is_nan() || along <= 1e-3 * gap.norm() {
        return Err(at(format!(
            "axis: the upper platen `{}` (its nodes centred at {} m) does not lie on the +axis side of the lower \
             `{}` (at {} m) along axis {}: the load and the strain would come out zero or with the wrong sign; \
             swap `upper` and `lower`, or reverse `axis`",
            s.upper,
            show(c_u),
            s.lower,
            show(c_l),
            show(axis)
        )));
    }
    let angle = (along / gap.norm()).clamp(-1.0, 1.0).acos().to_degrees();
    if angle > 30.0 {
        warnings.push(
            at(format!(
                "axis: {} is {angle:.0}° from the line between the platens' centres ({} m): the load and the \
                 strain are taken along `axis`",
                show(axis),
                show(gap)
            ))
            .to_string(),
        );
    }
    if s.length > 1.5 * along || s.length < 0.1 * along {
        warnings.push(
            at(format!(
                "length: {} m, against {along:.4e} m between the platens' centres along the axis: `length` is the \
                 specimen's length d of Eq. 22 in m (the disc's diameter), which lies between the platens' faces",
                s.length
            ))
            .to_string(),
        );
    }
    Ok(Some(LoadStrain { upper, lower, length: s.length, axis, stop_below_peak: s.stop_below_peak }))
}

/// What `[output]` resolves to for a run of `end_time` seconds.
#[derive(Debug, Clone)]
pub struct OutputSettings {
    /// Simulated time between VTU frames, s.
    pub interval: f64,
    /// Simulated time between history rows, s.
    pub history_interval: f64,
    /// Fields written.
    pub fields: Vec<String>,
    /// Compression of the VTU frames.
    pub compression: Compression,
    /// When checkpoints are written.
    pub checkpoint: CheckpointSettings,
}

/// `[output.checkpoint]`, resolved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CheckpointSettings {
    /// Steps between checkpoints (0: none by step count).
    pub interval_steps: u64,
    /// Wall-clock time between checkpoints, s (0: none by wall time).
    pub interval_wall: f64,
}

/// The default wall-clock interval between checkpoints, s: half an hour
/// bounds the work a crash loses on a long run, and a run shorter than
/// that writes none (but the one a signal asks for).
pub const CHECKPOINT_WALL_DEFAULT: f64 = 1800.0;

/// Resolves and checks `[output]`: `dir` as [`check_dir`], intervals finite and > 0 s (defaults
/// `end_time / 20` and a tenth of the frame interval), fields among
/// `fields_known`, the compression one of [`compression`]'s.
///
/// # Errors
/// A located [`CaseError`] naming the key.
pub fn output(case: &LoadedCase, end_time: f64, fields_known: &[&str]) -> Result<OutputSettings, CaseError> {
    let default = OutputSpec::default();
    let (spec, span) = match &case.case.output {
        Some(o) => (o.get_ref(), Some(o.span())),
        None => (&default, None),
    };
    let at = |msg: String| match span.clone() {
        Some(span) => case.error_at(span, format!("output: {msg}")),
        None => CaseError { path: case.path.clone(), at: None, message: format!("output: {msg}") },
    };
    check_dir(case)?;
    let interval = spec.interval.unwrap_or(end_time / 20.0);
    if !(interval.is_finite() && interval > 0.0) {
        return Err(at(format!("`interval` must be finite and > 0 s, got {interval} s")));
    }
    let history_interval = spec.history_interval.unwrap_or(interval / 10.0);
    if !(history_interval.is_finite() && history_interval > 0.0) {
        return Err(at(format!("`history_interval` must be finite and > 0 s, got {history_interval} s")));
    }
    let fields = spec.fields.clone().unwrap_or_else(|| fields_known.iter().map(|s| s.to_string()).collect());
    if let Some(f) = fields.iter().find(|f| !fields_known.contains(&f.as_str())) {
        return Err(at(format!("`fields`: `{f}` is not one of {}", fields_known.join(", "))));
    }
    let compression = compression(spec.compression.as_deref().unwrap_or("lz4")).map_err(at)?;
    let default_checkpoint = crate::format::CheckpointSpec::default();
    let (cp, cp_span) = match &spec.checkpoint {
        Some(c) => (c.get_ref(), Some(c.span())),
        None => (&default_checkpoint, None),
    };
    let interval_wall = cp.interval_wall.unwrap_or(CHECKPOINT_WALL_DEFAULT);
    if !(interval_wall.is_finite() && interval_wall >= 0.0) {
        let message = format!("output.checkpoint: `interval_wall` must be finite and ≥ 0 s, got {interval_wall} s");
        return Err(match cp_span {
            Some(span) => case.error_at(span, message),
            None => CaseError { path: case.path.clone(), at: None, message },
        });
    }
    let checkpoint = CheckpointSettings { interval_steps: cp.interval_steps.unwrap_or(0), interval_wall };
    Ok(OutputSettings { interval, history_interval, fields, compression, checkpoint })
}

/// Checks `[output] dir`: an empty name would put the results beside the
/// case file.
///
/// # Errors
/// A located [`CaseError`] at `[output]` for an empty or blank `dir`.
pub fn check_dir(case: &LoadedCase) -> Result<(), CaseError> {
    match &case.case.output {
        Some(o) if o.get_ref().dir.as_deref().is_some_and(|d| d.trim().is_empty()) => Err(case.error_at(
            o.span(),
            "output: `dir` is empty; name a folder for the results (relative to the case file), or leave `dir` \
             out for out/<case file stem> (in the current folder)",
        )),
        _ => Ok(()),
    }
}

/// `[output] compression`: `lz4` (read by VTK 8.1 and later, ParaView 5.5
/// and later; not by meshio), `zlib` (level 6) or `zlib:N` (N = 0–9; read
/// by every VTK version and by meshio, slower to write), `none` (read by
/// every reader, largest files).
///
/// # Errors
/// The message for any other value.
pub fn compression(name: &str) -> Result<Compression, String> {
    let bad = || format!("`compression`: `{name}` is not one of lz4, zlib, zlib:N (N = 0 to 9), none");
    match name {
        "lz4" => Ok(Compression::Lz4),
        "none" => Ok(Compression::None),
        "zlib" => Ok(Compression::Zlib { level: 6 }),
        _ => match name.strip_prefix("zlib:").map(str::parse::<u32>) {
            Some(Ok(level)) if level <= 9 => Ok(Compression::Zlib { level }),
            _ => Err(bad()),
        },
    }
}
