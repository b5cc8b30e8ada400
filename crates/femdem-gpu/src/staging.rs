//! The pool of read-back buffers (host-visible memory a copy from the
//! device lands in): allocating one costs more than the copy, so
//! buffers are kept between read-backs.
//!
//! Small buffers (up to [`SMALL`] bytes) are kept four at a time, the
//! largest; larger ones, two at a time, the last returned. A read-back
//! that recurs every step at model size — the contactable nodes' state,
//! the contact pairs' results of a large model — reuses its buffer (it
//! was made afresh every step before: at 603k tets that was two buffers of
//! 32 and 128 MiB a step), while a one-off (an output frame of every
//! node) holds at most two such buffers until two others replace them.

use std::collections::VecDeque;

/// The largest buffer kept among the small ones, bytes.
pub(crate) const SMALL: u64 = 16 << 20;
/// Small buffers kept (the largest).
const SMALL_KEPT: usize = 4;
/// Large buffers kept (the last returned).
const LARGE_KEPT: usize = 2;

/// Something with a size in bytes: a buffer.
pub(crate) trait Sized64 {
    fn bytes(&self) -> u64;
}

impl Sized64 for wgpu::Buffer {
    fn bytes(&self) -> u64 {
        self.size()
    }
}

/// The kept buffers.
#[derive(Debug)]
pub(crate) struct Pool<B> {
    /// Largest first.
    small: Vec<B>,
    /// Oldest first.
    large: VecDeque<B>,
}

impl<B> Default for Pool<B> {
    fn default() -> Self {
        Pool { small: Vec::new(), large: VecDeque::new() }
    }
}

impl<B: Sized64> Pool<B> {
    /// The smallest kept buffer of at least `bytes` bytes, taken out of the
    /// pool, if any.
    pub fn take(&mut self, bytes: u64) -> Option<B> {
        if let Some(k) = self.small.iter().rposition(|b| b.bytes() >= bytes) {
            return Some(self.small.remove(k));
        }
        let k =
            (0..self.large.len()).filter(|&k| self.large[k].bytes() >= bytes).min_by_key(|&k| self.large[k].bytes())?;
        self.large.remove(k)
    }

    /// Keeps `buffer` (see the module documentation for which are kept).
    pub fn keep(&mut self, buffer: B) {
        if buffer.bytes() > SMALL {
            self.large.push_back(buffer);
            if self.large.len() > LARGE_KEPT {
                self.large.pop_front();
            }
        } else {
            self.small.push(buffer);
            self.small.sort_by_key(|b| std::cmp::Reverse(b.bytes()));
            self.small.truncate(SMALL_KEPT);
        }
    }

    /// Bytes held.
    #[cfg(test)]
    fn held(&self) -> u64 {
        self.small.iter().chain(&self.large).map(Sized64::bytes).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, PartialEq)]
    struct Fake(u64, u32);

    impl Sized64 for Fake {
        fn bytes(&self) -> u64 {
            self.0
        }
    }

    const MIB: u64 = 1 << 20;

    #[test]
    fn a_recurring_large_read_back_reuses_its_buffer() {
        let mut pool = Pool::default();
        // Each step: the watched nodes (128 MiB) and the pairs (32 MiB).
        pool.keep(Fake(128 * MIB, 1));
        pool.keep(Fake(32 * MIB, 2));
        for _ in 0..3 {
            let watched = pool.take(116 * MIB).expect("kept");
            assert_eq!(watched, Fake(128 * MIB, 1));
            let pairs = pool.take(31 * MIB).expect("kept");
            assert_eq!(pairs, Fake(32 * MIB, 2));
            pool.keep(watched);
            pool.keep(pairs);
        }
        assert_eq!(pool.held(), 160 * MIB);
    }

    #[test]
    fn the_smallest_that_fits_is_taken() {
        let mut pool = Pool::default();
        for (k, mib) in [1, 4, 8, 2].into_iter().enumerate() {
            pool.keep(Fake(mib * MIB, k as u32));
        }
        assert_eq!(pool.take(3 * MIB), Some(Fake(4 * MIB, 1)));
        assert_eq!(pool.take(9 * MIB), None);
        pool.keep(Fake(64 * MIB, 7));
        pool.keep(Fake(32 * MIB, 8));
        assert_eq!(pool.take(9 * MIB), Some(Fake(32 * MIB, 8)), "a small request may take a large buffer");
    }

    #[test]
    fn what_is_held_is_bounded() {
        let mut pool = Pool::default();
        for k in 0..10 {
            pool.keep(Fake((k + 1) * MIB, k as u32));
            pool.keep(Fake((k + 20) * MIB, k as u32));
        }
        // Four small (the largest: 7..10 MiB) and the last two large.
        assert_eq!(pool.held(), (7 + 8 + 9 + 10 + 28 + 29) * MIB);
        assert_eq!(pool.take(29 * MIB), Some(Fake(29 * MIB, 9)));
        assert_eq!(pool.take(29 * MIB), None);
    }
}
