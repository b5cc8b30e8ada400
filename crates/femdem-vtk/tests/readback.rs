//! Independent-reader check: files written by femdem-vtk are read back by
//! VTK's own XML reader (what ParaView uses) and by meshio, in Python, and
//! every coordinate, connectivity entry and field value must come back bit
//! for bit. The `.pvd` collections are parsed with Python's `xml.etree`.
//!
//! Set-up: the test makes a virtual environment under the Cargo target
//! directory (`target/tmp/femdem-vtk-python`) and installs meshio, numpy and
//! vtk into it with pip the first time (about 15 s and 800 MB, mostly VTK);
//! later runs reuse it. It needs `python3` with the `venv` module and access
//! to PyPI, and fails with a message saying so when they are missing. Set
//! `FEMDEM_PYTHON` to use another interpreter for the set-up.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use femdem_vtk::{Compression, Field, Frame, SeriesWriter, VtuOptions, write_vtu_with};
use serde_json::Value;

/// What the virtual environment gets; changing it rebuilds the environment.
const REQUIREMENTS: &[&str] = &["meshio==5.3.5", "numpy", "vtk>=9.1,<10"];
const READER: &str = include_str!("readback/read_vtu.py");
const VTK_TETRA: u64 = 10;

// ---------------------------------------------------------------- python --

/// The Python interpreter of the test's virtual environment, created once.
fn venv_python() -> &'static Path {
    static PYTHON: OnceLock<PathBuf> = OnceLock::new();
    PYTHON.get_or_init(|| {
        let root = Path::new(env!("CARGO_TARGET_TMPDIR"));
        let venv = root.join("femdem-vtk-python");
        let stamp = REQUIREMENTS.join("\n");
        let ready = |dir: &Path| fs::read_to_string(dir.join("femdem-ready")).is_ok_and(|s| s == stamp);
        if !ready(&venv) {
            // Build beside the final place and rename, so that concurrent
            // test runs never use a half-installed environment.
            let building = root.join(format!("femdem-vtk-python.building-{}", std::process::id()));
            let _ = fs::remove_dir_all(&building);
            create_venv(&building);
            fs::write(building.join("femdem-ready"), &stamp).unwrap();
            if !ready(&venv) {
                let _ = fs::remove_dir_all(&venv);
            }
            if fs::rename(&building, &venv).is_err() {
                assert!(ready(&venv), "could not move {building:?} to {venv:?}");
                let _ = fs::remove_dir_all(&building);
            }
        }
        python_in(&venv)
    })
}

fn python_in(venv: &Path) -> PathBuf {
    if cfg!(windows) { venv.join("Scripts").join("python.exe") } else { venv.join("bin").join("python") }
}

/// Runs `cmd`, failing the test with `what`, the hint and the output if it
/// cannot start or exits non-zero.
fn run(cmd: &mut Command, what: &str, hint: &str) -> String {
    let out = cmd.output().unwrap_or_else(|e| panic!("{what}: could not run {cmd:?}: {e}\n{hint}"));
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "{what}: {cmd:?} failed ({})\n{hint}\n--- stdout ---\n{stdout}\n--- stderr ---\n{stderr}",
        out.status
    );
    stdout
}

fn create_venv(dir: &Path) {
    let python = std::env::var("FEMDEM_PYTHON").unwrap_or_else(|_| "python3".to_owned());
    run(
        Command::new(&python).arg("--version"),
        "the readback test needs Python 3",
        "Install python3 (with pip and venv) or set FEMDEM_PYTHON to an interpreter.",
    );
    run(
        Command::new(&python).args(["-m", "venv"]).arg(dir),
        "creating the readback test's virtual environment",
        "Python's venv module is missing (Debian: apt-get install python3-venv).",
    );
    let mut pip = Command::new(python_in(dir));
    pip.args(["-m", "pip", "install", "--quiet", "--disable-pip-version-check"]).args(REQUIREMENTS);
    run(
        &mut pip,
        "installing the readback test's Python packages",
        "pip needs access to PyPI (or a local index) for meshio, numpy and vtk.",
    );
}

/// Reads every `.vtu` of `vtu` (with meshio too where flagged) and every
/// `.pvd` of `pvd` in one Python process.
fn read_back(dir: &Path, vtu: &[(PathBuf, bool)], pvd: &[PathBuf]) -> Value {
    let script = dir.join("read_vtu.py");
    fs::write(&script, READER).unwrap();
    let manifest = serde_json::json!({
        "vtu": vtu.iter().map(|(p, meshio)| serde_json::json!({"path": p, "meshio": meshio})).collect::<Vec<_>>(),
        "pvd": pvd,
    });
    let manifest_path = dir.join("manifest.json");
    fs::write(&manifest_path, manifest.to_string()).unwrap();
    let stdout =
        run(Command::new(venv_python()).arg(&script).arg(&manifest_path), "reading the files back in Python", "");
    let line = stdout
        .lines()
        .find_map(|l| l.strip_prefix("FEMDEM-JSON "))
        .unwrap_or_else(|| panic!("no JSON line in the reader's output:\n{stdout}"));
    serde_json::from_str(line).unwrap()
}

// ------------------------------------------------------------- test data --

/// Deterministic bit patterns spread over the whole `f64` range (finite).
struct Bits(u64);

impl Bits {
    fn next(&mut self) -> f64 {
        loop {
            // splitmix64
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            let x = f64::from_bits(z ^ (z >> 31));
            if x.is_finite() {
                return x;
            }
        }
    }
}

/// Owned arrays of one frame.
struct Data {
    points: Vec<[f64; 3]>,
    tets: Vec<[u32; 4]>,
    displacement: Vec<[f64; 3]>,
    stress: Vec<[f64; 9]>,
    region: Vec<f64>,
}

impl Data {
    /// A few tets, some sharing nodes, with awkward values everywhere.
    fn small(step: u64) -> Data {
        let mut bits = Bits(step);
        let points = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [2.5, 0.1, -3e-9],
            [1.0 / 3.0, std::f64::consts::PI, -1e300],
            [5e-324, -0.0, 6.022_140_76e23],
        ];
        let tets = vec![[0, 1, 2, 3], [1, 2, 3, 4], [4, 5, 6, 7], [0, 7, 6, 5]];
        let mut displacement: Vec<[f64; 3]> =
            (0..points.len()).map(|_| [bits.next(), bits.next(), bits.next()]).collect();
        displacement[0] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
        displacement[1] = [-0.0, f64::MIN_POSITIVE, f64::MAX];
        displacement[2] = [0.1 + 0.2, 1e-310, step as f64];
        let stress = (0..tets.len())
            .map(|_| {
                let [a, b, c, d, e, f] = std::array::from_fn(|_| bits.next());
                [a, b, c, b, d, e, c, e, f]
            })
            .collect();
        let region = (0..tets.len()).map(|i| (i % 2) as f64).collect();
        Data { points, tets, displacement, stress, region }
    }

    /// 4096 points and tets: every array except `types` is a whole number
    /// of vtkio's 32 KiB compression blocks, the case where vtkio writes a
    /// trailing empty block.
    fn block_edges() -> Data {
        let mut bits = Bits(99);
        let n = 4096;
        let points = (0..n).map(|_| [bits.next(), bits.next(), bits.next()]).collect();
        let tets = (0..n as u32).map(|i| [i, (i + 1) % 4096, (i + 7) % 4096, (i + 4000) % 4096]).collect();
        let displacement = (0..n).map(|_| [bits.next(), bits.next(), bits.next()]).collect();
        let stress = (0..n).map(|_| std::array::from_fn(|_| bits.next())).collect();
        let region = (0..n).map(|i| i as f64).collect();
        Data { points, tets, displacement, stress, region }
    }

    fn empty(num_points: usize) -> Data {
        Data {
            points: vec![[1.5, -2.0, 0.25]; num_points],
            tets: Vec::new(),
            displacement: vec![[0.0; 3]; num_points],
            stress: Vec::new(),
            region: Vec::new(),
        }
    }

    fn write(&self, f: impl FnOnce(&Frame<'_>)) {
        let pf = [Field::vector("displacement", &self.displacement)];
        let cf = [Field::tensor("stress", &self.stress), Field::scalar("region", &self.region)];
        let frame = Frame::new(&self.points, &self.tets).with_point_fields(&pf).with_cell_fields(&cf);
        f(&frame);
    }
}

// ------------------------------------------------------------ comparison --

fn decode<const N: usize>(hex: &str) -> Vec<[u8; N]> {
    assert!(hex.len().is_multiple_of(2 * N), "hex length {}", hex.len());
    hex.as_bytes()
        .chunks(2 * N)
        .map(|c| {
            std::array::from_fn(|i| u8::from_str_radix(std::str::from_utf8(&c[2 * i..2 * i + 2]).unwrap(), 16).unwrap())
        })
        .collect()
}

fn f64_bits(hex: &Value) -> Vec<u64> {
    decode::<8>(hex.as_str().unwrap()).into_iter().map(u64::from_le_bytes).collect()
}

fn i64s(hex: &Value) -> Vec<u64> {
    decode::<8>(hex.as_str().unwrap()).into_iter().map(|b| u64::try_from(i64::from_le_bytes(b)).unwrap()).collect()
}

fn bits_of(values: &[f64]) -> Vec<u64> {
    values.iter().map(|x| x.to_bits()).collect()
}

/// Asserts two bit-pattern arrays are equal, naming the first difference.
fn assert_same(what: &str, got: &[u64], want: &[u64]) {
    assert_eq!(got.len(), want.len(), "{what}: length");
    if let Some(i) = (0..got.len()).find(|&i| got[i] != want[i]) {
        panic!(
            "{what}: value {i} differs: read {:e} ({:#x}), written {:e} ({:#x})",
            f64::from_bits(got[i]),
            got[i],
            f64::from_bits(want[i]),
            want[i]
        );
    }
}

/// The fields of `data` as `name -> (components, values)`.
fn expected_fields(data: &Data) -> [BTreeMap<&'static str, (u64, Vec<u64>)>; 2] {
    let point = BTreeMap::from([("displacement", (3, bits_of(data.displacement.as_flattened())))]);
    let cell =
        BTreeMap::from([("stress", (9, bits_of(data.stress.as_flattened()))), ("region", (1, bits_of(&data.region)))]);
    [point, cell]
}

fn check_fields(what: &str, got: &Value, want: &BTreeMap<&str, (u64, Vec<u64>)>) {
    let got = got.as_object().unwrap();
    let mut names: Vec<&str> = got.keys().map(String::as_str).collect();
    names.sort_unstable();
    assert_eq!(names, want.keys().copied().collect::<Vec<_>>(), "{what}: names");
    for (name, (components, values)) in want {
        let array = &got[*name];
        assert_eq!(array["components"], *components, "{what} {name}: components");
        assert!(matches!(array["type"].as_str(), Some("double" | "float64")), "{what} {name}: type {}", array["type"]);
        assert_same(&format!("{what} {name}"), &f64_bits(&array["values"]), values);
    }
}

/// Everything VTK read from one file against what was written.
fn check_vtk(file: &str, got: &Value, data: &Data) {
    let what = format!("VTK reading {file}");
    assert_eq!(got["messages"], serde_json::json!([]), "{what}: reader messages");
    assert_eq!(got["num_points"], data.points.len(), "{what}: points");
    assert_eq!(got["num_cells"], data.tets.len(), "{what}: cells");
    assert_same(&format!("{what}: coordinates"), &f64_bits(&got["points"]), &bits_of(data.points.as_flattened()));
    let types: Vec<u64> = got["types"].as_array().unwrap().iter().map(|t| t.as_u64().unwrap()).collect();
    assert_eq!(types, vec![VTK_TETRA; data.tets.len()], "{what}: cell types");
    if !data.tets.is_empty() {
        let offsets: Vec<u64> = (0..=data.tets.len() as u64).map(|i| 4 * i).collect();
        assert_eq!(i64s(&got["offsets"]), offsets, "{what}: offsets");
        let conn: Vec<u64> = data.tets.as_flattened().iter().map(|&n| n.into()).collect();
        assert_eq!(i64s(&got["connectivity"]), conn, "{what}: connectivity");
    }
    let [point, cell] = expected_fields(data);
    check_fields(&format!("{what}: point data"), &got["point_data"], &point);
    check_fields(&format!("{what}: cell data"), &got["cell_data"], &cell);
}

/// Everything meshio read from one file against what was written.
fn check_meshio(file: &str, got: &Value, data: &Data) {
    let what = format!("meshio reading {file}");
    assert!(got.get("error").is_none(), "{what}: {}", got["error"]);
    assert_same(&format!("{what}: coordinates"), &f64_bits(&got["points"]), &bits_of(data.points.as_flattened()));
    let blocks = got["cells"].as_array().unwrap();
    assert_eq!(blocks.len(), 1, "{what}: cell blocks");
    assert_eq!(blocks[0]["type"], "tetra", "{what}: cell type");
    let conn: Vec<u64> = data.tets.as_flattened().iter().map(|&n| n.into()).collect();
    assert_eq!(i64s(&blocks[0]["connectivity"]), conn, "{what}: connectivity");
    let [point, cell] = expected_fields(data);
    check_fields(&format!("{what}: point data"), &got["point_data"], &point);
    check_fields(&format!("{what}: cell data"), &got["cell_data"], &cell);
}

fn case_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("femdem-vtk-readback").join(name);
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

const COMPRESSIONS: [(&str, Compression); 3] =
    [("none", Compression::None), ("zlib", Compression::Zlib { level: 6 }), ("lz4", Compression::Lz4)];

/// meshio 5.3 reads uncompressed and zlib data but not LZ4.
fn meshio_reads(compression: Compression) -> bool {
    compression != Compression::Lz4
}

// ----------------------------------------------------------------- tests --

#[test]
fn series_reads_back_bit_for_bit_in_vtk_and_meshio() {
    let dir = case_dir("series");
    let times = [0.0, 1e-7, 0.1 + 0.2];
    let mut vtu = Vec::new();
    let mut pvd = Vec::new();
    let mut written = Vec::new();
    for (name, compression) in COMPRESSIONS {
        let mut series = SeriesWriter::new(&dir.join(name), "block").unwrap().with_options(VtuOptions { compression });
        for (step, &t) in times.iter().enumerate() {
            let data = Data::small(step as u64);
            let mut path = PathBuf::new();
            data.write(|frame| path = series.write(t, frame).unwrap());
            vtu.push((path.clone(), meshio_reads(compression)));
            written.push((path, data));
        }
        pvd.push(series.pvd_path());
    }

    let result = read_back(&dir, &vtu, &pvd);
    eprintln!("readers: {}", result["versions"]);
    for (path, data) in &written {
        let key = path.to_str().unwrap();
        let entry = &result["vtu"][key];
        check_vtk(key, &entry["vtk"], data);
        if let Some(meshio) = entry.get("meshio") {
            check_meshio(key, meshio, data);
        }
    }
    for path in &pvd {
        let got = &result["pvd"][path.to_str().unwrap()];
        assert_eq!(got["root"], "VTKFile", "{path:?}");
        assert_eq!(got["type"], "Collection", "{path:?}");
        assert_eq!(got["collections"], 1, "{path:?}");
        let sets = got["datasets"].as_array().unwrap();
        assert_eq!(sets.len(), times.len(), "{path:?}: DataSet entries");
        for (i, (set, &t)) in sets.iter().zip(&times).enumerate() {
            let ts: f64 = set["timestep"].as_str().unwrap().parse().unwrap();
            assert_eq!(ts.to_bits(), t.to_bits(), "{path:?}: timestep {i}");
            let file = set["file"].as_str().unwrap();
            assert_eq!(file, format!("block_{i:06}.vtu"), "{path:?}");
            assert!(path.parent().unwrap().join(file).is_file(), "{file} missing");
        }
    }
}

#[test]
fn edge_frames_read_back_in_vtk_and_meshio() {
    let dir = case_dir("edges");
    let cases = [("block_edges", Data::block_edges()), ("empty", Data::empty(0)), ("points_only", Data::empty(3))];
    let mut vtu = Vec::new();
    let mut written = Vec::new();
    for (case, data) in &cases {
        for (name, compression) in COMPRESSIONS {
            let path = dir.join(format!("{case}_{name}.vtu"));
            data.write(|frame| write_vtu_with(&path, frame, VtuOptions { compression }).unwrap());
            // meshio 5.3 cannot read a file without cells.
            let meshio = meshio_reads(compression) && !data.tets.is_empty();
            vtu.push((path.clone(), meshio));
            written.push((path, data));
        }
    }
    let result = read_back(&dir, &vtu, &[]);
    for (path, data) in written {
        let key = path.to_str().unwrap();
        let entry = &result["vtu"][key];
        check_vtk(key, &entry["vtk"], data);
        if let Some(meshio) = entry.get("meshio") {
            check_meshio(key, meshio, data);
        }
    }
}
