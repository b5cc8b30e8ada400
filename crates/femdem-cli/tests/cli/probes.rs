//! `[[output.probes]]` read back from the history: a P-wave in the confined
//! bar of `cases/elastic-bar.toml` passing a probe at mid-length, against
//! the closed form of a plane wave, and bad probes refused with file, line
//! and key.

use std::path::{Path, PathBuf};

use crate::common::{femdem, history, history_csv, root};

/// The bundled bar case with `probes` (TOML text) appended, written to a
/// fresh folder of the test's own; returns the case path and an output
/// folder that does not exist yet.
fn bar_with(name: &str, probes: &str) -> (PathBuf, PathBuf) {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(root().join("cases/elastic-bar.toml")).unwrap();
    let case = dir.join("bar.toml");
    std::fs::write(&case, format!("{text}\n{probes}")).unwrap();
    (case, dir.join("out"))
}

/// The column `name` of a history, by rows.
fn column(header: &[&str], rows: &[Vec<f64>], name: &str) -> Vec<f64> {
    let k = header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    rows.iter().map(|r| r[k]).collect()
}

/// The piston of the bar case pushes the end z = 0 at V = 0.1 m/s (ramped
/// over 2 µs, stopped at 10 µs) into a bar confined laterally, so a plane
/// P-wave runs along z at `c = √(M/ρ)`, `M = E(1−ν)/((1+ν)(1−2ν))`,
/// carrying the particle velocity V and the stress `σzz = −ρ c V`. A probe
/// at z = L/2 = 0.1 m sees it arrive at `L/(2c) + 1 µs` (half the ramp),
/// and keeps the displacement the piston gave, `V (10 − 1) µs`, once it has
/// passed (before the echo from z = 0.2 m comes back, at 3L/(2c)).
#[test]
fn a_probe_records_the_p_wave_passing_mid_bar() {
    let (case, out) = bar_with(
        "probe-bar",
        "[[output.probes]]\nname = \"mid\"\nat = [0.01, 0.01, 0.1]\n\n[[output.probes]]\nname = \"end\"\nat = [0.01, 0.01, 0.0]\n",
    );
    let o = femdem(&["run", case.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let table = history(&out);
    let header: Vec<&str> = table.columns.iter().map(String::as_str).collect();
    let rows = &table.rows;
    let (t, vz, szz, uz) = (
        column(&header, rows, "time"),
        column(&header, rows, "mid_vz"),
        column(&header, rows, "mid_szz"),
        column(&header, rows, "mid_uz"),
    );
    let (e, nu, rho, v0): (f64, f64, f64, f64) = (26.0e9, 0.2, 2340.0, 0.1);
    let c = (e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)) / rho).sqrt();
    let arrival = 0.1 / c + 1.0e-6;
    // Arrival: the first row at half the piston speed.
    let first = t.iter().zip(&vz).find(|(_, v)| **v > 0.5 * v0).map(|(t, _)| *t).expect("the wave never arrived");
    assert!((first - arrival).abs() < 0.05 * arrival, "arrival {first:e} s against {arrival:e} s");
    // Nothing moves before the front (dispersion ahead of it is small).
    let quiet = t.iter().zip(&vz).filter(|(t, _)| **t < 0.8 * arrival).map(|(_, v)| v.abs()).fold(0.0, f64::max);
    assert!(quiet < 0.05 * v0, "motion {quiet} m/s before the front");
    // On the plateau: velocity V and stress −ρcV, to the mesh's dispersion.
    let plateau: Vec<usize> = (0..t.len()).filter(|&i| t[i] > arrival + 2.0e-6 && t[i] < arrival + 7.0e-6).collect();
    assert!(plateau.len() > 5, "{} rows on the plateau", plateau.len());
    let mean = |f: &[f64]| plateau.iter().map(|&i| f[i]).sum::<f64>() / plateau.len() as f64;
    let (v_mid, s_mid) = (mean(&vz), mean(&szz));
    assert!((v_mid - v0).abs() < 0.05 * v0, "plateau velocity {v_mid} m/s against {v0}");
    let s_exact = -rho * c * v0;
    assert!((s_mid - s_exact).abs() < 0.05 * s_exact.abs(), "plateau σzz {s_mid:e} Pa against {s_exact:e}");
    // After the pulse, before the echo: the piston's displacement.
    let after: Vec<f64> =
        (0..t.len()).filter(|&i| t[i] > arrival + 14.0e-6 && t[i] < 3.0 * 0.1 / c - 2.0e-6).map(|i| uz[i]).collect();
    assert!(!after.is_empty());
    let u_exact = v0 * 9.0e-6;
    for u in after {
        assert!((u - u_exact).abs() < 0.05 * u_exact, "displacement {u:e} m after the pulse against {u_exact:e}");
    }
    // The probe at the piston's face moves with the piston's nodes.
    let (end, piston) = (column(&header, rows, "end_uz"), column(&header, rows, "piston_uz"));
    for (a, b) in end.iter().zip(&piston) {
        assert!((a - b).abs() <= 1e-9 * b.abs().max(1e-12), "end probe {a:e} m, piston {b:e} m");
    }
}

/// Bad probes: the error names the case file, the line of the probe and
/// `output.probes[i]`.
#[test]
fn bad_probes_are_refused_with_file_line_and_key() {
    let cases = [
        (
            "probe-outside",
            "[[output.probes]]\nname = \"far\"\nat = [1.0, 0.0, 0.0]\n",
            "output.probes[0]: `at` [1.0, 0.0, 0.0] m lies in no tet",
        ),
        (
            "probe-twice",
            "[[output.probes]]\nname = \"g\"\nat = [0.01, 0.01, 0.1]\n[[output.probes]]\nname = \"g\"\nat = [0.01, 0.01, 0.05]\n",
            "output.probes[1]: name `g` is used by another probe",
        ),
        (
            "probe-load-name",
            "[[output.probes]]\nname = \"piston\"\nat = [0.01, 0.01, 0.1]\n",
            "output.probes[0]: name `piston` is already a load's",
        ),
        (
            "probe-bad-name",
            "[[output.probes]]\nname = \"a b\"\nat = [0.01, 0.01, 0.1]\n",
            "output.probes[0]: name `a b` must be",
        ),
        (
            "probe-nan",
            "[[output.probes]]\nname = \"n\"\nat = [nan, 0.0, 0.0]\n",
            "output.probes[0]: `at` must be finite",
        ),
    ];
    for (name, probes, words) in cases {
        let (case, _) = bar_with(name, probes);
        let text = std::fs::read_to_string(&case).unwrap();
        // The probe's table starts on the line of its `[[output.probes]]`.
        let index: usize = words["output.probes[".len()..].split(']').next().unwrap().parse().unwrap();
        let line =
            text.lines().enumerate().filter(|(_, l)| l.starts_with("[[output.probes]]")).nth(index).unwrap().0 + 1;
        let o = femdem(&["check", case.to_str().unwrap()]);
        assert!(!o.status.success(), "{name} was accepted");
        let err = String::from_utf8(o.stderr).unwrap();
        assert!(err.contains(&format!("{}:{line}:", case.display())), "{name}: expected line {line} in: {err}");
        assert!(err.contains(words), "{name}: expected `{words}` in: {err}");
    }
}

/// A named fixed support records its reaction and changes nothing else.
/// The bar's far end (z = L, held along z), named `anvil`, reflects the
/// P-wave pulse as a fixed end and so takes twice its momentum: the
/// impulse of the reaction over the reflection is `2 ρ A c V τ` (A the
/// 20 mm × 20 mm section, τ = 9 µs the pulse's length in time: the
/// piston's 10 µs less half its 2 µs ramp). The pulse's dispersion on the
/// mesh spreads and rounds the reaction (its peak is 19% above `2ρcVA`)
/// but moves no momentum, so the impulse is a sharp check. Every other
/// column of the history is the same, bit for bit, as with the support
/// unnamed.
#[test]
fn a_named_fixed_support_records_its_reaction() {
    let probe = "[[output.probes]]\nname = \"mid\"\nat = [0.01, 0.01, 0.1]\n";
    let run = |name: &str, named: bool| {
        let (case, out) = bar_with(name, probe);
        if named {
            let text = std::fs::read_to_string(&case).unwrap();
            let held = "kind = \"fixed\"\nnodes = { group = \"bar.zmax\" }";
            assert_eq!(text.matches(held).count(), 1);
            std::fs::write(
                &case,
                text.replace(held, "kind = \"fixed\"\nname = \"anvil\"\nnodes = { group = \"bar.zmax\" }"),
            )
            .unwrap();
        }
        let o = femdem(&["run", case.to_str().unwrap(), "--out", out.to_str().unwrap()]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        history_csv(&out)
    };
    let (plain, named) = (run("fixed-unnamed", false), run("fixed-named", true));
    let table = |text: &str| -> (Vec<String>, Vec<Vec<f64>>) {
        let mut lines = text.lines();
        let header = lines.next().unwrap().split(',').map(String::from).collect();
        (header, lines.map(|l| l.split(',').map(|x| x.parse().unwrap()).collect()).collect())
    };
    let ((h0, r0), (h1, r1)) = (table(&plain), table(&named));
    assert_eq!(r0.len(), r1.len());
    for (k, name) in h0.iter().enumerate() {
        let j = h1.iter().position(|h| h == name).unwrap_or_else(|| panic!("{name} lost"));
        for (a, b) in r0.iter().zip(&r1) {
            assert_eq!(a[k].to_bits(), b[j].to_bits(), "{name} changed");
        }
    }
    let h1: Vec<&str> = h1.iter().map(String::as_str).collect();
    let fz = column(&h1, &r1, "anvil_fz");
    let (e, nu, rho, v0, area): (f64, f64, f64, f64, f64) = (26.0e9, 0.2, 2340.0, 0.1, 0.02 * 0.02);
    let c = (e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)) / rho).sqrt();
    let t = column(&h1, &r1, "time");
    // Before the wave reaches the far end the support carries nothing.
    let (arrive, gone) = (0.8 * 0.2 / c, 0.2 / c + 25.0e-6);
    let force = 2.0 * rho * c * v0 * area;
    let early = t.iter().zip(&fz).filter(|(t, _)| **t < arrive).map(|(_, f)| f.abs()).fold(0.0, f64::max);
    assert!(early < 0.01 * force, "reaction {early} N before the wave arrives");
    // The impulse over the reflection (trapezoid over the history rows),
    // before the echo returns from the piston's end at 3L/c.
    let impulse: f64 = (1..t.len())
        .filter(|&i| t[i - 1] >= arrive && t[i] <= gone)
        .map(|i| 0.5 * (fz[i] + fz[i - 1]) * (t[i] - t[i - 1]))
        .sum();
    let exact = -force * 9.0e-6;
    assert!((impulse - exact).abs() < 0.02 * exact.abs(), "impulse {impulse:e} N s against −2ρAcVτ = {exact:e}");
}
