//! TEMPORARY: replays dumped candidate pairs through the kernel.
use femdem_contact::{contact_bound, tet_tet_contact};
use femdem_core::Vec3;
fn main() {
    let path = std::env::args().nth(1).unwrap_or("/tmp/pairs.bin".into());
    let penalty: f64 = std::env::args().nth(2).and_then(|a| a.parse().ok()).unwrap_or(60e9);
    let raw = std::fs::read(path).unwrap();
    let f: Vec<f64> = raw.chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect();
    let mut pairs = Vec::new();
    for r in f.chunks_exact(25) {
        let p = |k: usize| Vec3::new(r[1 + 3 * k], r[2 + 3 * k], r[3 + 3 * k]);
        pairs.push((r[0] as usize, [p(0), p(1), p(2), p(3)], [p(4), p(5), p(6), p(7)]));
    }
    for cat in 0..4 {
        let sel: Vec<_> = pairs.iter().filter(|p| p.0 == cat).collect();
        let mut mags: Vec<f64> = sel
            .iter()
            .map(|p| {
                let c = tet_tet_contact(&p.1, &p.2, penalty);
                c.on_b.iter().sum::<Vec3>().norm()
            })
            .filter(|m| *m > 0.0)
            .collect();
        mags.sort_by(|a, b| a.partial_cmp(b).unwrap());
        if !mags.is_empty() {
            let q = |f: f64| mags[((mags.len() - 1) as f64 * f) as usize];
            println!(
                "  |F| quantiles 0/10/50/90/100%: {:.2e} {:.2e} {:.2e} {:.2e} {:.2e}, sum {:.3e}",
                q(0.0),
                q(0.1),
                q(0.5),
                q(0.9),
                q(1.0),
                mags.iter().sum::<f64>()
            );
        }
        let mut viol = 0;
        let mut zero_bad = 0;
        let bounds: Vec<f64> = sel
            .iter()
            .map(|p| {
                let b = contact_bound(&p.1, &p.2);
                let c = tet_tet_contact(&p.1, &p.2, penalty);
                let m = c.on_a.iter().chain(&c.on_b).map(|f| f.norm()).fold(0.0, f64::max);
                if m > penalty * b * (1.0 + 1e-9) {
                    viol += 1;
                }
                if b == 0.0 && m > 0.0 {
                    zero_bad += 1;
                }
                let l2 = femdem_core::tet::signed_volume(&p.1)
                    .abs()
                    .min(femdem_core::tet::signed_volume(&p.2).abs())
                    .powf(2.0 / 3.0);
                b / l2
            })
            .collect();
        let t0 = std::time::Instant::now();
        let mut z = 0.0;
        for p in &sel {
            z += contact_bound(&p.1, &p.2);
        }
        let bns = t0.elapsed().as_secs_f64() * 1e9 / sel.len().max(1) as f64;
        println!("  bound: {bns:.0} ns/pair, violations {viol}, zero-bound with force {zero_bad} ({z:e})");
        for eps in [0.0, 1e-12, 1e-10, 1e-9, 1e-8] {
            println!("    eps {eps:e}: skip {} of {}", bounds.iter().filter(|&&b| b <= eps).count(), sel.len());
        }
        let touching = sel.iter().filter(|p| tet_tet_contact(&p.1, &p.2, penalty).centre.is_some()).count();
        let t = std::time::Instant::now();
        let mut s = 0.0;
        for _ in 0..5 {
            for p in &sel {
                s += tet_tet_contact(&p.1, &p.2, penalty).on_a[0].x;
            }
        }
        let ns = t.elapsed().as_secs_f64() * 1e9 / (5 * sel.len().max(1)) as f64;
        println!(
            "shared {cat}: {} pairs, {touching} touch, {ns:.0} ns/pair, total {:.1} ms/step ({s:e})",
            sel.len(),
            ns * sel.len() as f64 / 1e6
        );
    }
}
