//! EvoGym's tasks as environments for PPO (`vsrlab_learning`): one robot body on one task,
//! stepped with the policy's actions, an episode ending when the task ends it (goal,
//! instability) or at its length. As EvoGym's Python environments (`EvoGymBase.step` adds 1 to
//! the policy's output, commit 7db4202 `evogym/envs/base.py`), an action is an offset from the
//! rest length: output a becomes target ratio 1 + a, which the task clips into [0.6, 1.6].

use vsrlab_learning::{Environment, StepError, Transition};
use vsrlab_tasks::kinds::evogym::{EvoGymEnv, EvoGymError, EvoGymTask, MaterialGrid};

/// An EvoGym task with one body, as a PPO environment.
#[derive(Debug, Clone)]
pub struct EvoGymLearning {
    env: EvoGymEnv,
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
        for (target, a) in self.targets.iter_mut().zip(action) {
            *target = 1.0 + a;
        }
        let step = self.env.step(&self.targets)?;
        self.steps += 1;
        let capped = self.cap.is_some_and(|cap| self.steps >= cap);
        Ok(Transition {
            observation: step.observation.to_vec(),
            reward: step.reward,
            done: step.done || step.truncated || capped,
            truncated: !step.done && (step.truncated || capped),
        })
    }
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
}
