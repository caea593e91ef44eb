//! [`EnvLanes`]: up to [`LANES`] environments of one task and one robot body stepped together, their
//! physics in population lanes ([`MassSpringLanes`]), each environment answering exactly as
//! [`EvoGymEnv::step`] alone: the same rewards, observations and ends, bit for bit.

use super::env::EvoGymEnv;
use super::error::EvoGymError;
pub use vsrlab_physics::mass_spring::LANES;
use vsrlab_physics::mass_spring::{MassSpringLanes, MassSpringWorld};

/// What one environment's step in lanes gave (its observation is [`EvoGymEnv::observation`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaneStep {
    /// The step's reward.
    pub reward: f64,
    /// The episode ended: goal reached or unstable.
    pub done: bool,
    /// The episode reached its length.
    pub truncated: bool,
    /// The robot folded into itself or the state became non-finite.
    pub unstable: bool,
}

/// Lanes for environments of one task and body.
#[derive(Debug, Clone)]
pub struct EnvLanes {
    lanes: MassSpringLanes,
}

impl EnvLanes {
    /// Lanes for environments like `env` (its task, its robot's body).
    pub fn new(env: &EvoGymEnv) -> Self {
        EnvLanes {
            lanes: MassSpringLanes::new(env.world()),
        }
    }

    /// Whether `env` can step in these lanes (the same world shape).
    pub fn fits(&self, env: &EvoGymEnv) -> bool {
        self.lanes.fits(env.world())
    }

    /// One step of each of `envs` (at most [`LANES`], each fitting) with its `actions`, each answering
    /// as [`EvoGymEnv::step`] would, in `envs`' order. An environment whose step is refused (its
    /// episode is over, its actions are wrong) gives its error and does not move. Refuses more
    /// than [`LANES`] environments, or one that does not fit, before stepping any.
    pub fn step(
        &mut self,
        envs: &mut [&mut EvoGymEnv],
        actions: &[&[f64]],
    ) -> Result<Vec<Result<LaneStep, EvoGymError>>, EvoGymError> {
        if envs.len() > LANES || actions.len() != envs.len() || !envs.iter().all(|e| self.fits(e)) {
            return Err(EvoGymError::Lanes(format!(
                "{LANES} lanes step at most {LANES} environments of one task and body, one action list each \
                 (got {} environments, {} lists)",
                envs.len(),
                actions.len()
            )));
        }
        let starts: Vec<_> = envs.iter().zip(actions).map(|(e, a)| e.begin_step(a)).collect();
        let moving: Vec<usize> = (0..envs.len()).filter(|&k| starts[k].is_ok()).collect();
        let mut worlds: Vec<&mut MassSpringWorld> = envs
            .iter_mut()
            .enumerate()
            .filter(|(k, _)| starts[*k].is_ok())
            .map(|(_, e)| e.world_mut())
            .collect();
        let targets: Vec<&[f64]> = moving.iter().map(|&k| actions[k]).collect();
        let reports = self.lanes.step(&mut worlds, &targets).map_err(EvoGymError::Physics)?;
        let mut physics = moving.iter().zip(reports);
        let mut out = Vec::with_capacity(envs.len());
        for (env, start) in envs.iter_mut().zip(starts) {
            let step = start.and_then(|before| {
                let (_, report) = physics.next().expect("a report per moving environment");
                let physics = report.expect("a report per world").map(|_| ());
                env.finish_step(before, physics).map(|r| LaneStep {
                    reward: r.reward,
                    done: r.done,
                    truncated: r.truncated,
                    unstable: r.unstable,
                })
            });
            out.push(step);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::super::{EvoGymTask, Material, MaterialGrid};
    use super::*;
    use proptest::prelude::*;
    use rand::{Rng, SeedableRng};

    /// Steps `n` environments of `grid` on `task` alone and in lanes, each with its own random
    /// actions (in [lo, hi], beyond EvoGym's range included), for `steps` steps or until all
    /// ended; every reward, end, observation and point must have the same bits. Returns the
    /// steps each ran.
    fn alone_and_in_lanes(
        task: EvoGymTask,
        grid: &MaterialGrid,
        n: usize,
        steps: usize,
        (lo, hi): (f64, f64),
        seed: u64,
    ) -> Vec<usize> {
        let first = EvoGymEnv::new(task, grid).unwrap();
        let (mut alone, mut laned) = (vec![first.clone(); n], vec![first.clone(); n]);
        let mut lanes = EnvLanes::new(&first);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut ran = vec![0; n];
        for step in 0..steps {
            let running: Vec<usize> = (0..n).filter(|&k| !laned[k].is_over()).collect();
            if running.is_empty() {
                break;
            }
            let actions: Vec<Vec<f64>> = running
                .iter()
                .map(|_| (0..first.action_count()).map(|_| rng.random_range(lo..hi)).collect())
                .collect();
            let mut envs: Vec<&mut EvoGymEnv> = laned
                .iter_mut()
                .enumerate()
                .filter(|(k, _)| running.contains(k))
                .map(|(_, e)| e)
                .collect();
            let lists: Vec<&[f64]> = actions.iter().map(Vec::as_slice).collect();
            let answers = lanes.step(&mut envs, &lists).unwrap();
            for ((&k, answer), actions) in running.iter().zip(answers).zip(&actions) {
                let expected = alone[k].step(actions).unwrap();
                let got = answer.unwrap();
                assert_eq!(
                    (got.reward.to_bits(), got.done, got.truncated, got.unstable),
                    (
                        expected.reward.to_bits(),
                        expected.done,
                        expected.truncated,
                        expected.unstable
                    ),
                    "{task:?} env {k} step {step}"
                );
                let bits = |e: &EvoGymEnv| {
                    let w = e.world();
                    let values = [e.observation(), w.positions_x(), w.positions_y(), w.velocities_x()];
                    values.concat().iter().map(|v| v.to_bits()).collect::<Vec<u64>>()
                };
                assert!(
                    bits(&laned[k]) == bits(&alone[k]),
                    "{task:?} env {k} step {step}: state"
                );
                assert!(laned[k].observation().iter().all(|v| v.is_finite()));
                ran[k] += 1;
            }
        }
        ran
    }

    #[test]
    fn every_task_steps_in_lanes_as_alone() {
        let full = MaterialGrid::from_rows("33333/33333/33333/33333/33333").unwrap();
        let mixed = MaterialGrid::from_rows("13231/34443/32023/33033/40004").unwrap();
        for &task in EvoGymTask::ALL {
            for grid in [&full, &mixed] {
                // four environments in four lanes, and three (a lane without one)
                let ran = alone_and_in_lanes(task, grid, 4, 12, (0.4, 1.8), 1);
                assert!(ran.iter().all(|&r| r == 12), "{task:?}: {ran:?}");
                alone_and_in_lanes(task, grid, 3, 6, (0.6, 1.6), 2);
            }
        }
    }

    #[test]
    fn refused_steps_are_each_environments_own() {
        let grid = MaterialGrid::from_rows("33333/33333/33333").unwrap();
        let env = EvoGymEnv::new(EvoGymTask::Walker, &grid).unwrap();
        let mut lanes = EnvLanes::new(&env);
        let (mut a, mut b) = (env.clone(), env.clone());
        let mut extra = vec![env.clone(); 4];
        let good = vec![1.0; env.action_count()];
        let mut bad = good.clone();
        bad[3] = f64::NAN;
        let out = lanes.step(&mut [&mut a, &mut b], &[&good, &bad]).unwrap();
        assert!(out[0].is_ok());
        assert!(matches!(out[1], Err(EvoGymError::NonFiniteAction { index: 3, .. })));
        assert_eq!((a.steps(), b.steps()), (1, 0), "the refused one did not move");
        let mut more: Vec<&mut EvoGymEnv> = extra.iter_mut().collect();
        more.push(&mut a);
        let five: Vec<&[f64]> = vec![&good; 5];
        assert!(lanes.step(&mut more, &five).is_err(), "more environments than lanes");
        let other = EvoGymEnv::new(EvoGymTask::Walker, &MaterialGrid::from_rows("333/333").unwrap()).unwrap();
        assert!(!lanes.fits(&other));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(12))]

        /// Random grids of up to 4 × 4 cells with random actions, four environments in lanes:
        /// either refused as robots, or every lane answers as alone, finite.
        #[test]
        fn random_robots_in_lanes_stay_finite_and_match_alone(
            w in 1usize..=4,
            h in 1usize..=4,
            codes in prop::collection::vec(0u64..=4, 16),
            seed in 0u64..1000,
        ) {
            let cells = codes[..w * h].iter().map(|&c| Material::from_code(c).unwrap()).collect();
            let grid = MaterialGrid::new(w, h, cells).unwrap();
            if EvoGymEnv::new(EvoGymTask::Walker, &grid).is_err() {
                prop_assert!(grid.validate_robot().is_err());
                return Ok(());
            }
            alone_and_in_lanes(EvoGymTask::Walker, &grid, 4, 15, (-1.0, 3.0), seed);
        }
    }
}
