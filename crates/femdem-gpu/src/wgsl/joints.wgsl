// The joint pass (Eq. 3-13; `femdem_fracture::joint_update_fast`, whose
// comments say what each step is): each intact joint's forces on its six
// nodes into its own slots, its history updated, and whether it failed.
//
// Per joint j of n = params.count (law, history and slots are stored
// number by number, number k of joint j at k n + j: neighbouring joints'
// numbers side by side, so that the invocations of a workgroup read and
// write neighbouring words):
//   nodes   joints[6j..6j+6]
//   law     numbers 0..10 = penalty, ft, cohesion, Gf shear, h, delta_np,
//           delta_nc, tan phi, calibration (0 paper, 1 exact), coupling
//           (0 printed, 1 multiplicative, 2 capped)
//   history numbers 0..24 = damage[3], dissipated, released, work,
//           last[3][4] (opening, slip xyz), last_stress[3][2] (sigma, tau)
//   flags   flags[j]: bit 2i softened normal at point i, bit 2i+1 softened
//           shear, bit 6 failed
//   slots   numbers 0..18: node k's force, component c, is number 3k + c
//   sums    sums[2j..2j+2] = stored energy (flag bit 0), fracture
//           contribution (work of a failed joint, work less stored energy
//           of an intact one; flag bit 0)
//   failed  failed[j]: 0 none, else 1 + FailureMode (tensile, shear, mixed,
//           collapsed) when the joint failed in this evaluation, and j in
//           failed_list
// consts: z(0) (the CPU's, so that an undamaged point softens alike on
// both), the area under z (the exact calibration).

@group(0) @binding(1) var<storage, read> x: array<f64>;
@group(0) @binding(2) var<storage, read> joints: array<u32>;
@group(0) @binding(3) var<storage, read> law: array<f64>;
@group(0) @binding(4) var<storage, read_write> hist: array<f64>;
@group(0) @binding(5) var<storage, read_write> flags: array<u32>;
@group(0) @binding(6) var<storage, read_write> slots: array<f64>;
@group(0) @binding(7) var<storage, read_write> sums: array<f64>;
@group(0) @binding(8) var<storage, read_write> failed: array<u32>;
@group(0) @binding(9) var<storage, read> consts: array<f64>;
// [0]: how many joints failed in this evaluation; [1..]: which (in no
// particular order: the host sorts them). The host zeroes [0] first.
@group(0) @binding(10) var<storage, read_write> failed_list: array<atomic<u32>>;

// Where number k of joint j is in law, hist and slots.
fn at(j: u32, k: u32) -> u32 {
    return k * params.count + j;
}

fn report_failure(j: u32) {
    let k = atomicAdd(&failed_list[0], 1u);
    atomicStore(&failed_list[k + 1u], j);
}

const MODE_TENSILE: u32 = 1u;
const MODE_SHEAR: u32 = 2u;
const MODE_MIXED: u32 = 3u;
const MODE_COLLAPSED: u32 = 4u;
const DOMINANT_SHARE: f64 = 0.75;

// Munjiza's softening curve, Eq. 12 (femdem_fracture::softening): a = 0.63,
// b = 1.8, c = 6 (the power (1 - D)^6 taken as a cube of a square; the
// crate checks that c is 6).
const ZA: f64 = 0.63;
const ZB: f64 = 1.8;

fn z(d_in: f64) -> f64 {
    let d = clamp(d_in, 0.0, 1.0);
    let ab = ZA + ZB;
    let e = exp64(d * (ZA + ZB * 6.0) / (ab * (1.0 - ab)));
    let one_minus = 1.0 - d;
    let sq = one_minus * one_minus;
    return (1.0 - (ab - 1.0) / ab * e) * (ZA * one_minus + ZB * (sq * sq * sq));
}

// Eight-point Gauss-Legendre nodes and weights on [-1, 1].
const GL_X = array<f64, 8>(-0.9602898564975362, -0.7966664774136267, -0.525532409916329, -0.1834346424956498,
                           0.1834346424956498, 0.525532409916329, 0.7966664774136267, 0.9602898564975362);
const GL_W = array<f64, 8>(0.10122853629037626, 0.22238103445337447, 0.3137066458778873, 0.362683783378362,
                           0.362683783378362, 0.3137066458778873, 0.22238103445337447, 0.10122853629037626);

// Integral of z over [d0, d1] (four panels of Gauss-Legendre 8).
fn z_integral(d0_in: f64, d1_in: f64) -> f64 {
    let d0 = clamp(d0_in, 0.0, 1.0);
    let d1 = clamp(d1_in, 0.0, 1.0);
    if (d1 <= d0) {
        return 0.0;
    }
    let h = (d1 - d0) / 4.0;
    var sum: f64 = 0.0;
    for (var p = 0; p < 4; p++) {
        let mid = d0 + h * (f64(p) + 0.5);
        for (var k = 0; k < 8; k++) {
            sum = sum + GL_W[k] * z(mid + 0.5 * h * GL_X[k]);
        }
    }
    return sum * 0.5 * h;
}

fn z_known(d: f64) -> f64 {
    if (d == 0.0) {
        return consts[0];
    }
    return z(d);
}

fn hardening(f: f64, r: f64) -> f64 {
    return (2.0 * r - r * r) * f;
}

// Eq. 11's hardening branch under the chosen coupling.
fn hardening_branch(coupling: u32, f: f64, r: f64, zd: f64, softened: bool) -> f64 {
    if (coupling == 0u && !softened) {
        return hardening(f, r);
    }
    if (coupling == 1u) {
        return zd * hardening(f, r);
    }
    return min(hardening(f, r), zd * f);
}

fn capped_stored(f: f64, dp: f64, r: f64, zd: f64) -> f64 {
    let rs = 1.0 - sqrt(1.0 - clamp(zd, 0.0, 1.0));
    if (r <= rs) {
        return f * dp * (r * r - r * r * r / 3.0);
    } else if (zd > 0.0) {
        return f * dp * (rs * rs - rs * rs * rs / 3.0 + zd * (r - rs));
    }
    return 0.0;
}

// Energy stored per unit area of one direction (Eq. 11 integrated).
fn stored(coupling: u32, f: f64, dp: f64, r: f64, zd: f64, softened: bool) -> f64 {
    if (r < 0.0) {
        return f * dp * r * r;
    }
    if (coupling == 0u && !softened && r <= 1.0) {
        return f * dp * (r * r - r * r * r / 3.0);
    }
    if (coupling == 1u) {
        if (r <= 1.0) {
            return zd * f * dp * (r * r - r * r * r / 3.0);
        } else if (zd > 0.0) {
            return zd * f * dp * (r - 1.0 / 3.0);
        }
        return 0.0;
    }
    return capped_stored(f, dp, r, zd);
}

fn mode_of(dn: f64, ds: f64) -> u32 {
    let n2 = dn * dn;
    let s2 = ds * ds;
    let total = n2 + s2;
    if (total <= 0.0) {
        return MODE_MIXED;
    } else if (n2 >= DOMINANT_SHARE * total) {
        return MODE_TENSILE;
    } else if (s2 >= DOMINANT_SHARE * total) {
        return MODE_SHEAR;
    }
    return MODE_MIXED;
}

fn position(n: u32) -> vec3<f64> {
    return vec3<f64>(x[3u * n], x[3u * n + 1u], x[3u * n + 2u]);
}

// A joint's law (numbers 0..10 of `law`), read once per evaluation.
struct Law {
    penalty: f64,
    ft: f64,
    cohesion: f64,
    gf_shear: f64,
    h: f64,
    dnp: f64,
    dnc: f64,
    tan_phi: f64,
    exact: bool,
    coupling: u32,
}

fn law_of(j: u32) -> Law {
    return Law(law[at(j, 0u)], law[at(j, 1u)], law[at(j, 2u)], law[at(j, 3u)], law[at(j, 4u)], law[at(j, 5u)],
               law[at(j, 6u)], law[at(j, 7u)], law[at(j, 8u)] == 1.0, u32(law[at(j, 9u)]));
}

struct Point {
    sigma: f64,
    tau: f64,
    damage: f64,
    broke: u32,
    dissipated: f64,
    soft_n: bool,
    soft_s: bool,
    // For the stored energy.
    rn: f64,
    zd: f64,
    fs: f64,
    dsp: f64,
    rs: f64,
}

// One integration point (femdem_fracture's `point`: Eq. 5-7, 11-13).
fn point(lw: Law, dn: f64, ds: f64, d_hist: f64, soft_n_in: bool, soft_s_in: bool) -> Point {
    let penalty = lw.penalty;
    let ft = lw.ft;
    let cohesion = lw.cohesion;
    let gf_shear = lw.gf_shear;
    let h = lw.h;
    let dnp = lw.dnp;
    let dnc = lw.dnc;
    let tan_phi = lw.tan_phi;
    let exact = lw.exact;
    let coupling = lw.coupling;
    let z_hist = z_known(d_hist);
    let rn = dn / dnp;
    var dn_soft: f64 = 0.0;
    if (dn > dnp) {
        dn_soft = min((dn - dnp) / (dnc - dnp), 1.0);
    }
    var sigma_trial: f64;
    if (rn < 0.0) {
        sigma_trial = 2.0 * rn * ft;
    } else if (rn <= 1.0) {
        sigma_trial = hardening_branch(coupling, ft, rn, z_hist, soft_n_in);
    } else {
        let d = max(dn_soft, d_hist);
        var zz = z_hist;
        if (d != d_hist) {
            zz = z(d);
        }
        sigma_trial = zz * ft;
    }
    let over_the_apex = rn > 1.0 && !soft_n_in && cohesion <= ft * tan_phi
        && cohesion - hardening_branch(coupling, ft, 1.0, z_hist, false) * tan_phi <= 0.0;
    var fs: f64 = 0.0;
    if (!over_the_apex) {
        fs = cohesion - sigma_trial * tan_phi;
    }
    var dsp: f64 = 0.0;
    var dsc: f64 = 0.0;
    if (fs > 0.0) {
        dsp = 2.0 * fs * h / penalty;
        // JointParams::critical_displacement.
        if (exact) {
            dsc = dsp + gf_shear / (fs * consts[1]);
        } else {
            dsc = 3.0 * gf_shear / fs;
        }
        dsc = max(dsc, dsp * (1.0 + 1.0e-12));
    }
    var ds_soft: f64 = 0.0;
    if (fs <= 0.0) {
        ds_soft = 1.0;
    } else if (ds > dsp) {
        ds_soft = min((ds - dsp) / (dsc - dsp), 1.0);
    }
    // Eq. 13.
    var d_now: f64;
    if (dn >= dnc || (fs > 0.0 && ds >= dsc)) {
        d_now = 1.0;
    } else if (dn_soft > 0.0 && ds_soft > 0.0) {
        d_now = min(sqrt(dn_soft * dn_soft + ds_soft * ds_soft), 1.0);
    } else {
        d_now = dn_soft + ds_soft;
    }
    let damage = max(d_now, d_hist);
    var zd = z_hist;
    if (damage != d_hist) {
        zd = z(damage);
    }
    var rs: f64 = 0.0;
    if (fs > 0.0) {
        rs = ds / dsp;
    }
    let soft_n = soft_n_in || rn > 1.0 || fs <= 0.0;
    let soft_s = soft_s_in || fs <= 0.0 || rs > 1.0;
    // Eq. 11.
    var sigma: f64;
    if (rn < 0.0) {
        sigma = 2.0 * rn * ft;
    } else if (rn <= 1.0) {
        sigma = hardening_branch(coupling, ft, rn, zd, soft_n);
    } else {
        sigma = zd * ft;
    }
    var tau: f64;
    if (fs <= 0.0) {
        tau = 0.0;
    } else if (rs <= 1.0) {
        tau = hardening_branch(coupling, fs, rs, zd, soft_s);
    } else {
        tau = zd * fs;
    }
    var broke = 0u;
    if (d_hist < 1.0 && damage >= 1.0) {
        if (fs <= 0.0) {
            broke = MODE_TENSILE;
        } else {
            broke = mode_of(dn_soft, ds_soft);
        }
    }
    var dissipated: f64 = 0.0;
    if (damage > d_hist) {
        let norm = sqrt(dn_soft * dn_soft + ds_soft * ds_soft);
        var wn: f64 = 1.0;
        var ws: f64 = 0.0;
        if (norm > 0.0) {
            wn = dn_soft / norm;
            ws = ds_soft / norm;
        }
        var scale = ft * (dnc - dnp) * wn;
        if (fs > 0.0) {
            scale = scale + fs * (dsc - dsp) * ws;
        } else {
            scale = scale + 0.0;
        }
        dissipated = scale * z_integral(d_hist, damage);
    }
    return Point(sigma, tau, damage, broke, dissipated, soft_n, soft_s, rn, zd, fs, dsp, rs);
}

fn point_stored(lw: Law, p: Point) -> f64 {
    let coupling = lw.coupling;
    var s = stored(coupling, lw.ft, lw.dnp, p.rn, p.zd, p.soft_n);
    if (p.fs > 0.0) {
        s = s + stored(coupling, p.fs, p.dsp, p.rs, p.zd, p.soft_s);
    } else {
        s = s + 0.0;
    }
    return s;
}

const GAUSS = array<vec3<f64>, 3>(vec3<f64>(2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0),
                                  vec3<f64>(1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0),
                                  vec3<f64>(1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0));

fn zero_slots(j: u32) {
    for (var k = 0u; k < 18u; k++) {
        slots[at(j, k)] = 0.0;
    }
}

// Joint j fails now with `mode` (its flags before were `fl`): flagged,
// listed, no force; all its work is lost to fracture from now on.
fn fail(j: u32, fl: u32, mode: u32, want_energy: bool) {
    flags[j] = fl | 64u;
    failed[j] = mode;
    report_failure(j);
    zero_slots(j);
    if (want_energy) {
        sums[2u * j + 1u] = hist[at(j, 5u)];
    }
}

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>,
        @builtin(local_invocation_index) local: u32) {
    let j = item(wg, nwg, local);
    if (j >= params.count) {
        return;
    }
    let want_energy = (params.flags & 1u) != 0u;
    failed[j] = 0u;
    sums[2u * j] = 0.0;
    sums[2u * j + 1u] = 0.0;
    var fl = flags[j];
    if ((fl & 64u) != 0u) {
        // Failed before: no force, all its work lost.
        zero_slots(j);
        if (want_energy) {
            sums[2u * j + 1u] = hist[at(j, 5u)];
        }
        return;
    }
    var xs: array<vec3<f64>, 6>;
    for (var k = 0u; k < 6u; k++) {
        xs[k] = position(joints[6u * j + k]);
    }
    // Kinematics (femdem_fracture::joint_kinematics): the mid-plane frame.
    let m16 = (xs[0] + xs[5]) * 0.5;
    let m25 = (xs[1] + xs[4]) * 0.5;
    let m34 = (xs[2] + xs[3]) * 0.5;
    let e1 = m25 - m16;
    let nrm = cross(e1, m34 - m16);
    let twice_area = sqrt(dot(nrm, nrm));
    let len1 = sqrt(dot(e1, e1));
    if (!(twice_area > 0.0) || !(len1 > 0.0) || !(twice_area <= 1.7976931348623157e308)) {
        hist[at(j, 4u)] = 0.0;
        fail(j, fl, MODE_COLLAPSED, want_energy);
        return;
    }
    let zn = nrm / twice_area;
    let weight = 0.5 * twice_area / 3.0;
    var forces: array<vec3<f64>, 6>;
    for (var k = 0u; k < 6u; k++) {
        forces[k] = vec3<f64>(0.0, 0.0, 0.0);
    }
    var broken_points = 0u;
    var mode = 0u;
    var ending: f64 = 0.0;
    var stored_sum: f64 = 0.0;
    var points: array<Point, 3>;
    let lw = law_of(j);
    // The history's two running sums, kept here and stored once (the same
    // additions in the same order as number by number).
    var dissipated = hist[at(j, 3u)];
    var work = hist[at(j, 5u)];
    for (var i = 0u; i < 3u; i++) {
        let w = GAUSS[i];
        let pa = xs[0] * w[0] + xs[1] * w[1] + xs[2] * w[2];
        let pb = xs[5] * w[0] + xs[4] * w[1] + xs[3] * w[2];
        let g = pb - pa;
        let opening = dot(g, zn);
        let slip = g - zn * opening;
        let ds = sqrt(dot(slip, slip));
        let ps = point(lw, opening, ds, hist[at(j, i)], (fl & (1u << (2u * i))) != 0u,
                       (fl & (1u << (2u * i + 1u))) != 0u);
        points[i] = ps;
        hist[at(j, i)] = ps.damage;
        let soft_bits = (select(0u, 1u, ps.soft_n) | select(0u, 2u, ps.soft_s)) << (2u * i);
        fl = (fl & ~(3u << (2u * i))) | soft_bits;
        let lb = 6u + 4u * i;
        let ln = hist[at(j, lb)];
        let slip_last = vec3<f64>(hist[at(j, lb + 1u)], hist[at(j, lb + 2u)], hist[at(j, lb + 3u)]);
        let sigma_last = hist[at(j, 18u + 2u * i)];
        let tau_last = hist[at(j, 19u + 2u * i)];
        let d_slip = slip - slip_last;
        var shear = vec3<f64>(0.0, 0.0, 0.0);
        if (ds > 0.0) {
            shear = slip * (ps.tau / ds);
        }
        var traction = shear;
        let ds_last = sqrt(dot(slip_last, slip_last));
        if (ds_last > 0.0) {
            traction = traction + slip_last * (tau_last / ds_last);
        }
        let normal_work = 0.5 * (sigma_last + ps.sigma) * (opening - ln);
        work = work + weight * (normal_work + 0.5 * dot(traction, d_slip));
        ending = ending + weight * 0.5 * (ps.sigma * (opening - ln) + dot(shear, d_slip));
        hist[at(j, lb)] = opening;
        hist[at(j, lb + 1u)] = slip.x;
        hist[at(j, lb + 2u)] = slip.y;
        hist[at(j, lb + 3u)] = slip.z;
        hist[at(j, 18u + 2u * i)] = ps.sigma;
        hist[at(j, 19u + 2u * i)] = ps.tau;
        dissipated = dissipated + weight * ps.dissipated;
        if (ps.damage >= 1.0) {
            broken_points = broken_points + 1u;
        }
        if (ps.broke != 0u) {
            mode = ps.broke;
        }
        var t = zn * ps.sigma;
        if (ds > 0.0) {
            t = t + shear;
        }
        let f = t * weight;
        forces[0] = forces[0] + f * w[0];
        forces[5] = forces[5] - f * w[0];
        forces[1] = forces[1] + f * w[1];
        forces[4] = forces[4] - f * w[1];
        forces[2] = forces[2] + f * w[2];
        forces[3] = forces[3] - f * w[2];
    }
    if (broken_points >= 2u || want_energy) {
        for (var i = 0u; i < 3u; i++) {
            stored_sum = stored_sum + weight * point_stored(lw, points[i]);
        }
    }
    hist[at(j, 3u)] = dissipated;
    hist[at(j, 5u)] = work;
    if (broken_points >= 2u) {
        hist[at(j, 5u)] = work - ending;
        hist[at(j, 4u)] = stored_sum;
        if (mode == 0u) {
            mode = MODE_MIXED;
        }
        fail(j, fl, mode, want_energy);
        return;
    }
    flags[j] = fl;
    for (var k = 0u; k < 6u; k++) {
        slots[at(j, 3u * k)] = forces[k].x;
        slots[at(j, 3u * k + 1u)] = forces[k].y;
        slots[at(j, 3u * k + 2u)] = forces[k].z;
    }
    if (want_energy) {
        sums[2u * j] = stored_sum;
        sums[2u * j + 1u] = work - stored_sum;
    }
}
