//! A monotone integer priority queue for A* with a consistent heuristic: Dial's bucket queue
//! (R. B. Dial, "Algorithm 360: Shortest-path forest with topological ordering", CACM 1969),
//! circular, with a bitmap of non-empty buckets so finding the next one scans 64 at a time.
//!
//! Valid while every key pushed lies in [last popped, last popped + SPAN).

/// Buckets in the ring: more than the largest rise of f over one A* step.
pub const SPAN: u32 = 1 << 14;
const MASK: u32 = SPAN - 1;
const WORDS: usize = (SPAN / 64) as usize;

/// Min-queue of (key, value) pairs with monotone, bounded-rise keys; among equal keys the
/// latest pushed comes out first.
///
/// Each bucket is a stack threaded through one shared pool of entries, so a push writes
/// at the pool's end and the bucket heads stay small enough to sit in cache.
#[derive(Debug)]
pub struct BucketQueue {
    /// Per bucket, the pool index of its newest entry, or `NONE`.
    heads: Vec<u32>,
    /// (value, pool index of the next entry in the same bucket).
    pool: Vec<(u32, u32)>,
    occupied: Vec<u64>,
    current: u32,
    len: usize,
}

const NONE: u32 = u32::MAX;

impl Default for BucketQueue {
    fn default() -> Self {
        Self {
            heads: vec![NONE; SPAN as usize],
            pool: Vec::new(),
            occupied: vec![0; WORDS],
            current: 0,
            len: 0,
        }
    }
}

impl BucketQueue {
    /// Empties the queue; the next key pushed sets the floor.
    pub fn reset(&mut self, floor: u32) {
        if self.len > 0 {
            self.heads.fill(NONE);
            self.occupied.fill(0);
        }
        self.pool.clear();
        self.current = floor;
        self.len = 0;
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Adds a pair. Panics if `key` lies outside [last popped, last popped + SPAN).
    pub fn push(&mut self, key: u32, value: u32) {
        assert!(
            key >= self.current && key - self.current < SPAN,
            "bucket queue key {key} outside [{}, +{SPAN})",
            self.current
        );
        let b = (key & MASK) as usize;
        self.pool.push((value, self.heads[b]));
        self.heads[b] = (self.pool.len() - 1) as u32;
        self.occupied[b / 64] |= 1 << (b % 64);
        self.len += 1;
    }

    /// Takes a pair with the smallest key.
    pub fn pop(&mut self) -> Option<(u32, u32)> {
        if self.len == 0 {
            return None;
        }
        let from = (self.current & MASK) as usize;
        let mut word = from / 64;
        let mut bits = self.occupied[word] & (!0u64 << (from % 64));
        // At most one full turn of the ring, plus the first word's low bits at the end.
        for _ in 0..=WORDS {
            if bits != 0 {
                break;
            }
            word = (word + 1) % WORDS;
            bits = self.occupied[word];
        }
        let b = word * 64 + bits.trailing_zeros() as usize;
        let rise = (b as u32).wrapping_sub(from as u32) & MASK;
        self.current += rise;
        let (value, next) = self.pool[self.heads[b] as usize];
        self.heads[b] = next;
        if next == NONE {
            self.occupied[b / 64] &= !(1 << (b % 64));
        }
        self.len -= 1;
        Some((self.current, value))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pops_in_key_order_across_the_ring() {
        let mut q = BucketQueue::default();
        q.reset(SPAN - 3);
        for (k, v) in [(SPAN - 3, 0), (SPAN + 40, 1), (SPAN - 1, 2), (SPAN + 2, 3)] {
            q.push(k, v);
        }
        assert_eq!(q.pop(), Some((SPAN - 3, 0)));
        q.push(SPAN + 1, 4);
        let got: Vec<_> = std::iter::from_fn(|| q.pop()).collect();
        assert_eq!(
            got,
            vec![(SPAN - 1, 2), (SPAN + 1, 4), (SPAN + 2, 3), (SPAN + 40, 1)]
        );
    }
}
