//! A queue of same-body episodes run in the lanes of one [`LanedWorlds`] (issue 52): every lane
//! runs one episode after another, and a lane whose episode ends (its last step, or a failure
//! such as a diverged world) is restarted from the world's first state
//! ([`LanedWorlds::restart`]) with the queue's next episode while the other lanes step on. Each
//! lane is the bits of a world stepped alone, so every episode's result is the one it has when
//! run by itself, whatever its lane and its neighbours.

use vsrlab_physics3d::laned_worlds::LanedWorlds;
use vsrlab_physics3d::Physics3dError;

/// One episode as a laned population runs it: a task's loop body, lane by lane.
pub(crate) trait LaneEpisode {
    /// What the episode gives when it ends.
    type Result;
    /// The episode takes lane `lane` of a world that has not stepped in that lane.
    fn start(&mut self, world: &LanedWorlds, lane: usize);
    /// The episode's `k`-th step (from 1), after the world stepped: sense, control, actuate.
    /// False when the episode ended early (it failed).
    fn advance(&mut self, world: &mut LanedWorlds, lane: usize, k: u64) -> bool;
    /// The episode's result after its last step or its failure, read from lane `lane`.
    fn finish(self, world: &LanedWorlds, lane: usize) -> Self::Result;
    /// The episode's result when the world refused its `k`-th step (an error about `dt`, which
    /// every lane shares).
    fn refused(self, k: u64, error: &Physics3dError) -> Self::Result;
}

/// Runs every episode of `queue`, `steps` steps each unless it ends early, in the lanes of
/// `world` (which has not stepped); their results in the queue's order.
pub(crate) fn run_population<E: LaneEpisode>(
    world: &mut LanedWorlds,
    queue: Vec<E>,
    steps: u64,
    dt: f64,
) -> Vec<E::Result> {
    let mut results: Vec<Option<E::Result>> = queue.iter().map(|_| None).collect();
    let mut waiting = queue.into_iter().enumerate();
    // each lane's episode: its place in the queue, itself, and the world's step it started after
    let mut running: Vec<Option<(usize, E, u64)>> = (0..world.lane_count())
        .map(|lane| {
            let (index, mut episode) = waiting.next()?;
            episode.start(world, lane);
            Some((index, episode, 0))
        })
        .collect();
    let mut stepped = 0;
    while running.iter().any(Option::is_some) {
        if let Err(e) = world.step(dt) {
            let started = running.iter_mut().filter_map(Option::take);
            let queued = waiting.by_ref().map(|(index, episode)| (index, episode, stepped));
            for (index, episode, from) in started.chain(queued) {
                results[index] = Some(episode.refused(stepped + 1 - from, &e));
            }
            break;
        }
        stepped += 1;
        for (lane, slot) in running.iter_mut().enumerate() {
            let Some((_, episode, from)) = slot else {
                continue;
            };
            let k = stepped - *from;
            if episode.advance(world, lane, k) && k < steps {
                continue;
            }
            if let Some((index, episode, _)) = slot.take() {
                results[index] = Some(episode.finish(world, lane));
            }
            if let Some((index, mut episode)) = waiting.next() {
                world.restart(lane);
                episode.start(world, lane);
                *slot = Some((index, episode, stepped));
            }
        }
    }
    results
        .into_iter()
        .map(|r| r.expect("every queued episode ends"))
        .collect()
}
