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
    /// Reads `path`, skipping the comment lines (`#`) before the header
    /// (`history.csv` names its case there); an empty body gives a table
    /// with no rows.
    pub fn read(path: &Path) -> Result<Table> {
        let text = std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        let mut lines = text.lines().enumerate().skip_while(|(_, l)| l.starts_with('#'));
        let (_, header) = lines.next().with_context(|| format!("{}: no header line", path.display()))?;
        let columns: Vec<String> = header.split(',').map(|c| c.trim().to_owned()).collect();
        let mut rows = Vec::new();
        for (i, line) in lines.filter(|(_, l)| !l.trim().is_empty()) {
            let row = line
                .split(',')
                .map(|v| v.trim().parse::<f64>())
                .collect::<Result<Vec<f64>, _>>()
                .with_context(|| format!("{}:{}: not a row of numbers", path.display(), i + 1))?;
            if row.len() != columns.len() {
                bail!("{}:{}: {} values for {} columns", path.display(), i + 1, row.len(), columns.len());
            }
            rows.push(row);
        }
        Ok(Table { columns, rows })
    }

    /// The column names, in order.
    pub fn names(&self) -> &[String] {
        &self.columns
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_history_is_read_past_its_comment_lines_with_file_line_numbers() {
        let path = std::env::temp_dir().join(format!("xtask-history-{}.csv", std::process::id()));
        std::fs::write(&path, "# case: disc.toml\n# title: a disc\ntime,load\n0,1\n1e-6,2.5\n").unwrap();
        let t = Table::read(&path).unwrap();
        assert_eq!(t.len(), 2);
        assert_eq!(t.col("load").unwrap(), [1.0, 2.5]);
        std::fs::write(&path, "time,load\n0,1\n1e-6\n").unwrap();
        let err = Table::read(&path).unwrap_err().to_string();
        assert!(err.ends_with(":3: 1 values for 2 columns"), "{err}");
        std::fs::remove_file(&path).unwrap();
    }
}
