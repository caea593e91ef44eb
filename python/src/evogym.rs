//! EvoGym's tasks stepped from Python ([`PyEvoGymEnv`], behind `gymnasium.make("vsrlab/Walker-v0")`
//! and every other task of [`evogym_tasks`]): EvoGym's observation, action (one target length ratio in [0.6, 1.6] per
//! actuator voxel), reward and ends, on vsrlab's mass-spring engine (docs/multimaterial.md).

use crate::{action_rows, value_error};
use numpy::PyReadonlyArray2;
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use rayon::prelude::*;
use std::sync::Mutex;
use vsrlab_tasks::kinds::evogym::{
    world_from_json, EnvLanes, EvoGymEnv, EvoGymError, EvoGymSim, EvoGymTask, MaterialGrid, Orientation, CELL, LANES,
};

/// The EvoGym ids vsrlab implements, in EvoGym's registration order (the gym ids are these
/// under `vsrlab/`).
#[pyfunction]
pub fn evogym_tasks() -> Vec<&'static str> {
    EvoGymTask::ALL.iter().map(|t| t.name()).collect()
}

/// The steps of an episode of EvoGym task `task` (its `max_episode_steps`).
#[pyfunction]
pub fn evogym_episode_steps(task: &str) -> PyResult<usize> {
    EvoGymTask::from_name(task)
        .map(|t| t.episode_steps())
        .ok_or_else(|| value_error(format!("task: {}", EvoGymTask::unknown(task))))
}

/// The environment of EvoGym task `task` with the robot `body` (rows of digits joined by `/`);
/// errors name `task` or `body`.
fn make_env(task: &str, body: &str) -> PyResult<EvoGymEnv> {
    let which =
        EvoGymTask::from_name(task).ok_or_else(|| value_error(format!("task: {}", EvoGymTask::unknown(task))))?;
    let grid = MaterialGrid::from_rows(body).map_err(|e| value_error(e.at("body")))?;
    EvoGymEnv::new(which, &grid).map_err(|e| value_error(format!("body: {e}")))
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
        let env = make_env(task, body)?;
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

/// Checks the text of an EvoGym world file (`EvoWorld.from_json`): a `ValueError` naming the
/// field (`objects.ground.types[3]`, `grid_width`) when it is not a world vsrlab can build.
#[pyfunction]
pub fn evogym_check_world(text: &str) -> PyResult<()> {
    world_from_json(text).map(|_| ()).map_err(value_error)
}

/// A world of EvoGym objects simulated as EvoGym's `EvoSim` (behind `vsrlab.evogym.EvoSim`):
/// robots (objects with actuators) first, then the others, each group by name. Positions and
/// velocities in metres (EvoGym's `EvoSim` divides them by the cell size, 0.1 m).
#[pyclass(name = "EvoGymSim", module = "vsrlab")]
pub struct PyEvoGymSim {
    sim: Mutex<EvoGymSim>,
    /// Each object's orientation reference at the start, by the simulation's object order.
    orientations: Vec<Orientation>,
}

impl PyEvoGymSim {
    fn sim(&self) -> std::sync::MutexGuard<'_, EvoGymSim> {
        self.sim.lock().unwrap_or_else(|p| p.into_inner())
    }
}

/// `values` of the points `range` as a 2 × n array (x row, then y row).
fn rows<'py>(
    py: Python<'py>,
    xs: &[f64],
    ys: &[f64],
    range: std::ops::Range<usize>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let n = range.len();
    let data: Vec<f64> = xs[range.clone()].iter().chain(&ys[range]).copied().collect();
    PyArray1::from_vec(py, data).reshape([2, n])
}

#[pymethods]
impl PyEvoGymSim {
    /// The simulation of the world in `world_json` (EvoGym's world-file format).
    #[new]
    fn new(world_json: &str) -> PyResult<Self> {
        let world = world_from_json(world_json).map_err(value_error)?;
        let sim = EvoGymSim::new(&world).map_err(value_error)?;
        let (xs, ys) = (sim.world().positions_x(), sim.world().positions_y());
        let orientations = sim
            .objects()
            .iter()
            .map(|o| Orientation::new(xs, ys, o.points.clone()))
            .collect();
        Ok(PyEvoGymSim {
            sim: Mutex::new(sim),
            orientations,
        })
    }

    /// The objects in the simulation's order: (name, is a robot, points, actuators).
    fn objects(&self) -> Vec<(String, bool, usize, usize)> {
        self.sim()
            .objects()
            .iter()
            .map(|o| (o.name.clone(), o.robot, o.points.len(), o.actuators.len()))
            .collect()
    }

    /// Sets robot `name`'s targets (one per actuator) for the next steps.
    fn set_action(&self, name: &str, action: PyReadonlyArray1<'_, f64>) -> PyResult<()> {
        let a = action
            .as_slice()
            .map_err(|_| value_error("action: a contiguous 1-D float64 array is needed"))?;
        self.sim().set_action(name, a).map_err(value_error)
    }

    /// One step; `True` when the simulation became unstable.
    fn step(&self) -> PyResult<bool> {
        self.sim().step().map_err(value_error)
    }

    /// Back to the start.
    fn reset(&self) {
        self.sim().reset()
    }

    /// Steps taken since the start.
    #[getter]
    fn steps(&self) -> usize {
        self.sim().steps()
    }

    /// Positions of every point (`name` None) or of object `name`'s, 2 × n, in metres.
    #[pyo3(signature = (name = None))]
    fn positions<'py>(&self, py: Python<'py>, name: Option<&str>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let sim = self.sim();
        let range = self.range(&sim, name)?;
        rows(py, sim.world().positions_x(), sim.world().positions_y(), range)
    }

    /// Velocities of every point (`name` None) or of object `name`'s, 2 × n, in metres per second.
    #[pyo3(signature = (name = None))]
    fn velocities<'py>(&self, py: Python<'py>, name: Option<&str>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let sim = self.sim();
        let range = self.range(&sim, name)?;
        rows(py, sim.world().velocities_x(), sim.world().velocities_y(), range)
    }

    /// Object `name`'s orientation since the start (radians, EvoGym's measure).
    fn orientation(&self, name: &str) -> PyResult<f64> {
        let sim = self.sim();
        let k = sim
            .objects()
            .iter()
            .position(|o| o.name == name)
            .ok_or_else(|| value_error(sim.object(name).err().map_or_else(String::new, |e| e.to_string())))?;
        let (xs, ys) = (sim.world().positions_x(), sim.world().positions_y());
        Ok(self.orientations[k].angle(xs, ys, sim.objects()[k].points.clone()))
    }

    /// The current state as an RGB array (height × width × 3, uint8), drawn without OpenGL.
    fn render<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<u8>>> {
        let trace = vsrlab_tasks::kinds::evogym::sim_frame(&self.sim());
        crate::episode::rgb_frame(py, &trace)
    }

    /// The cell size (m): EvoGym's `EvoSim` reports positions in cells.
    #[classattr]
    fn cell() -> f64 {
        CELL
    }
}

impl PyEvoGymSim {
    fn range(&self, sim: &EvoGymSim, name: Option<&str>) -> PyResult<std::ops::Range<usize>> {
        match name {
            None => Ok(0..sim.world().point_count()),
            Some(n) => sim.object(n).map(|o| o.points.clone()).map_err(value_error),
        }
    }
}

/// One environment of a vector: its episode, the seed of its next reset, and whether its episode
/// ended at the last step.
struct Slot {
    env: EvoGymEnv,
    next_seed: u64,
    ended: bool,
}

/// What a vector's step gave one environment.
#[derive(Clone, Copy, Default)]
struct SlotStep {
    reward: f64,
    terminated: bool,
    truncated: bool,
    unstable: bool,
}

/// `count` environments of one EvoGym task and body stepped together on every core (the GIL
/// released), each group of four in population lanes (the bits of each stepped alone): the core
/// of the vectorised Gymnasium environment. An environment whose episode ended is reset at the
/// next step, which ignores its action and returns its first observation (Gymnasium's next-step
/// autoreset); environment i's episodes take seeds `seed + i`, then `+ count` each time.
#[pyclass(name = "EvoGymVectorEnv", module = "vsrlab")]
pub struct PyEvoGymVectorEnv {
    slots: Mutex<(Vec<Slot>, Vec<Option<EnvLanes>>)>,
    observation_size: usize,
    action_size: usize,
}

#[pymethods]
impl PyEvoGymVectorEnv {
    /// `count` environments of `task` with the robot `body` (rows of digits joined by `/`).
    #[new]
    fn new(task: &str, body: &str, count: usize) -> PyResult<Self> {
        if count == 0 {
            return Err(value_error("num_envs: at least one environment"));
        }
        let env = make_env(task, body)?;
        let (observation_size, action_size) = (env.observation_size(), env.action_count());
        let slots = (0..count as u64)
            .map(|i| Slot {
                env: env.clone(),
                next_seed: i,
                ended: false,
            })
            .collect();
        let lanes = (0..count.div_ceil(LANES)).map(|_| None).collect();
        Ok(PyEvoGymVectorEnv {
            slots: Mutex::new((slots, lanes)),
            observation_size,
            action_size,
        })
    }

    /// Number of environments.
    #[getter]
    fn count(&self) -> usize {
        self.slots.lock().map(|s| s.0.len()).unwrap_or(0)
    }

    /// Values per observation.
    #[getter]
    fn observation_size(&self) -> usize {
        self.observation_size
    }

    /// Actions per environment: one per actuator voxel.
    #[getter]
    fn action_size(&self) -> usize {
        self.action_size
    }

    /// Starts every environment anew, environment i with seed `seed + i`; returns the
    /// observations (count × observation_size).
    fn reset<'py>(&self, py: Python<'py>, seed: u64) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let mut guard = self.slots.lock().unwrap_or_else(|p| p.into_inner());
        let slots = &mut guard.0;
        let n = slots.len() as u64;
        py.detach(|| {
            slots.par_iter_mut().enumerate().for_each(|(i, slot)| {
                slot.env.reset(seed.wrapping_add(i as u64));
                slot.next_seed = seed.wrapping_add(i as u64).wrapping_add(n);
                slot.ended = false;
            })
        });
        self.observations(py, slots)
    }

    /// One step of every environment: `actions` is (count, action_size); returns
    /// (observations, rewards, terminated, truncated, unstable) as arrays.
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
        Bound<'py, PyArray1<bool>>,
    )> {
        let mut guard = self.slots.lock().unwrap_or_else(|p| p.into_inner());
        let (slots, lanes) = &mut *guard;
        let n = slots.len();
        let a = action_rows(&actions, n, self.action_size)?;
        if let Some(i) = a.iter().position(|v| !v.is_finite()) {
            return Err(value_error(format!(
                "actions: environment {}, action {} is not finite ({})",
                i / self.action_size,
                i % self.action_size,
                a[i]
            )));
        }
        let width = self.action_size;
        let groups: Result<Vec<Vec<SlotStep>>, EvoGymError> = py.detach(|| {
            slots
                .par_chunks_mut(LANES)
                .zip(lanes.par_iter_mut())
                .zip(a.par_chunks(LANES * width))
                .map(|((group, lanes), actions)| step_group(group, lanes, actions, width, n as u64))
                .collect()
        });
        let steps: Vec<SlotStep> = groups.map_err(|e| value_error(format!("actions: {e}")))?.concat();
        let obs = self.observations(py, slots)?;
        let column = |f: fn(&SlotStep) -> bool| PyArray1::from_vec(py, steps.iter().map(f).collect());
        Ok((
            obs,
            PyArray1::from_vec(py, steps.iter().map(|s| s.reward).collect()),
            column(|s| s.terminated),
            column(|s| s.truncated),
            column(|s| s.unstable),
        ))
    }
}

impl PyEvoGymVectorEnv {
    fn observations<'py>(&self, py: Python<'py>, slots: &[Slot]) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let data: Vec<f64> = slots.iter().flat_map(|s| s.env.observation().iter().copied()).collect();
        PyArray1::from_vec(py, data).reshape([slots.len(), self.observation_size])
    }
}

/// One step of a group of at most [`LANES`] environments: those whose episode ended are reset
/// (their action ignored), the others step together in the group's lanes (alone when fewer
/// than three step).
fn step_group(
    group: &mut [Slot],
    lanes: &mut Option<EnvLanes>,
    actions: &[f64],
    width: usize,
    count: u64,
) -> Result<Vec<SlotStep>, EvoGymError> {
    let mut stepping = Vec::with_capacity(group.len());
    for (k, slot) in group.iter_mut().enumerate() {
        if slot.ended {
            slot.env.reset(slot.next_seed);
            slot.next_seed = slot.next_seed.wrapping_add(count);
            slot.ended = false;
        } else {
            stepping.push(k);
        }
    }
    let chunk = |k: usize| &actions[k * width..(k + 1) * width];
    let mut out = vec![SlotStep::default(); group.len()];
    if stepping.len() >= 3 {
        let lanes = lanes.get_or_insert_with(|| EnvLanes::new(&group[stepping[0]].env));
        let mut envs: Vec<&mut EvoGymEnv> = group
            .iter_mut()
            .enumerate()
            .filter(|(k, _)| stepping.contains(k))
            .map(|(_, s)| &mut s.env)
            .collect();
        let targets: Vec<&[f64]> = stepping.iter().map(|&k| chunk(k)).collect();
        for (&k, step) in stepping.iter().zip(lanes.step(&mut envs, &targets)?) {
            let s = step?;
            out[k] = SlotStep {
                reward: s.reward,
                terminated: s.done,
                truncated: s.truncated,
                unstable: s.unstable,
            };
        }
    } else {
        for &k in &stepping {
            let r = group[k].env.step(chunk(k))?;
            out[k] = SlotStep {
                reward: r.reward,
                terminated: r.done,
                truncated: r.truncated,
                unstable: r.unstable,
            };
        }
    }
    for &k in &stepping {
        group[k].ended = out[k].terminated || out[k].truncated;
    }
    Ok(out)
}
