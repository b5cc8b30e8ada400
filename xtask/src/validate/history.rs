//! The CSV files `femdem run` writes (`history.csv`, `failures.csv`), read
//! as named columns of numbers.

use std::path::Path;

use anyhow::{Context, Result, bail};

/// A CSV file of numbers with a header row.
#[derive(Debug, Clone)]
pub struct Table {
    columns: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl Table {
    /// Reads `path`; an empty body gives a table with no rows.
    pub fn read(path: &Path) -> Result<Table> {
        let text = std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        let mut lines = text.lines();
        let header = lines.next().with_context(|| format!("{}: empty file", path.display()))?;
        let columns: Vec<String> = header.split(',').map(|c| c.trim().to_owned()).collect();
        let mut rows = Vec::new();
        for (i, line) in lines.enumerate().filter(|(_, l)| !l.trim().is_empty()) {
            let row = line
                .split(',')
                .map(|v| v.trim().parse::<f64>())
                .collect::<Result<Vec<f64>, _>>()
                .with_context(|| format!("{}:{}: not a row of numbers", path.display(), i + 2))?;
            if row.len() != columns.len() {
                bail!("{}:{}: {} values for {} columns", path.display(), i + 2, row.len(), columns.len());
            }
            rows.push(row);
        }
        Ok(Table { columns, rows })
    }

    /// The column `name`.
    pub fn col(&self, name: &str) -> Result<Vec<f64>> {
        let i = self.columns.iter().position(|c| c == name).with_context(|| format!("no column `{name}`"))?;
        Ok(self.rows.iter().map(|r| r[i]).collect())
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// The largest |balance| / external work over the rows once the work
    /// has reached 10% of its final value (earlier, both are tiny and their
    /// ratio is noise): the run's energy-balance error.
    pub fn energy_error(&self) -> Result<f64> {
        let (work, balance) = (self.col("external_work")?, self.col("balance")?);
        let w_end = work.last().copied().unwrap_or(0.0);
        Ok(work
            .iter()
            .zip(&balance)
            .filter(|(w, _)| **w >= 0.1 * w_end && **w > 0.0)
            .map(|(w, b)| b.abs() / w)
            .fold(0.0, f64::max))
    }
}
