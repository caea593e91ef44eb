//! Batches of a generation's evaluations that run together: genotypes whose robots share an
//! episode group (the task steps them in population lanes) in chunks of at least the task's
//! batch size, every other genotype alone; and the evaluations put back in the generation's
//! order.

use rayon::prelude::*;
use std::collections::HashMap;

/// The indices `0..count` in batches: those of one group (`group_of(i)`, `None`: alone) in
/// chunks of `size`, or of the group's share of `threads` when larger (a task refills its lanes
/// from a batch as episodes end, so fewer, larger batches keep the lanes full while every thread
/// still gets one), in the order their first member appears.
pub(crate) fn group(
    count: usize,
    size: usize,
    threads: usize,
    group_of: impl Fn(usize) -> Option<String> + Sync + Send,
) -> Vec<Vec<usize>> {
    let groups: Vec<Option<String>> = (0..count).into_par_iter().map(group_of).collect();
    let mut members: HashMap<&str, usize> = HashMap::new();
    for group in groups.iter().flatten() {
        *members.entry(group.as_str()).or_default() += 1;
    }
    let chunk = |group: &str| size.max(members[group].div_ceil(threads.max(1))).max(1);
    let mut batches: Vec<Vec<usize>> = Vec::new();
    let mut open: HashMap<&str, usize> = HashMap::new();
    for (i, group) in groups.iter().enumerate() {
        let Some(group) = group.as_deref() else {
            batches.push(vec![i]);
            continue;
        };
        match open.get(group) {
            Some(&b) if batches[b].len() < chunk(group) => batches[b].push(i),
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
        let batches = group(11, 2, 4, group_of);
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
        // one thread: each group in one batch, its lanes refilled from it
        assert_eq!(
            group(11, 2, 1, group_of),
            vec![vec![0], vec![1, 4, 7, 10], vec![2, 5, 8], vec![3], vec![6], vec![9]]
        );
        let tagged: Vec<Vec<(usize, usize)>> = batches
            .iter()
            .rev()
            .map(|b| b.iter().map(|&i| (i, 10 * i)).collect())
            .collect();
        assert_eq!(in_order(11, tagged), (0..11).map(|i| 10 * i).collect::<Vec<_>>());
    }
}
