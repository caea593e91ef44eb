//! The order in which a step solves its constraints: dyn4j's island walk. Starting from each
//! body not yet visited, in the order bodies were added, a depth-first walk (last pushed, first
//! visited) lists at each body first its contacts, then its joints (in the order they were
//! added), and pushes the bodies on their other ends; static geometry is visited but not walked
//! from. dyn4j 3.3.0 pushes a body only once (when first reached); 4.x pushes it again each time
//! it is reached before its visit, so it is visited from the last reach. Gauss–Seidel sweeps
//! depend on this order, so following it brings the trajectories closer to the original's.
//! With dyn4j 4.2.1's at-rest detection ([`Rest`]), a sleeping body does not start a walk, and a
//! body the walk reaches wakes up; the walk also lists each island's bodies.

use super::rest::Rest;

/// A joint of the solver by kind and index in its kind's list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Joint {
    Spring(u32),
    Rope(u32),
    Weld(u32),
}

/// Per body, its joints (with the body at the other end) in the order they were added, and the
/// buffers of the walk (reused: nothing is allocated once warm).
#[derive(Debug, Clone, Default)]
pub(crate) struct Island {
    /// Joints of body i: `joint_edges[joint_start[i]..joint_start[i + 1]]`.
    joint_start: Vec<u32>,
    joint_edges: Vec<(Joint, u32)>,
    /// Contacts of body i this step, as (contact, other body), in detection order.
    contact_start: Vec<u32>,
    contact_edges: Vec<(u32, u32)>,
    reached: Vec<bool>,
    visited: Vec<bool>,
    push_again: bool,
    joint_done: Vec<bool>,
    contact_done: Vec<bool>,
    stack: Vec<u32>,
    /// Where the next contact of each body goes in `contact_edges` while they are listed.
    cursor: Vec<u32>,
    /// The walk's result: joints and contacts in solving order.
    pub joints: Vec<Joint>,
    pub contacts: Vec<u32>,
    /// The dynamic bodies of each island, one island after the other: island k's are
    /// `bodies[island_start[k]..island_start[k + 1]]`.
    pub bodies: Vec<u32>,
    pub island_start: Vec<u32>,
    /// Index of each joint in `joint_done` (springs, then ropes, then welds).
    base: [u32; 3],
}

impl Island {
    /// `joints`: every joint with its two bodies, in the order they were added; `counts`: how
    /// many springs, ropes and welds there are.
    pub fn new(n_bodies: usize, joints: &[(Joint, u32, u32)], counts: [usize; 3]) -> Island {
        let mut per_body: Vec<Vec<(Joint, u32)>> = vec![Vec::new(); n_bodies];
        for &(j, a, b) in joints {
            per_body[a as usize].push((j, b));
            per_body[b as usize].push((j, a));
        }
        let mut joint_start = vec![0u32];
        let mut joint_edges = Vec::new();
        for edges in per_body {
            joint_edges.extend(edges);
            joint_start.push(joint_edges.len() as u32);
        }
        let total = counts.iter().sum();
        Island {
            joint_start,
            joint_edges,
            reached: vec![false; n_bodies],
            joint_done: vec![false; total],
            base: [0, counts[0] as u32, (counts[0] + counts[1]) as u32],
            ..Default::default()
        }
    }

    fn slot(&self, j: Joint) -> usize {
        match j {
            Joint::Spring(i) => (self.base[0] + i) as usize,
            Joint::Rope(i) => (self.base[1] + i) as usize,
            Joint::Weld(i) => (self.base[2] + i) as usize,
        }
    }

    /// Orders this step's constraints; `contacts` are the contacts' (body a, body b), body 0 being
    /// the static world. With `rest`, sleeping bodies start no walk and the bodies walked wake up.
    pub fn walk(
        &mut self,
        contacts: impl Iterator<Item = (u32, u32)> + Clone,
        push_again: bool,
        mut rest: Option<&mut Rest>,
    ) {
        let n = self.reached.len();
        // contacts per body, in detection order (a counting sort)
        self.contact_start.clear();
        self.contact_start.resize(n + 1, 0);
        let mut count = 0;
        for (a, b) in contacts.clone() {
            self.contact_start[a as usize + 1] += 1;
            self.contact_start[b as usize + 1] += 1;
            count += 1;
        }
        for i in 0..n {
            self.contact_start[i + 1] += self.contact_start[i];
        }
        self.contact_edges.clear();
        self.contact_edges.resize(2 * count, (0, 0));
        self.cursor.clear();
        self.cursor.extend_from_slice(&self.contact_start[..n]);
        for (k, (a, b)) in contacts.enumerate() {
            for (body, other) in [(a, b), (b, a)] {
                let at = &mut self.cursor[body as usize];
                self.contact_edges[*at as usize] = (k as u32, other);
                *at += 1;
            }
        }
        self.contact_done.clear();
        self.contact_done.resize(count, false);
        self.reached.iter_mut().for_each(|r| *r = false);
        self.visited.clear();
        self.visited.resize(n, false);
        self.joint_done.iter_mut().for_each(|d| *d = false);
        self.joints.clear();
        self.contacts.clear();
        self.bodies.clear();
        self.island_start.clear();
        self.island_start.push(0);
        self.push_again = push_again;
        for seed in 1..n {
            if self.reached[seed] || rest.as_ref().is_some_and(|r| r.asleep(seed)) {
                continue;
            }
            self.stack.clear();
            self.stack.push(seed as u32);
            self.reached[seed] = true;
            while let Some(body) = self.stack.pop() {
                let body = body as usize;
                if push_again {
                    // 4.x: a body counts as reached once visited; skip repeated pushes
                    if self.visited[body] {
                        continue;
                    }
                    self.visited[body] = true;
                }
                if body == 0 {
                    continue; // static geometry is visited but not walked from
                }
                if let Some(rest) = rest.as_deref_mut() {
                    rest.wake(body);
                }
                self.bodies.push(body as u32);
                let (lo, hi) = (self.contact_start[body] as usize, self.contact_start[body + 1] as usize);
                for e in lo..hi {
                    let (c, other) = self.contact_edges[e];
                    if self.contact_done[c as usize] {
                        continue;
                    }
                    self.contact_done[c as usize] = true;
                    self.contacts.push(c);
                    self.reach(other);
                }
                let (lo, hi) = (self.joint_start[body] as usize, self.joint_start[body + 1] as usize);
                for e in lo..hi {
                    let (j, other) = self.joint_edges[e];
                    let slot = self.slot(j);
                    if self.joint_done[slot] {
                        continue;
                    }
                    self.joint_done[slot] = true;
                    self.joints.push(j);
                    self.reach(other);
                }
            }
            self.island_start.push(self.bodies.len() as u32);
        }
    }

    /// The dynamic bodies of each island of the last walk.
    pub fn islands(&self) -> impl Iterator<Item = &[u32]> {
        self.island_start
            .windows(2)
            .map(|w| &self.bodies[w[0] as usize..w[1] as usize])
    }

    fn reach(&mut self, body: u32) {
        let b = body as usize;
        if self.push_again {
            if !self.visited[b] {
                self.reached[b] = true;
                self.stack.push(body);
            }
        } else if !self.reached[b] {
            self.reached[b] = true;
            self.stack.push(body);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bodies 1–2–3 in a chain of springs, 3 on the ground: the walk starts at 1, goes to 2, then
    /// 3, meeting 3's contact before its joint to 4.
    #[test]
    fn the_walk_is_depth_first_with_contacts_before_joints() {
        let joints = [
            (Joint::Spring(0), 1, 2),
            (Joint::Spring(1), 2, 3),
            (Joint::Weld(0), 3, 4),
            (Joint::Spring(2), 1, 4),
        ];
        let mut island = Island::new(5, &joints, [3, 0, 1]);
        island.walk([(0u32, 3u32)].into_iter(), false, None);
        // at 1: springs 0 (to 2) and 2 (to 4); 4 was reached last, so it is visited first: its
        // weld to 3; then 3: its contact, then spring 1 to 2; then 2: nothing new
        assert_eq!(
            island.joints,
            vec![Joint::Spring(0), Joint::Spring(2), Joint::Weld(0), Joint::Spring(1)]
        );
        assert_eq!(island.contacts, vec![0]);
    }

    /// 3 reaches 4, then 2 again (first reached from 1). 3.3.0 keeps 2 where 1 pushed it, so 4
    /// (and its spring to 6) comes first; 4.x pushes 2 again on top, so 2 (and its spring to 5)
    /// comes first.
    #[test]
    fn dyn4j_4_visits_a_body_from_its_last_reach() {
        let s = Joint::Spring;
        let joints = [
            (s(0), 1, 2),
            (s(1), 1, 3),
            (s(2), 3, 4),
            (s(3), 3, 2),
            (s(4), 2, 5),
            (s(5), 4, 6),
        ];
        let mut old = Island::new(7, &joints, [6, 0, 0]);
        old.walk(std::iter::empty(), false, None);
        assert_eq!(old.joints, vec![s(0), s(1), s(2), s(3), s(5), s(4)]);
        let mut new = Island::new(7, &joints, [6, 0, 0]);
        new.walk(std::iter::empty(), true, None);
        assert_eq!(new.joints, vec![s(0), s(1), s(2), s(3), s(4), s(5)]);
    }
}
