//! Which points the RK4 stages move. EvoGym integrates every point through the four stages and
//! only then zeroes the increments of fixed points, so a fixed point next to moving ones drifts
//! inside a substep and pulls on its neighbours. A free point's last stage needs the stage states
//! of its neighbours, which need their third stage, which needs the second stage two springs away
//! and the first three springs away. So stage `s` (0 to 3) needs the free points and the fixed
//! points at most `3 - s` springs from a free one: with those, free points move exactly as in
//! EvoGym while far terrain is left alone.

/// Springs between a fixed point and a free one can carry a fixed point's stage drift to the
/// free point's final increment through at most this many springs.
pub(crate) const HOPS: u32 = 3;

/// For each point, the fewest springs between it and a free point (0 for a free point), or
/// `u32::MAX` beyond [`HOPS`].
pub(crate) fn hops_from_free(fixed: &[bool], a: &[u32], b: &[u32]) -> Vec<u32> {
    let n = fixed.len();
    let mut first = vec![0usize; n + 1];
    for (&p, &q) in a.iter().zip(b) {
        first[p as usize + 1] += 1;
        first[q as usize + 1] += 1;
    }
    for i in 0..n {
        first[i + 1] += first[i];
    }
    let mut next = first.clone();
    let mut neighbours = vec![0u32; first[n]];
    for (&p, &q) in a.iter().zip(b) {
        neighbours[next[p as usize]] = q;
        next[p as usize] += 1;
        neighbours[next[q as usize]] = p;
        next[q as usize] += 1;
    }
    let mut hops: Vec<u32> = fixed.iter().map(|&f| if f { u32::MAX } else { 0 }).collect();
    let mut frontier: Vec<usize> = (0..n).filter(|&i| !fixed[i]).collect();
    for hop in 1..=HOPS {
        let mut reached = Vec::new();
        for &p in &frontier {
            for &q in &neighbours[first[p]..first[p + 1]] {
                if hops[q as usize] == u32::MAX {
                    hops[q as usize] = hop;
                    reached.push(q as usize);
                }
            }
        }
        frontier = reached;
    }
    hops
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hops_count_springs_from_the_nearest_free_point_up_to_three() {
        // A chain 0 - 1 - 2 - 3 - 4 - 5 with only point 0 free, and an isolated fixed pair 6 - 7.
        let fixed = [false, true, true, true, true, true, true, true];
        let (a, b) = ([0, 1, 2, 3, 4, 6], [1, 2, 3, 4, 5, 7]);
        let m = u32::MAX;
        assert_eq!(hops_from_free(&fixed, &a, &b), [0, 1, 2, 3, m, m, m, m]);
        assert_eq!(hops_from_free(&[true, true], &[0], &[1]), [m, m]);
    }
}
