//! `[contact]`: the contact settings and the run guard's energy check.

use femdem_mesh::JointedMesh;
use femdem_solver::{Activation, ContactModel, ContactSettings};

use crate::{CaseError, LoadedCase};

/// The case file's names of `[contact] activation`'s options.
const ACTIVATIONS: [(&str, Activation); 5] = [
    ("couple", Activation::Couple),
    ("offset", Activation::Offset),
    ("paper", Activation::Paper),
    ("ramp", Activation::Ramp),
    ("settle", Activation::Settle),
];

/// The case file's name of `activation`.
pub fn activation_name(activation: Activation) -> &'static str {
    ACTIVATIONS.iter().find(|(_, a)| *a == activation).map_or("?", |(n, _)| n)
}

/// The case file's names of `[contact] model`'s options.
const CONTACT_MODELS: [(&str, ContactModel); 2] =
    [("potential", ContactModel::Potential), ("gradient", ContactModel::Gradient)];

/// The contact model named `name` (`[contact] model`); `None` for an
/// unknown name.
fn contact_model(name: &str) -> Option<ContactModel> {
    CONTACT_MODELS.iter().find(|(n, _)| *n == name).map(|&(_, m)| m)
}

/// Builds the contact settings of the case's `[contact]`, if any.
///
/// # Errors
/// A located [`CaseError`] for a penalty that is not positive, a friction
/// coefficient that is negative or not finite, a negative buffer, a
/// `negligible` outside `[0, 1e-3)`, an unknown `activation` or `model`,
/// or an unknown region in `[[contact.pairs]]`.
pub fn contact(case: &LoadedCase, mesh: &JointedMesh) -> Result<Option<ContactSettings>, CaseError> {
    contact_noting(case, mesh, &mut Vec::new())
}

/// [`contact`], pushing onto `warnings` a friction coefficient far above
/// rock's ([`super::plausible::friction_warning`]: an angle given for μ).
///
/// # Errors
/// As [`contact`].
pub fn contact_noting(
    case: &LoadedCase,
    mesh: &JointedMesh,
    warnings: &mut Vec<String>,
) -> Result<Option<ContactSettings>, CaseError> {
    if let Some(c) = &case.case.contact {
        if let Some(w) = super::plausible::friction_warning("friction", c.get_ref().friction) {
            warnings.push(case.error_at(c.span(), format!("contact: {w}")).to_string());
        }
        for (i, p) in c.get_ref().pairs.iter().enumerate() {
            if let Some(w) = super::plausible::friction_warning("friction", p.get_ref().friction) {
                warnings.push(case.error_at(p.span(), format!("contact.pairs[{i}]: {w}")).to_string());
            }
        }
    }
    settings(case, mesh)
}

fn settings(case: &LoadedCase, mesh: &JointedMesh) -> Result<Option<ContactSettings>, CaseError> {
    let Some(c) = &case.case.contact else { return Ok(None) };
    let spec = c.get_ref();
    let at = |msg: String| case.error_at(c.span(), format!("contact.{msg}"));
    if !(spec.penalty.is_finite() && spec.penalty > 0.0) {
        return Err(at(format!("penalty must be > 0 Pa, got {}", spec.penalty)));
    }
    if !(spec.friction.is_finite() && spec.friction >= 0.0) {
        return Err(at(format!("friction must be ≥ 0, got {}", spec.friction)));
    }
    if !(spec.buffer.is_finite() && spec.buffer >= 0.0) {
        return Err(at(format!("buffer must be ≥ 0 m, got {}", spec.buffer)));
    }
    if !(spec.negligible.is_finite() && (0.0..1e-3).contains(&spec.negligible)) {
        return Err(at(format!("negligible must be in [0, 1e-3), got {}", spec.negligible)));
    }
    let activation = match spec.activation.as_deref() {
        None => Activation::default(),
        Some(name) => ACTIVATIONS.iter().find(|(n, _)| *n == name).map(|&(_, a)| a).ok_or_else(|| {
            let names: Vec<String> = ACTIVATIONS.iter().map(|(n, _)| format!("`{n}`")).collect();
            let (last, rest) = names.split_last().expect("activations");
            at(format!("activation `{name}` is not {} or {last}", rest.join(", ")))
        })?,
    };
    let model = match spec.model.as_deref() {
        None => ContactModel::default(),
        Some(name) => {
            contact_model(name).ok_or_else(|| at(format!("model `{name}` is not `potential` or `gradient`")))?
        }
    };
    let mut settings = ContactSettings {
        activation,
        penalty: spec.penalty,
        surfaces: spec.surfaces,
        friction: spec.friction,
        pair_friction: Vec::new(),
        buffer: spec.buffer,
        ramp_steps: spec.ramp_steps,
        incremental: true,
        certify: true,
        negligible: spec.negligible,
        model,
    };
    for (i, p) in spec.pairs.iter().enumerate() {
        let pair = p.get_ref();
        let at = |msg: String| case.error_at(p.span(), format!("contact.pairs[{i}]: {msg}"));
        let mut ids = [0u16; 2];
        for (k, name) in pair.regions.iter().enumerate() {
            ids[k] = mesh.mesh.region_index(name).ok_or_else(|| at(format!("`{name}` is not a region of the mesh")))?;
        }
        if !(pair.friction.is_finite() && pair.friction >= 0.0) {
            return Err(at(format!("friction must be ≥ 0, got {}", pair.friction)));
        }
        // The same pair twice (in either order) would leave which μ holds
        // to the solver's lookup order.
        let same = |q: &[u16; 2]| *q == ids || *q == [ids[1], ids[0]];
        if let Some(j) = settings.pair_friction.iter().position(|(q, _)| same(q)) {
            return Err(at(format!(
                "the regions `{}` and `{}` already have a friction, in contact.pairs[{j}]; give each pair once",
                pair.regions[0], pair.regions[1]
            )));
        }
        settings.pair_friction.push((ids, pair.friction));
    }
    Ok(Some(settings))
}

/// What the run guard does when contact has given back more energy than
/// it absorbed (`[contact] energy_check`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ContactCheck {
    /// Stop the run (the default).
    Stop,
    /// Warn once and go on.
    Warn,
}

/// The case's `[contact] energy_check` and `energy_tolerance` (`None`
/// without `[contact]` or with `energy_check = "off"`).
///
/// # Errors
/// A located [`CaseError`] for a check other than `stop`, `warn` or `off`,
/// or a tolerance outside (0, 1].
pub fn contact_check(case: &LoadedCase) -> Result<Option<(ContactCheck, f64)>, CaseError> {
    let Some(c) = &case.case.contact else { return Ok(None) };
    let spec = c.get_ref();
    let tolerance = spec.energy_tolerance.unwrap_or(femdem_solver::CONTACT_ENERGY_TOLERANCE);
    if !(tolerance > 0.0 && tolerance <= 1.0) {
        let message = format!(
            "contact.energy_tolerance must lie in (0, 1] (a fraction of the run's energy scale), got {tolerance}"
        );
        return Err(case.error_at(c.span(), message));
    }
    let check = match spec.energy_check.as_deref() {
        None | Some("stop") => ContactCheck::Stop,
        Some("warn") => ContactCheck::Warn,
        Some("off") => return Ok(None),
        Some(other) => {
            return Err(
                case.error_at(c.span(), format!("contact.energy_check `{other}` is not `stop`, `warn` or `off`"))
            );
        }
    };
    Ok(Some((check, tolerance)))
}
