//! Trace files: fracture maps as plain text (what a case's extrusion part
//! names as its `traces_file`; format in docs/case-format.md, "Trace
//! files"), read here so that the CLI and the validation read a map by
//! the same rules.
//!
//! One polyline per line, `x1 y1 x2 y2 ...` in metres, numbers separated by
//! spaces, tabs or commas; a line ending in `\` goes on on the next line;
//! `#` starts a comment; blank lines are ignored. The geometry (junctions,
//! the outline) is `femdem_mesh::generate::trace_network`'s business; this
//! module only reads numbers and remembers where each point was written,
//! so that an error found later can name the file's line.

/// One polyline of a trace file.
#[derive(Clone, Debug, PartialEq)]
pub struct TracePolyline {
    /// Its points, m.
    pub points: Vec<[f64; 2]>,
    /// For each point, the 1-based line and column of its x coordinate.
    pub at: Vec<(usize, usize)>,
}

/// A malformed trace file, at a 1-based line and column.
#[derive(Clone, Debug, PartialEq)]
pub struct TraceFileError {
    /// 1-based line.
    pub line: usize,
    /// 1-based column (in characters).
    pub column: usize,
    /// What is wrong there.
    pub message: String,
}

fn error(line: usize, column: usize, message: impl Into<String>) -> TraceFileError {
    TraceFileError { line, column, message: message.into() }
}

/// Parses the text of a trace file.
///
/// # Errors
/// A [`TraceFileError`] at the offending token or polyline for something
/// that is not a finite number, an odd number of coordinates, a polyline
/// of one point, or a zero-length segment (a point repeating the one
/// before it).
pub fn parse_traces(text: &str) -> Result<Vec<TracePolyline>, TraceFileError> {
    let mut out = Vec::new();
    // Numbers of the polyline being read, with their line and column, and
    // the line and column where it started.
    let mut numbers: Vec<(f64, (usize, usize))> = Vec::new();
    let mut start = (0, 0);
    // A byte order mark an editor put first is not part of line 1.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let content = raw.split('#').next().unwrap_or("");
        let trimmed = content.trim_end();
        let (body, continues) = match trimmed.strip_suffix('\\') {
            Some(b) => (b, true),
            None => (trimmed, false),
        };
        let mut chars = body.char_indices().peekable();
        while let Some(&(pos, c)) = chars.peek() {
            if c.is_whitespace() || c == ',' {
                chars.next();
                continue;
            }
            let mut end = pos;
            while let Some(&(p, c)) = chars.peek() {
                if c.is_whitespace() || c == ',' {
                    break;
                }
                end = p + c.len_utf8();
                chars.next();
            }
            let token = &body[pos..end];
            let column = body[..pos].chars().count() + 1;
            let value: f64 = token
                .parse()
                .ok()
                .filter(|v: &f64| v.is_finite())
                .ok_or_else(|| error(line, column, format!("`{token}` is not a finite number (metres)")))?;
            if numbers.is_empty() {
                start = (line, column);
            }
            numbers.push((value, (line, column)));
        }
        if continues || numbers.is_empty() {
            continue;
        }
        out.push(polyline(std::mem::take(&mut numbers), start)?);
    }
    if !numbers.is_empty() {
        out.push(polyline(numbers, start)?);
    }
    Ok(out)
}

fn polyline(numbers: Vec<(f64, (usize, usize))>, start: (usize, usize)) -> Result<TracePolyline, TraceFileError> {
    if numbers.len() % 2 == 1 {
        return Err(error(
            start.0,
            start.1,
            format!("{} coordinates: a polyline is x1 y1 x2 y2 ..., an even count", numbers.len()),
        ));
    }
    if numbers.len() < 4 {
        return Err(error(start.0, start.1, "a polyline needs at least 2 points, got 1"));
    }
    let points: Vec<[f64; 2]> = numbers.chunks(2).map(|c| [c[0].0, c[1].0]).collect();
    let at: Vec<(usize, usize)> = numbers.chunks(2).map(|c| c[0].1).collect();
    for k in 1..points.len() {
        if points[k] == points[k - 1] {
            return Err(error(
                at[k].0,
                at[k].1,
                format!(
                    "zero-length segment: point {} ({}, {}) repeats the point before it",
                    k + 1,
                    points[k][0],
                    points[k][1]
                ),
            ));
        }
    }
    Ok(TracePolyline { points, at })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polylines_comments_commas_and_continuations_are_read() {
        let text = "# a map\n\n0 0 1 1   # first\n0.5, 0.2, 0.5, 0.8 \\\n  0.7 0.9\n";
        let t = parse_traces(text).unwrap();
        assert_eq!(t.len(), 2);
        assert_eq!(t[0].points, vec![[0.0, 0.0], [1.0, 1.0]]);
        assert_eq!(t[1].points, vec![[0.5, 0.2], [0.5, 0.8], [0.7, 0.9]]);
        assert_eq!(t[1].at, vec![(4, 1), (4, 11), (5, 3)]);
    }

    #[test]
    fn a_byte_order_mark_is_not_part_of_the_first_line() {
        let t = parse_traces("\u{feff}0 0 1 1\n").unwrap();
        assert_eq!(t[0].points, vec![[0.0, 0.0], [1.0, 1.0]]);
        assert_eq!(t[0].at[0], (1, 1));
        assert_eq!(parse_traces("\u{feff}0 0 x 1\n").unwrap_err(), error(1, 5, "`x` is not a finite number (metres)"));
    }

    #[test]
    fn bad_tokens_and_counts_are_located() {
        assert_eq!(parse_traces("0 0 1 1\n0 0 x 1\n").unwrap_err(), error(2, 5, "`x` is not a finite number (metres)"));
        assert_eq!(parse_traces("0 0 nan 1\n").unwrap_err().column, 5);
        assert_eq!(parse_traces("\n 0 0 1\n").unwrap_err().line, 2);
        assert!(parse_traces("0 0\n").unwrap_err().message.contains("at least 2 points"));
        assert_eq!(parse_traces("0 0 1 1 1 1\n").unwrap_err().column, 9);
    }
}
