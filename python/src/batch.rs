//! Many genotypes evaluated in one call (`vsrlab.evaluate_batch`).

use crate::robot::PyRobot;
use crate::value_error;
use numpy::{PyArray1, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use vsrlab_experiment::BatchEvaluator;
use vsrlab_tasks::files::any_robot_from_json;

/// The evaluator of an experiment: genotypes (rows of genes) → fitness, exactly as `vsrlab run`
/// and `vsrlab evaluate` compute it for the same genotype and seed.
#[pyclass(name = "BatchEvaluator", module = "vsrlab", frozen)]
pub struct PyBatchEvaluator {
    batch: BatchEvaluator,
    pool: rayon::ThreadPool,
}

impl PyBatchEvaluator {
    /// Checks the arrays and returns the genes (row-major) and seeds.
    fn arrays<'a>(
        &self,
        genotypes: &'a PyReadonlyArray2<'_, f64>,
        seeds: &'a PyReadonlyArray1<'_, u64>,
    ) -> PyResult<(&'a [f64], &'a [u64])> {
        let shape = genotypes.shape();
        let width = self.batch.genotype_length();
        if shape[1] != width {
            return Err(value_error(format!(
                "genotypes: shape ({}, {}) has rows of {} genes; this experiment's genotypes have {width}",
                shape[0], shape[1], shape[1]
            )));
        }
        let genes = genotypes
            .as_slice()
            .map_err(|_| value_error("genotypes: a C-contiguous float64 array is needed"))?;
        let seeds = seeds
            .as_slice()
            .map_err(|_| value_error("seeds: a contiguous uint64 array is needed"))?;
        Ok((genes, seeds))
    }

    /// Every evaluation of the rows, in full, with the GIL released.
    fn evaluate_all(
        &self,
        py: Python<'_>,
        genotypes: &PyReadonlyArray2<'_, f64>,
        seeds: &PyReadonlyArray1<'_, u64>,
    ) -> PyResult<Vec<vsrlab_experiment::Evaluated>> {
        let (genes, seeds) = self.arrays(genotypes, seeds)?;
        py.detach(|| self.pool.install(|| self.batch.evaluate(genes, seeds)))
            .map_err(value_error)
    }
}

#[pymethods]
impl PyBatchEvaluator {
    /// `config`: an experiment file's TOML text; `origin` names it in error messages; `threads`
    /// 0 means every core.
    #[new]
    #[pyo3(signature = (config, origin = "config", threads = 0))]
    fn new(config: &str, origin: &str, threads: usize) -> PyResult<Self> {
        let batch = BatchEvaluator::from_text(config, origin).map_err(value_error)?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| value_error(format!("threads: {e}")))?;
        Ok(PyBatchEvaluator { batch, pool })
    }

    /// Genes per genotype.
    #[getter]
    fn genotype_length(&self) -> usize {
        self.batch.genotype_length()
    }

    /// Worker threads.
    #[getter]
    fn threads(&self) -> usize {
        self.pool.current_num_threads()
    }

    /// The first fitness value of every row (NaN where the evaluation failed), evaluated on
    /// every thread with the GIL released.
    fn fitness<'py>(
        &self,
        py: Python<'py>,
        genotypes: PyReadonlyArray2<'py, f64>,
        seeds: PyReadonlyArray1<'py, u64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (genes, seeds) = self.arrays(&genotypes, &seeds)?;
        let fitness = py
            .detach(|| self.pool.install(|| self.batch.fitness(genes, seeds)))
            .map_err(value_error)?;
        Ok(PyArray1::from_vec(py, fitness))
    }

    /// Every evaluation in full (fitness values, descriptor, features, record) as JSON text, the
    /// form the runner reads back (`vsrlab.Worker.evaluations` gives the same for any kind).
    fn evaluations(
        &self,
        py: Python<'_>,
        genotypes: PyReadonlyArray2<'_, f64>,
        seeds: PyReadonlyArray1<'_, u64>,
    ) -> PyResult<String> {
        let evaluated = self.evaluate_all(py, &genotypes, &seeds)?;
        serde_json::to_string(&evaluated).map_err(value_error)
    }

    /// The robot a genotype stands for (to simulate, render or save the best one).
    fn robot(&self, genotype: Vec<f64>) -> PyResult<PyRobot> {
        if let Some(i) = genotype.iter().position(|g| !g.is_finite()) {
            return Err(value_error(format!(
                "genotype: gene {i} is {} (genes must be finite)",
                genotype[i]
            )));
        }
        let robot = self
            .batch
            .experiment()
            .representation
            .any_robot(&genotype)
            .map_err(|e| value_error(format!("genotype: {e}")))?;
        // through its robot file, which validates it
        let robot = any_robot_from_json(&robot.to_json(None), "genotype").map_err(value_error)?;
        Ok(PyRobot::trained(robot))
    }

    /// The records of every row (fitness, distance, velocity, body, error), as a list of dicts'
    /// JSON text.
    fn records(
        &self,
        py: Python<'_>,
        genotypes: PyReadonlyArray2<'_, f64>,
        seeds: PyReadonlyArray1<'_, u64>,
    ) -> PyResult<String> {
        let evaluated = self.evaluate_all(py, &genotypes, &seeds)?;
        let records: Vec<_> = evaluated.into_iter().map(|e| e.record).collect();
        serde_json::to_string(&records).map_err(value_error)
    }
}
