//! EvoGym's tasks stepped from Python ([`PyEvoGymEnv`], behind `gymnasium.make("vsrlab/Walker-v0")`
//! and every other task of [`evogym_tasks`]): EvoGym's observation, action (one target length ratio in [0.6, 1.6] per
//! actuator voxel), reward and ends, on vsrlab's mass-spring engine (docs/multimaterial.md).

use crate::value_error;
use numpy::{PyArray1, PyArray3, PyReadonlyArray1};
use pyo3::prelude::*;
use std::sync::Mutex;
use vsrlab_tasks::kinds::evogym::{EvoGymEnv, EvoGymTask, MaterialGrid};

/// The EvoGym ids vsrlab implements, in EvoGym's registration order (the gym ids are these
/// under `vsrlab/`).
#[pyfunction]
pub fn evogym_tasks() -> Vec<&'static str> {
    EvoGymTask::ALL.iter().map(|t| t.name()).collect()
}

/// One EvoGym task with one robot.
#[pyclass(name = "EvoGymEnv", module = "vsrlab")]
pub struct PyEvoGymEnv {
    env: Mutex<EvoGymEnv>,
    observation_size: usize,
    action_size: usize,
}

impl PyEvoGymEnv {
    fn env(&self) -> std::sync::MutexGuard<'_, EvoGymEnv> {
        self.env.lock().unwrap_or_else(|p| p.into_inner())
    }
}

#[pymethods]
impl PyEvoGymEnv {
    /// `task`: an EvoGym id that vsrlab implements (`evogym_tasks()`: `Walker-v0`, …); `body`:
    /// the material grid as rows of digits 0-4 joined by `/`, top row first.
    #[new]
    fn new(task: &str, body: &str) -> PyResult<Self> {
        let which =
            EvoGymTask::from_name(task).ok_or_else(|| value_error(format!("task: {}", EvoGymTask::unknown(task))))?;
        let grid = MaterialGrid::from_rows(body).map_err(|e| value_error(e.at("body")))?;
        let env = EvoGymEnv::new(which, &grid).map_err(|e| value_error(format!("body: {e}")))?;
        Ok(PyEvoGymEnv {
            observation_size: env.observation_size(),
            action_size: env.action_count(),
            env: Mutex::new(env),
        })
    }

    /// Number of values per observation.
    #[getter]
    fn observation_size(&self) -> usize {
        self.observation_size
    }

    /// Number of actions: one per actuator voxel.
    #[getter]
    fn action_size(&self) -> usize {
        self.action_size
    }

    /// Steps taken in this episode.
    #[getter]
    fn steps(&self) -> usize {
        self.env().steps()
    }

    /// Back to the start; returns the first observation. `seed` draws what the task draws at
    /// reset (BidirectionalWalker's goals, Catcher's world); the other tasks have no randomness.
    #[pyo3(signature = (seed = 0))]
    fn reset<'py>(&self, py: Python<'py>, seed: u64) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.env().reset(seed))
    }

    /// One step with one action per actuator (EvoGym clips them into [0.6, 1.6]): returns
    /// (observation, reward, terminated, truncated, unstable).
    #[allow(clippy::type_complexity)]
    fn step<'py>(
        &self,
        py: Python<'py>,
        actions: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<(Bound<'py, PyArray1<f64>>, f64, bool, bool, bool)> {
        let a = actions
            .as_slice()
            .map_err(|_| value_error("actions: a contiguous 1-D float64 array is needed"))?;
        if a.len() != self.action_size {
            return Err(value_error(format!(
                "actions: {} values for a robot with {} actuators",
                a.len(),
                self.action_size
            )));
        }
        let mut env = self.env();
        let r = env.step(a).map_err(|e| value_error(format!("actions: {e}")))?;
        let obs = PyArray1::from_slice(py, r.observation);
        Ok((obs, r.reward, r.done, r.truncated, r.unstable))
    }

    /// The current state as an RGB array (height × width × 3, uint8), drawn without OpenGL as
    /// the CLI's videos are (Gymnasium's `render_mode="rgb_array"`).
    fn render<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<u8>>> {
        let trace = vsrlab_tasks::kinds::evogym::frame(&self.env());
        crate::episode::rgb_frame(py, &trace)
    }
}
