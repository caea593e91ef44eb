//! `vsrlab._native`: the Rust side of the Python package. Robots, tasks and episodes from the
//! same strings and files as the CLI, batch evaluation with the GIL released, and experiment runs
//! whose evaluations Python may send elsewhere (Ray). The Python modules in `python/vsrlab/`
//! wrap it; docs/python.md is the user's guide.
//!
//! Every bad input from Python raises `ValueError` naming the argument or field; nothing here
//! panics on user input.

mod batch;
mod campaign;
mod episode;
mod evogym;
mod robot;
mod run;
mod worker;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// A `ValueError` with `message`.
pub(crate) fn value_error(message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(message.to_string())
}

/// The rows of a vector environment's `actions` array: (rows, width) and C-contiguous, or an
/// error naming `actions`.
pub(crate) fn action_rows<'a>(
    actions: &'a numpy::PyReadonlyArray2<'_, f64>,
    rows: usize,
    width: usize,
) -> PyResult<&'a [f64]> {
    use numpy::PyUntypedArrayMethods;
    if actions.shape() != [rows, width] {
        return Err(value_error(format!(
            "actions: shape ({rows}, {width}) expected, got {:?}",
            actions.shape()
        )));
    }
    actions
        .as_slice()
        .map_err(|_| value_error("actions: a C-contiguous float64 array is needed"))
}

/// The extension module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<robot::PyRobot>()?;
    m.add_function(wrap_pyfunction!(robot::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(robot::task_json, m)?)?;
    m.add_class::<episode::PyEpisode>()?;
    m.add_class::<episode::PyVectorEpisode>()?;
    m.add_class::<evogym::PyEvoGymEnv>()?;
    m.add_function(wrap_pyfunction!(evogym::evogym_tasks, m)?)?;
    m.add_class::<evogym::PyEvoGymSim>()?;
    m.add_class::<evogym::PyEvoGymVectorEnv>()?;
    m.add_function(wrap_pyfunction!(evogym::evogym_check_world, m)?)?;
    m.add_function(wrap_pyfunction!(evogym::evogym_episode_steps, m)?)?;
    m.add_class::<batch::PyBatchEvaluator>()?;
    m.add_function(wrap_pyfunction!(run::run, m)?)?;
    m.add_function(wrap_pyfunction!(run::deterministic_files, m)?)?;
    m.add_function(wrap_pyfunction!(run::experiment_text, m)?)?;
    m.add_class::<worker::PyWorker>()?;
    m.add_function(wrap_pyfunction!(campaign::campaign_settings, m)?)?;
    m.add_function(wrap_pyfunction!(campaign::campaign, m)?)?;
    Ok(())
}
