//! The evaluations of a long generation, saved while it runs (`run-NN/unfinished-generation.jsonl`).
//!
//! A checkpoint is written between generations, so a kill used to lose the whole generation
//! under way: twenty minutes of a co-design generation whose bodies each train a policy. While a
//! generation runs longer than the checkpoint interval (at least [`MIN_SECONDS`]), every
//! finished evaluation is saved here as one line: its candidate seed, its genotype and what it
//! gave. An evaluation is a pure function of (genotype, seed), so `--resume` reuses a saved line
//! for any candidate of the same genotype and seed, and the run's files stay those of an
//! uninterrupted run. The file goes once a checkpoint covers its generation.

use crate::evaluator::Evaluated;
use crate::genotype::Genotype;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Instant;
use vsrlab_tasks::files::write_atomic;

/// Least seconds between two saves of the file, whatever the checkpoint interval.
pub const MIN_SECONDS: f64 = 1.0;

/// One saved evaluation (written with references, read back owned).
#[derive(Serialize, Deserialize)]
struct Line<G, E = Evaluated> {
    seed: u64,
    genotype: G,
    evaluated: E,
}

/// A line of the file that does not read. The file is only a cache: the run evaluates that
/// generation again without it.
#[derive(Debug, thiserror::Error)]
#[error("{} line {line}: {source}", path.display())]
pub struct UnreadableLine {
    /// The file.
    pub path: PathBuf,
    /// The line, from 1.
    pub line: usize,
    /// Why it does not read.
    pub source: serde_json::Error,
}

/// Evaluations read back from the file of an interrupted generation, by candidate seed and
/// genotype (its JSON text: equal genotypes, equal text).
#[derive(Default)]
pub struct Carried {
    by_candidate: HashMap<(u64, String), Evaluated>,
}

impl Carried {
    /// The evaluations saved in `path`; none when there is no file. A line that does not read
    /// (an edited or damaged file) is an error naming the file and the line.
    pub fn load<G: Genotype>(path: &Path) -> Result<Carried, UnreadableLine> {
        let Ok(text) = std::fs::read_to_string(path) else {
            return Ok(Carried::default());
        };
        let mut by_candidate = HashMap::new();
        for (number, line) in text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty()) {
            let saved: Line<G> = serde_json::from_str(line).map_err(|source| UnreadableLine {
                path: path.to_path_buf(),
                line: number + 1,
                source,
            })?;
            by_candidate.insert((saved.seed, genotype_text(&saved.genotype)), saved.evaluated);
        }
        Ok(Carried { by_candidate })
    }

    /// How many evaluations are still carried.
    pub fn len(&self) -> usize {
        self.by_candidate.len()
    }

    /// Whether none is.
    pub fn is_empty(&self) -> bool {
        self.by_candidate.is_empty()
    }

    /// The saved evaluation of this candidate, if there is one (taken out).
    pub fn take<G: Genotype>(&mut self, seed: u64, genotype: &G) -> Option<Evaluated> {
        if self.by_candidate.is_empty() {
            return None;
        }
        self.by_candidate.remove(&(seed, genotype_text(genotype)))
    }
}

/// Collects a generation's evaluations as they end and saves them at most every `every` seconds
/// (never before the generation has run that long). Until the first save an evaluation is only
/// kept (cloned), not serialised: short generations, the usual case, pay next to nothing.
pub struct Recorder<'a, G> {
    path: PathBuf,
    every: f64,
    genotypes: Vec<&'a G>,
    seeds: Vec<u64>,
    inner: Mutex<Pending>,
}

struct Pending {
    /// Finished evaluations by batch index; the first `written` are in `text`.
    finished: Vec<(usize, Evaluated)>,
    written: usize,
    text: String,
    last_save: Instant,
    error: Option<std::io::Error>,
}

impl<'a, G: Genotype> Recorder<'a, G> {
    /// A recorder for the batch of `genotypes` with their candidate `seeds`, starting now;
    /// `checkpoint_interval` as the run's.
    pub fn new(path: PathBuf, checkpoint_interval: f64, genotypes: Vec<&'a G>, seeds: Vec<u64>) -> Self {
        Recorder {
            path,
            every: checkpoint_interval.max(MIN_SECONDS),
            genotypes,
            seeds,
            inner: Mutex::new(Pending {
                finished: Vec::new(),
                written: 0,
                text: String::new(),
                last_save: Instant::now(),
                error: None,
            }),
        }
    }

    /// Adds the finished evaluation of the batch's candidate `index`; saves the file when the
    /// last save (or the generation's start) is at least the interval ago.
    pub fn done(&self, index: usize, evaluated: &Evaluated) {
        let mut pending = self.inner.lock().unwrap_or_else(|e| e.into_inner());
        pending.finished.push((index, evaluated.clone()));
        if pending.error.is_some() || pending.last_save.elapsed().as_secs_f64() < self.every {
            return;
        }
        let Pending {
            finished,
            written,
            text,
            ..
        } = &mut *pending;
        for (index, evaluated) in &finished[*written..] {
            let line = Line {
                seed: self.seeds[*index],
                genotype: self.genotypes[*index],
                evaluated,
            };
            // an evaluation that does not serialise is simply evaluated again
            if let Ok(json) = serde_json::to_string(&line) {
                text.push_str(&json);
                text.push('\n');
            }
        }
        *written = finished.len();
        if let Err(e) = write_atomic(&self.path, pending.text.as_bytes()) {
            pending.error = Some(e);
        }
        pending.last_save = Instant::now();
    }

    /// The first write error, if a save failed.
    pub fn into_error(self) -> Option<std::io::Error> {
        self.inner.into_inner().unwrap_or_else(|e| e.into_inner()).error
    }
}

fn genotype_text<G: Serialize>(genotype: &G) -> String {
    serde_json::to_string(genotype).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::evaluator::Record;

    fn evaluated(fitness: f64) -> Evaluated {
        Evaluated {
            objectives: vec![fitness],
            descriptor: vec![],
            features: vec![],
            record: Record {
                fitness: Some(fitness),
                ..Record::new(7)
            },
            seconds: 1.5,
        }
    }

    #[test]
    fn saved_evaluations_come_back_bit_for_bit_for_the_same_seed_and_genotype_only() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("unfinished-generation.jsonl");
        let a = vec![0.1f64, -2.5];
        let recorder = Recorder::new(path.clone(), 0.0, vec![&a, &a], vec![11, 12]);
        let third = 1.0 / 3.0;
        std::thread::sleep(std::time::Duration::from_secs_f64(MIN_SECONDS));
        recorder.done(0, &evaluated(third));
        recorder.done(1, &evaluated(f64::NAN));
        assert!(recorder.into_error().is_none());
        let mut carried = Carried::load::<Vec<f64>>(&path).unwrap();
        // the second line came within a second of the first save: it was kept but not yet written
        assert_eq!(carried.len(), 1);
        assert!(carried.take(11, &vec![0.1f64, -2.4]).is_none(), "another genotype");
        assert!(carried.take(12, &a).is_none(), "another seed, and not saved");
        let back = carried.take(11, &a).expect("saved");
        assert_eq!(back.fitness().to_bits(), third.to_bits());
        assert_eq!(back, evaluated(third));
        assert!(carried.is_empty());
    }

    #[test]
    fn nothing_is_written_before_the_generation_has_run_the_interval() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("unfinished-generation.jsonl");
        let g = vec![1.0f64];
        let recorder = Recorder::new(path.clone(), 30.0, vec![&g], vec![1]);
        recorder.done(0, &evaluated(1.0));
        assert!(!path.exists());
        assert!(Carried::load::<Vec<f64>>(&path).unwrap().is_empty());
    }

    #[test]
    fn a_damaged_file_is_refused_with_its_name_and_line() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("unfinished-generation.jsonl");
        std::fs::write(&path, "{\"seed\": 1, \"genotype\": [1.0], \"evaluated\": 3}\n").unwrap();
        let err = Carried::load::<Vec<f64>>(&path).err().unwrap();
        assert_eq!(err.line, 1);
        assert!(
            err.to_string()
                .contains("unfinished-generation.jsonl line 1: invalid type"),
            "{err}"
        );
    }
}
