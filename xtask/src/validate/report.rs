//! The validation report: one row per check, written as a Markdown table
//! (`report.md`) and as CSV (`checks.csv`).

use std::fmt::Write as _;
use std::path::Path;

use anyhow::Result;

/// How a row counts towards the exit status.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A check: a failure makes `cargo xtask validate` exit non-zero.
    Gate,
    /// A comparison reported with its measured value and the tolerance
    /// it is held to in another profile, without deciding the exit status
    /// here (the report says why).
    Info,
}

/// One row of the report.
#[derive(Debug, Clone)]
pub struct Check {
    /// The case, e.g. `brazilian`.
    pub case: String,
    /// What is measured, with its unit.
    pub metric: String,
    /// The paper's value or the closed form, as text.
    pub reference: String,
    /// femdem's value, as text.
    pub value: String,
    /// The tolerance, as text.
    pub tolerance: String,
    /// Whether the value is within the tolerance.
    pub pass: bool,
    /// Whether the row gates the exit status.
    pub kind: Kind,
}

/// The whole report of one `cargo xtask validate`.
#[derive(Debug, Default)]
pub struct Report {
    /// The checks, in order.
    pub checks: Vec<Check>,
    /// Markdown sections after the table (figures, run times, notes).
    pub sections: Vec<String>,
}

impl Report {
    /// Adds a row.
    #[allow(clippy::too_many_arguments)]
    pub fn check(
        &mut self,
        case: &str,
        metric: &str,
        reference: String,
        value: String,
        tolerance: &str,
        pass: bool,
        kind: Kind,
    ) {
        self.checks.push(Check {
            case: case.into(),
            metric: metric.into(),
            reference,
            value,
            tolerance: tolerance.into(),
            pass,
            kind,
        });
    }

    /// The gating checks that failed.
    pub fn failures(&self) -> impl Iterator<Item = &Check> {
        self.checks.iter().filter(|c| c.kind == Kind::Gate && !c.pass)
    }

    /// Writes `report.md` and `checks.csv` into `dir`.
    pub fn write(&self, dir: &Path, title: &str) -> Result<()> {
        let mut md = format!("# {title}\n\n");
        md.push_str("| case | metric | reference | femdem | tolerance | result |\n|---|---|---|---|---|---|\n");
        let mut csv = String::from("case,metric,reference,femdem,tolerance,pass,gate\n");
        for c in &self.checks {
            let result = match (c.kind, c.pass) {
                (Kind::Gate, true) => "pass",
                (Kind::Gate, false) => "**FAIL**",
                (Kind::Info, true) => "within (not gated)",
                (Kind::Info, false) => "outside (not gated)",
            };
            let _ = writeln!(
                md,
                "| {} | {} | {} | {} | {} | {} |",
                c.case, c.metric, c.reference, c.value, c.tolerance, result
            );
            let q = |s: &str| format!("\"{}\"", s.replace('"', "\"\""));
            let _ = writeln!(
                csv,
                "{},{},{},{},{},{},{}",
                q(&c.case),
                q(&c.metric),
                q(&c.reference),
                q(&c.value),
                q(&c.tolerance),
                c.pass,
                c.kind == Kind::Gate
            );
        }
        for s in &self.sections {
            md.push('\n');
            md.push_str(s);
            md.push('\n');
        }
        std::fs::write(dir.join("report.md"), md)?;
        std::fs::write(dir.join("checks.csv"), csv)?;
        Ok(())
    }
}
