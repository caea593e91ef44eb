//! A cluster worker's evaluator (`vsrlab._native.Worker`, what a Ray actor holds): an experiment's
//! evaluations for genotypes of any kind, sent as JSON text. The evaluator lives on a thread of
//! its own, built by the experiment's genotype kind as for a local run
//! ([`vsrlab_experiment::remote::serve`]); each call is a request to that thread.

use crate::value_error;
use numpy::{PyReadonlyArray1, PyUntypedArrayMethods};
use pyo3::prelude::*;
use std::sync::mpsc::{channel, Sender};
use std::sync::{Arc, Mutex};
use vsrlab_experiment::config;
use vsrlab_experiment::evaluator::Record;
use vsrlab_experiment::remote::{self, Served};

/// What the worker's thread is asked to do; each request carries where its answer goes.
enum Request {
    Evaluate {
        genotypes: Vec<String>,
        seeds: Vec<u64>,
        answer: Sender<Result<String, String>>,
    },
    RobotFile {
        genotype: String,
        record: Option<Record>,
        note: String,
        answer: Sender<Result<Vec<u8>, String>>,
    },
}

/// Answers requests until the worker is dropped (its sender closes), each on a thread of its own:
/// an actor that takes several calls at once (a campaign's) evaluates them side by side on the
/// worker's pool.
fn answer(served: &dyn Served, requests: std::sync::mpsc::Receiver<Request>) {
    std::thread::scope(|scope| {
        for request in requests {
            scope.spawn(move || handle(served, request));
        }
    });
}

fn handle(served: &dyn Served, request: Request) {
    match request {
        Request::Evaluate {
            genotypes,
            seeds,
            answer,
        } => {
            let text = served
                .evaluate(&genotypes, &seeds)
                .map_err(|e| e.to_string())
                .and_then(|e| serde_json::to_string(&e).map_err(|e| e.to_string()));
            let _ = answer.send(text);
        }
        Request::RobotFile {
            genotype,
            record,
            note,
            answer,
        } => {
            let _ = answer.send(
                served
                    .robot_file(&genotype, record.as_ref(), &note)
                    .map_err(|e| e.to_string()),
            );
        }
    }
}

/// The process's pool of `threads` threads: a worker process's evaluators share it, so that a
/// node given N CPUs evaluates on N threads whatever the number of experiments it serves.
fn shared_pool(threads: usize) -> PyResult<Arc<rayon::ThreadPool>> {
    static POOLS: Mutex<Vec<(usize, Arc<rayon::ThreadPool>)>> = Mutex::new(Vec::new());
    let mut pools = POOLS.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Some((_, pool)) = pools.iter().find(|(n, _)| *n == threads) {
        return Ok(pool.clone());
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| value_error(format!("threads: {e}")))?;
    let pool = Arc::new(pool);
    pools.push((threads, pool.clone()));
    Ok(pool)
}

/// An experiment's evaluator on a worker: genotypes of any kind (JSON texts) → evaluations (JSON
/// text), exactly as `vsrlab run` evaluates them for the same genotype and seed.
#[pyclass(name = "Worker", module = "vsrlab", frozen)]
pub struct PyWorker {
    requests: Mutex<Sender<Request>>,
    threads: usize,
}

impl PyWorker {
    /// Sends a request and waits for its answer with the GIL released.
    fn ask<T: Send>(&self, py: Python<'_>, request: impl FnOnce(Sender<T>) -> Request) -> PyResult<T> {
        let (send, receive) = channel();
        let sent = self
            .requests
            .lock()
            .map_err(|_| value_error("worker: poisoned"))?
            .send(request(send));
        sent.map_err(|_| value_error("worker: its evaluator has stopped"))?;
        py.detach(move || receive.recv())
            .map_err(|_| value_error("worker: its evaluator stopped before answering"))
    }
}

#[pymethods]
impl PyWorker {
    /// `config`: an experiment file's TOML text; `origin` names it in error messages; `threads`
    /// 0 means every core. A bad file raises `ValueError` naming the field.
    #[new]
    #[pyo3(signature = (config, origin = "config", threads = 0))]
    fn new(py: Python<'_>, config: &str, origin: &str, threads: usize) -> PyResult<Self> {
        let experiment = config::parse(config, origin).map_err(value_error)?;
        let threads = vsrlab_experiment::runner::worker_threads(threads);
        let pool = shared_pool(threads)?;
        let (requests, receive) = channel::<Request>();
        let (ready, started) = channel::<Result<(), String>>();
        let starting = ready.clone();
        std::thread::Builder::new()
            .name("vsrlab-worker".into())
            .spawn(move || {
                let served = remote::serve(&experiment, pool, move |served| {
                    let _ = starting.send(Ok(()));
                    answer(served, receive);
                });
                if let Err(e) = served {
                    let _ = ready.send(Err(e.to_string()));
                }
            })
            .map_err(|e| value_error(format!("worker: cannot start its thread: {e}")))?;
        py.detach(move || started.recv())
            .map_err(|_| value_error("worker: its evaluator stopped while starting"))?
            .map_err(value_error)?;
        Ok(PyWorker {
            requests: Mutex::new(requests),
            threads,
        })
    }

    /// Worker threads.
    #[getter]
    fn threads(&self) -> usize {
        self.threads
    }

    /// The vsrlab version this worker runs (a driver refuses workers of another version).
    #[getter]
    fn version(&self) -> &'static str {
        remote::VERSION
    }

    /// Evaluates `genotypes` (each one genotype's JSON text, as the runner sends it) with their
    /// candidate `seeds`, on every worker thread with the GIL released; the evaluations as JSON
    /// text, in order.
    fn evaluations(
        &self,
        py: Python<'_>,
        genotypes: Vec<String>,
        seeds: PyReadonlyArray1<'_, u64>,
    ) -> PyResult<String> {
        if seeds.len() != genotypes.len() {
            return Err(value_error(format!(
                "seeds: {} seeds for {} genotypes",
                seeds.len(),
                genotypes.len()
            )));
        }
        let seeds = seeds
            .as_slice()
            .map_err(|_| value_error("seeds: a contiguous uint64 array is needed"))?
            .to_vec();
        self.ask(py, |answer| Request::Evaluate {
            genotypes,
            seeds,
            answer,
        })?
        .map_err(value_error)
    }

    /// The robot file of a run's best `genotype` (JSON text) with its evaluation `record` (JSON
    /// text, or None), as the runner writes it.
    #[pyo3(signature = (genotype, record, note))]
    fn robot_file(&self, py: Python<'_>, genotype: String, record: Option<&str>, note: String) -> PyResult<Vec<u8>> {
        let record: Option<Record> = record
            .map(serde_json::from_str)
            .transpose()
            .map_err(|e| value_error(format!("record: {e}")))?;
        self.ask(py, |answer| Request::RobotFile {
            genotype,
            record,
            note,
            answer,
        })?
        .map_err(value_error)
    }
}
