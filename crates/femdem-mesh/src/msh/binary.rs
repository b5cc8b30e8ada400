//! The [`Source`] of a binary MSH file (4.1, and 2 through its `int` and
//! `double` values only): the values of `$Entities`,
//! `$Nodes` and `$Elements` as raw `int` (4 bytes), `size_t` (the header's
//! data size: 4 or 8 bytes) and `double` (8 bytes), in the byte order the
//! header's integer 1 shows.
//!
//! Gmsh writes a binary file in the byte order of the machine that wrote
//! it: `$MeshFormat` holds `4.1 1 <data size>` on a line, then the `int` 1
//! in binary, so a reader tells little- from big-endian files. The section
//! headers, the `$End` lines and `$PhysicalNames` stay text; the binary
//! data of a section starts right after its header's line break and is
//! followed by one line break before its `$End` line.
//!
//! Every error has the byte offset of the value that is wrong, or of the
//! end of the file when it ends too soon, and names the section.

use super::lex::Lines;
use super::report::{element_type_name, element_type_nodes};
use super::source::{At, Source};
use crate::MeshError;

/// Byte order of a binary file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Endian {
    Little,
    Big,
}

impl Endian {
    /// The byte order in which `bytes` hold the `int` 1, if either does.
    pub(super) fn of_one(bytes: [u8; 4]) -> Option<Endian> {
        if u32::from_le_bytes(bytes) == 1 {
            Some(Endian::Little)
        } else if u32::from_be_bytes(bytes) == 1 {
            Some(Endian::Big)
        } else {
            None
        }
    }
}

/// A binary MSH file past its `$MeshFormat` header.
pub(super) struct Binary<'a> {
    lines: Lines<'a>,
    endian: Endian,
    /// Bytes of a `size_t`: 4 or 8.
    size_t: usize,
    /// The section being read.
    section: &'static str,
    /// Offset of the current record.
    record_at: usize,
    /// Offset of the value last read.
    value_at: usize,
}

impl<'a> Binary<'a> {
    /// Reads the rest of a file whose text so far is `lines`, in byte
    /// order `endian` with `size_t` of `size_t` bytes (4 or 8).
    pub(super) fn new(mut lines: Lines<'a>, endian: Endian, size_t: usize) -> Self {
        debug_assert!(size_t == 4 || size_t == 8);
        lines.bytes_mode();
        let at = lines.offset();
        Binary { lines, endian, size_t, section: "", record_at: at, value_at: at }
    }

    /// The next `N` bytes, the value `name`.
    fn take<const N: usize>(&mut self, name: &str) -> Result<[u8; N], MeshError> {
        self.value_at = self.lines.offset();
        match self.lines.take(N) {
            Some(b) => Ok(b.try_into().expect("N bytes")),
            None => Err(self.truncated(name, N)),
        }
    }

    fn truncated(&self, name: &str, needed: usize) -> MeshError {
        let left = self.lines.left();
        At::Byte(self.value_at).err(
            self.section,
            format!(
                "file ends inside ${}: the {name} needs {needed} bytes, {left} are left (a truncated file?)",
                self.section
            ),
        )
    }

    fn u32(&mut self, name: &str) -> Result<u32, MeshError> {
        let b = self.take::<4>(name)?;
        Ok(match self.endian {
            Endian::Little => u32::from_le_bytes(b),
            Endian::Big => u32::from_be_bytes(b),
        })
    }

    /// A `size_t`.
    fn size(&mut self, name: &str) -> Result<u64, MeshError> {
        if self.size_t == 4 {
            return self.u32(name).map(u64::from);
        }
        let b = self.take::<8>(name)?;
        Ok(match self.endian {
            Endian::Little => u64::from_le_bytes(b),
            Endian::Big => u64::from_be_bytes(b),
        })
    }
}

impl<'a> Source<'a> for Binary<'a> {
    fn lines(&mut self) -> &mut Lines<'a> {
        &mut self.lines
    }

    fn record(&mut self, section: &'static str, _what: impl FnOnce() -> String) -> Result<(), MeshError> {
        self.section = section;
        self.record_at = self.lines.offset();
        self.value_at = self.record_at;
        Ok(())
    }

    fn at(&self) -> At {
        At::Byte(self.record_at)
    }

    fn err(&self, message: impl Into<String>) -> MeshError {
        At::Byte(self.value_at).err(self.section, message)
    }

    fn count(&mut self, name: &str) -> Result<usize, MeshError> {
        let n = self.size(name)?;
        usize::try_from(n).map_err(|_| self.err(format!("bad {name} {n}: more than this machine can address")))
    }

    fn int(&mut self, name: &str) -> Result<i32, MeshError> {
        self.u32(name).map(|v| v as i32)
    }

    fn uint(&mut self, name: &str) -> Result<u32, MeshError> {
        let v = self.int(name)?;
        u32::try_from(v).map_err(|_| self.err(format!("bad {name} {v}: expected a non-negative integer")))
    }

    fn node_tag(&mut self, name: &str) -> Result<u64, MeshError> {
        let tag = self.size(name)?;
        if tag == 0 {
            return Err(self.err(format!("bad {name} 0: tags start at 1")));
        }
        Ok(tag)
    }

    fn real(&mut self, name: &str) -> Result<f64, MeshError> {
        let b = self.take::<8>(name)?;
        let x = f64::from_bits(match self.endian {
            Endian::Little => u64::from_le_bytes(b),
            Endian::Big => u64::from_be_bytes(b),
        });
        if !x.is_finite() {
            return Err(self.err(format!("bad {name} {x}: expected a finite number")));
        }
        Ok(x)
    }

    fn end(&mut self, _what: &str) -> Result<(), MeshError> {
        Ok(())
    }

    fn fields(&self) -> Option<usize> {
        None
    }

    fn skip_element_nodes(&mut self, ty: u32) -> Result<(), MeshError> {
        let Some(k) = element_type_nodes(ty) else {
            return Err(self.err(format!(
                "element type {ty} is not one femdem knows, so its node tags cannot be skipped in a binary file; \
                 save the mesh as ASCII (in Gmsh, `Mesh.Binary = 0`) or without these elements"
            )));
        };
        let name = format!("node tags of a {}", element_type_name(ty).unwrap_or("element"));
        for _ in 0..k {
            self.size(&name)?;
        }
        Ok(())
    }

    fn next_at(&mut self, _section: &'static str) -> Result<At, MeshError> {
        Ok(At::Byte(self.lines.offset()))
    }

    fn end_of(&mut self, section: &'static str) -> Result<(), MeshError> {
        self.section = section;
        self.lines.skip_whitespace();
        let at = self.lines.offset();
        let found = match self.lines.next_line(section) {
            Ok(Some(l)) if l.trim() == format!("$End{section}") => return Ok(()),
            Ok(Some(l)) => format!("`{}`", l.trim().chars().take(40).collect::<String>().escape_debug()),
            Ok(None) => {
                return Err(At::Byte(at).err(section, format!("file ends inside ${section}: expected $End{section}")));
            }
            Err(_) => "binary data".to_owned(),
        };
        Err(At::Byte(at).err(
            section,
            format!(
                "expected $End{section} after the data, found {found}: do the counts in the section's \
                 headers match its data?"
            ),
        ))
    }
}
