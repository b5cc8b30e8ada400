//! `joints_within`: confining a breakable region's joints to zones, so that
//! only the part of a body that may fracture pays for joints.
//!
//! The rule: a tet of a breakable region with `joints_within` is *jointed*
//! (owns its four nodes, joints on its faces) when its centroid lies in at
//! least one of the region's zones, a point on a zone's surface counting
//! as inside; every other tet of the region shares its nodes with its
//! unjointed neighbours, a plain elastic continuum with the region's
//! material. The centroid puts each tet wholly on one side, so the zone's
//! edge follows element faces (the jointed set is a union of whole tets),
//! and a zone of a few elements' size around a notch holds tets whatever
//! the mesh. A face between a jointed and an unjointed tet carries a joint,
//! like a face between a breakable and an unbreakable region
//! (`femdem_mesh::insert_joints_within`).
//!
//! Refused, at the zone's line: a box with `min ≥ max` on an axis, a
//! sphere or cylinder with a radius that is not `> 0`, a cylinder whose
//! ends coincide, a non-finite coordinate, and a zone that holds no tet of
//! its region (a misplaced zone would silently make the region unbreakable
//! there: almost always a unit or sign mistake); at the region's line:
//! `joints_within` on an unbreakable region, and an empty list.

use femdem_core::tet::centroid;
use femdem_mesh::TetMesh;

use super::format::{MeshSection, ZoneSpec};
use super::{CaseError, LoadedCase};

impl ZoneSpec {
    /// Whether point `p` lies in the zone (its surface included).
    pub fn contains(&self, p: [f64; 3]) -> bool {
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        match self {
            ZoneSpec::Box(b) => (0..3).all(|k| b.min[k] <= p[k] && p[k] <= b.max[k]),
            ZoneSpec::Sphere(s) => {
                let d = sub(p, s.center);
                dot(d, d) <= s.radius * s.radius
            }
            ZoneSpec::Cylinder(c) => {
                let axis = sub(c.to, c.from);
                let d = sub(p, c.from);
                let s = dot(d, axis) / dot(axis, axis);
                let off = [d[0] - s * axis[0], d[1] - s * axis[1], d[2] - s * axis[2]];
                (0.0..=1.0).contains(&s) && dot(off, off) <= c.radius * c.radius
            }
        }
    }

    /// The zone's kind, as written in the case.
    fn kind(&self) -> &'static str {
        match self {
            ZoneSpec::Box(_) => "box",
            ZoneSpec::Sphere(_) => "sphere",
            ZoneSpec::Cylinder(_) => "cylinder",
        }
    }

    /// Why the zone cannot be used, if it cannot.
    fn invalid(&self) -> Option<String> {
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        let radius = |r: f64| {
            (!(r.is_finite() && r > 0.0))
                .then(|| format!("{}: `radius` must be finite and > 0 m, got {r}", self.kind()))
        };
        match self {
            ZoneSpec::Box(b) => {
                if !(finite(&b.min) && finite(&b.max)) {
                    Some("box: `min` and `max` must be finite".into())
                } else if (0..3).any(|k| b.min[k] >= b.max[k]) {
                    Some(format!("box: `min` {:?} must be below `max` {:?} on every axis", b.min, b.max))
                } else {
                    None
                }
            }
            ZoneSpec::Sphere(s) => {
                if finite(&s.center) {
                    radius(s.radius)
                } else {
                    Some("sphere: `center` must be finite".into())
                }
            }
            ZoneSpec::Cylinder(c) => {
                if !(finite(&c.from) && finite(&c.to)) {
                    Some("cylinder: `from` and `to` must be finite".into())
                } else if c.from == c.to {
                    Some(format!("cylinder: `from` and `to` are the same point {:?}: the axis has no length", c.from))
                } else {
                    radius(c.radius)
                }
            }
        }
    }
}

/// The zones of region `name` in `section`, if it has `joints_within`.
pub fn zones_of(section: &MeshSection, name: &str) -> Option<Vec<ZoneSpec>> {
    let region = section.regions.iter().find(|r| r.get_ref().name == name)?;
    region.get_ref().joints_within.as_ref().map(|z| z.iter().map(|s| *s.get_ref()).collect())
}

/// The joint zone of the case's mesh, for
/// `femdem_mesh::insert_joints_within`: `zone[t]` is false for the tets of
/// a region with `joints_within` whose centroid lies in none of its zones,
/// true for every other tet (whether a tet is jointed also needs its region
/// to be breakable). The zones must have passed [`check`]; `mesh.regions`
/// must be in the case's declared order, as `build_mesh` leaves them.
///
/// # Errors
/// A [`CaseError`] at the first zone that holds no tet of its region.
pub fn joint_zone(case: &LoadedCase, mesh: &TetMesh) -> Result<Vec<bool>, CaseError> {
    let mut zone = vec![true; mesh.num_tets()];
    for (r, spec) in case.case.mesh.regions.iter().enumerate() {
        let region = spec.get_ref();
        let Some(zones) = &region.joints_within else { continue };
        let key = format!("mesh.regions[{r}].joints_within");
        let tets: Vec<usize> = (0..mesh.num_tets()).filter(|&t| mesh.tet_region[t] as usize == r).collect();
        let mut holds = vec![false; zones.len()];
        for &t in &tets {
            let c = centroid(&mesh.tet_points(t));
            let c = [c[0], c[1], c[2]];
            let mut inside = false;
            for (k, z) in zones.iter().enumerate() {
                if z.get_ref().contains(c) {
                    holds[k] = true;
                    inside = true;
                }
            }
            zone[t] = inside;
        }
        if let Some(k) = holds.iter().position(|h| !h) {
            return Err(case.error_at(
                zones[k].span(),
                format!(
                    "{key}[{k}]: the {} holds no tet of region `{}` ({} tets): a tet is jointed when its centroid \
                     lies in a zone (coordinates are the mesh's, in metres)",
                    zones[k].get_ref().kind(),
                    region.name,
                    tets.len()
                ),
            ));
        }
    }
    Ok(zone)
}

/// Checks every region's `joints_within` before any mesh is built: the
/// region is breakable, the list is not empty, each zone is well formed.
///
/// # Errors
/// A [`CaseError`] at the region or zone.
pub fn check(case: &LoadedCase) -> Result<(), CaseError> {
    for (r, spec) in case.case.mesh.regions.iter().enumerate() {
        let region = spec.get_ref();
        let Some(zones) = &region.joints_within else { continue };
        let key = format!("mesh.regions[{r}].joints_within");
        if !region.breakable {
            return Err(case.error_at(
                spec.span(),
                format!("{key}: region `{}` is not breakable: it has no joints to confine", region.name),
            ));
        }
        if zones.is_empty() {
            return Err(case.error_at(
                spec.span(),
                format!("{key}: an empty list leaves region `{}` no joint; set breakable = false instead", region.name),
            ));
        }
        for (k, z) in zones.iter().enumerate() {
            if let Some(why) = z.get_ref().invalid() {
                return Err(case.error_at(z.span(), format!("{key}[{k}]: {why}")));
            }
        }
    }
    Ok(())
}

/// The share of the tets `tets` of `mesh` whose centroid lies in one of
/// `zones` (1 for no tet): the jointed share of a mesh read before the
/// case's mesh is built (the memory estimate of an MSH part).
pub fn centroid_share(zones: &[ZoneSpec], mesh: &TetMesh, tets: &[usize]) -> f64 {
    let inside = tets
        .iter()
        .filter(|&&t| {
            let c = centroid(&mesh.tet_points(t));
            zones.iter().any(|z| z.contains([c[0], c[1], c[2]]))
        })
        .count();
    if tets.is_empty() { 1.0 } else { inside as f64 / tets.len() as f64 }
}

/// Points per axis of [`sampled_share`]'s grid.
const SAMPLES: usize = 24;

/// The share of the volume `inside` selects within the box `[lo, hi]` that
/// lies in one of `zones`, sampled at the centres of a regular grid of
/// `SAMPLES³` cells (for the memory estimate, before any mesh exists; 1
/// when no sample is inside).
pub fn sampled_share(zones: &[ZoneSpec], lo: [f64; 3], hi: [f64; 3], inside: impl Fn([f64; 3]) -> bool) -> f64 {
    let (mut total, mut within) = (0usize, 0usize);
    for i in 0..SAMPLES {
        for j in 0..SAMPLES {
            for k in 0..SAMPLES {
                let at = |n: usize, a: usize| lo[a] + (n as f64 + 0.5) / SAMPLES as f64 * (hi[a] - lo[a]);
                let p = [at(i, 0), at(j, 1), at(k, 2)];
                if inside(p) {
                    total += 1;
                    within += usize::from(zones.iter().any(|z| z.contains(p)));
                }
            }
        }
    }
    if total == 0 { 1.0 } else { within as f64 / total as f64 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::{BoxSpec, CylinderSpec, SphereSpec};

    #[test]
    fn zones_contain_their_inside_and_surface() {
        let b = ZoneSpec::Box(BoxSpec { min: [0.0; 3], max: [1.0, 2.0, 3.0] });
        assert!(b.contains([0.5, 2.0, 0.0]) && !b.contains([0.5, 2.1, 0.0]));
        let s = ZoneSpec::Sphere(SphereSpec { center: [1.0, 0.0, 0.0], radius: 0.5 });
        assert!(s.contains([1.5, 0.0, 0.0]) && !s.contains([1.4, 0.4, 0.0]));
        let c = ZoneSpec::Cylinder(CylinderSpec { from: [0.0; 3], to: [0.0, 0.0, 2.0], radius: 1.0 });
        assert!(c.contains([1.0, 0.0, 2.0]) && c.contains([0.6, 0.6, 1.0]));
        assert!(!c.contains([0.0, 0.0, 2.01]) && !c.contains([0.8, 0.8, 1.0]));
    }

    #[test]
    fn bad_zones_say_why() {
        let bad = [
            (ZoneSpec::Box(BoxSpec { min: [0.0; 3], max: [1.0, 0.0, 1.0] }), "must be below `max`"),
            (ZoneSpec::Sphere(SphereSpec { center: [0.0; 3], radius: -1.0 }), "got -1"),
            (ZoneSpec::Sphere(SphereSpec { center: [f64::NAN; 3], radius: 1.0 }), "`center` must be finite"),
            (ZoneSpec::Cylinder(CylinderSpec { from: [1.0; 3], to: [1.0; 3], radius: 1.0 }), "no length"),
            (ZoneSpec::Cylinder(CylinderSpec { from: [0.0; 3], to: [1.0; 3], radius: 0.0 }), "got 0"),
        ];
        for (z, words) in bad {
            let why = z.invalid().expect("refused");
            assert!(why.contains(words), "{why}");
        }
    }

    /// A slab of a third of a unit cube holds a third of its volume, to the
    /// grid's resolution; a sphere of radius 0.5 in a cube, π/6 of it.
    #[test]
    fn sampled_share_is_the_volume_fraction() {
        let slab = [ZoneSpec::Box(BoxSpec { min: [-1.0, -1.0, 0.0], max: [2.0, 2.0, 1.0 / 3.0] })];
        let share = sampled_share(&slab, [0.0; 3], [1.0; 3], |_| true);
        assert!((share - 1.0 / 3.0).abs() < 1.0 / SAMPLES as f64, "{share}");
        let ball = [ZoneSpec::Sphere(SphereSpec { center: [0.5; 3], radius: 0.5 })];
        let share = sampled_share(&ball, [0.0; 3], [1.0; 3], |_| true);
        assert!((share - std::f64::consts::PI / 6.0).abs() < 0.02, "{share}");
        assert_eq!(sampled_share(&ball, [0.0; 3], [1.0; 3], |_| false), 1.0);
    }
}
