//! The solver's contact pass (reference paper §2.3): which tets may touch,
//! NBS detection among them, and the tet–tet potential forces (Eq. 17).
//!
//! A scene pays only for what it uses: with contact off nothing here runs;
//! with it on, only *contactable* tets are searched — the tets of rigid
//! regions, the tets on the outer surface of each body (when surface contact
//! is asked for), the tets on pre-existing fractures, and the two tets of
//! every joint that fails (added as it fails). Pairs still bonded by an
//! active joint, sharing a node (neighbours in a continuous region), or
//! sharing an original vertex while not both activated by a fracture
//! (neighbours in an intact body, which would otherwise push on each other
//! across their common edge) are excluded. Detection runs every step (NBS is O(N) in the contactable
//! tets); forces are summed over the pairs in the order NBS returns them,
//! which depends only on the input, so results do not depend on the thread
//! count.
//!
//! Not yet: friction coefficients per pair of regions, and a detection
//! interval from the largest velocity and a buffer.

use std::collections::HashSet;

use femdem_contact::{Nbs, tet_tet_forces};
use femdem_core::{Real, Vec3};

use crate::model::{Model, RIGID};

/// Contact settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactSettings {
    /// Normal penalty `p` of Eq. 17, Pa (a multiple of E).
    pub penalty: Real,
    /// Whether the outer surfaces of bodies are contactable (for collisions
    /// and platens); fracture surfaces always are.
    pub surfaces: bool,
    /// Coulomb friction coefficient μ (0: frictionless).
    pub friction: Real,
}

/// Steps over which the contact force of a joint that failed in
/// compression rises from zero to its full value (Eq. 18, `n_total`).
pub const RAMP_STEPS: u32 = 10;

/// The contact pass's state.
#[derive(Clone, Debug)]
pub struct Contact {
    /// Settings.
    pub settings: ContactSettings,
    contactable: Vec<bool>,
    /// Tets made contactable by a fracture (failed joint or pre-existing).
    activated: Vec<bool>,
    list: Vec<u32>,
    bonded: HashSet<(u32, u32)>,
    nbs: Nbs,
    centers: Vec<[Real; 3]>,
    radii: Vec<Real>,
    pairs: Vec<(u32, u32)>,
    /// Contact force per node from the last pass.
    pub force: Vec<Vec3>,
    touched: Vec<u32>,
    /// Pairs in contact at the last pass.
    pub active_pairs: usize,
    /// Tangential spring stretch of each pair in contact (friction history).
    stick: std::collections::HashMap<(u32, u32), Vec3>,
    stick_next: std::collections::HashMap<(u32, u32), Vec3>,
    /// Pairs of joints that failed in compression, with their step count
    /// `n_c` of Eq. 18.
    ramp: std::collections::HashMap<(u32, u32), u32>,
}

impl Contact {
    /// The contact state of `model` with `settings`; `initial` are tet pairs
    /// in contact from the start (pre-existing fractures).
    pub fn new(model: &Model, settings: ContactSettings, initial: &[(u32, u32)]) -> Contact {
        let n_tets = model.tets.len();
        let mut contactable: Vec<bool> = model.tet_material.iter().map(|&m| m == RIGID).collect();
        if settings.surfaces {
            for (t, on) in model.surface_tets().into_iter().enumerate() {
                contactable[t] |= on;
            }
        }
        let mut activated = vec![false; n_tets];
        for &(a, b) in initial {
            for t in [a, b] {
                contactable[t as usize] = true;
                activated[t as usize] = true;
            }
        }
        let bonded = model.joint_tets.iter().map(|&[a, b]| (a.min(b), a.max(b))).collect();
        let list = (0..n_tets as u32).filter(|&t| contactable[t as usize]).collect();
        Contact {
            settings,
            contactable,
            activated,
            list,
            bonded,
            nbs: Nbs::new(),
            centers: Vec::new(),
            radii: Vec::new(),
            pairs: Vec::new(),
            force: vec![Vec3::zeros(); model.num_nodes()],
            touched: Vec::new(),
            active_pairs: 0,
            stick: Default::default(),
            stick_next: Default::default(),
            ramp: Default::default(),
        }
    }

    /// Makes the two tets of a failed joint contactable and unbonds them
    /// (Eq. 14). A joint that failed in compression (`compressed`: its mean
    /// opening was negative) has the contact force between its two tets
    /// ramped in over [`RAMP_STEPS`] steps (Eq. 18), so that the joint force,
    /// which vanishes at failure, is not replaced by a sudden contact force.
    pub fn joint_failed(&mut self, tets: [u32; 2], compressed: bool) {
        let key = (tets[0].min(tets[1]), tets[0].max(tets[1]));
        self.bonded.remove(&key);
        if compressed {
            self.ramp.insert(key, 0);
        }
        for t in tets {
            self.activated[t as usize] = true;
            if !self.contactable[t as usize] {
                self.contactable[t as usize] = true;
                let at = self.list.partition_point(|&x| x < t);
                self.list.insert(at, t);
            }
        }
    }

    /// The nodes the last pass put a force on.
    pub fn touched(&self) -> &[u32] {
        &self.touched
    }

    /// Detects contacts at positions `x` and computes the contact force on
    /// every node into [`Contact::force`] (zero elsewhere; the nodes with a
    /// force are [`Contact::touched`]). `v` (velocities) and `dt` drive the
    /// friction springs.
    ///
    /// Friction: each pair in contact carries a tangential spring `s`,
    /// stretched by the tangential relative velocity of the two tets'
    /// centroids, `s += v_t Δt`, kept in the current tangent plane (normal
    /// `n̂` along the pair's normal force `N`); the friction force is
    /// `−k_t s` with `k_t = p ℓ` (`ℓ` the smaller tet's `V^{1/3}`, so that the
    /// tangential stiffness is of the order of the normal one), capped at the
    /// Coulomb limit `μ N`, where the spring slips (is shortened to the
    /// limit). It acts on the centroids (a quarter on each node).
    pub fn pass(&mut self, model: &Model, x: &[Vec3], v: &[Vec3], dt: Real) {
        for &n in &self.touched {
            self.force[n as usize] = Vec3::zeros();
        }
        self.touched.clear();
        self.centers.clear();
        self.radii.clear();
        for &t in &self.list {
            let p = model.tets[t as usize].map(|n| x[n as usize]);
            let c = (p[0] + p[1] + p[2] + p[3]) / 4.0;
            let r = p.iter().map(|q| (q - c).norm()).fold(0.0, Real::max);
            self.centers.push([c.x, c.y, c.z]);
            self.radii.push(r);
        }
        self.pairs.clear();
        self.nbs.detect(&self.centers, &self.radii, 0.0, &mut self.pairs);
        self.active_pairs = 0;
        for &(i, j) in &self.pairs {
            let (a, b) = (self.list[i as usize], self.list[j as usize]);
            if model.tet_material[a as usize] == RIGID && model.tet_material[b as usize] == RIGID {
                continue;
            }
            if self.bonded.contains(&(a.min(b), a.max(b))) {
                continue;
            }
            let (ta, tb) = (model.tets[a as usize], model.tets[b as usize]);
            if ta.iter().any(|n| tb.contains(n)) {
                continue;
            }
            // Neighbours in an intact body (sharing an original vertex) touch
            // only once a fracture has activated both (Eq. 15–16's groups).
            let (oa, ob) = (ta.map(|n| model.origin[n as usize]), tb.map(|n| model.origin[n as usize]));
            if oa.iter().any(|v| ob.contains(v)) && !(self.activated[a as usize] && self.activated[b as usize]) {
                continue;
            }
            let pa = ta.map(|n| x[n as usize]);
            let pb = tb.map(|n| x[n as usize]);
            let (mut fa, mut fb) = tet_tet_forces(&pa, &pb, self.settings.penalty);
            // Eq. 18: f = (n_c / n_total) f while the ramp lasts.
            if let Some(n_c) = self.ramp.get_mut(&(a.min(b), a.max(b))) {
                let factor = Real::from(*n_c) / Real::from(RAMP_STEPS);
                for f in fa.iter_mut().chain(fb.iter_mut()) {
                    *f *= factor;
                }
                *n_c += 1;
                if *n_c > RAMP_STEPS {
                    self.ramp.remove(&(a.min(b), a.max(b)));
                }
            }
            if fa.iter().all(|f| f.norm() == 0.0) && fb.iter().all(|f| f.norm() == 0.0) {
                continue;
            }
            self.active_pairs += 1;
            if self.settings.friction > 0.0 {
                let normal: Vec3 = fb.iter().sum();
                let n_mag = normal.norm();
                if n_mag > 0.0 {
                    let n = normal / n_mag;
                    let va: Vec3 = ta.iter().map(|&k| v[k as usize]).sum::<Vec3>() / 4.0;
                    let vb: Vec3 = tb.iter().map(|&k| v[k as usize]).sum::<Vec3>() / 4.0;
                    let rel = vb - va;
                    let vt = rel - n * rel.dot(&n);
                    let key = (a.min(b), a.max(b));
                    // Orient the spring as b relative to a.
                    let sign = if a < b { 1.0 } else { -1.0 };
                    let mut spring = self.stick.get(&key).copied().unwrap_or_else(Vec3::zeros) * sign;
                    spring -= n * spring.dot(&n);
                    spring += vt * dt;
                    let size = model.tet_ref[a as usize].volume.min(model.tet_ref[b as usize].volume).cbrt();
                    let kt = self.settings.penalty * size;
                    let limit = self.settings.friction * n_mag;
                    let mut ft = -spring * kt;
                    if ft.norm() > limit {
                        ft *= limit / ft.norm();
                        spring = -ft / kt;
                    }
                    self.stick_next.insert(key, spring * sign);
                    for k in 0..4 {
                        fb[k] += ft * 0.25;
                        fa[k] -= ft * 0.25;
                    }
                }
            }
            for (nodes, forces) in [(ta, fa), (tb, fb)] {
                for (n, f) in nodes.iter().zip(forces) {
                    if self.force[*n as usize] == Vec3::zeros() {
                        self.touched.push(*n);
                    }
                    self.force[*n as usize] += f;
                }
            }
        }
        self.touched.sort_unstable();
        self.touched.dedup();
        // Springs of pairs no longer in contact are dropped.
        std::mem::swap(&mut self.stick, &mut self.stick_next);
        self.stick_next.clear();
    }
}
