//! The TOML case format, version 1, as serde structs. Every table rejects
//! unknown keys. Units are SI (metres, seconds, pascals, kilograms).
//! The annotated reference is `docs/case-format.md`.

use serde::Deserialize;
use toml::Spanned;

/// The case format version this build reads.
pub const CASE_VERSION: u32 = 1;

/// A fixed-length array read exactly: `toml` fills `[T; N]` from the first
/// `N` entries of a longer array and drops the rest without a word (found
/// probing bad inputs: `gravity = [0, 0, -9.81, 1]` was read as
/// `[0, 0, -9.81]`), so every such key of a plain table reads a list and
/// refuses any other length. (Keys of the tables tagged by `kind` are
/// checked by serde itself.)
fn exact<'de, D, T, const N: usize>(d: D) -> Result<[T; N], D::Error>
where
    D: serde::Deserializer<'de>,
    T: Deserialize<'de>,
{
    let v = Vec::<T>::deserialize(d)?;
    let n = v.len();
    v.try_into().map_err(|_| serde::de::Error::invalid_length(n, &format!("an array of {N}").as_str()))
}

/// The keys whose value is a list of tables (`[[loads]]`), wherever they
/// sit: written with a single `[…]`, or another key with `[[…]]`, they are
/// the slip [`crate::load`] names.
pub const TABLE_LISTS: &[&str] =
    &["materials", "platens", "loads", "pairs", "probes", "regions", "parts", "joints_within"];

/// A whole case file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Case {
    /// Format version; must equal [`CASE_VERSION`].
    pub version: Spanned<u32>,
    /// Free text shown in reports.
    #[serde(default)]
    pub title: String,
    /// How the mesh is made.
    pub mesh: MeshSection,
    /// `[[materials]]`: one per deformable region.
    #[serde(default)]
    pub materials: Vec<Spanned<MaterialSpec>>,
    /// `[[platens]]`: rigid regions moved by a prescribed velocity.
    #[serde(default)]
    pub platens: Vec<Spanned<PlatenDrive>>,
    /// `[[loads]]`: constraints, velocities, pressures, tractions.
    #[serde(default)]
    pub loads: Vec<Spanned<LoadSpec>>,
    /// `[contact]`: tet–tet potential contact (Eq. 17); off when absent.
    pub contact: Option<Spanned<ContactSpec>>,
    /// `[heterogeneity]`: random joint strengths.
    pub heterogeneity: Option<Spanned<HeterogeneitySpec>>,
    /// `[solver]`: time span and the speed/accuracy knobs.
    pub solver: Option<Spanned<SolverSpec>>,
    /// `[output]`: what is written and how often (defaults when absent).
    pub output: Option<Spanned<OutputSpec>>,
}

/// `[[materials]]`: the material of one region, SI units.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// The region.
    pub region: String,
    /// `"neo-hookean"` (Eq. 1, default) or `"linear-elastic"` (small strain).
    #[serde(default = "default_law")]
    pub law: String,
    /// Density ρ, kg/m³.
    pub density: f64,
    /// Young's modulus E, Pa.
    pub young: f64,
    /// Poisson's ratio ν.
    pub poisson: f64,
    /// Viscous damping η of Eq. 1, Pa·s (exclusive with `damping_ratio`).
    pub viscosity: Option<f64>,
    /// η as a fraction of the critical value `2 h √(Eρ)`, `h` the region's
    /// mean edge length (exclusive with `viscosity`). Default: 0.
    pub damping_ratio: Option<f64>,
    /// Joint penalty p0, Pa (breakable regions; default 10 E, Eq. 9).
    pub penalty: Option<f64>,
    /// Tensile strength f_t, Pa (breakable regions).
    pub tensile_strength: Option<f64>,
    /// Cohesion c, Pa (breakable regions).
    pub cohesion: Option<f64>,
    /// Internal friction angle φ, degrees (breakable regions).
    pub friction_angle: Option<f64>,
    /// Fracture energy in tension G_ft, J/m² (breakable regions; Eq. 10).
    pub fracture_energy: Option<f64>,
    /// Fracture energy in shear G_fs, J/m² (default: `fracture_energy`).
    pub fracture_energy_shear: Option<f64>,
    /// `"paper"` (δc = 3 Gf / f, Eq. 10; default) or `"exact"` (δc set so the
    /// softening branch dissipates exactly Gf).
    pub gf_calibration: Option<String>,
    /// How damage acts on the hardening branches of Eq. 11: `"printed"`
    /// (default: Eq. 11 as printed, no `z` before the peak), `"capped"`
    /// (`min(hardening, z(D) f)`), `"multiplicative"` (`z(D) × hardening`,
    /// as in Munjiza's Y code). See `femdem_fracture::Coupling`.
    pub joint_coupling: Option<String>,
}

/// `[contact]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// Normal penalty p of Eq. 17, Pa (of the order of E).
    pub penalty: f64,
    /// Whether the outer surfaces of bodies can touch (platens, collisions;
    /// default true). Fracture surfaces always can.
    #[serde(default = "yes")]
    pub surfaces: bool,
    /// Coulomb friction coefficient μ between contacting surfaces of region
    /// pairs not listed in `pairs` (default 0: frictionless).
    #[serde(default)]
    pub friction: f64,
    /// Per-region-pair friction coefficients (`[[contact.pairs]]`).
    #[serde(default)]
    pub pairs: Vec<Spanned<FrictionPairSpec>>,
    /// Detection buffer, m (default 0: detect at every step). Detection is
    /// repeated once a contactable node has moved half of it; a larger
    /// buffer detects less often but evaluates more candidate pairs. It does
    /// not change the result.
    #[serde(default)]
    pub buffer: f64,
    /// Steps over which the contact force of a joint that failed in
    /// compression is ramped in (Eq. 18's `n_total`; default 10, 0: none).
    #[serde(default = "ten")]
    pub ramp_steps: u32,
    /// Pairs whose contact forces are provably below `negligible · p · ℓ²`
    /// (ℓ³ the smaller tet's volume: a contact pressure below
    /// `negligible · p`) are not evaluated (default 1e-10; 0 evaluates every
    /// candidate pair).
    #[serde(default = "negligible")]
    pub negligible: f64,
    /// How a pair that already overlaps when it is newly allowed to touch
    /// (around a failed joint, or at the first step) starts: `"couple"`
    /// (the default: Eq. 18 for the failed joint's own couple if it failed
    /// in compression, the other pairs' first overlap counted as zero),
    /// `"offset"` (every such pair's first overlap counted as zero),
    /// `"paper"` (Eq. 18 for the couple, the rest at full force) or
    /// `"ramp"` (Eq. 18 for every such pair). See
    /// `femdem_solver::Activation`.
    pub activation: Option<String>,
    /// The normal force: `"potential"` (the default: Eq. 17 as printed) or
    /// `"gradient"` (the exact gradient of Eq. 17's overlap energy, with
    /// energy-consistent kicks: contact gives back what it took over a
    /// closed cycle; 4–10 times Eq. 17's cost). See
    /// `femdem_solver::ContactModel`.
    pub model: Option<String>,
    /// What the run guard does when the normal contact forces have given
    /// back more than `energy_tolerance` of the run's energy scale beyond
    /// what they absorbed: `"stop"` (default: the run stops), `"warn"` (a
    /// warning of the run, once) or `"off"` (`crate::setup::contact_check`).
    pub energy_check: Option<String>,
    /// That tolerance, a fraction of the run's energy scale in (0, 1]
    /// (default `femdem_solver::CONTACT_ENERGY_TOLERANCE`, 0.05).
    pub energy_tolerance: Option<f64>,
}

fn negligible() -> f64 {
    femdem_solver::NEGLIGIBLE
}

fn ten() -> u32 {
    10
}

/// `[[contact.pairs]]`: the friction coefficient between two regions.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionPairSpec {
    /// The two regions (the same name twice for contacts within a region,
    /// e.g. crack faces).
    #[serde(deserialize_with = "exact")]
    pub regions: [String; 2],
    /// Coulomb friction coefficient μ.
    pub friction: f64,
}

fn yes() -> bool {
    true
}

/// `[heterogeneity]`: random joint strengths (f_t and c each times an
/// independent factor of mean 1).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeterogeneitySpec {
    /// `"weibull"` or `"normal"`.
    pub distribution: String,
    /// Weibull modulus (for `"weibull"`).
    pub modulus: Option<f64>,
    /// Coefficient of variation (for `"normal"`).
    pub cov: Option<f64>,
    /// Seed of the draws (default: `mesh.seed`).
    pub seed: Option<u64>,
}

fn default_law() -> String {
    "neo-hookean".into()
}

/// A set of nodes: the intersection of the criteria given.
#[derive(Debug, Deserialize, Default, Clone)]
#[serde(deny_unknown_fields)]
pub struct NodeSpec {
    /// Nodes on a boundary group, e.g. `"bar.zmin"`.
    pub group: Option<String>,
    /// Nodes of a region.
    pub region: Option<String>,
    /// Nodes whose initial position lies in a box.
    #[serde(rename = "box")]
    pub within: Option<BoxSpec>,
}

/// `{ min = [x, y, z], max = [x, y, z] }`, m.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct BoxSpec {
    /// Lower corner.
    #[serde(deserialize_with = "exact")]
    pub min: [f64; 3],
    /// Upper corner.
    #[serde(deserialize_with = "exact")]
    pub max: [f64; 3],
}

/// `[[platens]]`: a rigid region moved at a ramped velocity. Until contact
/// exists, it moves the specimen nodes in `drives` with it.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlatenDrive {
    /// The rigid region (declared unbreakable, with no material).
    pub region: String,
    /// Velocity, m/s.
    #[serde(deserialize_with = "exact")]
    pub velocity: [f64; 3],
    /// Linear rise time of the velocity, s (default 0).
    #[serde(default)]
    pub ramp_time: f64,
    /// Specimen nodes moved with the platen.
    pub drives: Option<NodeSpec>,
}

/// `[[loads]]`, told apart by `kind`.
#[derive(Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum LoadSpec {
    /// Zero velocity on the given components.
    Fixed {
        /// Name in the history: when given, the support's reaction force
        /// and mean displacement are recorded as `<name>_fx … <name>_uz`
        /// (and its work as `<name>_work`: zero when held from the start;
        /// with `start_time`, the work of stopping its nodes when it starts)
        /// (it is then a velocity drive of zero velocity, and its nodes may
        /// not share a held component with another support or drive).
        name: Option<String>,
        /// The nodes.
        nodes: NodeSpec,
        /// Components, letters of `"xyz"`.
        components: String,
        /// Time from which the components are held, s (default: from the
        /// start); before it they move freely. The nodes are held where
        /// they are at that time (a zero-velocity drive, named
        /// `fixed<i>` when `name` is not given).
        start_time: Option<f64>,
    },
    /// A prescribed, ramped velocity; its reaction force is recorded.
    Velocity {
        /// Name in the history (default `velocity<i>`).
        name: Option<String>,
        /// The nodes.
        nodes: NodeSpec,
        /// Velocity, m/s.
        velocity: [f64; 3],
        /// Components prescribed (default `"xyz"`).
        components: Option<String>,
        /// Rise time, s.
        #[serde(default)]
        ramp_time: f64,
        /// Time after which the velocity is zero, s.
        stop_time: Option<f64>,
        /// Time from which the velocity is prescribed, s (default: from the
        /// start); before it the components move freely and no reaction is
        /// recorded. `ramp_time` and `stop_time` count from t = 0.
        start_time: Option<f64>,
    },
    /// A pressure on a boundary group (positive pushes on it).
    Pressure {
        /// The boundary group.
        group: String,
        /// Pressure, Pa.
        pressure: f64,
        /// Rise time, s.
        #[serde(default)]
        ramp_time: f64,
        /// Time after which the load is removed, s (default: never).
        stop_time: Option<f64>,
    },
    /// A traction vector on a boundary group.
    Traction {
        /// The boundary group.
        group: String,
        /// Traction, Pa.
        traction: [f64; 3],
        /// Rise time, s.
        #[serde(default)]
        ramp_time: f64,
        /// Time after which the load is removed, s (default: never).
        stop_time: Option<f64>,
    },
}

/// `[solver]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// Simulated time, s.
    pub end_time: f64,
    /// Time step, s (default: `safety ×` the estimated critical step).
    pub time_step: Option<f64>,
    /// Fraction of the critical step used when `time_step` is not given
    /// (default 0.9).
    #[serde(default = "default_safety")]
    pub safety: f64,
    /// Nodal mass multiplier ≥ 1 (default 1: exact dynamics).
    #[serde(default = "one")]
    pub mass_scaling: f64,
    /// Body acceleration, m/s² (default none).
    #[serde(default)]
    #[serde(deserialize_with = "exact")]
    pub gravity: [f64; 3],
    /// Worker threads (default: all cores). Results do not depend on it.
    pub threads: Option<usize>,
    /// Steps between run-guard checks (non-finite values, inverted tets,
    /// the time step against the element-wise critical step; default 100;
    /// 0 turns the guard off).
    #[serde(default = "default_check_interval")]
    pub check_interval: u64,
    /// The run guard's energy check, at every check: the largest move of
    /// the energy balance since step 0, as a fraction of the run's energy
    /// scale (`femdem_solver::Imbalance`), in [0, 1]; default
    /// `femdem_solver::ENERGY_TOLERANCE` (0.01); 0 turns the energy check
    /// off.
    #[serde(default = "default_energy_tolerance")]
    pub energy_tolerance: f64,
    /// How the run starts: `"dynamic"` (default: at rest in the reference
    /// state, loads as their ramps say) or `"static"` (surface loads held
    /// in full from t = 0, the body first put into equilibrium under them
    /// and gravity by an implicit solve, `femdem-static`).
    pub start: Option<String>,
    /// Where the step runs: `"cpu"` (default) or `"gpu"` (a Vulkan device
    /// with 64-bit floats, `femdem-gpu`: the tet and joint passes, the
    /// gather, the surface loads, the update and the contact pairs' Eq. 17,
    /// the state resident there; failures, the rest of contact, the
    /// drives' reactions and the energy account on the CPU). Results agree
    /// to round-off.
    pub device: Option<String>,
}

fn default_check_interval() -> u64 {
    100
}

fn default_energy_tolerance() -> f64 {
    femdem_solver::ENERGY_TOLERANCE
}

fn default_safety() -> f64 {
    0.9
}

fn one() -> f64 {
    1.0
}

/// `[output]`.
#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Output directory (default `out/<case file stem>`; `--out` overrides).
    pub dir: Option<String>,
    /// Simulated time between VTU frames, s (default: end_time / 20).
    pub interval: Option<f64>,
    /// Simulated time between history rows, s (default: interval / 10).
    pub history_interval: Option<f64>,
    /// Fields written (default all): `displacement`, `velocity`, `stress`,
    /// `principal_stress`, `von_mises`, `region`.
    pub fields: Option<Vec<String>>,
    /// Compression of the VTU frames' binary arrays: `lz4` (default),
    /// `zlib` (level 6), `zlib:N` (level N, 0–9) or `none`.
    pub compression: Option<String>,
    /// `[output.load_strain]`: the load–strain curve of a specimen between
    /// two platens, as history columns `load` and `strain`.
    pub load_strain: Option<Spanned<LoadStrainSpec>>,
    /// `[output.checkpoint]`: how often the run's state is saved for
    /// `femdem run --resume`.
    pub checkpoint: Option<Spanned<CheckpointSpec>>,
    /// `[[output.probes]]`: points whose displacement, velocity and stress
    /// go to the history.
    pub probes: Option<Vec<Spanned<ProbeSpec>>>,
}

/// `[[output.probes]]`: a named point of the mesh, recorded in the history
/// as `<name>_ux … <name>_sxy` (see `case::probes`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProbeSpec {
    /// The column prefix: letters, digits, `_`, `-` and `.`.
    pub name: String,
    /// The point in the reference (unloaded) configuration, m.
    #[serde(deserialize_with = "exact")]
    pub at: [f64; 3],
}

/// `[output.checkpoint]`: a checkpoint is written when either interval has
/// passed since the last one (and always when a signal stops the run).
#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct CheckpointSpec {
    /// Steps between checkpoints (default 0: none by step count).
    pub interval_steps: Option<u64>,
    /// Wall-clock time between checkpoints, s (default 1800; 0: none by
    /// wall time).
    pub interval_wall: Option<f64>,
}

/// `[output.load_strain]`: the paper's load `F = ½ (F_upper + F_lower)`
/// (Eq. 21) and strain `ε = Δa / d` (Eq. 22) from two platens.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadStrainSpec {
    /// The platen on the `+axis` side (its region name).
    pub upper: String,
    /// The platen on the `−axis` side.
    pub lower: String,
    /// The specimen's length `d` between them (the disc's diameter), m.
    pub length: f64,
    /// Loading axis, from the lower platen to the upper one (default
    /// `[0, 1, 0]`; normalised).
    #[serde(default = "y_axis")]
    #[serde(deserialize_with = "exact")]
    pub axis: [f64; 3],
    /// Ends the run once a joint has failed and the load has fallen below
    /// this fraction of its largest value so far (post-peak), in (0, 1);
    /// default: run to `end_time`.
    pub stop_below_peak: Option<f64>,
}

fn y_axis() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}

/// `[mesh]`: regions, parts and the seed of random generators.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSection {
    /// Seed for every random choice of the generators (default 0).
    #[serde(default)]
    pub seed: u64,
    /// `[[mesh.regions]]`: every region a part or an MSH file uses.
    pub regions: Vec<Spanned<RegionSpec>>,
    /// `[[mesh.parts]]`: bodies, meshed in order and never sharing nodes.
    pub parts: Vec<Spanned<PartSpec>>,
}

/// `[[mesh.regions]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegionSpec {
    /// Region name, referred to by parts and by MSH physical volume names.
    pub name: String,
    /// Whether joints are inserted so the region can fracture.
    pub breakable: bool,
    /// Confines a breakable region's joints to these zones: a tet is
    /// jointed when its centroid lies in one of them (boundary included);
    /// the rest of the region is a plain elastic continuum with shared
    /// nodes. Default: joints everywhere in the region.
    pub joints_within: Option<Vec<Spanned<ZoneSpec>>>,
}

/// One zone of `joints_within`: `{ box = { … } }`, `{ sphere = { … } }` or
/// `{ cylinder = { … } }`, in the mesh's coordinates, m.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(rename_all = "lowercase", deny_unknown_fields)]
pub enum ZoneSpec {
    /// An axis-aligned box, `min < max` on every axis.
    Box(BoxSpec),
    /// A ball.
    Sphere(SphereSpec),
    /// A finite round cylinder (flat ends).
    Cylinder(CylinderSpec),
}

/// `sphere = { center = [x, y, z], radius = r }`, m.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct SphereSpec {
    /// Centre.
    #[serde(deserialize_with = "exact")]
    pub center: [f64; 3],
    /// Radius, > 0.
    pub radius: f64,
}

/// `cylinder = { from = [x, y, z], to = [x, y, z], radius = r }`, m: the
/// points within `radius` of the segment `from`–`to` whose projection on
/// its line falls between them.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct CylinderSpec {
    /// Centre of one end.
    #[serde(deserialize_with = "exact")]
    pub from: [f64; 3],
    /// Centre of the other end (not `from`).
    #[serde(deserialize_with = "exact")]
    pub to: [f64; 3],
    /// Radius, > 0.
    pub radius: f64,
}

/// `[[mesh.parts]]`, told apart by `kind`.
#[derive(Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum PartSpec {
    /// `kind = "box"`: a jittered lattice box.
    Box {
        /// Part name (default: the region name); prefixes its boundary groups.
        name: Option<String>,
        /// Region of its tets.
        region: String,
        /// Lower corner, m.
        min: [f64; 3],
        /// Upper corner, m.
        max: [f64; 3],
        /// Target element size, m.
        element_size: f64,
        /// Random vertex offset as a fraction of the element size (default 0.1).
        jitter: Option<f64>,
    },
    /// `kind = "extrusion"`: a 2D outline extruded along z.
    Extrusion {
        /// Part name (default: the region name).
        name: Option<String>,
        /// Region of its tets.
        region: String,
        /// Circular outline (exclusive with `polygon`).
        circle: Option<CircleSpec>,
        /// Polygonal outline (exclusive with `circle`).
        polygon: Option<Vec<[f64; 2]>>,
        /// Pre-existing fracture traces: polylines inside the outline.
        #[serde(default)]
        traces: Vec<Vec<[f64; 2]>>,
        /// Pre-existing fracture traces from a trace file (relative to the
        /// case file; exclusive with `traces`).
        traces_file: Option<String>,
        /// Bottom z, m (default 0).
        #[serde(default)]
        z0: f64,
        /// Extrusion height, m.
        thickness: f64,
        /// Target element size, m.
        element_size: f64,
        /// Number of layers (default: thickness / element_size, rounded).
        layers: Option<usize>,
    },
    /// `kind = "platen"`: a rigid loading platen against the parts before it.
    Platen {
        /// Part name (default: the region name).
        name: Option<String>,
        /// Region of its tets.
        region: String,
        /// Side of the specimen: `"+x"`, `"-x"`, `"+y"`, `"-y"`, `"+z"`, `"-z"`.
        side: String,
        /// Thickness along the side's normal, m.
        thickness: f64,
        /// Extent along the two other axes in axis order, m (default: the
        /// specimen's extent).
        extent: Option<[f64; 2]>,
        /// Target element size, m.
        element_size: f64,
    },
    /// `kind = "msh"`: a Gmsh MSH 4.1 or 2.2 file, ASCII or binary.
    Msh {
        /// Part name (default: the file stem).
        name: Option<String>,
        /// Path, relative to the case file.
        path: String,
        /// Factor on the file's coordinates, to metres (1e-3 for a file in
        /// millimetres; default 1).
        scale: Option<f64>,
        /// Added to the scaled coordinates, m (a file in site coordinates
        /// brought near the origin; default none).
        translate: Option<[f64; 3]>,
    },
}

/// `circle = { center = [x, y], radius = r }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CircleSpec {
    /// Centre, m.
    pub center: [f64; 2],
    /// Radius, m.
    pub radius: f64,
}
