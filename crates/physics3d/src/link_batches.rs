//! The links of one world updated four at a time (issue 52, item 4: SIMD inside one episode).
//! Links along the same axis with the same constants form batches of four; each step a batch
//! gathers its links' ends and carried state into AVX2 lanes (`LinkLanes<Avx<4>>`), runs the
//! laned update, and writes forces, moments, strain and state back to the four `Link`s. Each
//! lane gives `Link::update`'s bits (link_lanes.rs), so the world's step keeps its bits; links
//! left over, and every link on a CPU without AVX2, update one by one.

use crate::batching::{in_fours, BATCH};
use crate::link::{End, Link};
use crate::link_lanes::{EndLanes, LinkLanes};
use vsrlab_lanes::Lanes;

/// Which links update together.
#[derive(Debug, Clone, Default)]
pub(crate) struct LinkBatches {
    /// Four links each, of one axis and one set of constants.
    batches: Vec<[usize; BATCH]>,
    /// The links in no batch.
    single: Vec<usize>,
}

impl LinkBatches {
    /// Batches for `links`: grouped by axis and constants in link order, four at a time; what
    /// is left of each group updates alone. No batches when `lanes` is false (a CPU without
    /// AVX2).
    pub fn plan(links: &[Link], lanes: bool) -> LinkBatches {
        let keys = links.iter().map(|l| lanes.then_some((l.axis, l.k, l.area.to_bits())));
        let (batches, single) = in_fours(keys);
        LinkBatches {
            batches: batches.into_iter().map(|(_, b)| b).collect(),
            single,
        }
    }

    /// Updates every link from `ends` (each voxel's state at the start of the step): the forces,
    /// moments, strain and carried state of `Link::update` for each, bit for bit.
    pub fn update(&self, links: &mut [Link], ends: &[End]) {
        #[cfg(target_arch = "x86_64")]
        if !self.batches.is_empty() {
            // SAFETY: batches exist only where `lanes_available` found AVX2
            unsafe { update_avx2(&self.batches, links, ends) };
        }
        for &i in &self.single {
            let l = &mut links[i];
            let (a, b) = (ends[l.neg], ends[l.pos]);
            l.update(&a, &b);
        }
    }
}

/// Whether this CPU runs the laned updates (AVX2).
pub(crate) fn lanes_available() -> bool {
    #[cfg(target_arch = "x86_64")]
    return vsrlab_lanes::avx::available();
    #[cfg(not(target_arch = "x86_64"))]
    false
}

/// The batches in AVX2 lanes.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn update_avx2(batches: &[[usize; BATCH]], links: &mut [Link], ends: &[End]) {
    for batch in batches {
        update_batch::<vsrlab_lanes::avx::Avx<BATCH>>(batch, links, ends);
    }
}

/// One batch: gathered into lanes, updated, written back.
#[inline(always)]
fn update_batch<L: Lanes>(batch: &[usize; BATCH], links: &mut [Link], ends: &[End]) {
    let (mut a, mut b) = (EndLanes::<L>::zero(), EndLanes::<L>::zero());
    for (lane, &i) in batch.iter().enumerate() {
        let l = &links[i];
        a.set_lane(lane, &ends[l.neg]);
        b.set_lane(lane, &ends[l.pos]);
    }
    let mut laned = LinkLanes::<L>::gather(&batch.map(|i| &links[i]));
    laned.update(&a, &b);
    for (lane, &i) in batch.iter().enumerate() {
        laned.scatter(lane, &mut links[i]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::axis::Axis;
    use crate::material::LinkConstants;
    use crate::quat::from_rotation_vector;
    use glam::DVec3;

    /// Nine links of two constants and three axes, bent at random every update: the batches
    /// give each link the bits of its own update, over modes that change between updates.
    #[test]
    fn batched_links_give_each_links_own_bits() {
        let mut next = crate::validation::uniform(0x9E37_79B9_7F4A_7C15_u64);
        let soft = LinkConstants::new(1e6, 1e6, 0.01);
        let stiff = LinkConstants::new(1e6, 1e8, 0.01);
        let axes = [Axis::X, Axis::Y, Axis::Z];
        let mut links: Vec<Link> = (0..13)
            .map(|i| {
                let k = if i % 5 == 0 { stiff } else { soft };
                Link::new(i, i + 13, axes[(i / 6) % 3], k, 1e-4, 0.01 * (1.0 + 0.01 * i as f64))
            })
            .collect();
        let mut alone = links.clone();
        let plan = LinkBatches::plan(&links, lanes_available());
        if lanes_available() {
            assert!(!plan.batches.is_empty() && !plan.single.is_empty(), "{plan:?}");
        }
        let mut large = 0;
        for round in 0..60 {
            let bend = [0.002, 0.02, 0.3, 1.5][round % 4];
            let ends: Vec<End> = (0..26)
                .map(|v| {
                    let mut random = || DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5);
                    // the positive end one lattice step along its link's axis
                    let at = match (v >= 13).then(|| axes[((v - 13) / 6) % 3]) {
                        None => DVec3::ZERO,
                        Some(Axis::X) => DVec3::X * 0.01,
                        Some(Axis::Y) => DVec3::Y * 0.01,
                        Some(Axis::Z) => DVec3::Z * 0.01,
                    };
                    End {
                        pos: at + random() * 0.01 * bend,
                        orient: from_rotation_vector(random() * bend),
                        damping: if round == 0 { 0.0 } else { 3.0 * next() },
                    }
                })
                .collect();
            plan.update(&mut links, &ends);
            for l in &mut alone {
                let (a, b) = (ends[l.neg], ends[l.pos]);
                l.update(&a, &b);
            }
            for (i, (l, s)) in links.iter().zip(&alone).enumerate() {
                let bits = |v: DVec3| v.to_array().map(f64::to_bits);
                let what = format!("round {round}, link {i}");
                assert_eq!(bits(l.force_neg), bits(s.force_neg), "{what}");
                assert_eq!(bits(l.force_pos), bits(s.force_pos), "{what}");
                assert_eq!(bits(l.moment_neg), bits(s.moment_neg), "{what}");
                assert_eq!(bits(l.moment_pos), bits(s.moment_pos), "{what}");
                assert_eq!(l.strain.to_bits(), s.strain.to_bits(), "{what}");
                large += usize::from(!l.small_angle());
            }
        }
        // both modes were met
        assert!(large > 50 && large < 60 * 13 - 50, "{large}");
    }
}
