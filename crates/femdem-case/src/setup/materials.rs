//! The regions' behaviours (`[[materials]]`, `[[platens]]`) and the model
//! built from them, with `[heterogeneity]`'s strengths.

use femdem_fracture::heterogeneity::Distribution;
use femdem_fracture::{Coupling, GfCalibration, JointParams};
use femdem_material::{ElasticParams, Law};
use femdem_mesh::JointedMesh;
use femdem_solver::{Model, RegionBehaviour};

use crate::{CaseError, LoadedCase};

/// The default joint penalty as a multiple of E (the top of Eq. 9's range).
pub const DEFAULT_PENALTY_FACTOR: f64 = 10.0;

/// Builds the region behaviours of the case.
///
/// # Errors
/// A located [`CaseError`] for an unknown region, a region with two
/// materials, a deformable region without one, bad parameters, or missing
/// joint strengths in a breakable region. What is legal but probably not
/// meant (a cohesion that caps the tensile strength through Eq. 5's
/// tension cut-off; values outside any solid's range, see
/// [`super::plausible`]) is pushed onto `warnings`.
pub fn behaviours(
    case: &LoadedCase,
    mesh: &JointedMesh,
    warnings: &mut Vec<String>,
) -> Result<Vec<RegionBehaviour>, CaseError> {
    let m = &mesh.mesh;
    let stats = femdem_mesh::stats(m);
    let mut out: Vec<Option<RegionBehaviour>> = vec![None; m.regions.len()];
    for p in &case.case.platens {
        let r = m.region_index(&p.get_ref().region).ok_or_else(|| {
            case.error_at(p.span(), format!("platens.region: `{}` is not a region of the mesh", p.get_ref().region))
        })?;
        if m.regions[r as usize].breakable {
            return Err(case.error_at(
                p.span(),
                format!("platens.region: `{}` is breakable; a rigid platen cannot break", p.get_ref().region),
            ));
        }
        out[r as usize] = Some(RegionBehaviour::Rigid);
    }
    for (i, spec) in case.case.materials.iter().enumerate() {
        let s = spec.get_ref();
        let key = format!("materials[{i}]");
        let at = |msg: String| case.error_at(spec.span(), format!("{key}: {msg}"));
        for warning in super::plausible::material_warnings(s) {
            warnings.push(at(warning).to_string());
        }
        let r = m
            .region_index(&s.region)
            .ok_or_else(|| at(format!("region `{}` is not a region of the mesh", s.region)))?;
        if out[r as usize].is_some() {
            return Err(at(format!("region `{}` already has a material or is a platen", s.region)));
        }
        let law = match s.law.as_str() {
            "neo-hookean" => Law::NeoHookean,
            "linear-elastic" => Law::LinearElastic,
            other => {
                return Err(at(format!("law `{other}` is not `neo-hookean` or `linear-elastic`")));
            }
        };
        let mean_edge = {
            // Mean edge of this region's tets.
            let mut sum = 0.0;
            let mut count = 0usize;
            for t in (0..m.num_tets()).filter(|&t| m.tet_region[t] == r) {
                sum += femdem_core::tet::edge_lengths(&m.tet_points(t)).iter().sum::<f64>();
                count += 6;
            }
            if count > 0 { sum / count as f64 } else { stats.mean_edge }
        };
        let viscosity = match (s.viscosity, s.damping_ratio) {
            (Some(_), Some(_)) => {
                return Err(at("give `viscosity` or `damping_ratio`, not both".into()));
            }
            (Some(v), None) => v,
            (None, Some(xi)) => {
                if !(xi.is_finite() && xi >= 0.0) {
                    return Err(at(format!("`damping_ratio` must be finite and ≥ 0, got {xi}")));
                }
                xi * femdem_material::critical_viscosity(mean_edge, s.young, s.density)
            }
            (None, None) => 0.0,
        };
        let material = ElasticParams { young: s.young, poisson: s.poisson, density: s.density, viscosity }
            .validate()
            .map_err(|e| at(e.to_string()))?;
        let joints = if m.regions[r as usize].breakable {
            let need = |v: Option<f64>, name: &str| {
                v.ok_or_else(|| at(format!("region `{}` is breakable: `{name}` is required", s.region)))
            };
            let calibration = match s.gf_calibration.as_deref() {
                None | Some("paper") => GfCalibration::Paper,
                Some("exact") => GfCalibration::Exact,
                Some(other) => {
                    return Err(at(format!("gf_calibration `{other}` is not `paper` or `exact`")));
                }
            };
            let coupling = match s.joint_coupling.as_deref() {
                Some("capped") => Coupling::Capped,
                None | Some("printed") => Coupling::Printed,
                Some("multiplicative") => Coupling::Multiplicative,
                Some(other) => {
                    return Err(at(format!("joint_coupling `{other}` is not `capped`, `printed` or `multiplicative`")));
                }
            };
            let gf = need(s.fracture_energy, "fracture_energy")?;
            // Checked here in the case's own keys and units (the library's
            // checks name its fields, in radians).
            let phi = need(s.friction_angle, "friction_angle")?;
            if !(phi.is_finite() && (0.0..90.0).contains(&phi)) {
                return Err(at(format!("`friction_angle` must lie in [0°, 90°), got {phi}°")));
            }
            for (key, value) in [("fracture_energy", Some(gf)), ("fracture_energy_shear", s.fracture_energy_shear)] {
                if let Some(v) = value.filter(|v| !(v.is_finite() && *v > 0.0)) {
                    return Err(at(format!("`{key}` must be finite and > 0 J/m², got {v} J/m²")));
                }
            }
            let params = JointParams {
                penalty: s.penalty.unwrap_or(DEFAULT_PENALTY_FACTOR * s.young),
                tensile_strength: need(s.tensile_strength, "tensile_strength")?,
                cohesion: need(s.cohesion, "cohesion")?,
                friction_angle: need(s.friction_angle, "friction_angle")?.to_radians(),
                gf_tension: gf,
                gf_shear: s.fracture_energy_shear.unwrap_or(gf),
                calibration,
                coupling,
            };
            let params = params.validate().map_err(|e| at(e.to_string()))?;
            if params.cohesion_limits_tension() {
                warnings.push(format!(
                    "{}: cohesion {} Pa ≤ tensile_strength × tan(friction_angle): Eq. 5's tension cut-off \
                     caps the tensile strength at c / tan φ = {:.6e} Pa",
                    at(format!("materials, region `{}`", s.region)),
                    params.cohesion,
                    params.effective_tensile_strength()
                ));
            }
            Some(params)
        } else {
            None
        };
        out[r as usize] = Some(RegionBehaviour::Deformable { law, material, joints });
    }
    out.into_iter()
        .enumerate()
        .map(|(r, b)| {
            b.ok_or_else(|| {
                let name = &m.regions[r].name;
                let message = format!("region `{name}` has no [[materials]] entry and is not a [[platens]] region");
                // At the region's declaration where the case has one.
                match case.case.mesh.regions.iter().position(|q| q.get_ref().name == *name) {
                    Some(i) => case.error_at(case.case.mesh.regions[i].span(), format!("mesh.regions[{i}]: {message}")),
                    None => CaseError { path: case.path.clone(), at: None, message },
                }
            })
        })
        .collect()
}

/// Builds the model with the case's mass scaling.
///
/// # Errors
/// As [`behaviours`], plus model set-up errors; its warnings are pushed
/// onto `warnings`.
pub fn model(
    case: &LoadedCase,
    mesh: &JointedMesh,
    mass_scaling: f64,
    warnings: &mut Vec<String>,
) -> Result<Model, CaseError> {
    let b = behaviours(case, mesh, warnings)?;
    let mut model = Model::new(mesh, &b, mass_scaling).map_err(|e| CaseError {
        path: case.path.clone(),
        at: None,
        message: e.to_string(),
    })?;
    if let Some(h) = &case.case.heterogeneity {
        let spec = h.get_ref();
        let at = |msg: String| case.error_at(h.span(), format!("heterogeneity: {msg}"));
        // The other distribution's parameter is ignored: said (a warning,
        // since `--set` switching the distribution cannot remove the key).
        let stray = match (spec.distribution.as_str(), spec.modulus, spec.cov) {
            ("weibull", _, Some(_)) => Some("`cov` is the normal distribution's, and a Weibull one ignores it"),
            ("normal", Some(_), _) => Some("`modulus` is the Weibull distribution's, and a normal one ignores it"),
            _ => None,
        };
        if let Some(message) = stray {
            warnings.push(at(message.into()).to_string());
        }
        let dist = match spec.distribution.as_str() {
            "weibull" => Distribution::Weibull {
                modulus: spec.modulus.ok_or_else(|| at("`modulus` is required for a Weibull distribution".into()))?,
            },
            "normal" => Distribution::Normal {
                cov: spec.cov.ok_or_else(|| at("`cov` is required for a normal distribution".into()))?,
            },
            other => {
                return Err(at(format!("distribution `{other}` is not `weibull` or `normal`")));
            }
        };
        model.randomise_strengths(dist, spec.seed.unwrap_or(case.case.mesh.seed)).map_err(|e| at(e.to_string()))?;
    }
    Ok(model)
}
