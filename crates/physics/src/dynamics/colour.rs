//! Greedy colouring of constraints by the bodies they join: within a colour no two constraints
//! share a moving body, so the constraints of a colour can be solved side by side with the result
//! of solving them one by one. Used for the soft solver's springs and ropes (at build time) and
//! for the sequential-impulse solver's coloured joint sweeps (every step).

/// Reusable buffers of [`greedy_colours`] (nothing is allocated once warm).
#[derive(Debug, Clone, Default)]
pub(crate) struct ColourBuffers {
    /// Colours already taken at each body, as a bit set of 64 colours per word.
    taken: Vec<Vec<u64>>,
    /// The colour of each constraint, in the given order.
    pub colours: Vec<u32>,
}

/// Gives each constraint (a pair of bodies, in order) the first colour free at both its bodies;
/// body 0, the static world, never moves and takes no colour. The colours land in
/// `buffers.colours`; returns how many colours there are.
pub(crate) fn greedy_colours(
    pairs: impl Iterator<Item = (u32, u32)>,
    n_bodies: usize,
    buffers: &mut ColourBuffers,
) -> u32 {
    let ColourBuffers { taken, colours } = buffers;
    taken.resize_with(n_bodies.max(taken.len()), Vec::new);
    taken.iter_mut().for_each(|t| t.iter_mut().for_each(|w| *w = 0));
    colours.clear();
    let mut count = 0;
    for (a, b) in pairs {
        let (a, b) = (a as usize, b as usize);
        let mut c = 0;
        loop {
            let (w, bit) = (c / 64, 1u64 << (c % 64));
            let is_taken = |body: usize| body != 0 && taken[body].get(w).is_some_and(|x| x & bit != 0);
            if !(is_taken(a) || is_taken(b)) {
                break;
            }
            c += 1;
        }
        for body in [a, b] {
            let t = &mut taken[body];
            if t.len() <= c / 64 {
                t.resize(c / 64 + 1, 0);
            }
            t[c / 64] |= 1 << (c % 64);
        }
        colours.push(c as u32);
        count = count.max(c as u32 + 1);
    }
    count
}

/// A permutation of constraints (given as body pairs) grouped by greedy colour, and the range of
/// each colour in it. Colours keep the original order inside them.
pub(crate) fn colour_order(pairs: &[(u32, u32)]) -> (Vec<usize>, Vec<(u32, u32)>) {
    let n_bodies = pairs.iter().map(|&(a, b)| a.max(b) as usize + 1).max().unwrap_or(0);
    let mut buffers = ColourBuffers::default();
    greedy_colours(pairs.iter().copied(), n_bodies, &mut buffers);
    let colours = &buffers.colours;
    let mut order: Vec<usize> = (0..pairs.len()).collect();
    order.sort_by_key(|&i| colours[i]);
    let mut ranges: Vec<(u32, u32)> = Vec::new();
    for (k, &i) in order.iter().enumerate() {
        match ranges.last_mut() {
            Some(r) if colours[order[r.0 as usize]] == colours[i] => r.1 = k as u32 + 1,
            _ => ranges.push((k as u32, k as u32 + 1)),
        }
    }
    (order, ranges)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_body_with_more_than_64_constraints_gets_more_than_64_colours() {
        // a star: body 1 joined to bodies 2..=71, so every constraint needs a colour of its own
        let pairs: Vec<(u32, u32)> = (2..72).map(|k| (1, k)).collect();
        let (order, ranges) = colour_order(&pairs);
        assert_eq!(ranges.len(), 70);
        assert_eq!(order, (0..70).collect::<Vec<_>>());
    }

    #[test]
    fn joints_to_the_static_world_share_colour_zero() {
        let mut b = ColourBuffers::default();
        let n = greedy_colours([(0, 1), (0, 2), (1, 0), (1, 2)].into_iter(), 3, &mut b);
        assert_eq!(b.colours, vec![0, 0, 1, 2]);
        assert_eq!(n, 3);
    }
}
