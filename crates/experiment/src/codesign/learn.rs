//! One inner loop of the co-design: PPO trains a policy for one body on one EvoGym task, and
//! off-line episodes of its mean action measure what it learned (thesis §5.2.4, eq. 5.7, and the
//! learning curves of §5.2.5.6).

use crate::learning_env::EvoGymLearning;
use vsrlab_brain::{BrainSpec, PolicySpec, TargetAction};
use vsrlab_learning::mean_policy::{self, MeanPolicy};
use vsrlab_learning::{Environment, Ppo, PpoConfig, PpoError};
use vsrlab_tasks::kinds::evogym::{
    EvoGymError, EvoGymRobot, EvoGymTask, MaterialGrid, LANES, TARGET_CENTRE, TARGET_HALF_RANGE, TARGET_RANGE,
};

/// The name of the learning curve among an evaluation's series: the off-line reward per step
/// before training and after each PPO iteration (`iterations + 1` values).
pub const LEARNING_CURVE: &str = "learning_curve";

/// The name of the training rewards among an evaluation's series: the mean reward per step of
/// each iteration's rollouts (noisy actions; `iterations` values, always recorded).
pub const TRAINING_REWARD: &str = "training_reward";

/// What one training gave.
#[derive(Debug, Clone)]
pub struct Learned {
    /// The fitness: the off-line mean reward per step after the last iteration.
    pub fitness: f64,
    /// The learning curve (empty unless asked for).
    pub curve: Vec<f64>,
    /// The mean reward per step of each iteration's rollouts.
    pub training: Vec<f64>,
    /// The learner with its final policy.
    pub ppo: Ppo,
}

/// An EvoGym task and the steps of its episodes (its own length, or fewer when the experiment's
/// `task.duration` says so).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Episode {
    /// The task.
    pub task: EvoGymTask,
    /// Steps of an episode (n_sim).
    pub steps: usize,
}

/// Why a body could not be trained.
#[derive(Debug, thiserror::Error)]
pub enum LearnError {
    /// The body does not make an environment of the task.
    #[error(transparent)]
    Environment(#[from] EvoGymError),
    /// PPO refused its settings or stopped (an environment's step, a non-finite value).
    #[error(transparent)]
    Ppo(#[from] PpoError),
    /// The settings asked for no iteration, so there is no policy to score.
    #[error("PPO ran no iteration")]
    NoIteration,
}

/// Trains PPO (`config`, `config.environments` copies of the task stepped in parallel) for
/// `body` on `episode`'s task from `seed`. With `curve`, an off-line episode after every iteration (and
/// before the first) gives the learning curve; otherwise only the last one is run. An episode's
/// reward per step divides its total by the episode's full length (eq. 5.7's n_sim), also when
/// it ended early.
pub fn learn(
    body: &MaterialGrid,
    episode: Episode,
    config: &PpoConfig,
    curve: bool,
    seed: u64,
) -> Result<Learned, LearnError> {
    let Episode { task, steps } = episode;
    let env = EvoGymLearning::new(task, body)?.with_episode_steps(steps);
    let mut ppo = Ppo::new(env.observation_size(), env.action_size(), config.clone(), seed)?;
    let mut environments = vec![env.clone(); config.environments];
    let offline = env;
    // the off-line episodes wait for a lane group's worth of policies (the last one does not
    // wait) and run together, each with the bits of its episode alone
    let mut waiting: Vec<MeanPolicy> = Vec::new();
    let mut points = Vec::new();
    let mut run_waiting = |waiting: &mut Vec<MeanPolicy>| -> Result<(), PpoError> {
        let results = mean_policy::episodes(waiting, &offline, seed, steps);
        waiting.clear();
        for result in results {
            let (total, _) = result?;
            points.push(total / steps as f64);
        }
        Ok(())
    };
    let trained = ppo.train_observed(&mut environments, |p, stats| {
        let last = stats.is_some_and(|s| s.iteration + 1 == config.iterations);
        if curve || last {
            waiting.push(MeanPolicy::of(p));
            if waiting.len() == LANES || last {
                run_waiting(&mut waiting)?;
            }
        }
        Ok::<(), PpoError>(())
    });
    // an iteration that failed came after the episodes still waiting: their error comes first
    run_waiting(&mut waiting)?;
    let stats = trained?;
    let fitness = *points.last().ok_or(LearnError::NoIteration)?;
    Ok(Learned {
        fitness,
        curve: if curve { points } else { Vec::new() },
        training: stats.iter().map(|s| s.mean_reward).collect(),
        ppo,
    })
}

/// The learned policy as a brain of an EvoGym robot: its mean action a drives an actuator to
/// EvoGym's target 1 + a clipped into [0.6, 1.6] (the learning environment's), given to the robot
/// as the actuation o whose target 1.1 + 0.5 o is that one to the last bit.
pub fn policy_brain(ppo: &Ppo) -> BrainSpec {
    let sizes = ppo.actor().sizes();
    BrainSpec::Policy(PolicySpec {
        hidden: sizes[1..sizes.len() - 1].to_vec(),
        mean: ppo.normalizer().mean().to_vec(),
        var: ppo.normalizer().var().to_vec(),
        scale: None,
        offset: None,
        target: Some(TargetAction {
            shift: 1.0,
            low: TARGET_RANGE.0,
            high: TARGET_RANGE.1,
            centre: TARGET_CENTRE,
            half_range: TARGET_HALF_RANGE,
        }),
        weights: ppo.actor().parameters.clone(),
    })
}

/// The robot a training made: the body with its learned policy, on the episode's task.
pub fn learned_robot(body: &MaterialGrid, episode: Episode, ppo: &Ppo) -> EvoGymRobot {
    EvoGymRobot {
        body: body.to_rows(),
        env: episode.task.name().to_string(),
        brain: policy_brain(ppo),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vsrlab_tasks::registry::TaskSpec;
    use vsrlab_tasks::TraceLevel;

    /// The learning curve, whose off-line episodes wait and run in lane groups, has the bits of
    /// the episodes run one by one after each iteration; an error-free training of 6 iterations
    /// gives 7 points (two groups: 4, then 3 with the last).
    #[test]
    fn the_learning_curve_run_in_groups_is_the_curve_run_one_by_one() {
        let body = MaterialGrid::from_rows("33333/34443/30003/40004/40004").unwrap();
        let episode = Episode {
            task: EvoGymTask::Walker,
            steps: 40,
        };
        let config = PpoConfig {
            iterations: 6,
            environments: 2,
            steps_per_environment: 16,
            hidden: vec![8],
            initial_log_std: 1.0,
            ..PpoConfig::default()
        };
        let learned = learn(&body, episode, &config, true, 5).unwrap();
        let env = EvoGymLearning::new(episode.task, &body).unwrap().with_episode_steps(40);
        let mut ppo = Ppo::new(env.observation_size(), env.action_size(), config.clone(), 5).unwrap();
        let (mut environments, mut offline) = (vec![env.clone(); 2], env);
        let mut one_by_one = Vec::new();
        ppo.train_observed(&mut environments, |p, _| {
            let (total, _) = p.episode(&mut offline, 5, 40)?;
            one_by_one.push((total / 40.0).to_bits());
            Ok(())
        })
        .unwrap();
        let grouped: Vec<u64> = learned.curve.iter().map(|v| v.to_bits()).collect();
        assert_eq!(grouped.len(), 7);
        assert_eq!(grouped, one_by_one);
        assert_eq!(learned.fitness.to_bits(), one_by_one[6]);
        let mut distinct = grouped.clone();
        distinct.sort_unstable();
        distinct.dedup();
        assert!(distinct.len() > 1, "the policy changed the episodes");
    }

    /// The saved robot replays, on the task, to the very reward its fitness came from: the
    /// policy brain gives the robot EvoGym's clipped target bit for bit (before, the robot's
    /// 1.1 + 0.5·clamp(2a − 0.2, −1, 1) missed 1 + a in the last bit, and a long BeamToppler
    /// episode drifted by 0.19 %). Wide initial actions reach both ends of the range.
    #[test]
    fn a_learned_robot_replays_its_fitness_bit_for_bit() {
        let body = MaterialGrid::from_rows("33333/34443/30003/40004/40004").unwrap();
        let steps = 150;
        let episode = Episode {
            task: EvoGymTask::BeamToppler,
            steps,
        };
        let config = PpoConfig {
            iterations: 2,
            environments: 2,
            steps_per_environment: 32,
            hidden: vec![16],
            initial_log_std: 1.0,
            ..PpoConfig::default()
        };
        let learned = learn(&body, episode, &config, false, 7).unwrap();
        let robot = learned_robot(&body, episode, &learned.ppo);
        let duration = steps as f64 * vsrlab_tasks::kinds::evogym::STEP_SECONDS;
        let task = TaskSpec::parse("evogym:BeamToppler-v0")
            .unwrap()
            .with_settings(&[("duration", serde_json::json!(duration))])
            .unwrap();
        let replay = vsrlab_tasks::episode::run(&robot, task.task(), 7, TraceLevel::None).unwrap();
        assert_eq!(replay.metrics["steps"], steps as f64);
        let total = replay.metrics["reward"];
        assert_eq!(
            (total / steps as f64).to_bits(),
            learned.fitness.to_bits(),
            "replayed {total} / {steps} vs learned {}",
            learned.fitness
        );
    }
}
