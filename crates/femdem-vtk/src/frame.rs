//! What one output step holds: points, tets and the fields on them.
//!
//! A [`Frame`] borrows everything; building one costs nothing, and writing
//! it copies the data once into the encoder.

use std::collections::HashSet;
use std::fmt;

use crate::VtkError;

/// Whether a field lives on points or on cells (tets).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Location {
    /// One tuple per point (VTK `PointData`).
    Point,
    /// One tuple per tet (VTK `CellData`).
    Cell,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Location::Point => "point",
            Location::Cell => "cell",
        })
    }
}

/// A named array of `components` values per point or per cell, stored flat:
/// tuple `i` is `values[i * components..(i + 1) * components]`, so
/// `values.len() == components × count`.
///
/// Written as a VTK `Float64` `DataArray` with `NumberOfComponents =
/// components`. Conventions that readers rely on:
///
/// * **scalars**: 1 component;
/// * **vectors** (displacement, velocity, force): 3 components `x, y, z`;
///   a `&[[f64; 3]]` becomes a flat slice with `as_flattened()`;
/// * **tensors** (stress, strain), symmetric or not: all 9 components of the
///   3×3 matrix in row-major order `xx, xy, xz, yx, yy, yz, zx, zy, zz`.
///   ParaView recognises 9-component arrays as tensors (component names
///   `XX … ZZ`, eigenvalue filters, tensor glyphs). Do not pass the 6
///   independent components of a symmetric tensor: VTK's 6-component order
///   (`XX YY ZZ XY YZ XZ`) differs from Voigt notation and is easily
///   misread.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Field<'a> {
    /// Array name shown by ParaView; unique among the frame's point fields
    /// (or cell fields) and not empty.
    pub name: &'a str,
    /// Values per point or cell (at least 1, at most `u32::MAX`).
    pub components: usize,
    /// `components × count` values, tuple after tuple.
    pub values: &'a [f64],
}

impl<'a> Field<'a> {
    /// A field of `components` values per point or cell.
    pub fn new(name: &'a str, components: usize, values: &'a [f64]) -> Self {
        Field { name, components, values }
    }

    /// A scalar field: one value per point or cell.
    pub fn scalar(name: &'a str, values: &'a [f64]) -> Self {
        Field::new(name, 1, values)
    }

    /// A vector field: `x, y, z` per point or cell.
    pub fn vector(name: &'a str, values: &'a [[f64; 3]]) -> Self {
        Field::new(name, 3, values.as_flattened())
    }

    /// A 3×3 tensor field, each tensor as 9 values in row-major order
    /// (`xx, xy, xz, yx, yy, yz, zx, zy, zz`); see the type's documentation.
    pub fn tensor(name: &'a str, values: &'a [[f64; 9]]) -> Self {
        Field::new(name, 9, values.as_flattened())
    }

    /// Checks the field against the number of points or cells it lives on.
    fn validate(&self, location: Location, count: usize) -> Result<(), VtkError> {
        if self.name.is_empty() {
            return Err(VtkError::EmptyFieldName { location });
        }
        if self.components == 0 || u32::try_from(self.components).is_err() {
            return Err(VtkError::BadComponents { location, name: self.name.to_owned() });
        }
        let expected = self.components.checked_mul(count);
        if expected != Some(self.values.len()) {
            return Err(VtkError::FieldLength {
                location,
                name: self.name.to_owned(),
                components: self.components,
                count,
                expected: expected.unwrap_or(usize::MAX),
                actual: self.values.len(),
            });
        }
        Ok(())
    }
}

/// One output step: a mesh of 4-node tets (VTK_TETRA, cell type 10) and the
/// fields on its points and cells.
///
/// The node order of each tet is written as given; VTK expects the fourth
/// node on the side of the first three's right-handed normal (positive
/// volume), which is femdem's convention too.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame<'a> {
    /// Point coordinates.
    pub points: &'a [[f64; 3]],
    /// Tets as four indices into `points` (cells `0..tets.len()`).
    pub tets: &'a [[u32; 4]],
    /// Triangles as three indices into `points`, written after the tets as
    /// VTK_TRIANGLE (5) cells; a fracture surface is a frame of triangles
    /// only.
    pub triangles: &'a [[u32; 3]],
    /// Fields with one tuple per point.
    pub point_fields: &'a [Field<'a>],
    /// Fields with one tuple per tet.
    pub cell_fields: &'a [Field<'a>],
}

impl<'a> Frame<'a> {
    /// A frame with no fields.
    pub fn new(points: &'a [[f64; 3]], tets: &'a [[u32; 4]]) -> Self {
        Frame { points, tets, triangles: &[], point_fields: &[], cell_fields: &[] }
    }

    /// The same frame with these triangles (after the tets).
    pub fn with_triangles(self, triangles: &'a [[u32; 3]]) -> Self {
        Frame { triangles, ..self }
    }

    /// Number of cells: tets then triangles.
    pub fn num_cells(&self) -> usize {
        self.tets.len() + self.triangles.len()
    }

    /// The same frame with these point fields.
    pub fn with_point_fields(self, point_fields: &'a [Field<'a>]) -> Self {
        Frame { point_fields, ..self }
    }

    /// The same frame with these cell fields.
    pub fn with_cell_fields(self, cell_fields: &'a [Field<'a>]) -> Self {
        Frame { cell_fields, ..self }
    }

    /// Checks that every field has `components × count` values, that field
    /// names are non-empty and unique per location, that every tet refers to
    /// an existing point, and that the counts fit a VTU piece (`u32`).
    ///
    /// The writers call this first and write nothing when it fails.
    pub fn validate(&self) -> Result<(), VtkError> {
        let max = u32::MAX as usize;
        if self.points.len() > max {
            return Err(VtkError::TooLarge { what: "points", count: self.points.len(), max });
        }
        if self.num_cells() > max {
            return Err(VtkError::TooLarge { what: "cells", count: self.num_cells(), max });
        }
        let num_points = self.points.len();
        for (tet, nodes) in self.tets.iter().enumerate() {
            if let Some(&node) = nodes.iter().find(|&&n| n as usize >= num_points) {
                return Err(VtkError::NodeOutOfRange { tet, node, num_points });
            }
        }
        for (k, nodes) in self.triangles.iter().enumerate() {
            if let Some(&node) = nodes.iter().find(|&&n| n as usize >= num_points) {
                return Err(VtkError::NodeOutOfRange { tet: self.tets.len() + k, node, num_points });
            }
        }
        check_fields(self.point_fields, Location::Point, num_points)?;
        check_fields(self.cell_fields, Location::Cell, self.num_cells())?;
        Ok(())
    }
}

/// Validates each field and the uniqueness of their names.
fn check_fields(fields: &[Field<'_>], location: Location, count: usize) -> Result<(), VtkError> {
    let mut seen = HashSet::with_capacity(fields.len());
    for field in fields {
        field.validate(location, count)?;
        if !seen.insert(field.name) {
            return Err(VtkError::DuplicateField { location, name: field.name.to_owned() });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const POINTS: [[f64; 3]; 5] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 1.0]];
    const TETS: [[u32; 4]; 2] = [[0, 1, 2, 3], [1, 2, 3, 4]];

    #[test]
    fn valid_frame_with_fields_passes() {
        let disp = [[0.5; 3]; 5];
        let stress = [[1.0; 9]; 2];
        let region = [0.0, 1.0];
        let pf = [Field::vector("displacement", &disp)];
        let cf = [Field::tensor("stress", &stress), Field::scalar("region", &region)];
        let frame = Frame::new(&POINTS, &TETS).with_point_fields(&pf).with_cell_fields(&cf);
        frame.validate().unwrap();
    }

    #[test]
    fn empty_frame_is_valid() {
        Frame::new(&[], &[]).validate().unwrap();
    }

    #[test]
    fn point_field_of_wrong_length_is_rejected() {
        let values = [0.0; 14];
        let pf = [Field::new("displacement", 3, &values)];
        let err = Frame::new(&POINTS, &TETS).with_point_fields(&pf).validate().unwrap_err();
        match err {
            VtkError::FieldLength { location, expected, actual, count, .. } => {
                assert_eq!(location, Location::Point);
                assert_eq!((expected, actual, count), (15, 14, 5));
            }
            other => panic!("unexpected error {other}"),
        }
    }

    #[test]
    fn cell_field_sized_for_points_is_rejected() {
        let values = [0.0; 5];
        let cf = [Field::scalar("region", &values)];
        let err = Frame::new(&POINTS, &TETS).with_cell_fields(&cf).validate().unwrap_err();
        assert!(matches!(err, VtkError::FieldLength { location: Location::Cell, expected: 2, actual: 5, .. }), "{err}");
        assert!(err.to_string().contains("cell field `region`"), "{err}");
    }

    #[test]
    fn zero_components_are_rejected_even_with_no_values() {
        let pf = [Field::new("nothing", 0, &[])];
        let err = Frame::new(&POINTS, &TETS).with_point_fields(&pf).validate().unwrap_err();
        assert!(matches!(err, VtkError::BadComponents { .. }), "{err}");
    }

    #[test]
    fn empty_and_duplicate_names_are_rejected() {
        let v = [0.0; 2];
        let cf = [Field::scalar("", &v)];
        let err = Frame::new(&POINTS, &TETS).with_cell_fields(&cf).validate().unwrap_err();
        assert!(matches!(err, VtkError::EmptyFieldName { .. }), "{err}");

        let cf = [Field::scalar("a", &v), Field::scalar("a", &v)];
        let err = Frame::new(&POINTS, &TETS).with_cell_fields(&cf).validate().unwrap_err();
        assert!(matches!(err, VtkError::DuplicateField { .. }), "{err}");
    }

    #[test]
    fn same_name_on_points_and_cells_is_allowed() {
        let pv = [0.0; 5];
        let cv = [0.0; 2];
        let pf = [Field::scalar("damage", &pv)];
        let cf = [Field::scalar("damage", &cv)];
        Frame::new(&POINTS, &TETS).with_point_fields(&pf).with_cell_fields(&cf).validate().unwrap();
    }

    #[test]
    fn tet_with_missing_node_is_rejected() {
        let tets = [[0, 1, 2, 3], [1, 2, 5, 4]];
        let err = Frame::new(&POINTS, &tets).validate().unwrap_err();
        match err {
            VtkError::NodeOutOfRange { tet, node, num_points } => assert_eq!((tet, node, num_points), (1, 5, 5)),
            other => panic!("unexpected error {other}"),
        }
    }

    #[test]
    fn oversized_component_counts_are_rejected() {
        let pf = [Field::new("x", usize::MAX, &[])];
        let err = Frame::new(&POINTS, &TETS).with_point_fields(&pf).validate().unwrap_err();
        assert!(matches!(err, VtkError::BadComponents { .. }), "{err}");

        let pf = [Field::new("x", u32::MAX as usize, &[])];
        let err = Frame::new(&POINTS, &TETS).with_point_fields(&pf).validate().unwrap_err();
        assert!(matches!(err, VtkError::FieldLength { .. }), "{err}");
    }
}
