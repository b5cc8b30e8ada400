//! The static description of a simulation: reference geometry, lumped
//! masses, element properties and the node-to-slot gather tables.

use femdem_core::{Real, Vec3};
use femdem_fracture::heterogeneity::{Distribution, strength_factors};
use femdem_fracture::{Joint, JointParams};
use femdem_material::{Law, Material, TetReference};
use femdem_mesh::JointedMesh;

use crate::SolverError;

/// How the tets of one region behave.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RegionBehaviour {
    /// Deformable: stress from `law` with `material`; joints (if the region
    /// is breakable) follow `joints`.
    Deformable {
        /// Constitutive law (Eq. 1 or small-strain linear).
        law: Law,
        /// Validated material.
        material: Material,
        /// Joint parameters for the joints of a breakable region.
        joints: Option<JointParams>,
    },
    /// Rigid: no stress, no mass; its nodes must be moved by a velocity
    /// drive (a platen).
    Rigid,
}

/// What a tet is made of ([`Model::tet_material`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TetMaterial {
    /// A rigid tet: no stress, no mass (a platen's).
    Rigid,
    /// A deformable tet of [`Model::materials`]`[i]`.
    Deformable(u16),
}

impl TetMaterial {
    /// The index into [`Model::materials`]; `None` for a rigid tet.
    #[inline]
    pub fn index(self) -> Option<usize> {
        match self {
            TetMaterial::Rigid => None,
            TetMaterial::Deformable(i) => Some(i as usize),
        }
    }

    /// Whether the tet is rigid.
    #[inline]
    pub fn is_rigid(self) -> bool {
        self == TetMaterial::Rigid
    }
}

/// Node-to-slot table in compressed rows: the slots of node `i` are
/// `slots[offsets[i]..offsets[i + 1]]`, in increasing slot order, so sums
/// over them are taken in a fixed order whatever the thread count.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Gather {
    /// Row offsets, one more than the node count.
    pub offsets: Vec<u32>,
    /// Slot ids.
    pub slots: Vec<u32>,
}

impl Gather {
    fn build(num_nodes: usize, entries: impl Iterator<Item = (u32, u32)> + Clone) -> Gather {
        let mut offsets = vec![0u32; num_nodes + 1];
        for (node, _) in entries.clone() {
            offsets[node as usize + 1] += 1;
        }
        for i in 0..num_nodes {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut slots = vec![0u32; offsets[num_nodes] as usize];
        for (node, slot) in entries {
            slots[fill[node as usize] as usize] = slot;
            fill[node as usize] += 1;
        }
        Gather { offsets, slots }
    }

    /// The slots of node `i`.
    #[inline]
    pub fn of(&self, i: usize) -> &[u32] {
        &self.slots[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }
}

/// A model ready to integrate. Units SI.
#[derive(Clone, Debug)]
pub struct Model {
    /// Reference (initial) node positions.
    pub x0: Vec<Vec3>,
    /// Lumped nodal masses, kg (zero on rigid nodes), after mass scaling.
    pub mass: Vec<Real>,
    /// Tet connectivity.
    pub tets: Vec<[u32; 4]>,
    /// Region of each tet.
    pub tet_region: Vec<u16>,
    /// Reference shape data of each tet (inverse edge matrix, volume).
    pub tet_ref: Vec<TetReference>,
    /// What each tet is made of: an index into [`Model::materials`], or rigid.
    pub tet_material: Vec<TetMaterial>,
    /// Distinct (law, material) pairs.
    pub materials: Vec<(Law, Material)>,
    /// Joint connectivity `[N1 … N6]`.
    pub joints: Vec<[u32; 6]>,
    /// Law, parameters and reference size of each joint.
    pub joint_law: Vec<Joint>,
    /// The tets on either side of each joint (`N1 N2 N3` side first).
    pub joint_tets: Vec<[u32; 2]>,
    /// Node → tet slots (`tet * 4 + local`).
    pub tet_gather: Gather,
    /// Node → joint slots (`joint * 6 + k`).
    pub joint_gather: Gather,
    /// Nodes of rigid tets.
    pub rigid_node: Vec<bool>,
    /// For each node, the vertex of the unsplit mesh it came from.
    pub origin: Vec<u32>,
    /// The mass-scaling factor applied (1 = none).
    pub mass_scaling: Real,
}

impl Model {
    /// Builds the model of a jointed mesh. `behaviour[r]` says how region
    /// `r` behaves. `mass_scaling ≥ 1` multiplies every nodal mass: it
    /// lengthens the stable time step by `√mass_scaling` at the price of
    /// inertia (a knob for quasi-static runs; 1 is exact dynamics). Gravity
    /// acts on the physical mass, `mass / mass_scaling`, so a body's weight
    /// does not change with the factor.
    ///
    /// Joints take the parameters of their breakable side; where both sides
    /// are breakable with different parameters, those of the weaker side
    /// (lower tensile strength).
    ///
    /// # Errors
    /// [`SolverError::RegionCount`], [`SolverError::MissingJointParams`],
    /// [`SolverError::InvertedTet`], [`SolverError::UnbreakableJoint`] or
    /// [`SolverError::MassScaling`].
    pub fn new(mesh: &JointedMesh, behaviour: &[RegionBehaviour], mass_scaling: Real) -> Result<Model, SolverError> {
        let m = &mesh.mesh;
        if behaviour.len() != m.regions.len() {
            return Err(SolverError::RegionCount { regions: m.regions.len(), behaviours: behaviour.len() });
        }
        if !(mass_scaling.is_finite() && mass_scaling >= 1.0) {
            return Err(SolverError::MassScaling(mass_scaling));
        }
        let x0: Vec<Vec3> = m.coords.iter().map(|c| Vec3::new(c[0], c[1], c[2])).collect();
        let mut materials: Vec<(Law, Material)> = Vec::new();
        let mut region_material = Vec::with_capacity(behaviour.len());
        for (r, b) in behaviour.iter().enumerate() {
            match b {
                RegionBehaviour::Deformable { law, material, joints } => {
                    if m.regions[r].breakable && joints.is_none() {
                        return Err(SolverError::MissingJointParams(m.regions[r].name.clone()));
                    }
                    let idx = materials.iter().position(|q| q == &(*law, *material)).unwrap_or_else(|| {
                        materials.push((*law, *material));
                        materials.len() - 1
                    });
                    region_material.push(TetMaterial::Deformable(idx as u16));
                }
                RegionBehaviour::Rigid => region_material.push(TetMaterial::Rigid),
            }
        }
        let mut mass = vec![0.0; x0.len()];
        let mut rigid_node = vec![false; x0.len()];
        let mut tet_ref = Vec::with_capacity(m.tets.len());
        let mut tet_material = Vec::with_capacity(m.tets.len());
        for (t, tet) in m.tets.iter().enumerate() {
            let p = tet.map(|n| x0[n as usize]);
            let reference = TetReference::new(&p).ok_or(SolverError::InvertedTet(t))?;
            let mat = region_material[m.tet_region[t] as usize];
            if let Some(i) = mat.index() {
                let share = materials[i].1.density() * reference.volume * mass_scaling / 4.0;
                for &n in tet {
                    mass[n as usize] += share;
                }
            } else {
                for &n in tet {
                    rigid_node[n as usize] = true;
                }
            }
            tet_ref.push(reference);
            tet_material.push(mat);
        }
        let joint_params = |t: u32| match behaviour[m.tet_region[t as usize] as usize] {
            RegionBehaviour::Deformable { joints, .. } if m.regions[m.tet_region[t as usize] as usize].breakable => {
                joints
            }
            _ => None,
        };
        let mut joint_law = Vec::with_capacity(mesh.joints.len());
        for (j, (jn, (fa, fb))) in mesh.joints.iter().zip(&mesh.joint_faces).enumerate() {
            let params = match (joint_params(fa.tet), joint_params(fb.tet)) {
                (Some(a), Some(b)) => {
                    if b.tensile_strength < a.tensile_strength {
                        b
                    } else {
                        a
                    }
                }
                (Some(a), None) | (None, Some(a)) => a,
                (None, None) => {
                    return Err(SolverError::UnbreakableJoint(j));
                }
            };
            let p = [jn[0], jn[1], jn[2]].map(|n| x0[n as usize]);
            let h = ((p[1] - p[0]).norm() + (p[2] - p[1]).norm() + (p[0] - p[2]).norm()) / 3.0;
            joint_law.push(Joint::new(params, h));
        }
        let n = x0.len();
        let tet_gather = Gather::build(
            n,
            m.tets.iter().enumerate().flat_map(|(t, tet)| (0..4).map(move |k| (tet[k], (t * 4 + k) as u32))),
        );
        let joint_gather = Gather::build(
            n,
            mesh.joints.iter().enumerate().flat_map(|(j, jn)| (0..6).map(move |k| (jn[k], (j * 6 + k) as u32))),
        );
        Ok(Model {
            x0,
            mass,
            tets: m.tets.clone(),
            tet_region: m.tet_region.clone(),
            tet_ref,
            tet_material,
            materials,
            joints: mesh.joints.clone(),
            joint_law,
            joint_tets: mesh.joint_faces.iter().map(|(a, b)| [a.tet, b.tet]).collect(),
            tet_gather,
            joint_gather,
            rigid_node,
            origin: mesh.origin.clone(),
            mass_scaling,
        })
    }

    /// Makes the joints' tensile strength and cohesion heterogeneous: each
    /// is multiplied by an independent factor of mean 1 drawn from `dist`
    /// (streams `seed` for `f_t` and `seed + 1` for `c`), and the derived
    /// quantities are recomputed.
    ///
    /// # Errors
    /// [`SolverError::Heterogeneity`] for a bad distribution parameter.
    pub fn randomise_strengths(&mut self, dist: Distribution, seed: u64) -> Result<(), SolverError> {
        let n = self.joint_law.len();
        let ft = strength_factors(n, dist, seed).map_err(SolverError::Heterogeneity)?;
        let c = strength_factors(n, dist, seed.wrapping_add(1)).map_err(SolverError::Heterogeneity)?;
        for (j, joint) in self.joint_law.iter_mut().enumerate() {
            let mut p = joint.params;
            p.tensile_strength *= ft[j];
            p.cohesion *= c[j];
            *joint = Joint::new(p, joint.h);
        }
        Ok(())
    }

    /// Whether each tet has a face on the outer surface of its body (a face
    /// no other tet shares, joints and pre-existing fractures not counting
    /// as surface): found from the faces' original vertices.
    pub fn surface_tets(&self) -> Vec<bool> {
        let mut keys: Vec<(u128, u32)> = Vec::with_capacity(self.tets.len() * 4);
        for (t, tet) in self.tets.iter().enumerate() {
            for face in femdem_core::tet::FACES {
                let v = face.map(|k| self.origin[tet[k] as usize]);
                keys.push((femdem_mesh::faces::face_key(v), t as u32));
            }
        }
        keys.sort_unstable();
        let mut out = vec![false; self.tets.len()];
        let mut i = 0;
        while i < keys.len() {
            let mut j = i + 1;
            while j < keys.len() && keys[j].0 == keys[i].0 {
                j += 1;
            }
            if j - i == 1 {
                out[keys[i].1 as usize] = true;
            }
            i = j;
        }
        out
    }

    /// Number of nodes.
    pub fn num_nodes(&self) -> usize {
        self.x0.len()
    }

    /// Number of deformable tets (the ones that cost a stress evaluation).
    pub fn num_deformable_tets(&self) -> usize {
        self.tet_material.iter().filter(|m| !m.is_rigid()).count()
    }
}
