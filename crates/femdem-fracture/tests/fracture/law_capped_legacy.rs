//! `Coupling::Capped` (the default until the Brazilian comparison made it
//! `Printed`) is bit for bit the law femdem had
//! before the coupling became an option (commit 8aff2fa, law.rs): the old
//! `point_stress` is kept below, verbatim but for its failure labels
//! (changed on purpose since) and its return type, and compared on
//! `f64::to_bits` of every number it returns, at random openings, slips and
//! damage histories over the proptest parameter ranges of `law_curves.rs`.

use crate::law_reference::{case_strategy, dc_ref, dp_ref};

use femdem_core::Real;
use femdem_fracture::softening::{z, z_integral};
use femdem_fracture::{Coupling, Joint, point_stress};
use proptest::prelude::*;

/// The old stored energy (the capped parabola).
fn stored(f: Real, dp: Real, r: Real, zd: Real) -> Real {
    if r < 0.0 {
        return f * dp * r * r;
    }
    let rs = 1.0 - (1.0 - zd.clamp(0.0, 1.0)).sqrt();
    if r <= rs {
        f * dp * (r * r - r * r * r / 3.0)
    } else if zd > 0.0 {
        f * dp * (rs * rs - rs * rs * rs / 3.0 + zd * (r - rs))
    } else {
        0.0
    }
}

/// `[2r − r²] f`.
fn hardening(f: Real, r: Real) -> Real {
    (2.0 * r - r * r) * f
}

/// The old `point_stress`: `(σ, τ, D, dissipated, stored)`.
fn legacy_point_stress(joint: &Joint, dn: Real, ds: Real, d_hist: Real) -> (Real, Real, Real, Real, Real) {
    let p = &joint.params;
    let ft = p.tensile_strength;
    let (dnp, dnc) = (joint.delta_np, joint.delta_nc);
    let rn = dn / dnp;
    // Normal softening displacement, and the normal stress without shear
    // damage, which sets the shear strength (Eq. 5).
    let dn_soft = if dn > dnp { ((dn - dnp) / (dnc - dnp)).min(1.0) } else { 0.0 };
    let sigma_trial = if rn < 0.0 {
        2.0 * rn * ft
    } else if rn <= 1.0 {
        hardening(ft, rn).min(z(d_hist) * ft)
    } else {
        z(dn_soft.max(d_hist)) * ft
    };
    let fs = p.cohesion - sigma_trial * joint.tan_phi;
    let (dsp, dsc) = if fs > 0.0 {
        let dsp = 2.0 * fs * joint.h / p.penalty;
        (dsp, p.critical_displacement(fs, dsp, p.gf_shear))
    } else {
        (0.0, 0.0)
    };
    let ds_soft = if fs <= 0.0 {
        1.0
    } else if ds > dsp {
        ((ds - dsp) / (dsc - dsp)).min(1.0)
    } else {
        0.0
    };
    // Eq. 13.
    let d_now = if dn >= dnc || (fs > 0.0 && ds >= dsc) {
        1.0
    } else if dn_soft > 0.0 && ds_soft > 0.0 {
        (dn_soft * dn_soft + ds_soft * ds_soft).sqrt().min(1.0)
    } else {
        dn_soft + ds_soft
    };
    let damage = d_now.max(d_hist);
    let zd = z(damage);
    let sigma = if rn < 0.0 {
        2.0 * rn * ft
    } else if rn <= 1.0 {
        hardening(ft, rn).min(zd * ft)
    } else {
        zd * ft
    };
    let tau = if fs <= 0.0 {
        0.0
    } else {
        let rs = ds / dsp;
        if rs <= 1.0 { hardening(fs, rs).min(zd * fs) } else { zd * fs }
    };
    let dissipated = if damage > d_hist {
        // Along a radial path in (Dn, Ds), dDn = (Dn/D) dD and dDs = (Ds/D) dD.
        let norm = (dn_soft * dn_soft + ds_soft * ds_soft).sqrt();
        let (wn, ws) = if norm > 0.0 { (dn_soft / norm, ds_soft / norm) } else { (1.0, 0.0) };
        let scale = ft * (dnc - dnp) * wn + if fs > 0.0 { fs * (dsc - dsp) * ws } else { 0.0 };
        scale * z_integral(d_hist, damage)
    } else {
        0.0
    };
    let stored = stored(ft, dnp, rn, zd) + if fs > 0.0 { stored(fs, dsp, ds / dsp, zd) } else { 0.0 };
    (sigma, tau, damage, dissipated, stored)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Openings in `[−3 δnp, 1.2 δnc]`, slips in `[0, 1.2 δsc(c)]`, damage
    /// histories 0, 1 or in between: identical bits.
    #[test]
    fn capped_is_the_old_law_bit_for_bit(
        case in case_strategy(),
        pts in prop::collection::vec((-1.0..1.2f64, 0.0..1.2f64, 0.0..1.0f64, 0..3u8), 64),
    ) {
        let case = crate::law_reference::Case { params: crate::law_reference::with_coupling(case.params, Coupling::Capped), ..case };
        let j = case.joint();
        let p = &case.params;
        let (ft, c) = (p.tensile_strength, p.cohesion);
        let dnp = dp_ref(p, case.h, ft);
        let dnc = dc_ref(p, ft, dnp, p.gf_tension);
        let dsc = dc_ref(p, c, dp_ref(p, case.h, c), p.gf_shear);
        for (a, b, d, kind) in pts {
            let dn = if a < 0.0 { 3.0 * a * dnp } else { a * dnc };
            let ds = b * dsc;
            let d_hist = match kind { 0 => 0.0, 1 => 1.0, _ => d };
            let new = point_stress(&j, dn, ds, d_hist);
            let old = legacy_point_stress(&j, dn, ds, d_hist);
            let bits = |v: (Real, Real, Real, Real, Real)| [v.0, v.1, v.2, v.3, v.4].map(Real::to_bits);
            prop_assert_eq!(
                bits((new.sigma, new.tau, new.damage, new.dissipated, new.stored)),
                bits(old),
                "δn {} δs {} D_hist {}", dn, ds, d_hist
            );
        }
    }
}
