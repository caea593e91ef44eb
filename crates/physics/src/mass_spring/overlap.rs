//! The instability test: a watched body whose non-neighbouring boundary quads overlap too often
//! has folded into itself (EvoGym's "unstable" end of an episode).

use super::bodies::Bodies;
use super::MassSpringError;

/// Ordered pairs of body `b`'s boundary quads that were not neighbours at build time and whose
/// current boxes overlap (boxes as last updated).
pub(crate) fn overlapping_pairs(bodies: &Bodies, b: usize) -> usize {
    let slots = bodies.slots(b);
    let mut pairs = 0;
    for (i, si) in slots.clone().enumerate() {
        for (j, sj) in slots.clone().enumerate().skip(i + 1) {
            if !bodies.are_neighbours(b, i, j) && bodies.boxes[si].overlaps(&bodies.boxes[sj]) {
                pairs += 2;
            }
        }
    }
    pairs
}

/// Fails with [`MassSpringError::SelfOverlap`] for the first watched body with more overlapping
/// ordered pairs than boundary quads.
pub(crate) fn check_self_overlap(bodies: &Bodies, substep: u64) -> Result<(), MassSpringError> {
    for body in 0..bodies.len() {
        if !bodies.watched[body] {
            continue;
        }
        let pairs = overlapping_pairs(bodies, body);
        let limit = bodies.slots(body).len();
        if pairs > limit {
            return Err(MassSpringError::SelfOverlap {
                substep,
                body,
                pairs,
                limit,
            });
        }
    }
    Ok(())
}
