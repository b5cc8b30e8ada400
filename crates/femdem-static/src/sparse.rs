//! The assembled stiffness as a sparse symmetric matrix (its lower
//! triangle, compressed by columns), its product with a vector, and the
//! sparse Cholesky factorisation through faer, sequential (`Par::Seq`) so
//! that the result does not depend on the thread count.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky};
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par, Side};
use femdem_core::Real;

use crate::StaticError;

/// Entries `(column, row, value)` with `row ≥ column`, in the order they
/// were added; duplicates are summed in that order.
#[derive(Clone, Debug, Default)]
pub struct Triplets {
    entries: Vec<(u32, u32, Real)>,
}

impl Triplets {
    /// Adds `value` at `(i, j)` of the symmetric matrix (either triangle).
    #[inline]
    pub fn add(&mut self, i: u32, j: u32, value: Real) {
        let (row, col) = if i >= j { (i, j) } else { (j, i) };
        self.entries.push((col, row, value));
    }
}

/// A symmetric `n × n` matrix stored by its lower triangle in compressed
/// columns, rows sorted within each column.
#[derive(Clone, Debug)]
pub struct SymmetricCsc {
    /// Order.
    pub n: usize,
    /// Column starts, `n + 1` of them.
    pub col_ptr: Vec<u32>,
    /// Row of each entry.
    pub row_idx: Vec<u32>,
    /// Value of each entry.
    pub values: Vec<Real>,
}

impl SymmetricCsc {
    /// Compresses `triplets` (a stable sort: duplicates are summed in the
    /// order they were added, so the matrix is the same bit for bit every
    /// time).
    pub fn from_triplets(n: usize, mut triplets: Triplets) -> SymmetricCsc {
        let e = &mut triplets.entries;
        e.sort_by_key(|&(c, r, _)| (c, r));
        let mut col_ptr = vec![0u32; n + 1];
        let mut row_idx = Vec::with_capacity(e.len() / 2);
        let mut values: Vec<Real> = Vec::with_capacity(e.len() / 2);
        let mut last = None;
        for &(c, r, v) in e.iter() {
            if last == Some((c, r)) {
                *values.last_mut().expect("an entry") += v;
            } else {
                row_idx.push(r);
                values.push(v);
                col_ptr[c as usize + 1] += 1;
                last = Some((c, r));
            }
        }
        for j in 0..n {
            col_ptr[j + 1] += col_ptr[j];
        }
        SymmetricCsc { n, col_ptr, row_idx, values }
    }

    /// Entries stored (the lower triangle).
    pub fn nnz(&self) -> usize {
        self.values.len()
    }

    /// The diagonal.
    pub fn diagonal(&self) -> Vec<Real> {
        let mut d = vec![0.0; self.n];
        for (j, dj) in d.iter_mut().enumerate() {
            for k in self.col_ptr[j] as usize..self.col_ptr[j + 1] as usize {
                if self.row_idx[k] as usize == j {
                    *dj = self.values[k];
                }
            }
        }
        d
    }

    /// `y = A x`, sequential.
    pub fn mul(&self, x: &[Real], y: &mut [Real]) {
        y.iter_mut().for_each(|v| *v = 0.0);
        for j in 0..self.n {
            for k in self.col_ptr[j] as usize..self.col_ptr[j + 1] as usize {
                let (i, a) = (self.row_idx[k] as usize, self.values[k]);
                y[i] += a * x[j];
                if i != j {
                    y[j] += a * x[i];
                }
            }
        }
    }

    /// The matrix with `shift[i]` added to its diagonal (every column must
    /// hold its diagonal entry, as a stiffness's does).
    pub fn shifted(&self, shift: &[Real]) -> SymmetricCsc {
        let mut out = self.clone();
        for (j, &s) in shift.iter().enumerate() {
            if s != 0.0 {
                let k = (out.col_ptr[j] as usize..out.col_ptr[j + 1] as usize)
                    .find(|&k| out.row_idx[k] as usize == j)
                    .expect("a stiffness has its diagonal");
                out.values[k] += s;
            }
        }
        out
    }
}

/// A sparse `L Lᵀ` factorisation (AMD ordering, faer's choice of
/// simplicial or supernodal), computed and applied sequentially.
pub struct Cholesky {
    symbolic: SymbolicCholesky<u32>,
    values: Vec<Real>,
}

impl Cholesky {
    /// Factorises `a`.
    ///
    /// # Errors
    /// [`StaticError::Factorisation`] when `a` is not numerically positive
    /// definite or memory runs out.
    pub fn new(a: &SymmetricCsc) -> Result<Cholesky, StaticError> {
        let fail = |reason: String| StaticError::Factorisation { dofs: a.n, reason };
        let symbolic_matrix =
            SymbolicSparseColMat::<u32>::new_checked(a.n, a.n, a.col_ptr.clone(), None, a.row_idx.clone());
        let matrix = SparseColMat::new(symbolic_matrix, a.values.clone());
        let symbolic =
            factorize_symbolic_cholesky(matrix.symbolic(), Side::Lower, SymmetricOrdering::Amd, Default::default())
                .map_err(|e| fail(format!("{e:?}")))?;
        let mut values = Vec::new();
        values.try_reserve_exact(symbolic.len_val()).map_err(|_| fail("out of memory for the factor".into()))?;
        values.resize(symbolic.len_val(), 0.0);
        let mut scratch =
            MemBuffer::try_new(symbolic.factorize_numeric_llt_scratch::<Real>(Par::Seq, Default::default()))
                .map_err(|_| fail("out of memory for the scratch".into()))?;
        symbolic
            .factorize_numeric_llt(
                &mut values,
                matrix.as_ref(),
                Side::Lower,
                LltRegularization::default(),
                Par::Seq,
                MemStack::new(&mut scratch),
                Default::default(),
            )
            .map_err(|e| fail(format!("{e:?}")))?;
        Ok(Cholesky { symbolic, values })
    }

    /// Entries of the factor `L` (its memory is 8 bytes each, plus indices).
    pub fn factor_entries(&self) -> usize {
        self.values.len()
    }

    /// Solves `A x = b` in place.
    pub fn solve_in_place(&self, b: &mut [Real]) {
        let n = b.len();
        let llt = faer::sparse::linalg::cholesky::LltRef::new(&self.symbolic, &self.values);
        let mut scratch = MemBuffer::new(self.symbolic.solve_in_place_scratch::<Real>(1, Par::Seq));
        let rhs = MatMut::from_column_major_slice_mut(b, n, 1);
        llt.solve_in_place_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(&mut scratch));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 1D chain of springs fixed at one end (a tridiagonal SPD matrix):
    /// the factorisation solves it to round-off, and `mul` is the full
    /// symmetric product.
    #[test]
    fn a_spring_chain_is_solved() {
        let n = 50;
        let mut t = Triplets::default();
        for i in 0..n as u32 {
            t.add(i, i, 1.0);
            t.add(i, i, 1.0);
            if i + 1 < n as u32 {
                t.add(i + 1, i, -1.0);
            }
        }
        let a = SymmetricCsc::from_triplets(n, t);
        assert_eq!(a.nnz(), 2 * n - 1);
        let x: Vec<Real> = (0..n).map(|i| (i as Real * 0.3).sin()).collect();
        let mut b = vec![0.0; n];
        a.mul(&x, &mut b);
        let chol = Cholesky::new(&a).unwrap();
        chol.solve_in_place(&mut b);
        let err = x.iter().zip(&b).map(|(p, q)| (p - q).abs()).fold(0.0, Real::max);
        assert!(err < 1e-12, "{err}");
    }
}
