//! Robots from short forms or robot files, and one episode's outcome (`vsrlab.simulate`).

use crate::value_error;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use vsrlab_tasks::files::{any_robot_from_json, load_any_robot, save_any_robot};
use vsrlab_tasks::{episode, kinds, AnyRobot, RobotArgs, TaskSpec, TraceLevel};

/// Episode length of a task short form when no duration is given (the CLI's default).
const DEFAULT_DURATION: f64 = 30.0;

/// A robot: a body, its sensors and a brain, voxel-based or pressure-based; what a robot file
/// holds. Immutable.
#[pyclass(name = "Robot", module = "vsrlab", frozen)]
#[derive(Clone)]
pub struct PyRobot {
    pub(crate) robot: AnyRobot,
    /// Made from short forms (its weights, if any, drawn at random): a task may give it the
    /// brain it runs with (`RobotDescription::for_task`), as the CLI's `simulate --body` does.
    pub(crate) untrained: bool,
}

impl PyRobot {
    /// A robot read from a file or made from a genotype: its brain is kept as it is.
    pub(crate) fn trained(robot: AnyRobot) -> PyRobot {
        PyRobot {
            robot,
            untrained: false,
        }
    }
}

#[pymethods]
impl PyRobot {
    /// A robot from the CLI's short forms: `body` a named shape, a text grid ("###/#.#") or
    /// `psa[:small|medium|large]`; `brain` (default `phase`, `heads` for a PSA); `sensors` and
    /// `preset` for voxel bodies.
    #[new]
    #[pyo3(signature = (body = "biped-4x3", brain = None, sensors = None, preset = None))]
    fn new(body: &str, brain: Option<&str>, sensors: Option<&str>, preset: Option<&str>) -> PyResult<Self> {
        let robot = kinds::from_short_forms(&RobotArgs {
            body,
            brain,
            sensors,
            preset,
        })
        .map_err(|e| value_error(format!("{}: {}", e.part(), e.message())))?;
        Ok(PyRobot { robot, untrained: true })
    }

    /// Reads a robot file (either kind).
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        let robot = load_any_robot(&path).map_err(value_error)?;
        Ok(PyRobot::trained(robot))
    }

    /// A robot from a robot file's JSON text.
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        let robot = any_robot_from_json(text, "robot").map_err(value_error)?;
        Ok(PyRobot::trained(robot))
    }

    /// Writes the robot file (atomically), with an optional note.
    #[pyo3(signature = (path, note = None))]
    fn save(&self, path: PathBuf, note: Option<&str>) -> PyResult<()> {
        save_any_robot(&path, &self.robot, note).map_err(value_error)
    }

    /// The robot file's JSON text.
    #[pyo3(signature = (note = None))]
    fn to_json(&self, note: Option<&str>) -> String {
        self.robot.to_json(note)
    }

    /// The robot's kind: `"voxel"`, `"psa"`, … (`vsrlab_tasks::ROBOT_KINDS`).
    #[getter]
    fn kind(&self) -> &'static str {
        self.robot.kind().name
    }

    /// The brain's kind (`phase`, `mlp`, `heads`, …).
    #[getter]
    fn brain(&self) -> String {
        self.robot.brain().kind().to_string()
    }

    /// The body as rows of `#` and `.` (voxel robots), `None` for a PSA.
    #[getter]
    fn body(&self) -> Option<String> {
        self.robot.as_robot().summary().map(|s| s.text)
    }

    fn __repr__(&self) -> String {
        format!("Robot({})", self.robot.description().label())
    }
}

/// A task from a short form (`locomotion:hilly-1-10`, `jump`, `escape`, `carrier`; 30 s unless
/// `duration` says otherwise) or an experiment file (`.toml`, or a `vsrlab run` output folder;
/// its own duration unless `duration` is given).
pub(crate) fn task_spec(task: &str, duration: Option<f64>) -> PyResult<TaskSpec> {
    let from_file = task.ends_with(".toml") || std::path::Path::new(task).is_dir();
    let duration = if from_file {
        duration
    } else {
        duration.or(Some(DEFAULT_DURATION))
    };
    let spec = if from_file {
        vsrlab_experiment::config::load_task(std::path::Path::new(task))
            .map_err(|e| value_error(format!("task: {e}")))?
    } else {
        TaskSpec::parse(task).map_err(|e| value_error(format!("task: {e}")))?
    };
    let spec = match duration {
        None => spec,
        Some(d) => spec
            .with_settings(&[("duration", serde_json::json!(d))])
            .map_err(|e| value_error(format!("duration: {}", e.message)))?,
    };
    spec.task().validate().map_err(|e| value_error(format!("task: {e}")))?;
    Ok(spec)
}

/// The task's settings as JSON (what `task` resolves to), for display and checks.
#[pyfunction]
#[pyo3(signature = (task, duration = None))]
pub fn task_json(task: &str, duration: Option<f64>) -> PyResult<String> {
    let spec = task_spec(task, duration)?;
    serde_json::to_string(&spec).map_err(value_error)
}

/// Runs one episode of `robot` on `task` and returns its outcome: `fitness` (a list), the task's
/// metrics (distance, velocity, …), `steps` and `units`. `video` writes a GIF/MP4/PNG like the
/// CLI's `--video`. The GIL is released during the episode.
#[pyfunction]
#[pyo3(signature = (robot, task = "locomotion:flat", duration = None, seed = 0, video = None))]
pub fn simulate<'py>(
    py: Python<'py>,
    robot: &PyRobot,
    task: &str,
    duration: Option<f64>,
    seed: u64,
    video: Option<PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    let spec = task_spec(task, duration)?;
    let level = if video.is_some() {
        TraceLevel::Full
    } else {
        TraceLevel::None
    };
    // a robot whose brain depends on the task (EvoGym's) runs as the task runs it, as in the
    // CLI's simulate
    let any = robot
        .robot
        .description()
        .for_task(spec.task(), robot.untrained)
        .unwrap_or_else(|| robot.robot.clone());
    let (outcome, written) = py
        .detach(move || -> Result<_, String> {
            let outcome = episode::run(any.as_robot(), spec.task(), seed, level).map_err(|e| e.to_string())?;
            let mut written = None;
            if let (Some(path), Some(trace)) = (&video, &outcome.trace) {
                let info = vsrlab_render::save_video(trace, &vsrlab_render::RenderOptions::default(), path)
                    .map_err(|e| format!("video: {e}"))?;
                written = Some(info.frames);
            }
            Ok((outcome, written))
        })
        .map_err(value_error)?;
    let out = PyDict::new(py);
    out.set_item("fitness", outcome.fitness.clone())?;
    for (name, value) in &outcome.metrics {
        out.set_item(name, value)?;
    }
    out.set_item("steps", outcome.steps)?;
    out.set_item("units", outcome.units)?;
    out.set_item("seed", seed)?;
    if let Some(frames) = written {
        out.set_item("video_frames", frames)?;
    }
    Ok(out)
}
