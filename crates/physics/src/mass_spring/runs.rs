//! Sets of indices stored as runs of consecutive indices, so that hot loops walk plain ranges
//! (contiguous slices the compiler can check once and vectorise) instead of an index list.

use std::ops::Range;

/// Ascending, disjoint runs `[start, end)` of indices.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub(crate) struct Runs {
    runs: Vec<(u32, u32)>,
}

impl Runs {
    /// The indices of `0..n` for which `keep` holds.
    pub fn where_(n: usize, keep: impl Fn(usize) -> bool) -> Runs {
        let mut runs: Vec<(u32, u32)> = Vec::new();
        for i in (0..n).filter(|&i| keep(i)) {
            match runs.last_mut() {
                Some(last) if last.1 as usize == i => last.1 += 1,
                _ => runs.push((i as u32, i as u32 + 1)),
            }
        }
        Runs { runs }
    }

    /// The runs as ranges.
    pub fn ranges(&self) -> impl Iterator<Item = Range<usize>> + '_ {
        self.runs.iter().map(|&(s, e)| s as usize..e as usize)
    }

    /// Every index, ascending.
    pub fn indices(&self) -> impl Iterator<Item = usize> + '_ {
        self.ranges().flatten()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_join_consecutive_indices_and_list_them_back() {
        let keep = [true, true, false, true, false, false, true, true, true];
        let r = Runs::where_(keep.len(), |i| keep[i]);
        assert_eq!(r.ranges().collect::<Vec<_>>(), vec![0..2, 3..4, 6..9]);
        assert_eq!(r.indices().collect::<Vec<_>>(), vec![0, 1, 3, 6, 7, 8]);
        assert_eq!(Runs::where_(3, |_| false).indices().count(), 0);
    }
}
