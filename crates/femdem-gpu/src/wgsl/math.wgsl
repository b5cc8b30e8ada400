// Natural logarithm and exponential in 64-bit floats.
//
// SPIR-V's extended instructions `Log` and `Exp` take 16- and 32-bit floats
// only (Vulkan drivers return garbage or single precision for f64), so the
// kernels carry their own, built from +, -, *, /, `ldexp` and comparisons
// alone. `ldexp` is exact; Vulkan does not promise correctly rounded f64
// division everywhere, so the tests (crates/femdem-gpu/tests/gpu/math.rs,
// in ulps against the CPU's libm) are what vouches for a device.
//
// ln x, x > 0 finite: x = m 2^e with m in [1/sqrt2, sqrt2) (e from the
// f32 logarithm, then corrected; `ldexp` is exact), and
//     ln m = 2 atanh s = 2 (s + s^3/3 + s^5/5 + ...),   s = (m - 1)/(m + 1),
// |s| <= (sqrt2 - 1)/(sqrt2 + 1) = 0.1716, so the series to s^23 leaves
// less than 2e-17 of ln m. ln 2 is split as LN2_HI + LN2_LO, LN2_HI with
// 21 significant bits, so e * LN2_HI is exact for |e| < 2^11.
//
// exp x: x = k ln2 + r, k = round(x / ln2), r = (x - k LN2_HI) - k LN2_LO,
// |r| <= 0.347; exp r by its Taylor series to r^15/15! (the rest is below
// 1e-17 of the result), then exp x = ldexp(exp r, k).

const LN2_HI: f64 = 0.6931467056274414;
const LN2_LO: f64 = 4.7493250390316726e-07;
const INV_LN2: f64 = 1.4426950408889634;
const SQRT_HALF: f64 = 0.7071067811865476;
const SQRT2: f64 = 1.4142135623730951;

// ln x for x > 0 finite (ln 0 = -inf; negative or NaN input: NaN).
fn ln64(x_in: f64) -> f64 {
    if (!(x_in > 0.0)) {
        if (x_in == 0.0) {
            return -1.0 / abs(x_in);
        }
        return (x_in - x_in) / (x_in - x_in);
    }
    if (x_in > 1.7976931348623157e308) {
        return x_in;
    }
    // Bring x within f32's normal range first, by exact scalings by
    // 2^±200 (a step narrower than that range, so none overshoots it).
    var x = x_in;
    var e: i32 = 0;
    for (var k = 0; k < 6; k++) {
        if (x < 1.0e-37) {
            x = ldexp(x, 200);
            e = e - 200;
        } else if (x > 1.0e37) {
            x = ldexp(x, -200);
            e = e + 200;
        }
    }
    let e0 = i32(floor(log2(f32(x))));
    var m = ldexp(x, -e0);
    e = e + e0;
    // f32's logarithm may land one off: move m into [1/sqrt2, sqrt2).
    if (m < SQRT_HALF) {
        m = m * 2.0;
        e = e - 1;
    }
    if (m < SQRT_HALF) {
        m = m * 2.0;
        e = e - 1;
    }
    if (m >= SQRT2) {
        m = m * 0.5;
        e = e + 1;
    }
    if (m >= SQRT2) {
        m = m * 0.5;
        e = e + 1;
    }
    let s = (m - 1.0) / (m + 1.0);
    let z = s * s;
    // 2 atanh s = 2s + 2s z p, the small part added last.
    let ln_m = 2.0 * s + 2.0 * s * z * atanh_tail(z);
    let k = f64(e);
    return k * LN2_HI + (ln_m + k * LN2_LO);
}

// p(z) = 1/3 + z/5 + z^2/7 + ... + z^10/23, so that
// 2 atanh s = 2s + 2s z p(s^2) for |s| <= 0.1716 (see ln64).
fn atanh_tail(z: f64) -> f64 {
    var p: f64 = 1.0 / 23.0;
    p = p * z + 1.0 / 21.0;
    p = p * z + 1.0 / 19.0;
    p = p * z + 1.0 / 17.0;
    p = p * z + 1.0 / 15.0;
    p = p * z + 1.0 / 13.0;
    p = p * z + 1.0 / 11.0;
    p = p * z + 1.0 / 9.0;
    p = p * z + 1.0 / 7.0;
    p = p * z + 1.0 / 5.0;
    p = p * z + 1.0 / 3.0;
    return p;
}

// (ln(1 + x), x - ln(1 + x)) for x > -1 without cancellation at small x
// (femdem_material::log1p): s = x/(2 + x), ln(1 + x) = 2 atanh s and
// x - ln(1 + x) = s x - 2 s z p(z), z = s^2, for |s| <= 0.1716; plainly
// outside it, where the difference loses at most a factor 6.5 of the
// rounding of ln(1 + x) (at x = -0.2929): a few ulps.
fn ln1p_and_excess(x: f64) -> vec2<f64> {
    let s = x / (2.0 + x);
    if (abs(s) <= 0.1715728752538099) {
        let z = s * s;
        let tail = 2.0 * s * z * atanh_tail(z);
        return vec2<f64>(2.0 * s + tail, s * x - tail);
    }
    let plain = ln64(1.0 + x);
    return vec2<f64>(plain, x - plain);
}

// exp x (0 below -745.2, +inf above 709.79, NaN for NaN).
fn exp64(x: f64) -> f64 {
    if (x != x) {
        return x;
    }
    if (x > 709.782712893384) {
        return x * 1.0e308 * 1.0e308;
    }
    if (x < -745.2) {
        return 0.0;
    }
    let k = floor(x * INV_LN2 + 0.5);
    let r = (x - k * LN2_HI) - k * LN2_LO;
    var p: f64 = 1.0 / 1307674368000.0;
    p = p * r + 1.0 / 87178291200.0;
    p = p * r + 1.0 / 6227020800.0;
    p = p * r + 1.0 / 479001600.0;
    p = p * r + 1.0 / 39916800.0;
    p = p * r + 1.0 / 3628800.0;
    p = p * r + 1.0 / 362880.0;
    p = p * r + 1.0 / 40320.0;
    p = p * r + 1.0 / 5040.0;
    p = p * r + 1.0 / 720.0;
    p = p * r + 1.0 / 120.0;
    p = p * r + 1.0 / 24.0;
    p = p * r + 1.0 / 6.0;
    p = p * r + 0.5;
    // exp r = 1 + r + r^2 p, the small part added last.
    let er = 1.0 + (r + r * r * p);
    // ldexp's exponent is an i32; split it where 2^k alone would overflow
    // or underflow (k in [-1075, 1024]).
    let ki = i32(k);
    if (ki > 1000 || ki < -1000) {
        let half = ki / 2;
        return ldexp(ldexp(er, half), ki - half);
    }
    return ldexp(er, ki);
}
