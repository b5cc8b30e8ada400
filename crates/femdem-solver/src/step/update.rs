//! Stage 5 of the step: the central-difference update of every node, in
//! parallel over fixed chunks (per-chunk sums added in chunk order, so the
//! result does not depend on the thread count).

use femdem_core::{Real, Vec3};
use rayon::prelude::*;

use super::external::{External, weight};
use crate::forces::CHUNK;
use crate::loads::Loads;
use crate::model::Model;
use crate::state::State;

/// What the update reports for the energy account (see `super`'s module
/// documentation for the time-centring).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Powers {
    /// `Σ m_i g · v_{n−½}` over the nodes: gravity's power against the
    /// velocity before step `n`, W (the surface loads' powers are each
    /// load's own: `External::powers`).
    pub back: Real,
    /// `Σ m_i g · v_{n+½}`: against the velocity after it, W.
    pub ahead: Real,
    /// With `want_kinetic`, the leapfrog kinetic energy of `t_n`,
    /// `½ Σ m v_{n−½} · v_{n+½}`, J (else 0).
    pub kinetic: Real,
}

impl Powers {
    fn add(self, o: Powers) -> Powers {
        Powers { back: self.back + o.back, ahead: self.ahead + o.ahead, kinetic: self.kinetic + o.kinetic }
    }
}

/// The update stage's state: per-chunk partial sums.
pub(super) struct Update {
    partials: Vec<Powers>,
}

impl Update {
    pub fn new(nodes: usize) -> Update {
        Update { partials: vec![Powers::default(); nodes.div_ceil(CHUNK)] }
    }

    /// `v_{n+½} = v_{n−½} + Δt f / m` with the prescribed components
    /// imposed (those of started drives and fixed sets), `x_{n+1} = x_n + Δt v_{n+½}`. Returns the powers of
    /// gravity against `v_{n−½}` and
    /// `v_{n+½}`, and, with `want_kinetic`, the kinetic energy of `t_n`
    /// ([`Powers`]). A non-empty `before` (the velocities of the step
    /// before, one per node) receives `v_{n−½}`.
    #[allow(clippy::too_many_arguments)]
    pub fn advance(
        &mut self,
        model: &Model,
        loads: &Loads,
        external: &External,
        internal: &[Vec3],
        contact: Option<&[Vec3]>,
        state: &mut State,
        before: &mut [Vec3],
        dt: Real,
        want_kinetic: bool,
    ) -> Powers {
        let chunks = state.x.par_chunks_mut(CHUNK).zip(state.v.par_chunks_mut(CHUNK)).zip(self.partials.par_iter_mut());
        let go = |c: usize, xs: &mut [Vec3], vs: &mut [Vec3], before: &mut [Vec3]| {
            advance_chunk(model, loads, external, internal, contact, c * CHUNK, xs, vs, before, dt, want_kinetic)
        };
        if before.is_empty() {
            chunks.enumerate().for_each(|(c, ((xs, vs), partial))| *partial = go(c, xs, vs, &mut []));
        } else {
            chunks
                .zip(before.par_chunks_mut(CHUNK))
                .enumerate()
                .for_each(|(c, (((xs, vs), partial), before))| *partial = go(c, xs, vs, before));
        }
        self.partials.iter().fold(Powers::default(), |p, &q| p.add(q))
    }
}

/// The nodes `first..first + xs.len()` (one chunk of the update; not
/// inlined, so that profiles name it): returns its share of [`Powers`].
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn advance_chunk(
    model: &Model,
    loads: &Loads,
    external: &External,
    internal: &[Vec3],
    contact: Option<&[Vec3]>,
    first: usize,
    xs: &mut [Vec3],
    vs: &mut [Vec3],
    before: &mut [Vec3],
    dt: Real,
    want_kinetic: bool,
) -> Powers {
    let f_surface = &external.f_surface;
    let mut sums = Powers::default();
    for (k, (x, v)) in xs.iter_mut().zip(vs.iter_mut()).enumerate() {
        let i = first + k;
        let m = model.mass[i];
        let w = weight(model, loads, i);
        let f_ext = f_surface[i] + w;
        let f_in = match contact {
            Some(f) => internal[i] + f[i],
            None => internal[i],
        };
        let old = *v;
        let mut new = if m > 0.0 { old + (f_in + f_ext) * (dt / m) } else { old };
        for comp in 0..3 {
            if let Some(imposed) = external.imposed(i, comp) {
                new[comp] = imposed;
            }
        }
        sums.back += w.dot(&old);
        sums.ahead += w.dot(&new);
        if want_kinetic {
            sums.kinetic += 0.5 * m * old.dot(&new);
        }
        if let Some(b) = before.get_mut(k) {
            *b = old;
        }
        *v = new;
        *x += new * dt;
    }
    sums
}
