//! Stage 5 of the step: the central-difference update of every node, in
//! parallel over fixed chunks (per-chunk sums added in chunk order, so the
//! result does not depend on the thread count).

use femdem_core::{Real, Vec3};
use rayon::prelude::*;

use super::external::{External, weight};
use super::prescribed::{FIXED, FREE};
use crate::forces::CHUNK;
use crate::loads::Loads;
use crate::model::Model;
use crate::state::State;

/// The update stage's state: per-chunk partial sums.
pub(super) struct Update {
    partials: Vec<[Real; 2]>,
}

impl Update {
    pub fn new(nodes: usize) -> Update {
        Update { partials: vec![[0.0; 2]; nodes.div_ceil(CHUNK)] }
    }

    /// `v_{n+½} = v_{n−½} + Δt f / m` with the prescribed components
    /// imposed, `x_{n+1} = x_n + Δt v_{n+½}`. Returns the power of the
    /// external forces at `v_n` (surface loads and gravity), W, and, with
    /// `want_kinetic`, the kinetic energy at `v_n`, J.
    #[allow(clippy::too_many_arguments)]
    pub fn advance(
        &mut self,
        model: &Model,
        loads: &Loads,
        external: &External,
        internal: &[Vec3],
        contact: Option<&[Vec3]>,
        state: &mut State,
        dt: Real,
        want_kinetic: bool,
    ) -> (Real, Real) {
        state
            .x
            .par_chunks_mut(CHUNK)
            .zip(state.v.par_chunks_mut(CHUNK))
            .zip(self.partials.par_iter_mut())
            .enumerate()
            .for_each(|(c, ((xs, vs), partial))| {
                *partial =
                    advance_chunk(model, loads, external, internal, contact, c * CHUNK, xs, vs, dt, want_kinetic);
            });
        self.partials.iter().fold((0.0, 0.0), |(p, k), q| (p + q[0], k + q[1]))
    }
}

/// The nodes `first..first + xs.len()` (one chunk of the update; not
/// inlined, so that profiles name it): returns `[power, kinetic]`.
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
    dt: Real,
    want_kinetic: bool,
) -> [Real; 2] {
    let (prescribed, f_surface, targets) = (&external.prescribed, &external.f_surface, &external.targets);
    let mut power = 0.0;
    let mut kinetic = 0.0;
    for (k, (x, v)) in xs.iter_mut().zip(vs.iter_mut()).enumerate() {
        let i = first + k;
        let m = model.mass[i];
        let f_ext = f_surface[i] + weight(model, loads, i);
        let f_in = match contact {
            Some(f) => internal[i] + f[i],
            None => internal[i],
        };
        let old = *v;
        let mut new = if m > 0.0 { old + (f_in + f_ext) * (dt / m) } else { old };
        for comp in 0..3 {
            match prescribed[i][comp] {
                FREE => {}
                FIXED => new[comp] = 0.0,
                d => new[comp] = targets[d as usize][comp],
            }
        }
        let v_n = (old + new) * 0.5;
        power += f_ext.dot(&v_n);
        if want_kinetic {
            kinetic += 0.5 * m * v_n.norm_squared();
        }
        *v = new;
        *x += new * dt;
    }
    [power, kinetic]
}
