//! Claims on a fleet's shared work: a block is worked on by one robot at a time. Each
//! robot says what it wants (the block it picks up or carries); the first to want a
//! block holds it until it wants something else, and the others are told it is taken.

use std::collections::{BTreeMap, BTreeSet};

/// Who holds each claimed item (a block's odd marker), by robot index.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Claims {
    holders: BTreeMap<u32, usize>,
}

impl Claims {
    /// Takes what each robot wants now (`wants[i]` for robot `i`): a robot that wants
    /// something else lets its old claim go, and a free item goes to the first robot in
    /// order that wants it. Returns, for each robot, whether it holds what it wants.
    pub fn settle(&mut self, wants: &[Option<u32>]) -> Vec<bool> {
        self.holders
            .retain(|item, robot| wants.get(*robot).copied().flatten() == Some(*item));
        (wants.iter().enumerate())
            .map(|(robot, want)| match want {
                None => true,
                Some(item) => *self.holders.entry(*item).or_insert(robot) == robot,
            })
            .collect()
    }

    /// The items robot `robot` may not take: those the others hold.
    pub fn taken_for(&self, robot: usize) -> BTreeSet<u32> {
        (self.holders.iter())
            .filter(|(_, r)| **r != robot)
            .map(|(item, _)| *item)
            .collect()
    }

    /// Who holds `item`, if anyone.
    pub fn holder(&self, item: u32) -> Option<usize> {
        self.holders.get(&item).copied()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    #[test]
    fn the_first_to_want_a_block_holds_it_until_it_wants_another() {
        let mut claims = Claims::default();
        assert_eq!(claims.settle(&[Some(421), None]), [true, true]);
        // Robot 1 wants the same block: refused, and told it is taken.
        assert_eq!(claims.settle(&[Some(421), Some(421)]), [true, false]);
        assert_eq!(claims.taken_for(1), BTreeSet::from([421]));
        assert!(claims.taken_for(0).is_empty());
        // Robot 0 moves on: the block is free, and robot 1 gets it.
        assert_eq!(claims.settle(&[Some(423), Some(421)]), [true, true]);
        assert_eq!((claims.holder(421), claims.holder(423)), (Some(1), Some(0)));
    }

    #[test]
    fn no_block_is_ever_held_by_two_robots() {
        // Five robots wanting among four blocks, drawn anew each round for 2000 rounds.
        let mut claims = Claims::default();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12345);
        for _ in 0..2000 {
            let wants: Vec<Option<u32>> = (0..5)
                .map(|_| match rng.random_range(0..5) {
                    0 => None,
                    k => Some(419 + 2 * k),
                })
                .collect();
            let held = claims.settle(&wants);
            for item in [421, 423, 425, 427] {
                let holding: Vec<usize> = (0..5)
                    .filter(|&r| held[r] && wants[r] == Some(item))
                    .collect();
                assert!(holding.len() <= 1, "{item} held by {holding:?}");
                assert_eq!(holding.first().copied(), claims.holder(item));
                for r in 0..5 {
                    let refused = wants[r] == Some(item) && !held[r];
                    assert_eq!(
                        refused,
                        claims.taken_for(r).contains(&item) && wants[r] == Some(item)
                    );
                }
            }
        }
    }
}
