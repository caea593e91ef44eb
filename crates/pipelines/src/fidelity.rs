//! The 2D fidelity protocol behind `vsrlab fidelity` (docs/fidelity.md, "The protocol"): for
//! every reference case (preset, body, terrain, brain), vsrlab's start-shift ensemble against the
//! original simulator's, stored as data (`assets/fidelity/original-2d.csv`: one row per start,
//! measured with the instrument docs/fidelity.md describes). Each case gets a two-sample
//! Kolmogorov–Smirnov test, a Mann–Whitney test, the bootstrap interval of the median difference
//! and the equivalence test of the medians against the original's own split-half variability
//! ([`vsrlab_analysis::equivalence`]).
//!
//! A case passes when the medians are shown equivalent and the KS test does not reject the same
//! distribution at 0.1 %; a sample of the original's own distribution passes about 97 % of the
//! time (the equivalence module's calibration), so a faithful solver is expected to fail a few
//! cases in a hundred by chance.

use rayon::prelude::*;
use serde::Serialize;
use std::collections::BTreeMap;
use vsrlab_analysis::equivalence::{kolmogorov_smirnov, median_equivalence, KolmogorovSmirnov, MedianEquivalence};
use vsrlab_analysis::stats::{mann_whitney_u, quantile};
use vsrlab_body::Morphology;
use vsrlab_experiment::cpu_time::thread_cpu_seconds;
use vsrlab_tasks::ensemble;
use vsrlab_tasks::{RobotSpec, TaskSpec};

/// The original's ensembles shipped with vsrlab: `preset,body,terrain,brain,k,velocity`.
pub const ORIGINAL_2D: &str = include_str!("../../../assets/fidelity/original-2d.csv");

/// The distance between neighbouring starts of every ensemble (the robot's left edge moves by
/// k·δ).
pub const SHIFT: f64 = 1e-6;

/// Below this KS p-value a case fails on the shape of its distribution.
pub const KS_LEVEL: f64 = 0.001;

/// The sensors of every case's robot: its brain reads none, and the instrument's robots have
/// none (the same work on both sides when their speeds are compared).
const SENSORS: &str = "empty";

/// The evolved robots of the cases whose brain is `robot:NAME`: vsrlab robot files (body,
/// sensors, MLP weights), the same weights the instrument's driver gave the original
/// (`assets/fidelity/robots/`, evolved by `mlp-biped.toml` there).
const ROBOTS: &[(&str, &str)] = &[
    (
        "mlp-biped-2021",
        include_str!("../../../assets/fidelity/robots/mlp-biped-2021.robot.json"),
    ),
    (
        "mlp-biped-2022",
        include_str!("../../../assets/fidelity/robots/mlp-biped-2022.robot.json"),
    ),
];

/// One reference case: the original's velocities from starts shifted by k·[`SHIFT`].
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// Physical preset: 2021 (2D-VSR-Sim v1.10.0) or 2022 (its HEAD, e569066).
    pub preset: String,
    /// Body short form (`biped-4x3`).
    pub body: String,
    /// Terrain (`flat`, `hilly-1-10-0`, …).
    pub terrain: String,
    /// Brain short form (`phase`, `constant:1`), or `robot:NAME`, an evolved robot of
    /// `assets/fidelity/robots/` (its own sensors and brain, on this case's body and preset).
    pub brain: String,
    /// Start offsets k (the start is shifted by k·[`SHIFT`]) and the original's velocity from each.
    pub starts: Vec<(i64, f64)>,
}

impl Case {
    /// `preset/body/terrain/brain`, as `--cases` filters match it.
    pub fn name(&self) -> String {
        format!("{}/{}/{}/{}", self.preset, self.body, self.terrain, self.brain)
    }
}

/// A reference file that cannot be read, or a case vsrlab cannot run.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum FidelityError {
    /// A line of the reference is malformed.
    #[error("reference, line {line}: {msg}")]
    Reference {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        msg: String,
    },
    /// A case's robot or task cannot be built or run.
    #[error("case {case}: {msg}")]
    Case {
        /// The case's name.
        case: String,
        /// What failed.
        msg: String,
    },
}

/// The cases of a reference CSV (`preset,body,terrain,brain,k,velocity` with a header), in file
/// order.
pub fn read_cases(text: &str) -> Result<Vec<Case>, FidelityError> {
    let mut cases: Vec<Case> = Vec::new();
    let mut index: BTreeMap<[String; 4], usize> = BTreeMap::new();
    for (i, line) in text.lines().enumerate().skip(1) {
        let line_no = i + 1;
        if line.trim().is_empty() {
            continue;
        }
        let bad = |msg: String| FidelityError::Reference { line: line_no, msg };
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let [preset, body, terrain, brain, k, velocity] = fields[..] else {
            return Err(bad(format!(
                "6 fields expected (preset,body,terrain,brain,k,velocity), got {}",
                fields.len()
            )));
        };
        let k: i64 = k.parse().map_err(|_| bad(format!("k: not a whole number: {k:?}")))?;
        let v: f64 = velocity
            .parse()
            .map_err(|_| bad(format!("velocity: not a number: {velocity:?}")))?;
        if !v.is_finite() {
            return Err(bad(format!("velocity: not finite: {v}")));
        }
        let key = [preset, body, terrain, brain].map(str::to_string);
        let at = *index.entry(key).or_insert_with(|| {
            cases.push(Case {
                preset: preset.into(),
                body: body.into(),
                terrain: terrain.into(),
                brain: brain.into(),
                starts: Vec::new(),
            });
            cases.len() - 1
        });
        cases[at].starts.push((k, v));
    }
    Ok(cases)
}

/// Quartiles and median of an ensemble (NumPy's linear interpolation).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Spread {
    /// First quartile.
    pub q1: f64,
    /// Median.
    pub median: f64,
    /// Third quartile.
    pub q3: f64,
}

impl Spread {
    fn of(values: &[f64]) -> Spread {
        Spread {
            q1: quantile(values, 0.25),
            median: quantile(values, 0.5),
            q3: quantile(values, 0.75),
        }
    }
}

/// One case's row of the protocol's table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaseResult {
    /// `preset/body/terrain/brain`.
    pub case: String,
    /// Starts on each side.
    pub n: usize,
    /// The original's ensemble.
    pub original: Spread,
    /// vsrlab's ensemble from the same starts.
    pub ours: Spread,
    /// The medians' equivalence test.
    pub equivalence: MedianEquivalence,
    /// Two-sided Mann–Whitney p-value.
    pub mann_whitney_p: f64,
    /// The Kolmogorov–Smirnov test.
    pub ks: KolmogorovSmirnov,
    /// Equivalent medians and KS p ≥ [`KS_LEVEL`].
    pub passed: bool,
    /// vsrlab's velocities, in the order of the starts.
    pub values: Vec<f64>,
    /// Simulated steps and the CPU seconds they took, summed over the ensemble's episodes.
    pub steps: u64,
    /// CPU seconds of the ensemble's episodes.
    pub seconds: f64,
}

/// Options of [`run_case`].
#[derive(Debug, Clone, Default)]
pub struct FidelityOptions {
    /// The 2D solver (`soft-substeps`, `sequential-impulses`); None: the task's default.
    pub solver: Option<String>,
    /// Use only the starts with |k| ≤ this (the reference's own: all).
    pub max_k: Option<i64>,
    /// Task settings to change (`physics.contact_hertz`, …), as `vsrlab run`'s overrides: a
    /// solver variant to put under the protocol.
    pub settings: Vec<(String, serde_json::Value)>,
}

/// vsrlab's ensemble for `case` and the protocol's tests against the original's.
pub fn run_case(case: &Case, options: &FidelityOptions) -> Result<CaseResult, FidelityError> {
    let fail = |msg: String| FidelityError::Case { case: case.name(), msg };
    let starts: Vec<(i64, f64)> = case
        .starts
        .iter()
        .copied()
        .filter(|(k, _)| options.max_k.is_none_or(|m| k.abs() <= m))
        .collect();
    if starts.len() < 4 {
        return Err(fail(format!("{} starts: the tests need at least 4", starts.len())));
    }
    let robot = case_robot(case).map_err(fail)?;
    let mut task = TaskSpec::parse(&format!("locomotion:{}", case.terrain)).map_err(|e| fail(e.to_string()))?;
    let mut settings: Vec<(&str, serde_json::Value)> = Vec::new();
    if let Some(solver) = &options.solver {
        settings.push(("physics.solver", serde_json::json!(solver)));
    }
    settings.extend(options.settings.iter().map(|(k, v)| (k.as_str(), v.clone())));
    if !settings.is_empty() {
        task = task.with_settings(&settings).map_err(|e| fail(e.to_string()))?;
    }
    let tasks = starts
        .iter()
        .map(|&(k, _)| ensemble::shifted_task(&task, k as f64 * SHIFT))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| fail(e.to_string()))?;
    let episodes = tasks
        .par_iter()
        .map(|t| {
            let clock = thread_cpu_seconds();
            let outcome = vsrlab_tasks::episode::run(&robot, t.task(), 0, vsrlab_tasks::TraceLevel::None);
            outcome.map(|o| (o.metric("velocity"), o.steps, thread_cpu_seconds() - clock))
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| fail(e.to_string()))?;
    let values: Vec<f64> = episodes.iter().map(|e| e.0).collect();
    let original: Vec<f64> = starts.iter().map(|s| s.1).collect();
    let equivalence = median_equivalence(&values, &original, seed_of(&case.name()));
    let ks = kolmogorov_smirnov(&values, &original).ok_or_else(|| fail("a NaN velocity".into()))?;
    let mann_whitney_p = mann_whitney_u(&values, &original).map_or(f64::NAN, |m| m.p);
    Ok(CaseResult {
        case: case.name(),
        n: values.len(),
        original: Spread::of(&original),
        ours: Spread::of(&values),
        passed: equivalence.equivalent && ks.p >= KS_LEVEL,
        equivalence,
        mann_whitney_p,
        ks,
        steps: episodes.iter().map(|e| e.1).sum(),
        seconds: episodes.iter().map(|e| e.2).sum(),
        values,
    })
}

/// The robot of `case`: its body and preset with no sensors and the brain's short form, or, for
/// `robot:NAME`, the shipped evolved robot, which must have the case's body and preset.
fn case_robot(case: &Case) -> Result<RobotSpec, String> {
    let Some(name) = case.brain.strip_prefix("robot:") else {
        return RobotSpec::from_short_forms(&case.body, &case.preset, SENSORS, &case.brain)
            .map_err(|e| format!("--{}: {}", e.part(), e.message()));
    };
    let names = || ROBOTS.iter().map(|r| r.0).collect::<Vec<_>>().join(", ");
    let (_, text) = ROBOTS
        .iter()
        .find(|r| r.0 == name)
        .ok_or_else(|| format!("brain: no shipped robot '{name}' (there are: {})", names()))?;
    let robot = vsrlab_tasks::kinds::voxel::robot_from_json(text, name).map_err(|e| e.to_string())?;
    let body = Morphology::parse(&case.body).map_err(|e| format!("body: {e}"))?;
    if robot.body != body || robot.preset.to_string() != case.preset {
        return Err(format!(
            "brain: robot '{name}' has another body or preset than the case's {} {}",
            case.body, case.preset
        ));
    }
    Ok(robot)
}

/// The resampling seed of a case: its name hashed (FNV-1a), so that a case's table does not
/// depend on which other cases run.
fn seed_of(name: &str) -> u64 {
    name.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shipped_reference_reads_into_cases_of_whole_ensembles() {
        let cases = read_cases(ORIGINAL_2D).unwrap();
        assert!(!cases.is_empty());
        for case in &cases {
            assert!(case.starts.len() >= 30, "{}: {}", case.name(), case.starts.len());
            assert!(
                !case.starts.iter().any(|&(k, _)| k == 0),
                "{}: no unshifted start",
                case.name()
            );
        }
        let names: std::collections::BTreeSet<String> = cases.iter().map(Case::name).collect();
        assert_eq!(names.len(), cases.len(), "each case once");
    }

    #[test]
    fn every_shipped_case_builds_its_robot_and_task() {
        let cases = read_cases(ORIGINAL_2D).unwrap();
        for case in &cases {
            let robot = case_robot(case).unwrap_or_else(|e| panic!("{}: {e}", case.name()));
            assert_eq!(robot.preset.to_string(), case.preset, "{}", case.name());
            TaskSpec::parse(&format!("locomotion:{}", case.terrain)).unwrap();
        }
        let evolved = cases.iter().filter(|c| c.brain.starts_with("robot:")).count();
        assert_eq!(evolved, 6, "the evolved brains' cases");
    }

    #[test]
    fn bad_reference_lines_name_the_line_and_the_field() {
        let header = "preset,body,terrain,brain,k,velocity\n";
        let err = read_cases(&format!("{header}2021,biped-4x3,flat,phase,1\n")).unwrap_err();
        assert_eq!(
            err.to_string(),
            "reference, line 2: 6 fields expected (preset,body,terrain,brain,k,velocity), got 5"
        );
        let err = read_cases(&format!("{header}2021,biped-4x3,flat,phase,one,0.5\n")).unwrap_err();
        assert!(err.to_string().starts_with("reference, line 2: k: "), "{err}");
        let err = read_cases(&format!("{header}\n2021,biped-4x3,flat,phase,1,NaN\n")).unwrap_err();
        assert!(
            err.to_string().starts_with("reference, line 3: velocity: not finite"),
            "{err}"
        );
    }

    #[test]
    fn a_case_vsrlab_cannot_build_is_an_error_naming_it() {
        let case = Case {
            preset: "2021".into(),
            body: "biped-4x3".into(),
            terrain: "marsh".into(),
            brain: "phase".into(),
            starts: (1..=4).map(|k| (k, 0.1)).collect(),
        };
        let err = run_case(&case, &FidelityOptions::default()).unwrap_err();
        assert!(
            err.to_string().starts_with("case 2021/biped-4x3/marsh/phase: "),
            "{err}"
        );
    }

    #[test]
    fn an_evolved_robot_case_runs_the_shipped_robot_and_a_mismatch_is_named() {
        let mut case = Case {
            preset: "2021".into(),
            body: "biped-4x3".into(),
            terrain: "flat".into(),
            brain: "robot:mlp-biped-2021".into(),
            starts: (1..=4).map(|k| (k, 0.1)).collect(),
        };
        let options = FidelityOptions::default();
        let result = run_case(&case, &options).unwrap();
        // the evolved gait walks (the original's ensemble of this case: median 2.4); a body
        // without its brain stands still
        assert!(result.ours.median > 1.0, "{result:?}");
        case.preset = "2022".into();
        let err = run_case(&case, &options).unwrap_err().to_string();
        assert!(err.contains("another body or preset"), "{err}");
        case.brain = "robot:nobody".into();
        let err = run_case(&case, &options).unwrap_err().to_string();
        assert!(err.contains("no shipped robot 'nobody'"), "{err}");
    }

    #[test]
    fn a_case_against_its_own_velocities_passes_and_against_shifted_ones_fails() {
        // vsrlab's own ensemble as the reference: equivalent by construction; moved up by far
        // more than its spread: not
        let mut case = Case {
            preset: "2022".into(),
            body: "worm-4x2".into(),
            terrain: "flat".into(),
            brain: "phase".into(),
            starts: (-8..=8).filter(|&k| k != 0).map(|k| (k, 0.0)).collect(),
        };
        let options = FidelityOptions {
            solver: Some("soft-substeps".into()),
            ..FidelityOptions::default()
        };
        let first = run_case(&case, &options).unwrap();
        case.starts = case
            .starts
            .iter()
            .zip(&first.values)
            .map(|(&(k, _), &v)| (k, v))
            .collect();
        let same = run_case(&case, &options).unwrap();
        assert!(
            same.passed && same.equivalence.difference == 0.0 && same.ks.d == 0.0,
            "{same:?}"
        );
        let spread = (first.ours.q3 - first.ours.q1).max(1e-3);
        case.starts.iter_mut().for_each(|s| s.1 += 20.0 * spread);
        let moved = run_case(&case, &options).unwrap();
        assert!(!moved.passed && !moved.equivalence.equivalent, "{moved:?}");
        assert_eq!(moved.n, 16);
    }
}
