//! The damage the fuzz campaign does to recordings and shard files: bytes
//! flipped, the file cut short, bytes copied over others, another file grafted.

use proptest::prelude::*;
use proptest::sample::Index;

/// Damage done to a file's bytes.
#[derive(Debug, Clone)]
pub(super) enum Damage {
    /// Bytes at `at` xored with `mask` (never 0).
    Flip { at: Vec<Index>, mask: u8 },
    /// The file cut short at `at`.
    Truncate { at: Index },
    /// `len` bytes from `from` copied over those at `to`.
    Splice { from: Index, to: Index, len: usize },
    /// The file cut at `at` and continued from `from` of another good file.
    Graft { at: Index, other: Index, from: Index },
}

pub(super) fn damage() -> impl Strategy<Value = Damage> {
    prop_oneof![
        3 => (prop::collection::vec(any::<Index>(), 1..=4), 1..=255u8).prop_map(|(at, mask)| Damage::Flip { at, mask }),
        1 => any::<Index>().prop_map(|at| Damage::Truncate { at }),
        1 => (any::<Index>(), any::<Index>(), 1..4096usize).prop_map(|(from, to, len)| Damage::Splice { from, to, len }),
        1 => (any::<Index>(), any::<Index>(), any::<Index>()).prop_map(|(at, other, from)| Damage::Graft { at, other, from }),
    ]
}

/// `good[which]` with `damage` done to it, grafting from the others.
pub(super) fn damaged(good: &[Vec<u8>], which: &Index, damage: &Damage) -> Vec<u8> {
    let mut bytes = good[which.index(good.len())].clone();
    let len = bytes.len();
    match damage {
        Damage::Flip { at, mask } => {
            for at in at {
                bytes[at.index(len)] ^= mask;
            }
        }
        Damage::Truncate { at } => bytes.truncate(at.index(len)),
        Damage::Splice { from, to, len: n } => {
            let (from, to) = (from.index(len), to.index(len));
            let n = (*n).min(len - from).min(len - to);
            bytes.copy_within(from..from + n, to);
        }
        Damage::Graft { at, other, from } => {
            let other = &good[other.index(good.len())];
            bytes.truncate(at.index(len));
            bytes.extend_from_slice(&other[from.index(other.len())..]);
        }
    }
    bytes
}
