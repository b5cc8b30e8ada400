//! Loads and kinematic constraints, with the paper's ramp: a load rises
//! linearly from zero over `ramp_time` and is then held (§3.1, §3.2).

use femdem_core::{Real, Vec3};

/// Time history factor of a load: `min(t / ramp_time, 1)` until
/// `stop_time`, zero after it. `ramp_time = 0` applies the load at once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ramp {
    /// Duration of the linear rise, s.
    pub ramp_time: Real,
    /// Time after which the load is removed (a velocity drive stops), s.
    pub stop_time: Option<Real>,
}

impl Ramp {
    /// Applied at once and never removed.
    pub const STEP: Ramp = Ramp { ramp_time: 0.0, stop_time: None };

    /// The factor at time `t`.
    #[inline]
    pub fn factor(&self, t: Real) -> Real {
        if self.stop_time.is_some_and(|s| t > s) {
            return 0.0;
        }
        if self.ramp_time <= 0.0 { 1.0 } else { (t / self.ramp_time).min(1.0) }
    }
}

/// Fixed velocity components (zero) on a node set.
#[derive(Clone, Debug, PartialEq)]
pub struct Fixed {
    /// Node ids.
    pub nodes: Vec<u32>,
    /// Which of x, y, z are held.
    pub components: [bool; 3],
}

/// A prescribed velocity on a node set, `v(t) = ramp(t) · velocity` on the
/// components given; its reaction force is recorded under `name`.
///
/// With a `start_time`, the components are free before it (the nodes move
/// under their forces; the recorded reaction is zero and does no work) and
/// prescribed from it on: a zero `velocity` then holds the nodes where they
/// are at `start_time` (e.g. faces held where a pressure ramp left them).
#[derive(Clone, Debug, PartialEq)]
pub struct VelocityDrive {
    /// Name of the recorded force (e.g. `"platen_top"`).
    pub name: String,
    /// Node ids.
    pub nodes: Vec<u32>,
    /// Target velocity, m/s.
    pub velocity: Vec3,
    /// Which components are prescribed (the others move freely).
    pub components: [bool; 3],
    /// Time history.
    pub ramp: Ramp,
    /// Time from which the components are prescribed, s (`None`: from the
    /// start). The ramp's times are absolute, not counted from it.
    pub start_time: Option<Real>,
}

impl VelocityDrive {
    /// Whether the drive prescribes the velocity at time `t`: the step from
    /// `t_n` prescribes `v_{n+½}` when `t = t_n + Δt/2 ≥ start_time`, so a
    /// node held at zero velocity keeps its position of the first `t_n ≥
    /// start_time − Δt/2` from then on.
    #[inline]
    pub fn active(&self, t: Real) -> bool {
        self.start_time.is_none_or(|s| t >= s)
    }

    /// Whether the drive prescribes its components from the first step on
    /// (no `start_time`, or one ≤ 0 s): only then are its nodes held for
    /// the stable-step estimate and the static start.
    #[inline]
    pub fn from_start(&self) -> bool {
        self.start_time.is_none_or(|s| s <= 0.0)
    }
}

/// What a surface load applies on each face.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SurfaceKind {
    /// Pressure, Pa, along the inward normal of the current face (positive
    /// pushes on the surface).
    Pressure(Real),
    /// Traction, Pa, a fixed vector per unit current area.
    Traction(Vec3),
}

/// A pressure or traction on a set of boundary faces.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceLoad {
    /// Name of the load in the history (its total force is recorded).
    pub name: String,
    /// Face node triples, counter-clockwise seen from outside the body.
    pub faces: Vec<[u32; 3]>,
    /// Pressure or traction.
    pub kind: SurfaceKind,
    /// Time history.
    pub ramp: Ramp,
}

/// Everything applied to a model besides its internal forces.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Loads {
    /// Body acceleration (gravity), m/s².
    pub gravity: Vec3,
    /// Fixed components.
    pub fixed: Vec<Fixed>,
    /// Prescribed velocities (including rigid platens driving node sets).
    pub drives: Vec<VelocityDrive>,
    /// Pressures and tractions.
    pub surfaces: Vec<SurfaceLoad>,
}

/// The nodal forces of a surface load at factor `s` on current positions:
/// each face carries `s · A · t` with `t = −p n` (pressure) or the traction,
/// shared equally by its three nodes (exact for a uniform traction on a
/// linear triangle). Calls `add(node, force)` for each node of each face,
/// in face order.
pub fn surface_forces(load: &SurfaceLoad, x: &[Vec3], s: Real, mut add: impl FnMut(u32, Vec3)) {
    if s == 0.0 {
        return;
    }
    for f in &load.faces {
        let [a, b, c] = f.map(|n| x[n as usize]);
        let area_normal = (b - a).cross(&(c - a)) * 0.5; // outward, |·| = area
        let force = match load.kind {
            SurfaceKind::Pressure(p) => -area_normal * (p * s),
            SurfaceKind::Traction(t) => t * (area_normal.norm() * s),
        };
        for &n in f {
            add(n, force / 3.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_rises_then_holds_then_stops() {
        let r = Ramp { ramp_time: 2.0, stop_time: Some(5.0) };
        assert_eq!(r.factor(0.0), 0.0);
        assert_eq!(r.factor(1.0), 0.5);
        assert_eq!(r.factor(3.0), 1.0);
        assert_eq!(r.factor(5.5), 0.0);
        assert_eq!(Ramp::STEP.factor(0.0), 1.0);
    }

    #[test]
    fn a_drive_acts_from_its_start_time() {
        let mut d = VelocityDrive {
            name: "d".into(),
            nodes: vec![0],
            velocity: Vec3::zeros(),
            components: [true; 3],
            ramp: Ramp::STEP,
            start_time: None,
        };
        assert!(d.active(0.0) && d.from_start());
        d.start_time = Some(1e-3);
        assert!(!d.active(0.999e-3) && d.active(1e-3) && d.active(2e-3));
        assert!(!d.from_start());
        d.start_time = Some(0.0);
        assert!(d.active(0.0) && d.from_start());
    }

    #[test]
    fn pressure_on_a_face_pushes_inward_with_p_times_area() {
        let x = vec![Vec3::zeros(), Vec3::x(), Vec3::y()];
        // Counter-clockwise seen from +z: outward normal +z.
        let load = SurfaceLoad {
            name: "p".into(),
            faces: vec![[0, 1, 2]],
            kind: SurfaceKind::Pressure(6.0),
            ramp: Ramp::STEP,
        };
        let mut total = Vec3::zeros();
        surface_forces(&load, &x, 1.0, |_, f| total += f);
        assert!((total - Vec3::new(0.0, 0.0, -3.0)).norm() < 1e-15);
    }
}
