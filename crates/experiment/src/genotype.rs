//! [`Genotype`]: what the runner needs of a genotype type: serde (checkpoints, snapshots) and a
//! key that identifies equal genotypes (to match evaluation records to population members).

use serde::de::DeserializeOwned;
use serde::Serialize;

/// A genotype the runner can carry: flat vectors today, graphs or grids through their own impl.
pub trait Genotype: Clone + Serialize + DeserializeOwned + Send + Sync + 'static {
    /// A hash that equal genotypes share (collisions only cost a record).
    fn key(&self) -> u64;
}

/// FNV-1a over bytes, the hash behind [`Genotype::key`] implementations.
pub fn fnv1a(bytes: impl IntoIterator<Item = u8>) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

impl Genotype for Vec<f64> {
    /// FNV-1a over the bits of the genes.
    fn key(&self) -> u64 {
        fnv1a(self.iter().flat_map(|g| g.to_bits().to_le_bytes()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_vectors_share_a_key_and_different_ones_do_not() {
        let a = vec![0.5, -1.0, 2.0];
        assert_eq!(a.key(), a.clone().key());
        assert_ne!(a.key(), vec![0.5, -1.0, 2.000_000_1].key());
        assert_ne!(vec![0.0].key(), vec![-0.0].key());
    }
}
