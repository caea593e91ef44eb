//! Termination criteria of [`CmaEs`](super::cma_es::CmaEs): the stopping rules of Hansen's
//! tutorial ("The CMA Evolution Strategy: A Tutorial", 2016, Appendix B.3) with the defaults and
//! the exact definitions of pycma 4.5.0 (`cma/options_parameters.py` for the defaults,
//! `_CMAStopDict._update` in `cma/evolution_strategy.py` for the tests).
//!
//! Why: without them a run left going past convergence wastes its budget and drifts into
//! numerically meaningless states (σ creeping up while C shrinks). Once a criterion holds the
//! optimizer reports it through [`Optimizer::stop_reason`](crate::Optimizer::stop_reason) as
//! `"cma-es:<name>"`, with pycma's key as the name.
//!
//! Every threshold can be set to 0 to turn its criterion off; `enabled = false` turns them all
//! off. Fitness values enter as utilities (larger is better), so the tests read the same for
//! maximisation and minimisation; ranges are sign-independent.

use serde::{Deserialize, Serialize};

/// Thresholds of the termination criteria (0 turns one off). Defaults are pycma 4.5.0's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct CmaTermination {
    /// Master switch: `false` turns every criterion off (the run then ends only by its budget).
    /// Written `termination` (an experiment's `[optimizer]` table holds the criteria flat, beside
    /// the switch); checkpoints before 2026-11-28 wrote `enabled`, still read.
    #[serde(rename = "termination", alias = "enabled")]
    pub enabled: bool,
    /// `tolx`: stop when σ·√C_ii and σ·|p_c,i| are below this in every coordinate (pycma 1e-11).
    pub tolx: f64,
    /// `tolfun`: stop when the range of this generation's values and of the best values of the
    /// last 10 + ⌈30n/λ⌉ generations are both below this (pycma 1e-11).
    pub tolfun: f64,
    /// `tolfunhist`: stop when the range of the best values of the last 10 + ⌈30n/λ⌉
    /// generations (at least 10 of them) is below this (pycma 1e-12).
    pub tolfunhist: f64,
    /// `tolconditioncov`: stop when the condition number of C exceeds this (pycma and the
    /// tutorial's `ConditionCov`: 1e14).
    pub tolconditioncov: f64,
    /// `tolfacupx`: stop when σ·√C_ii exceeds σ0 times this in some coordinate, i.e. σ0 was far
    /// too small or the function is unbounded (pycma 1e3).
    pub tolfacupx: f64,
    /// `tolupsigma`: stop when σ/σ0 exceeds this times the largest √eigenvalue of C: σ creeps up
    /// while C shrinks (pycma and the tutorial's `TolUpSigma`: 1e20).
    pub tolupsigma: f64,
    /// `tolstagnation`: generations without improvement of the median of the best and of the
    /// median values (pycma's test, 0 = off). `None` = pycma's ⌊100 + 100·n^1.5/λ⌋.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tolstagnation: Option<u64>,
    /// `tolxstagnation`: stop when the mean moved less than this (growing with √time) over
    /// 20 + 0.1·g generations (pycma 4.x `tolxstagnation = [1e-9, 20, 0.1]`).
    pub tolxstagnation: f64,
    /// `noeffectaxis`: stop when adding 0.1 standard deviations along a principal axis of C
    /// (axis g mod n, as pycma) leaves the mean unchanged (tutorial `NoEffectAxis`).
    pub noeffectaxis: bool,
    /// `noeffectcoord`: stop when adding 0.2 standard deviations in some coordinate leaves that
    /// coordinate of the mean unchanged (tutorial `NoEffectCoord`).
    pub noeffectcoord: bool,
}

impl Default for CmaTermination {
    /// pycma 4.5.0's defaults, all criteria on.
    fn default() -> Self {
        Self {
            enabled: true,
            tolx: 1e-11,
            tolfun: 1e-11,
            tolfunhist: 1e-12,
            tolconditioncov: 1e14,
            tolfacupx: 1e3,
            tolupsigma: 1e20,
            tolstagnation: None,
            tolxstagnation: 1e-9,
            noeffectaxis: true,
            noeffectcoord: true,
        }
    }
}

impl CmaTermination {
    /// All criteria off: the run ends only by its budget (numerical guards still apply).
    pub fn off() -> Self {
        Self {
            enabled: false,
            ..Self::default()
        }
    }

    /// Checks that every threshold is finite and ≥ 0; `Err((field, why))` otherwise.
    pub fn validate(&self) -> Result<(), (&'static str, String)> {
        let fields = [
            ("tolx", self.tolx),
            ("tolfun", self.tolfun),
            ("tolfunhist", self.tolfunhist),
            ("tolconditioncov", self.tolconditioncov),
            ("tolfacupx", self.tolfacupx),
            ("tolupsigma", self.tolupsigma),
            ("tolxstagnation", self.tolxstagnation),
        ];
        for (name, value) in fields {
            if !(value.is_finite() && value >= 0.0) {
                return Err((name, format!("must be finite and ≥ 0 (0 = off), got {value}")));
            }
        }
        Ok(())
    }

    /// The stagnation horizon in generations for dimension `n` and population `lambda`.
    fn stagnation(&self, n: usize, lambda: usize) -> u64 {
        self.tolstagnation
            .unwrap_or_else(|| (100.0 + 100.0 * (n as f64).powf(1.5) / lambda as f64) as u64)
    }
}

/// A criterion that ended a run; `name` is pycma's key for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Criterion {
    /// σ·√C_ii > tolfacupx·σ0 in some coordinate.
    TolFacUpX,
    /// Step sizes and the covariance path below tolx in every coordinate.
    TolX,
    /// Current and recent best fitness ranges below tolfun.
    TolFun,
    /// Recent best fitness range below tolfunhist.
    TolFunHist,
    /// No improvement of best and median fitness for tolstagnation generations.
    TolStagnation,
    /// The mean has not moved.
    TolXStagnation,
    /// σ/σ0 > tolupsigma·max √eigenvalue.
    TolUpSigma,
    /// A coordinate step of 0.2 standard deviations does not change the mean.
    NoEffectCoord,
    /// A principal-axis step of 0.1 standard deviations does not change the mean.
    NoEffectAxis,
    /// Condition number of C above tolconditioncov.
    TolConditionCov,
}

impl Criterion {
    /// The stop reason reported by the optimizer, `"cma-es:<pycma key>"`.
    pub fn reason(self) -> &'static str {
        match self {
            Criterion::TolFacUpX => "cma-es:tolfacupx",
            Criterion::TolX => "cma-es:tolx",
            Criterion::TolFun => "cma-es:tolfun",
            Criterion::TolFunHist => "cma-es:tolfunhist",
            Criterion::TolStagnation => "cma-es:tolstagnation",
            Criterion::TolXStagnation => "cma-es:tolxstagnation",
            Criterion::TolUpSigma => "cma-es:tolupsigma",
            Criterion::NoEffectCoord => "cma-es:noeffectcoord",
            Criterion::NoEffectAxis => "cma-es:noeffectaxis",
            Criterion::TolConditionCov => "cma-es:tolconditioncov",
        }
    }
}

/// What the criteria look at after a generation, borrowed from the optimizer.
pub(crate) struct Snapshot<'a> {
    /// Completed generations, including this one.
    pub generation: u64,
    /// λ.
    pub lambda: usize,
    /// Current σ and σ0.
    pub sigma: f64,
    pub sigma0: f64,
    /// Mean after the update.
    pub mean: &'a [f64],
    /// C, row-major n × n.
    pub covariance: &'a [f64],
    /// Covariance path p_c.
    pub path_c: &'a [f64],
    /// √eigenvalues of C and the eigenvectors (columns, row-major).
    pub scales: &'a [f64],
    pub basis: &'a [f64],
    /// This generation's utilities (larger is better), sorted best first.
    pub utilities: &'a [f64],
    /// Generations since the best-ever individual was born.
    pub since_best: u64,
}

/// Longest kept best/median history (pycma: 2·10⁴ entries, one every 5 generations).
const LONG_HISTORY: usize = 20_000;
/// The long history takes one entry every this many generations (pycma).
const LONG_HISTORY_EVERY: u64 = 5;
/// tolxstagnation's time threshold `offset + fraction·g` (pycma 4.x defaults).
const XSTAGNATION_OFFSET: f64 = 20.0;
const XSTAGNATION_FRACTION: f64 = 0.1;

/// The histories the criteria need, kept in the optimizer (and its checkpoints).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub(crate) struct Monitor {
    /// Best utility of each of the last 10 + ⌈30n/λ⌉ generations, oldest first.
    #[serde(with = "crate::serde_float::vec")]
    recent_best: Vec<f64>,
    /// Best utility every 5th generation, oldest first (for tolstagnation).
    #[serde(with = "crate::serde_float::vec")]
    long_best: Vec<f64>,
    /// Median utility every 5th generation, oldest first.
    #[serde(with = "crate::serde_float::vec")]
    long_median: Vec<f64>,
    /// tolxstagnation: the mean when it last moved, and the generation of that.
    x_reference: Vec<f64>,
    x_reference_generation: u64,
    /// The first criterion that held, kept once set.
    stopped: Option<Criterion>,
}

impl Monitor {
    /// The criterion that stopped the run, if any.
    pub fn stopped(&self) -> Option<Criterion> {
        self.stopped
    }

    /// Records this generation and, when no criterion held before, tests them all.
    pub fn update(&mut self, config: &CmaTermination, s: &Snapshot) {
        self.record(s);
        self.record_mean(config.tolxstagnation, s);
        if config.enabled && self.stopped.is_none() {
            self.stopped = first_holding(config, self, s);
        }
    }

    /// Appends the generation's best and median to the histories (pycma's bookkeeping).
    fn record(&mut self, s: &Snapshot) {
        let n = s.mean.len();
        let best = s.utilities.first().copied().unwrap_or(f64::NEG_INFINITY);
        let capacity = 10 + (30 * n).div_ceil(s.lambda.max(1));
        if self.recent_best.len() >= capacity {
            self.recent_best.remove(0);
        }
        self.recent_best.push(best);
        if s.generation.is_multiple_of(LONG_HISTORY_EVERY) {
            if self.long_best.len() >= LONG_HISTORY {
                self.long_best.remove(0);
                self.long_median.remove(0);
            }
            self.long_best.push(best);
            self.long_median.push(median_sorted_desc(s.utilities));
        }
    }

    /// tolxstagnation's reference mean (pycma's `_StopTolXStagnation.update`): reset whenever
    /// the mean is further than `delta·√max(1, elapsed/threshold)` from it.
    fn record_mean(&mut self, delta: f64, s: &Snapshot) {
        let elapsed = s.generation.saturating_sub(self.x_reference_generation) as f64;
        let tolerance = delta * (elapsed / xstagnation_threshold(s.generation)).max(1.0).sqrt();
        let moved = delta <= 0.0 || self.x_reference.len() != s.mean.len() || {
            let moved_by = distance(&self.x_reference, s.mean);
            moved_by.is_nan() || moved_by > tolerance
        };
        if moved {
            self.x_reference.clear();
            self.x_reference.extend_from_slice(s.mean);
            self.x_reference_generation = s.generation;
        }
    }
}

/// tolxstagnation's time threshold in generations, `20 + 0.1·g`.
fn xstagnation_threshold(generation: u64) -> f64 {
    XSTAGNATION_OFFSET + XSTAGNATION_FRACTION * generation as f64
}

/// A criterion's test.
type Test = fn(&CmaTermination, &Monitor, &Snapshot) -> bool;

/// The first criterion that holds, in pycma's order of tests.
fn first_holding(config: &CmaTermination, monitor: &Monitor, s: &Snapshot) -> Option<Criterion> {
    let tests: [(Criterion, Test); 10] = [
        (Criterion::TolFacUpX, tol_fac_up_x),
        (Criterion::TolX, tol_x),
        (Criterion::TolFun, tol_fun),
        (Criterion::TolFunHist, tol_fun_hist),
        (Criterion::TolStagnation, tol_stagnation),
        (Criterion::TolXStagnation, tol_x_stagnation),
        (Criterion::TolUpSigma, tol_up_sigma),
        (Criterion::NoEffectCoord, no_effect_coord),
        (Criterion::NoEffectAxis, no_effect_axis),
        (Criterion::TolConditionCov, tol_condition_cov),
    ];
    tests
        .into_iter()
        .find(|(_, holds)| holds(config, monitor, s))
        .map(|(criterion, _)| criterion)
}

/// σ·√C_ii of coordinate `i`.
fn coordinate_std(s: &Snapshot, i: usize) -> f64 {
    let n = s.mean.len();
    s.sigma * s.covariance[i * n + i].max(0.0).sqrt()
}

fn tol_fac_up_x(c: &CmaTermination, _: &Monitor, s: &Snapshot) -> bool {
    c.tolfacupx > 0.0 && (0..s.mean.len()).any(|i| coordinate_std(s, i) > s.sigma0 * c.tolfacupx)
}

fn tol_x(c: &CmaTermination, _: &Monitor, s: &Snapshot) -> bool {
    (0..s.mean.len()).all(|i| coordinate_std(s, i) < c.tolx) && s.path_c.iter().all(|p| s.sigma * p.abs() < c.tolx)
}

/// max − min of `values` (NaN, which never passes a `<` test, when a value is infinite).
fn range(values: &[f64]) -> f64 {
    let max = values.iter().fold(f64::NEG_INFINITY, |m, v| m.max(*v));
    let min = values.iter().fold(f64::INFINITY, |m, v| m.min(*v));
    if max.is_finite() && min.is_finite() {
        max - min
    } else {
        f64::NAN
    }
}

fn tol_fun(c: &CmaTermination, m: &Monitor, s: &Snapshot) -> bool {
    range(s.utilities) < c.tolfun && range(&m.recent_best) < c.tolfun
}

fn tol_fun_hist(c: &CmaTermination, m: &Monitor, _: &Snapshot) -> bool {
    m.recent_best.len() > 9 && range(&m.recent_best) < c.tolfunhist
}

/// pycma's stagnation test: over the long (every-5th-generation) histories, compare the median
/// of the most recent `l` entries with that of the `l` before; stop when neither the best nor
/// the median values improved and the best-ever is older than half the horizon.
fn tol_stagnation(c: &CmaTermination, m: &Monitor, s: &Snapshot) -> bool {
    let n = s.mean.len();
    let horizon = c.stagnation(n, s.lambda);
    if horizon == 0 {
        return false;
    }
    let entries = m.long_best.len();
    let l = (horizon as f64 / 5.0 / 2.0).max(entries as f64 / 10.0);
    let generation = s.generation as f64;
    if l > generation || generation <= n as f64 * (5.0 + 100.0 / s.lambda as f64) {
        return false;
    }
    let l = l as usize;
    let since_best = s.since_best as f64 > horizon as f64 / 2.0;
    since_best && entries > 100 && 2 * l < entries && {
        let not_better = |h: &[f64]| median(&h[entries - l..]) <= median(&h[entries - 2 * l..entries - l]);
        not_better(&m.long_median) && not_better(&m.long_best)
    }
}

fn tol_x_stagnation(c: &CmaTermination, m: &Monitor, s: &Snapshot) -> bool {
    c.tolxstagnation > 0.0
        && s.generation.saturating_sub(m.x_reference_generation) as f64 > xstagnation_threshold(s.generation)
}

fn tol_up_sigma(c: &CmaTermination, _: &Monitor, s: &Snapshot) -> bool {
    let d_max = s.scales.iter().fold(0.0f64, |m, v| m.max(*v));
    c.tolupsigma > 0.0 && s.sigma / d_max > s.sigma0 * c.tolupsigma
}

fn no_effect_coord(c: &CmaTermination, _: &Monitor, s: &Snapshot) -> bool {
    c.noeffectcoord && (0..s.mean.len()).any(|i| s.mean[i] == s.mean[i] + 0.2 * coordinate_std(s, i))
}

/// Tests axis g mod n only, as pycma does, so each generation costs O(n).
fn no_effect_axis(c: &CmaTermination, _: &Monitor, s: &Snapshot) -> bool {
    let n = s.mean.len();
    let axis = (s.generation % n as u64) as usize;
    let step = 0.1 * s.sigma * s.scales[axis];
    c.noeffectaxis && (0..n).all(|i| s.mean[i] == s.mean[i] + step * s.basis[i * n + axis])
}

fn tol_condition_cov(c: &CmaTermination, _: &Monitor, s: &Snapshot) -> bool {
    let max = s.scales.iter().fold(0.0f64, |m, v| m.max(*v));
    let min = s.scales.iter().fold(f64::INFINITY, |m, v| m.min(*v));
    c.tolconditioncov > 0.0 && max > c.tolconditioncov.sqrt() * min
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt()
}

/// Median of values sorted best (largest) first.
fn median_sorted_desc(sorted: &[f64]) -> f64 {
    let k = sorted.len();
    match k {
        0 => f64::NEG_INFINITY,
        _ if k % 2 == 1 => sorted[k / 2],
        _ => 0.5 * (sorted[k / 2 - 1] + sorted[k / 2]),
    }
}

/// Median of unsorted values (a sorted copy; called at most once per generation on ≤ 2·10⁴/10
/// entries when the stagnation test is reached).
fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(|a, b| b.total_cmp(a));
    median_sorted_desc(&sorted)
}
