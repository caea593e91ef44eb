//! The joints of a sweep grouped by greedy colour: within a colour no two joints share a moving
//! body, so a vectorised sweep could solve a colour's joints side by side and get the result of
//! solving them one by one. Grouping changes the Gauss–Seidel order (and so the motion) against
//! dyn4j's island walk; docs/fidelity.md measures by how much.

use super::island::Joint;
use crate::dynamics::colour::{greedy_colours, ColourBuffers};

/// Reusable buffers of the colouring (nothing is allocated once warm).
#[derive(Debug, Clone, Default)]
pub(crate) struct JointColours {
    colouring: ColourBuffers,
    sorted: Vec<Joint>,
}

impl JointColours {
    /// Reorders `joints` by greedy colour ([`greedy_colours`], in the given order) and keeps the
    /// given order within a colour. `ends` gives a joint's two bodies.
    pub fn group(&mut self, joints: &mut [Joint], n_bodies: usize, ends: impl Fn(Joint) -> (u32, u32)) {
        let count = greedy_colours(joints.iter().map(|&j| ends(j)), n_bodies, &mut self.colouring);
        self.sorted.clear();
        for c in 0..count {
            let same = joints.iter().zip(&self.colouring.colours).filter(|(_, &k)| k == c);
            self.sorted.extend(same.map(|(&j, _)| j));
        }
        joints.copy_from_slice(&self.sorted);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chain_alternates_two_colours_and_keeps_the_order_within_each() {
        // bodies 1-2-3-4-5 joined in a chain: joints 0..4 colour 0,1,0,1
        let mut joints: Vec<Joint> = (0..4).map(Joint::Spring).collect();
        let ends = |j: Joint| match j {
            Joint::Spring(i) => (i + 1, i + 2),
            _ => unreachable!(),
        };
        JointColours::default().group(&mut joints, 6, ends);
        let order: Vec<u32> = joints
            .iter()
            .map(|j| match j {
                Joint::Spring(i) => *i,
                _ => unreachable!(),
            })
            .collect();
        assert_eq!(order, vec![0, 2, 1, 3]);
    }

    #[test]
    fn joints_to_the_static_world_share_a_colour() {
        // three bodies each joined to the static world, then 1-2
        let mut joints: Vec<Joint> = (0..4).map(Joint::Weld).collect();
        let ends = |j: Joint| match j {
            Joint::Weld(3) => (1, 2),
            Joint::Weld(i) => (0, i + 1),
            _ => unreachable!(),
        };
        JointColours::default().group(&mut joints, 4, ends);
        assert_eq!(
            joints,
            vec![Joint::Weld(0), Joint::Weld(1), Joint::Weld(2), Joint::Weld(3)]
        );
        let mut within: Vec<Joint> = vec![Joint::Weld(3), Joint::Weld(0), Joint::Weld(1)];
        JointColours::default().group(&mut within, 4, ends);
        // 3 takes colour 0 at bodies 1 and 2; 0 (body 1) and 1 (body 2) take colour 1
        assert_eq!(within, vec![Joint::Weld(3), Joint::Weld(0), Joint::Weld(1)]);
    }
}
