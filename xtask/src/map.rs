//! `cargo xtask map [--seed N] [--out FILE] [--width W] [--height H]
//! [--clearance C]`: a seeded layered fracture map in the trace-file format of
//! docs/case-format.md, like the map of the reference paper's §3.3 (a
//! limestone horizon of the Bristol Channel Basin): layers of varying
//! thickness separated by persistent, layer-parallel fractures (the layer
//! interfaces, from outline to outline), and in each layer cross fractures
//! at a spacing proportional to the layer's thickness (the usual fracture
//! spacing–bed thickness ratio of order 1: 0.5–1 here), most ending at both layer
//! boundaries, some ending inside the layer, a few crossing several layers,
//! each within a few degrees of normal to the layering.
//!
//! Every coordinate is rounded to 0.1 mm before it is used, so that the
//! file holds exactly the geometry that was generated: a cross fracture
//! ending on an interface has exactly the interface's y. Fracture ends on
//! an interface are kept at least `MIN_GAP` apart, and away from the
//! outline's sides, so that the map does not force tiny elements.
//!
//! `--clearance C` (m) then leaves out every cross fracture that comes
//! closer than `C` to the outline's left or right side (x = 0 or x = W),
//! so that the rock between the side and the nearest cross fracture is at
//! least `C` wide. The map is drawn as without it and only filtered, so
//! the layers and every other cross fracture stay those of the same seed.
//! Without the option nothing is left out (the generator's own `MIN_GAP`
//! applies to the ends on the interfaces).

use std::fmt::Write as _;

use anyhow::{Context, Result, bail};

/// Layer thicknesses are drawn in this range, m.
const THICKNESS: (f64, f64) = (0.15, 0.40);
/// Cross-fracture spacing over layer thickness, drawn in this range.
const SPACING: (f64, f64) = (0.5, 1.0);
/// Largest angle of a cross fracture from the normal to the layering, degrees.
const SCATTER_DEG: f64 = 6.0;
/// Smallest distance between fracture ends on an interface, and from the
/// outline's sides, m.
const MIN_GAP: f64 = 0.05;

/// SplitMix64: a small, fixed generator, so the same seed gives the same
/// map on every platform and version (the validation draws its baseline
/// points with it too).
pub(crate) struct Rng(u64);

impl Rng {
    /// The generator started at `seed`.
    pub(crate) fn new(seed: u64) -> Rng {
        Rng(seed)
    }

    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [lo, hi).
    pub(crate) fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Rounds to 0.1 mm.
fn round(x: f64) -> f64 {
    (x * 1e4).round() / 1e4
}

/// A layered map of `width × height` m from `seed`, as trace-file text;
/// with `clearance` (m), without the cross fractures closer than that to
/// the sides x = 0 and x = `width`.
pub fn layered_map(seed: u64, width: f64, height: f64, clearance: Option<f64>) -> String {
    let mut rng = Rng(seed);
    // Interfaces: y of each layer boundary, 0 and height included.
    let mut ys = vec![0.0];
    loop {
        let y = round(ys.last().unwrap() + rng.uniform(THICKNESS.0, THICKNESS.1));
        if height - y < THICKNESS.0 {
            break;
        }
        ys.push(y);
    }
    ys.push(height);
    let layers = ys.len() - 1;
    // Fracture ends on each interface (index into ys), to keep them apart.
    let mut ends: Vec<Vec<f64>> = vec![Vec::new(); ys.len()];
    let free = |ends: &[Vec<f64>], k: usize, x: f64| {
        x > MIN_GAP && x < width - MIN_GAP && ends[k].iter().all(|e| (e - x).abs() >= MIN_GAP)
    };
    // Each cross fracture's two ends and its kind (index into `kinds`).
    let mut cross: Vec<(Vec<[f64; 2]>, usize)> = Vec::new();
    for l in 0..layers {
        let t = ys[l + 1] - ys[l];
        let mut x = t * rng.uniform(0.1, 0.6) - t * SPACING.1;
        loop {
            x += t * rng.uniform(SPACING.0, SPACING.1);
            if x < MIN_GAP {
                continue;
            }
            if x > width - MIN_GAP {
                break;
            }
            let slope = rng.uniform(-SCATTER_DEG, SCATTER_DEG).to_radians().tan();
            let kind = rng.uniform(0.0, 1.0);
            // Through-going: up to two more layers; non-persistent: from one
            // interface to a tip inside the layer; otherwise interface to interface.
            let (lo, hi, tip) = if kind < 0.12 && l + 1 < layers {
                (l, (l + 1 + (rng.uniform(0.0, 1.0) < 0.5) as usize).min(layers - 1) + 1, None)
            } else if kind < 0.32 {
                (l, l + 1, Some(rng.uniform(0.4, 0.75)))
            } else {
                (l, l + 1, None)
            };
            let x0 = round(x);
            let at = |y: f64| round(x0 + (y - ys[lo]) * slope);
            let (a, b) = match tip {
                None => ([at(ys[lo]), ys[lo]], [at(ys[hi]), ys[hi]]),
                Some(f) => {
                    let y = round(ys[lo] + f * t);
                    // From the lower or from the upper interface.
                    if rng.uniform(0.0, 1.0) < 0.5 {
                        ([at(ys[lo]), ys[lo]], [at(y), y])
                    } else {
                        ([at(y), y], [at(ys[hi]), ys[hi]])
                    }
                }
            };
            // The interfaces this fracture ends on, and the ones it crosses.
            let mut on: Vec<(usize, f64)> = Vec::new();
            for (k, &y) in ys.iter().enumerate().take(hi + 1).skip(lo) {
                if y >= a[1] && y <= b[1] {
                    on.push((k, at(y)));
                }
            }
            // A fracture crossing an interface must keep clear of the other
            // fractures there, and so must its ends.
            let clear = on.iter().all(|&(k, xk)| free(&ends, k, xk))
                && cross.iter().all(|c| {
                    // No other fracture in the same span of y within MIN_GAP.
                    let (c0, c1) = (c.0[0], c.0[1]);
                    c1[1] <= a[1] || c0[1] >= b[1] || {
                        let y = a[1].max(c0[1]).midpoint(b[1].min(c1[1]));
                        let xc = c0[0] + (y - c0[1]) / (c1[1] - c0[1]) * (c1[0] - c0[0]);
                        (xc - (x0 + (y - ys[lo]) * slope)).abs() >= MIN_GAP
                    }
                });
            if !clear {
                continue;
            }
            for &(k, xk) in &on {
                ends[k].push(xk);
            }
            let class = if hi > lo + 1 {
                2
            } else if tip.is_some() {
                1
            } else {
                0
            };
            cross.push((vec![a, b], class));
        }
    }
    if let Some(c) = clearance {
        cross.retain(|(ends, _)| ends.iter().all(|p| p[0] >= c && p[0] <= width - c));
    }
    let mut kinds = [0usize; 3];
    for (_, k) in &cross {
        kinds[*k] += 1;
    }

    let mut out = String::new();
    let option = clearance.map_or_else(String::new, |c| format!(" --clearance {c}"));
    let _ =
        writeln!(out, "# A layered fracture map: `cargo xtask map --seed {seed}{option}` ({width} m x {height} m).");
    let _ = writeln!(out, "# Trace-file format: docs/case-format.md. Coordinates in metres.");
    let _ = writeln!(
        out,
        "# {layers} layers; {} cross fractures: {} from interface to interface, {} ending inside \
         their layer, {} through two or three layers.",
        cross.len(),
        kinds[0],
        kinds[1],
        kinds[2]
    );
    let _ = writeln!(out, "\n# Layer interfaces (persistent fractures, outline to outline).");
    for y in &ys[1..layers] {
        let _ = writeln!(out, "0 {y:.4} {width:.4} {y:.4}");
    }
    let _ = writeln!(out, "\n# Cross fractures.");
    for (c, _) in &cross {
        let _ = writeln!(out, "{:.4} {:.4} {:.4} {:.4}", c[0][0], c[0][1], c[1][0], c[1][1]);
    }
    out
}

/// `cargo xtask map`'s arguments.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The seed of the map's random traces.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The trace file to write (default: standard output).
    #[arg(long, value_name = "FILE")]
    out: Option<String>,
    /// The block's width, m.
    #[arg(long, default_value_t = 1.5)]
    width: f64,
    /// The block's height, m.
    #[arg(long, default_value_t = 1.5)]
    height: f64,
    /// Leave out the cross fractures closer than this to the left or the
    /// right side, m (the rest of the seed's map unchanged).
    #[arg(long, value_name = "C")]
    clearance: Option<f64>,
}

/// Parses the arguments and writes the map.
pub fn run(args: Args) -> Result<()> {
    let Args { seed, out, width, height, clearance } = args;
    if let Some(c) = clearance
        && !(c >= 0.0 && 2.0 * c < width)
    {
        bail!("--clearance must be ≥ 0 m and less than half the width ({width} m), got {c}");
    }
    if !(width > 2.0 * MIN_GAP && height >= 2.0 * THICKNESS.0) {
        bail!("the map must be wider than {} m and at least {} m high", 2.0 * MIN_GAP, 2.0 * THICKNESS.0);
    }
    let text = layered_map(seed, width, height, clearance);
    match out {
        Some(path) => std::fs::write(&path, text).with_context(|| format!("writing {path}"))?,
        None => print!("{text}"),
    }
    Ok(())
}

/// `n` points drawn uniformly in the rectangle `lo`–`hi` from `seed`: the
/// baseline a placement "near the sites" has to beat.
pub fn uniform_points(n: usize, lo: [f64; 2], hi: [f64; 2], seed: u64) -> Vec<[f64; 2]> {
    let mut rng = Rng::new(seed);
    (0..n).map(|_| [rng.uniform(lo[0], hi[0]), rng.uniform(lo[1], hi[1])]).collect()
}

#[cfg(test)]
mod tests {
    use super::{layered_map, uniform_points};

    #[test]
    fn the_same_seed_gives_the_same_map_and_another_seed_another() {
        assert_eq!(layered_map(3, 1.5, 1.5, None), layered_map(3, 1.5, 1.5, None));
        assert_ne!(layered_map(3, 1.5, 1.5, None), layered_map(4, 1.5, 1.5, None));
    }

    /// The polylines of a map's text, each as its numbers.
    fn lines(text: &str) -> Vec<Vec<f64>> {
        text.lines()
            .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
            .map(|l| l.split_whitespace().map(|t| t.parse().unwrap()).collect())
            .collect()
    }

    #[test]
    fn a_clearance_leaves_out_exactly_the_cross_fractures_near_the_sides() {
        let (w, c) = (1.5, 0.2);
        let all = lines(&layered_map(1, w, 1.5, None));
        let kept = lines(&layered_map(1, w, 1.5, Some(c)));
        let near = |l: &Vec<f64>| [l[0], l[2]].iter().any(|&x| x < c || x > w - c);
        // Interfaces run from side to side: they are kept, and every cross
        // fracture of the unfiltered map that keeps clear of the sides.
        let interface = |l: &Vec<f64>| l[0] == 0.0 && l[2] == w;
        let expected: Vec<_> = all.iter().filter(|l| interface(l) || !near(l)).cloned().collect();
        assert_eq!(kept, expected);
        assert!(kept.len() < all.len(), "seed 1 has cross fractures within {c} m of a side");
        // The shipped map has cross fractures within 0.15 m of both sides.
        assert!(all.iter().any(|l| !interface(l) && l[0].min(l[2]) < 0.15));
        assert!(all.iter().any(|l| !interface(l) && l[0].max(l[2]) > w - 0.15));
    }

    #[test]
    fn the_default_map_is_the_shipped_stand_in() {
        let shipped = std::fs::read_to_string(crate::root().join("cases/paper/multilayer-map.txt")).unwrap();
        assert_eq!(layered_map(1, 1.5, 1.5, None), shipped);
    }

    #[test]
    fn uniform_points_cover_the_rectangle_evenly_and_repeat_with_the_seed() {
        let p = uniform_points(20_000, [0.0, 0.0], [2.0, 1.0], 7);
        assert_eq!(p, uniform_points(20_000, [0.0, 0.0], [2.0, 1.0], 7));
        assert!(p.iter().all(|q| (0.0..2.0).contains(&q[0]) && (0.0..1.0).contains(&q[1])));
        // A disc of radius 0.25 around the centre holds π/32 of the area;
        // the binomial standard error at n = 20,000 is 0.0018.
        let share = femdem_post::tips::share_within(&p, &[[1.0, 0.5]], 0.25);
        assert!((share - std::f64::consts::PI / 32.0).abs() < 0.006, "{share}");
    }
}
