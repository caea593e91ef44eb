//! Items of one world put in batches of four for lanes inside one episode (links in
//! `link_batches.rs`, voxels in `voxel_batches.rs`): items with equal keys, in item order, four at
//! a time; items without a key, and what is left of each key's group, go alone.

/// Items per batch.
pub(crate) const BATCH: usize = 4;

/// Batches of items with equal keys, each with its key, and the items that go alone (no key, or
/// left over), for items whose keys are `keys` in item order.
pub(crate) fn in_fours<K: PartialEq + Copy>(
    keys: impl Iterator<Item = Option<K>>,
) -> (Vec<(K, [usize; BATCH])>, Vec<usize>) {
    let mut groups: Vec<(K, Vec<usize>)> = Vec::new();
    let mut single = Vec::new();
    for (i, key) in keys.enumerate() {
        match key {
            None => single.push(i),
            Some(key) => match groups.iter_mut().find(|g| g.0 == key) {
                Some(g) => g.1.push(i),
                None => groups.push((key, vec![i])),
            },
        }
    }
    let mut batches = Vec::new();
    for (key, members) in groups {
        let mut chunks = members.chunks_exact(BATCH);
        batches.extend(chunks.by_ref().map(|c| (key, [c[0], c[1], c[2], c[3]])));
        single.extend_from_slice(chunks.remainder());
    }
    (batches, single)
}
