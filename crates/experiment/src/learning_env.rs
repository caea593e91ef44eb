//! EvoGym's tasks as environments for PPO (`vsrlab_learning`): one robot body on one task,
//! stepped with the policy's actions, an episode ending when the task ends it (goal,
//! instability) or at its length. As EvoGym's Python environments (`EvoGymBase.step` adds 1 to
//! the policy's output, commit 7db4202 `evogym/envs/base.py`), an action is an offset from the
//! rest length: output a becomes target ratio 1 + a, which the task clips into [0.6, 1.6].

use rayon::prelude::*;
use vsrlab_learning::{Environment, StepError, Transition};
use vsrlab_tasks::kinds::evogym::{EnvLanes, EvoGymEnv, EvoGymError, EvoGymTask, LaneStep, MaterialGrid, LANES};

/// An EvoGym task with one body, as a PPO environment.
#[derive(Debug, Clone)]
pub struct EvoGymLearning {
    env: EvoGymEnv,
    /// The lanes of the group this environment leads in [`Environment::step_all`] (made at the
    /// first group step).
    lanes: Option<Box<EnvLanes>>,
    /// The policy's action shifted to EvoGym's units.
    targets: Vec<f64>,
    /// Steps after which an episode ends, when fewer than the task's own length.
    cap: Option<usize>,
    /// Steps of the current episode.
    steps: usize,
}

impl EvoGymLearning {
    /// `body` on `task`.
    pub fn new(task: EvoGymTask, body: &MaterialGrid) -> Result<EvoGymLearning, EvoGymError> {
        let env = EvoGymEnv::new(task, body)?;
        Ok(EvoGymLearning {
            targets: vec![1.0; env.action_count()],
            env,
            lanes: None,
            cap: None,
            steps: 0,
        })
    }

    /// The same with episodes ending after at most `steps` steps (a task's `duration`).
    pub fn with_episode_steps(mut self, steps: usize) -> EvoGymLearning {
        self.cap = Some(steps);
        self
    }
}

impl Environment for EvoGymLearning {
    fn observation_size(&self) -> usize {
        self.env.observation_size()
    }

    fn action_size(&self) -> usize {
        self.env.action_count()
    }

    fn reset(&mut self, seed: u64) -> Vec<f64> {
        self.steps = 0;
        self.env.reset(seed).to_vec()
    }

    fn step(&mut self, action: &[f64]) -> Result<Transition, StepError> {
        self.set_targets(action);
        let step = self.env.step(&self.targets)?;
        let (reward, done, truncated) = (step.reward, step.done, step.truncated);
        Ok(self.transition(reward, done, truncated))
    }

    /// Groups of up to four environments of one body step in population lanes (the same bits as
    /// alone), the groups in parallel.
    fn step_all(environments: &mut [Self], actions: &[Vec<f64>]) -> Vec<Result<Transition, StepError>> {
        environments
            .par_chunks_mut(LANES)
            .zip(actions.par_chunks(LANES))
            .flat_map_iter(|(group, actions)| step_group(group, actions))
            .collect()
    }
}

impl EvoGymLearning {
    /// The targets of the policy's action (EvoGym's offset from the rest length).
    fn set_targets(&mut self, action: &[f64]) {
        for (target, a) in self.targets.iter_mut().zip(action) {
            *target = 1.0 + a;
        }
    }

    /// The transition of a step that gave `reward`, `done` and `truncated` (the observation is
    /// the environment's), counting it against the cap.
    fn transition(&mut self, reward: f64, done: bool, truncated: bool) -> Transition {
        self.steps += 1;
        let capped = self.cap.is_some_and(|cap| self.steps >= cap);
        Transition {
            observation: self.env.observation().to_vec(),
            reward,
            done: done || truncated || capped,
            truncated: !done && (truncated || capped),
        }
    }
}

/// One step of a group of environments in lanes, led by the first (which keeps the lanes); a
/// group that does not fit the lanes (another body) steps one by one.
fn step_group(group: &mut [EvoGymLearning], actions: &[Vec<f64>]) -> Vec<Result<Transition, StepError>> {
    if group.len() < 3 {
        // fewer worlds than lanes cost as many as a full group: alone is as fast
        return group
            .iter_mut()
            .zip(actions)
            .map(|(env, action)| env.step(action))
            .collect();
    }
    for (env, action) in group.iter_mut().zip(actions) {
        env.set_targets(action);
    }
    let mut lanes = match group[0].lanes.take() {
        Some(lanes) if group.iter().all(|g| lanes.fits(&g.env)) => lanes,
        _ => Box::new(EnvLanes::new(&group[0].env)),
    };
    let steps = {
        let (mut envs, targets): (Vec<&mut EvoGymEnv>, Vec<&[f64]>) =
            group.iter_mut().map(|g| (&mut g.env, g.targets.as_slice())).unzip();
        lanes.step(&mut envs, &targets)
    };
    group[0].lanes = Some(lanes);
    let steps: Vec<Result<LaneStep, EvoGymError>> = match steps {
        Ok(steps) => steps,
        Err(_) => {
            // environments the lanes cannot take together (not expected of one training)
            return group
                .iter_mut()
                .zip(actions)
                .map(|(env, action)| env.step(action))
                .collect();
        }
    };
    group
        .iter_mut()
        .zip(steps)
        .map(|(env, step)| {
            let step = step?;
            Ok(env.transition(step.reward, step.done, step.truncated))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use vsrlab_learning::{Ppo, PpoConfig};

    fn walker() -> EvoGymLearning {
        let body = MaterialGrid::from_rows("33333/33333/33333/33333/33333").unwrap();
        EvoGymLearning::new(EvoGymTask::Walker, &body).unwrap()
    }

    #[test]
    fn steps_are_evogyms_and_an_episode_ends_at_its_length() {
        let mut env = walker();
        assert_eq!((env.observation_size(), env.action_size()), (74, 25));
        let first = env.reset(0);
        let mut direct = EvoGymEnv::new(
            EvoGymTask::Walker,
            &MaterialGrid::from_rows("33333/33333/33333/33333/33333").unwrap(),
        )
        .unwrap();
        assert_eq!(first, direct.reset(0));
        // a policy output of 0.6 is EvoGym's target 1.6
        let (action, target) = (vec![0.6; 25], vec![1.6; 25]);
        let mut steps = 0;
        loop {
            let ours = env.step(&action).unwrap();
            let theirs = direct.step(&target).unwrap();
            assert_eq!(
                (ours.reward, ours.observation.as_slice()),
                (theirs.reward, theirs.observation)
            );
            steps += 1;
            if ours.done {
                break;
            }
        }
        assert_eq!(steps, EvoGymTask::Walker.episode_steps());
        let mut short = walker().with_episode_steps(7);
        for episode in 0..2 {
            short.reset(episode);
            let ends: Vec<bool> = (0..7).map(|_| short.step(&action).unwrap().done).collect();
            assert_eq!(ends, [false, false, false, false, false, false, true]);
        }
    }

    #[test]
    fn ppo_trains_a_walker_deterministically() {
        let config = PpoConfig {
            iterations: 2,
            steps_per_environment: 32,
            ..PpoConfig::default()
        };
        let train = || {
            let mut ppo = Ppo::new(74, 25, config.clone(), 3).unwrap();
            let mut envs = vec![walker(), walker()];
            let stats = ppo.train(&mut envs).unwrap();
            (format!("{stats:?}"), ppo.act(&envs[0].reset(0)))
        };
        let (stats, action) = train();
        assert!(action.iter().all(|a| a.is_finite()) && stats.contains("mean_reward"));
        assert_eq!(train(), (stats, action));
    }

    /// An EvoGym environment that steps alone even in a group (the default `step_all`).
    struct Alone(EvoGymLearning);

    impl Environment for Alone {
        fn observation_size(&self) -> usize {
            self.0.observation_size()
        }
        fn action_size(&self) -> usize {
            self.0.action_size()
        }
        fn reset(&mut self, seed: u64) -> Vec<f64> {
            self.0.reset(seed)
        }
        fn step(&mut self, action: &[f64]) -> Result<Transition, StepError> {
            self.0.step(action)
        }
    }

    /// Seven environments (a group of four in lanes, one of three, the episodes capped so that
    /// they end and restart within the rollout) train the same policy as seven stepped alone.
    #[test]
    fn ppo_with_environments_in_lanes_learns_what_it_learns_alone() {
        let body = MaterialGrid::from_rows("3333/3003/3333").unwrap();
        let make = || {
            EvoGymLearning::new(EvoGymTask::Walker, &body)
                .unwrap()
                .with_episode_steps(13)
        };
        let config = PpoConfig {
            iterations: 2,
            steps_per_environment: 20,
            ..PpoConfig::default()
        };
        let mut laned: Vec<EvoGymLearning> = (0..7).map(|_| make()).collect();
        let mut alone: Vec<Alone> = (0..7).map(|_| Alone(make())).collect();
        let size = (laned[0].observation_size(), laned[0].action_size());
        let (mut a, mut b) = (
            Ppo::new(size.0, size.1, config.clone(), 5).unwrap(),
            Ppo::new(size.0, size.1, config, 5).unwrap(),
        );
        let (stats_laned, stats_alone) = (a.train(&mut laned).unwrap(), b.train(&mut alone).unwrap());
        assert_eq!(format!("{stats_laned:?}"), format!("{stats_alone:?}"));
        let probe = laned[0].reset(1);
        let (act_a, act_b) = (a.act(&probe), b.act(&probe));
        assert_eq!(
            act_a.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            act_b.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
        );
        assert!(
            laned[0].lanes.is_some() && laned[4].lanes.is_some(),
            "both groups stepped in lanes"
        );
    }
}
