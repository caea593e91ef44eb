//! Broad phase: which shape pairs might touch this step (sweep and prune along x), and which
//! static polygons each shape might touch (binary search over x-sorted statics).

use crate::geometry::aabb::Aabb;

/// One box in sweep order, stored contiguously so the sweep reads memory linearly.
#[derive(Debug, Clone, Copy)]
struct Entry {
    min_x: f64,
    max_x: f64,
    min_y: f64,
    max_y: f64,
    index: u32,
    group: u32,
}

/// Persistent sweep-and-prune state; the sort order is reused between steps (nearly sorted).
#[derive(Debug, Clone, Default)]
pub(crate) struct SweepAndPrune {
    order: Vec<u32>,
    entries: Vec<Entry>,
}

impl SweepAndPrune {
    pub fn new(n: usize) -> Self {
        SweepAndPrune {
            order: (0..n as u32).collect(),
            entries: Vec::with_capacity(n),
        }
    }

    /// Calls `f(i, j)` with i < j for every pair of overlapping boxes whose `groups` differ
    /// (boxes of one group, e.g. one rigid body, never pair).
    pub fn for_each_pair(&mut self, aabbs: &[Aabb], groups: impl Fn(usize) -> u32, mut f: impl FnMut(u32, u32)) {
        // insertion sort: O(n) when the order barely changed since the last step
        let order = &mut self.order;
        for i in 1..order.len() {
            let mut j = i;
            while j > 0 && aabbs[order[j - 1] as usize].min.x > aabbs[order[j] as usize].min.x {
                order.swap(j - 1, j);
                j -= 1;
            }
        }
        self.entries.clear();
        self.entries.extend(order.iter().map(|&i| {
            let b = &aabbs[i as usize];
            Entry {
                min_x: b.min.x,
                max_x: b.max.x,
                min_y: b.min.y,
                max_y: b.max.y,
                index: i,
                group: groups(i as usize),
            }
        }));
        for (k, ei) in self.entries.iter().enumerate() {
            for ej in &self.entries[k + 1..] {
                if ej.min_x > ei.max_x {
                    break;
                }
                if ei.group != ej.group && ei.min_y <= ej.max_y && ej.min_y <= ei.max_y {
                    f(ei.index.min(ej.index), ei.index.max(ej.index));
                }
            }
        }
    }
}

/// Static polygons sorted by min x, with a running maximum of max x for range queries.
#[derive(Debug, Clone, Default)]
pub(crate) struct StaticIndex {
    pub min_x: Vec<f64>,
    pub prefix_max_x: Vec<f64>,
}

impl StaticIndex {
    pub fn new(aabbs: &[Aabb]) -> Self {
        let mut prefix = Vec::with_capacity(aabbs.len());
        let mut m = f64::NEG_INFINITY;
        for b in aabbs {
            m = m.max(b.max.x);
            prefix.push(m);
        }
        StaticIndex {
            min_x: aabbs.iter().map(|b| b.min.x).collect(),
            prefix_max_x: prefix,
        }
    }

    /// Index range of statics whose x extent may overlap [x0, x1].
    pub fn candidates(&self, x0: f64, x1: f64) -> std::ops::Range<usize> {
        let start = self.prefix_max_x.partition_point(|&m| m < x0);
        let end = self.min_x.partition_point(|&m| m <= x1);
        start..end.max(start)
    }
}

/// Part pairs that never collide, as a list of larger partners per part (each part has only a
/// few, so a linear scan beats a binary search over all pairs).
#[derive(Debug, Clone, Default)]
pub(crate) struct ExcludedPairs {
    /// `partners[start[p]..start[p + 1]]` are the parts q > p excluded with p.
    start: Vec<u32>,
    partners: Vec<u32>,
}

impl ExcludedPairs {
    /// From pairs of part indices (any order, duplicates allowed) among `n` parts.
    pub fn new(n: usize, pairs: impl IntoIterator<Item = (u32, u32)>) -> Self {
        let mut keys: Vec<(u32, u32)> = pairs.into_iter().map(|(a, b)| (a.min(b), a.max(b))).collect();
        keys.sort_unstable();
        keys.dedup();
        let mut start = vec![0u32; n + 1];
        for &(lo, _) in &keys {
            start[lo as usize + 1] += 1;
        }
        for p in 0..n {
            start[p + 1] += start[p];
        }
        ExcludedPairs {
            start,
            partners: keys.iter().map(|&(_, hi)| hi).collect(),
        }
    }

    /// Whether parts `a` and `b` never collide.
    #[inline]
    pub fn contains(&self, a: u32, b: u32) -> bool {
        let (lo, hi) = (a.min(b) as usize, a.max(b));
        match (self.start.get(lo), self.start.get(lo + 1)) {
            (Some(&s), Some(&e)) => self.partners[s as usize..e as usize].contains(&hi),
            _ => false,
        }
    }
}
