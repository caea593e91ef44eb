//! Batches of a generation's evaluations that run together: genotypes whose robots share an
//! episode group (the task steps them in population lanes) in chunks of the task's batch size,
//! every other genotype alone; and the evaluations put back in the generation's order.

use rayon::prelude::*;
use std::collections::HashMap;

/// The indices `0..count` in batches: those of one group (`group_of(i)`, `None`: alone) in
/// chunks of `size`, in the order their first member appears.
pub(crate) fn group(
    count: usize,
    size: usize,
    group_of: impl Fn(usize) -> Option<String> + Sync + Send,
) -> Vec<Vec<usize>> {
    let groups: Vec<Option<String>> = (0..count).into_par_iter().map(group_of).collect();
    let mut batches: Vec<Vec<usize>> = Vec::new();
    let mut open: HashMap<String, usize> = HashMap::new();
    for (i, group) in groups.into_iter().enumerate() {
        let Some(group) = group else {
            batches.push(vec![i]);
            continue;
        };
        match open.get(&group) {
            Some(&b) if batches[b].len() < size.max(1) => batches[b].push(i),
            _ => {
                open.insert(group, batches.len());
                batches.push(vec![i]);
            }
        }
    }
    batches
}

/// The items of `batches` (each tagged with its index in `0..count`) in index order.
pub(crate) fn in_order<T>(count: usize, batches: Vec<Vec<(usize, T)>>) -> Vec<T> {
    let mut slots: Vec<Option<T>> = (0..count).map(|_| None).collect();
    for (i, item) in batches.into_iter().flatten() {
        slots[i] = Some(item);
    }
    slots
        .into_iter()
        .map(|s| s.expect("every index is in one batch"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn robots_of_one_group_share_batches_of_the_batch_size_and_come_back_in_order() {
        let group_of = |i: usize| match i % 3 {
            0 => None,
            1 => Some("a".to_string()),
            _ => Some("b".to_string()),
        };
        let batches = group(11, 2, group_of);
        assert_eq!(
            batches,
            vec![
                vec![0],
                vec![1, 4],
                vec![2, 5],
                vec![3],
                vec![6],
                vec![7, 10],
                vec![8],
                vec![9]
            ]
        );
        let tagged: Vec<Vec<(usize, usize)>> = batches
            .iter()
            .rev()
            .map(|b| b.iter().map(|&i| (i, 10 * i)).collect())
            .collect();
        assert_eq!(in_order(11, tagged), (0..11).map(|i| 10 * i).collect::<Vec<_>>());
    }
}
