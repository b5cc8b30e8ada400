//! What `femdem run` writes: VTU frames with a PVD series, and the CSV
//! history of energies and recorded forces.

use std::path::Path;

use anyhow::{Result, bail};
use femdem_material::{principal_stresses, von_mises};
use femdem_solver::Solver;
use femdem_vtk::{Field, Frame, HistoryWriter, SeriesWriter};

/// Fields a case may ask for.
pub const FIELDS: [&str; 6] = [
    "displacement",
    "velocity",
    "stress",
    "principal_stress",
    "von_mises",
    "region",
];

/// The run's writers.
pub struct Output {
    series: SeriesWriter,
    history: HistoryWriter,
    fields: Vec<String>,
}

impl Output {
    /// Creates the writers in `dir`; `fields` are checked against
    /// [`FIELDS`].
    pub fn create(dir: &Path, stem: &str, fields: Vec<String>, solver: &Solver) -> Result<Output> {
        for f in &fields {
            if !FIELDS.contains(&f.as_str()) {
                bail!("output.fields: `{f}` is not one of {}", FIELDS.join(", "));
            }
        }
        let series = SeriesWriter::new(dir, stem)?;
        let mut columns: Vec<String> = [
            "time",
            "step",
            "kinetic",
            "tet_elastic",
            "joint_elastic",
            "damping",
            "external_work",
            "balance",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        for d in &solver.loads.drives {
            columns.extend(["fx", "fy", "fz"].map(|c| format!("{}_{c}", d.name)));
        }
        for s in &solver.loads.surfaces {
            columns.extend(["fx", "fy", "fz"].map(|c| format!("{}_{c}", s.name)));
        }
        let names: Vec<&str> = columns.iter().map(String::as_str).collect();
        let history = HistoryWriter::create(&dir.join("history.csv"), &names)?;
        Ok(Output {
            series,
            history,
            fields,
        })
    }

    /// Appends a history row for time `t` (the state the last step's
    /// energies and forces belong to).
    pub fn history_row(&mut self, solver: &Solver, t: f64, step: u64) -> Result<()> {
        let e = &solver.energies;
        let mut row = vec![
            t,
            step as f64,
            e.kinetic,
            e.tet_elastic,
            e.joint_elastic,
            e.damping,
            e.external_work,
            e.balance(),
        ];
        for f in solver
            .report
            .drive_forces
            .iter()
            .chain(&solver.report.surface_forces)
        {
            row.extend([f.x, f.y, f.z]);
        }
        self.history.row(&row)?;
        Ok(())
    }

    /// Writes the frame of time `t`: positions `x_n = x_{n+1} − Δt v_{n+½}`
    /// (the state the stresses of the last step belong to), velocities
    /// `v_{n+½}`, and the tet fields.
    pub fn frame(&mut self, solver: &Solver, t: f64) -> Result<()> {
        let s = &solver.state;
        let m = &solver.model;
        let points: Vec<[f64; 3]> =
            s.x.iter()
                .zip(&s.v)
                .map(|(x, v)| (x - v * solver.dt).into())
                .collect();
        let disp: Vec<[f64; 3]> = points
            .iter()
            .zip(&m.x0)
            .map(|(p, x0)| [p[0] - x0.x, p[1] - x0.y, p[2] - x0.z])
            .collect();
        let vel: Vec<[f64; 3]> = s.v.iter().map(|v| (*v).into()).collect();
        let stress: Vec<[f64; 9]> = solver
            .workspace
            .stress
            .iter()
            .map(|m| {
                let mut a = [0.0; 9];
                for r in 0..3 {
                    for c in 0..3 {
                        a[3 * r + c] = m[(r, c)];
                    }
                }
                a
            })
            .collect();
        let principal: Vec<[f64; 3]> = solver
            .workspace
            .stress
            .iter()
            .map(principal_stresses)
            .collect();
        let vm: Vec<f64> = solver.workspace.stress.iter().map(von_mises).collect();
        let region: Vec<f64> = m.tet_region.iter().map(|&r| f64::from(r)).collect();
        let want = |n: &str| self.fields.iter().any(|f| f == n);
        let mut point_fields = Vec::new();
        if want("displacement") {
            point_fields.push(Field::vector("displacement", &disp));
        }
        if want("velocity") {
            point_fields.push(Field::vector("velocity", &vel));
        }
        let mut cell_fields = Vec::new();
        if want("stress") {
            cell_fields.push(Field::tensor("stress", &stress));
        }
        if want("principal_stress") {
            cell_fields.push(Field::vector("principal_stress", &principal));
        }
        if want("von_mises") {
            cell_fields.push(Field::scalar("von_mises", &vm));
        }
        if want("region") {
            cell_fields.push(Field::scalar("region", &region));
        }
        let frame = Frame::new(&points, &m.tets)
            .with_point_fields(&point_fields)
            .with_cell_fields(&cell_fields);
        self.series.write(t, &frame)?;
        Ok(())
    }

    /// Flushes the history.
    pub fn flush(&mut self) -> Result<()> {
        self.history.flush()?;
        Ok(())
    }

    /// The `.pvd` file.
    pub fn pvd(&self) -> std::path::PathBuf {
        self.series.pvd_path()
    }

    /// The history file.
    pub fn history_path(&self) -> &Path {
        self.history.path()
    }
}
