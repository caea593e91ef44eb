//! Episodes stepped from Python: one ([`PyEpisode`], behind `gymnasium.make("vsrlab/…")`) or
//! many at once in Rust threads ([`PyVectorEpisode`], behind the vectorised environment).
//!
//! Observation: the robot's sensor readings; action: one value in [-1, 1] per actuator, applied
//! for the next physics step; reward: the step's Δx of the point locomotion measures (a voxel
//! robot's mean voxel-polygon centre, `Body::outcome_center`), so that the rewards add up to the
//! task's distance; terminated: the task stopped the episode; truncated: its duration is over.

use crate::robot::{task_spec, PyRobot};
use crate::{action_rows, value_error};
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use rayon::prelude::*;
use std::sync::Mutex;
use vsrlab_tasks::AnyRobot;
use vsrlab_tasks::{Episode, EpisodeError, TaskSpec, TraceLevel};

/// One environment: the robot, the task and the running episode.
struct Env {
    robot: AnyRobot,
    task: TaskSpec,
    level: TraceLevel,
    episode: Episode,
    /// Where the measured point was after the last step; none before the first step, which earns
    /// nothing: the task's distance counts from the first observation, after the first step (as
    /// the original's `Outcome`), and the rewards add up to it.
    last_x: Option<f64>,
    /// The seed of the running episode (automatic resets derive the next one from it).
    seed: u64,
}

/// What one step returns.
struct StepResult {
    reward: f64,
    terminated: bool,
    truncated: bool,
}

impl Env {
    fn new(robot: AnyRobot, task: TaskSpec, seed: u64, level: TraceLevel) -> Result<Env, EpisodeError> {
        let episode = start(&robot, &task, seed, level)?;
        Ok(Env {
            robot,
            task,
            level,
            episode,
            last_x: None,
            seed,
        })
    }

    fn reset(&mut self, seed: u64) -> Result<(), EpisodeError> {
        self.episode = start(&self.robot, &self.task, seed, self.level)?;
        self.last_x = None;
        self.seed = seed;
        Ok(())
    }

    fn step(&mut self, actions: &[f64]) -> Result<StepResult, EpisodeError> {
        if let Some(i) = actions.iter().position(|a| !a.is_finite()) {
            return Err(EpisodeError::Invalid(format!(
                "actions: value {i} is {} (actions must be finite, in [-1, 1])",
                actions[i]
            )));
        }
        self.episode.step(Some(actions))?;
        let x = self.episode.outcome_center().x;
        let reward = self.last_x.map_or(0.0, |last| x - last);
        self.last_x = Some(x);
        let terminated = self.episode.stopped_by_task();
        Ok(StepResult {
            reward,
            terminated,
            truncated: !terminated && self.episode.is_over(),
        })
    }

    fn done(&self) -> bool {
        self.episode.is_over()
    }
}

/// A new episode with its first sensor reading.
fn start(robot: &AnyRobot, task: &TaskSpec, seed: u64, level: TraceLevel) -> Result<Episode, EpisodeError> {
    let rigid = task.task().rigid().ok_or_else(|| {
        EpisodeError::Field(vsrlab_tasks::FieldError::new(
            "task",
            format!(
                "{} episodes run whole on their own engine; step them with vsrlab.simulate, not an Episode",
                task.task().kind()
            ),
        ))
    })?;
    let mut e = Episode::new(robot.as_robot(), rigid, seed, level)?;
    e.sense();
    Ok(e)
}

/// The actions of a 1-D array, checked for length.
fn actions_of<'a>(actions: &'a PyReadonlyArray1<'_, f64>, expected: usize) -> PyResult<&'a [f64]> {
    let a = actions
        .as_slice()
        .map_err(|_| value_error("actions: a contiguous 1-D float64 array is needed"))?;
    if a.len() != expected {
        return Err(value_error(format!(
            "actions: {} values for a robot with {expected} actuators",
            a.len()
        )));
    }
    Ok(a)
}

/// An episode of a robot on a task, stepped from Python (the core of the Gymnasium environment).
#[pyclass(name = "Episode", module = "vsrlab")]
pub struct PyEpisode {
    env: Mutex<Env>,
    observation_size: usize,
    action_size: usize,
}

impl PyEpisode {
    fn env(&self) -> std::sync::MutexGuard<'_, Env> {
        self.env.lock().unwrap_or_else(|p| p.into_inner())
    }
}

#[pymethods]
impl PyEpisode {
    /// `task` as in `simulate` (a short form or an experiment file); `render` keeps what frames
    /// are drawn from (costs memory and time).
    #[new]
    #[pyo3(signature = (robot, task = "locomotion:flat", duration = None, seed = 0, render = false))]
    fn new(robot: &PyRobot, task: &str, duration: Option<f64>, seed: u64, render: bool) -> PyResult<Self> {
        let spec = task_spec(task, duration)?;
        let level = if render { TraceLevel::Full } else { TraceLevel::None };
        let env = Env::new(robot.robot.clone(), spec, seed, level).map_err(value_error)?;
        let observation_size = env.episode.agent().readings().len();
        let action_size = env.episode.agent().action_count();
        Ok(PyEpisode {
            env: Mutex::new(env),
            observation_size,
            action_size,
        })
    }

    /// Number of sensor readings per observation.
    #[getter]
    fn observation_size(&self) -> usize {
        self.observation_size
    }

    /// Number of actuation values per action.
    #[getter]
    fn action_size(&self) -> usize {
        self.action_size
    }

    /// Simulated time (s).
    #[getter]
    fn time(&self) -> f64 {
        self.env().episode.time()
    }

    /// The episode's length (s).
    #[getter]
    fn duration(&self) -> f64 {
        self.env().episode.duration()
    }

    /// Starts a new episode with this seed (terrain, noise) and returns its first observation.
    fn reset<'py>(&self, py: Python<'py>, seed: u64) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let mut env = self.env();
        env.reset(seed).map_err(value_error)?;
        Ok(PyArray1::from_slice(py, env.episode.agent().readings()))
    }

    /// The current observation.
    fn observation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.env().episode.agent().readings())
    }

    /// One step: returns (observation, reward, terminated, truncated).
    #[allow(clippy::type_complexity)]
    fn step<'py>(
        &self,
        py: Python<'py>,
        actions: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<(Bound<'py, PyArray1<f64>>, f64, bool, bool)> {
        let a = actions_of(&actions, self.action_size)?;
        let mut env = self.env();
        if env.done() {
            return Err(value_error("the episode is over: call reset() first"));
        }
        let r = env.step(a).map_err(value_error)?;
        let obs = PyArray1::from_slice(py, env.episode.agent().readings());
        Ok((obs, r.reward, r.terminated, r.truncated))
    }

    /// The task's metrics so far (distance, velocity, …).
    fn metrics(&self) -> std::collections::BTreeMap<String, f64> {
        self.env().episode.metrics().into_iter().collect()
    }

    /// The current frame as an RGB array (height × width × 3, uint8), drawn like the CLI's
    /// videos; needs `render=True`.
    fn render<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<u8>>> {
        let env = self.env();
        let trace = env
            .episode
            .trace()
            .ok_or_else(|| value_error("render: this episode was made with render=False"))?;
        rgb_frame(py, trace)
    }
}

/// The last frame of `trace` as an RGB array (height × width × 3, uint8), drawn like the CLI's
/// videos; a blank frame of the right size before the first step.
pub(crate) fn rgb_frame<'py>(py: Python<'py>, trace: &vsrlab_tasks::Trace) -> PyResult<Bound<'py, PyArray3<u8>>> {
    let options = vsrlab_render::RenderOptions::default();
    let step = trace.times.len().saturating_sub(1);
    let pixmap = if trace.times.is_empty() {
        vsrlab_render::Pixmap::new(options.width, options.height).ok_or_else(|| value_error("render: empty frame"))?
    } else {
        vsrlab_render::render_frame(trace, step, &options)
    };
    let (w, h) = (pixmap.width() as usize, pixmap.height() as usize);
    let rgb: Vec<u8> = pixmap.data().chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
    PyArray1::from_vec(py, rgb).reshape([h, w, 3])
}

/// Many episodes of one robot and task stepped together on Rust threads (the GIL released):
/// the core of the vectorised Gymnasium environment. An episode that ended is reset at the next
/// step, which ignores its action and returns its first observation (Gymnasium's next-step
/// autoreset).
#[pyclass(name = "VectorEpisode", module = "vsrlab")]
pub struct PyVectorEpisode {
    envs: Mutex<Vec<Env>>,
    observation_size: usize,
    action_size: usize,
}

#[pymethods]
impl PyVectorEpisode {
    /// `count` episodes; episode i starts with seed `seed + i`.
    #[new]
    #[pyo3(signature = (robot, count, task = "locomotion:flat", duration = None, seed = 0))]
    fn new(robot: &PyRobot, count: usize, task: &str, duration: Option<f64>, seed: u64) -> PyResult<Self> {
        if count == 0 {
            return Err(value_error("count: at least one episode"));
        }
        let spec = task_spec(task, duration)?;
        let envs = (0..count as u64)
            .map(|i| Env::new(robot.robot.clone(), spec.clone(), seed + i, TraceLevel::None))
            .collect::<Result<Vec<_>, _>>()
            .map_err(value_error)?;
        let observation_size = envs[0].episode.agent().readings().len();
        let action_size = envs[0].episode.agent().action_count();
        Ok(PyVectorEpisode {
            envs: Mutex::new(envs),
            observation_size,
            action_size,
        })
    }

    /// Number of episodes.
    #[getter]
    fn count(&self) -> usize {
        self.envs.lock().map(|e| e.len()).unwrap_or(0)
    }

    /// Number of sensor readings per observation.
    #[getter]
    fn observation_size(&self) -> usize {
        self.observation_size
    }

    /// Number of actuation values per action.
    #[getter]
    fn action_size(&self) -> usize {
        self.action_size
    }

    /// Starts every episode anew, episode i with seed `seed + i`; returns the observations.
    fn reset<'py>(&self, py: Python<'py>, seed: u64) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let mut guard = self.envs.lock().unwrap_or_else(|p| p.into_inner());
        let envs: &mut Vec<Env> = &mut guard;
        py.detach(|| {
            envs.par_iter_mut()
                .enumerate()
                .try_for_each(|(i, e)| e.reset(seed + i as u64))
        })
        .map_err(value_error)?;
        observations(py, envs, self.observation_size)
    }

    /// One step of every episode: `actions` is (count, action_size); returns (observations,
    /// rewards, terminated, truncated) as arrays.
    #[allow(clippy::type_complexity)]
    fn step<'py>(
        &self,
        py: Python<'py>,
        actions: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<(
        Bound<'py, PyArray2<f64>>,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<bool>>,
        Bound<'py, PyArray1<bool>>,
    )> {
        let mut guard = self.envs.lock().unwrap_or_else(|p| p.into_inner());
        let envs: &mut Vec<Env> = &mut guard;
        let n = envs.len();
        let a = action_rows(&actions, n, self.action_size)?;
        let width = self.action_size;
        let results: Vec<StepResult> = py
            .detach(|| {
                envs.par_iter_mut()
                    .zip(a.par_chunks(width))
                    .map(|(e, act)| {
                        if e.done() {
                            let next = e.seed.wrapping_add(n as u64);
                            e.reset(next)?;
                            Ok(StepResult {
                                reward: 0.0,
                                terminated: false,
                                truncated: false,
                            })
                        } else {
                            e.step(act)
                        }
                    })
                    .collect::<Result<Vec<_>, EpisodeError>>()
            })
            .map_err(value_error)?;
        let obs = observations(py, envs, self.observation_size)?;
        let rewards: Vec<f64> = results.iter().map(|r| r.reward).collect();
        let terminated: Vec<bool> = results.iter().map(|r| r.terminated).collect();
        let truncated: Vec<bool> = results.iter().map(|r| r.truncated).collect();
        Ok((
            obs,
            PyArray1::from_vec(py, rewards),
            PyArray1::from_vec(py, terminated),
            PyArray1::from_vec(py, truncated),
        ))
    }
}

/// The observations of every episode as a (count, size) array.
fn observations<'py>(py: Python<'py>, envs: &[Env], size: usize) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = envs
        .iter()
        .flat_map(|e| e.episode.agent().readings().iter().copied())
        .collect();
    PyArray1::from_vec(py, flat).reshape([envs.len(), size])
}
