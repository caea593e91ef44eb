//! A run whose batches go elsewhere: an in-process worker built by `remote::serve` (what a Ray
//! actor holds) answers the runner's transport. The toy genotype kind, which no line of the
//! remote layer names, runs through it with the same files as locally.

use crate::common;
use crate::toy_genotype_kind::experiment;
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::{Arc, Mutex};
use vsrlab_experiment::config::Experiment;
use vsrlab_experiment::evaluator::{Evaluated, EvaluatorError, Record};
use vsrlab_experiment::remote::{serve, Evaluations, Served, Transport};
use vsrlab_experiment::run_configured;
use vsrlab_experiment::runner::{deterministic_files, RunOptions, Silent};

/// A worker's pool of one thread.
fn one_thread() -> Arc<rayon::ThreadPool> {
    Arc::new(rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap())
}

/// A request to the worker's thread, with where its answer goes.
enum Request {
    Batch(Vec<String>, Vec<u64>, Sender<Result<Vec<Evaluated>, String>>),
    Robot(String, Option<Record>, String, Sender<Result<Vec<u8>, String>>),
}

/// A worker on a thread of its own, answering over a channel; counts the batches it served.
struct Loopback {
    requests: Mutex<Sender<Request>>,
    served: Arc<Mutex<usize>>,
}

fn answer(served: &dyn Served, requests: Receiver<Request>, count: &Mutex<usize>) {
    for request in requests {
        match request {
            Request::Batch(genotypes, seeds, reply) => {
                *count.lock().unwrap() += 1;
                let _ = reply.send(served.evaluate(&genotypes, &seeds).map_err(|e| e.to_string()));
            }
            Request::Robot(genotype, record, note, reply) => {
                let _ = reply.send(
                    served
                        .robot_file(&genotype, record.as_ref(), &note)
                        .map_err(|e| e.to_string()),
                );
            }
        }
    }
}

impl Loopback {
    fn start(experiment: &Experiment) -> Loopback {
        let (requests, receive) = channel::<Request>();
        let served = Arc::new(Mutex::new(0));
        let count = served.clone();
        let experiment = experiment.clone();
        std::thread::spawn(move || {
            serve(&experiment, one_thread(), move |s| answer(s, receive, &count)).unwrap();
        });
        Loopback {
            requests: Mutex::new(requests),
            served,
        }
    }
}

impl Transport for Loopback {
    fn evaluate(&self, genotypes: &[String], seeds: &[u64]) -> Result<Vec<Evaluated>, EvaluatorError> {
        let (reply, answer) = channel();
        let request = Request::Batch(genotypes.to_vec(), seeds.to_vec(), reply);
        self.requests.lock().unwrap().send(request).unwrap();
        answer.recv().unwrap().map_err(EvaluatorError::Remote)
    }

    fn robot_file(
        &self,
        genotype: &str,
        record: Option<&Record>,
        note: &str,
    ) -> Result<Option<Vec<u8>>, EvaluatorError> {
        let (reply, answer) = channel();
        let request = Request::Robot(genotype.to_string(), record.cloned(), note.to_string(), reply);
        self.requests.lock().unwrap().send(request).unwrap();
        answer.recv().unwrap().map(Some).map_err(EvaluatorError::Remote)
    }
}

#[test]
fn a_toy_kind_run_evaluated_by_a_served_worker_writes_the_local_runs_files() {
    let experiment = experiment("kind = \"ga\"\npopulation_size = 6\noffspring_size = 6");
    experiment.validate().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let local = dir.path().join("local");
    run_configured(&experiment, &local, &common::two_threads(false), &mut Silent).unwrap();

    let worker = Arc::new(Loopback::start(&experiment));
    let options = RunOptions {
        threads: 1,
        evaluations: Evaluations::Remote(worker.clone()),
        ..RunOptions::default()
    };
    let remote = dir.path().join("remote");
    run_configured(&experiment, &remote, &options, &mut Silent).unwrap();
    // 2 runs of 24 evaluations in batches of 6: every batch went to the worker
    assert_eq!(*worker.served.lock().unwrap(), 8);
    let (a, b) = (
        deterministic_files(&local).unwrap(),
        deterministic_files(&remote).unwrap(),
    );
    assert!(a.iter().any(|(name, _)| name.ends_with("best.robot.json")), "{a:?}");
    assert_eq!(a.len(), b.len());
    for ((name, x), (_, y)) in a.iter().zip(&b) {
        assert!(x == y, "{name} differs between the local and the served run");
    }
}

/// Loses every batch.
struct Short;

impl Transport for Short {
    fn evaluate(&self, genotypes: &[String], _seeds: &[u64]) -> Result<Vec<Evaluated>, EvaluatorError> {
        Err(EvaluatorError::Remote(format!("lost {} genotypes", genotypes.len())))
    }
}

#[test]
fn a_batch_that_does_not_come_back_stops_the_run_with_the_transports_reason() {
    let experiment = experiment("kind = \"ga\"\npopulation_size = 6\noffspring_size = 6");
    let dir = tempfile::tempdir().unwrap();
    let options = RunOptions {
        evaluations: Evaluations::Remote(Arc::new(Short)),
        ..RunOptions::default()
    };
    let err = run_configured(&experiment, dir.path(), &options, &mut Silent)
        .unwrap_err()
        .to_string();
    assert!(err.contains("lost 6 genotypes"), "{err}");
}

#[test]
fn a_worker_refuses_genotypes_of_another_kind_by_index() {
    let experiment = experiment("kind = \"ga\"\npopulation_size = 6\noffspring_size = 6");
    let (send, receive) = channel();
    serve(&experiment, one_thread(), move |served| {
        let _ = send.send(
            served
                .evaluate(&["[1,2,3]".into(), "{\"neurons\":[]}".into()], &[1, 2])
                .map_err(|e| e.to_string()),
        );
    })
    .unwrap();
    let err = receive.recv().unwrap().unwrap_err();
    assert!(err.starts_with("genotypes[1]: "), "{err}");
}
