//! The Pareto analysis of `vsrlab analyze` for runs with two objectives (NSGA-II; thesis ch.
//! 5.1): each run's final population, its first front, knee and specialists
//! ([`vsrlab_analysis::pareto`]), as `pareto.csv` and a scatter of every final population with
//! the fronts drawn larger.

use crate::error::AnalysisError;
use crate::output::{create_folder, write_output};
use crate::replay::ReplaySetup;
use crate::settings::Setting;
use std::fmt::Write as _;
use std::path::Path;
use vsrlab_analysis::pareto::{first_front, knee, specialist};
use vsrlab_analysis::plot::{ScatterFigure, ScatterPoint};
use vsrlab_analysis::progress::Progress;
use vsrlab_analysis::results::{read_snapshot, ExperimentData};

/// One objective of an experiment: its metric and whether it is minimised.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ObjectiveSense {
    pub metric: String,
    pub minimize: bool,
}

/// The objectives of an experiment's task (`task.fitness` of its resolved configuration).
pub(crate) fn objectives(experiment: &ExperimentData) -> Vec<ObjectiveSense> {
    let one = |v: &toml::Value| match v {
        toml::Value::String(metric) => Some(ObjectiveSense {
            metric: metric.clone(),
            minimize: false,
        }),
        toml::Value::Table(t) => Some(ObjectiveSense {
            metric: t.get("metric")?.as_str()?.to_string(),
            minimize: t.get("sense").and_then(|s| s.as_str()) == Some("minimize"),
        }),
        _ => None,
    };
    match experiment.config_value("task.fitness") {
        Some(toml::Value::Array(items)) => items.iter().filter_map(one).collect(),
        Some(v) => one(v).into_iter().collect(),
        None => Vec::new(),
    }
}

/// One member of a final population.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Member {
    pub setting: usize,
    /// Its experiment (an index into the experiments).
    pub experiment: usize,
    pub run: String,
    pub index: usize,
    pub objectives: Vec<f64>,
    /// `front`, `knee`, `specialist-<metric>` (joined by `+`), or empty.
    pub role: String,
    /// The genotype of a knee or specialist (to save it as a robot file), else `None`.
    pub genotype: Option<serde_json::Value>,
}

/// Every final-population member of every run of the settings whose experiments have two
/// objectives, with their roles; and the objectives (those of the first such experiment).
pub(crate) fn members(settings: &[Setting], experiments: &[ExperimentData]) -> (Vec<ObjectiveSense>, Vec<Member>) {
    let mut senses = Vec::new();
    let mut all = Vec::new();
    for (s, setting) in settings.iter().enumerate() {
        let runs = setting
            .experiments
            .iter()
            .flat_map(|&e| experiments[e].runs.iter().map(move |r| (e, r)));
        for (e, run) in runs {
            let experiment = &experiments[e];
            let own = objectives(experiment);
            if own.len() != 2 {
                continue;
            }
            if senses.is_empty() {
                senses = own.clone();
            }
            let Some((_, path)) = run.final_snapshot() else {
                continue;
            };
            let Ok(rows) = read_snapshot(path) else { continue };
            let points: Vec<Vec<f64>> = rows
                .iter()
                .map(|r| {
                    r.record
                        .as_ref()
                        .and_then(|rec| rec.objectives.clone())
                        .unwrap_or_else(|| vec![f64::NAN; 2])
                })
                .collect();
            let minimize: Vec<bool> = own.iter().map(|o| o.minimize).collect();
            let front = first_front(&points, &minimize);
            let knee = knee(&points, &front);
            let specialists: Vec<Option<usize>> = (0..2).map(|k| specialist(&points, &front, k, minimize[k])).collect();
            for (i, p) in points.into_iter().enumerate() {
                let mut roles = Vec::new();
                if front.contains(&i) {
                    roles.push("front".to_string());
                }
                if knee == Some(i) {
                    roles.push("knee".to_string());
                }
                for (k, &sp) in specialists.iter().enumerate() {
                    if sp == Some(i) {
                        roles.push(format!("specialist-{}", own[k].metric));
                    }
                }
                let chosen = roles.iter().any(|r| r != "front");
                all.push(Member {
                    setting: s,
                    experiment: e,
                    run: experiment.run_label(run),
                    index: rows[i].index,
                    objectives: p,
                    role: roles.join("+"),
                    genotype: chosen.then(|| rows[i].genotype.clone()),
                });
            }
        }
    }
    (senses, all)
}

/// Saves every run's knee and specialists as robot files in `dir`
/// (`<setting>-<run>-<roles>.robot.json`, the roles joined by `+`), for `vsrlab simulate --robot`;
/// returns how many were written. A member whose experiment cannot be replayed is skipped with
/// a warning.
pub(crate) fn save_role_robots(
    dir: &Path,
    settings: &[Setting],
    setups: &[Option<ReplaySetup>],
    members: &[Member],
    progress: &dyn Progress,
) -> Result<usize, AnalysisError> {
    let mut written = 0;
    for m in members {
        let (Some(genotype), Some(setup)) = (&m.genotype, &setups[m.experiment]) else {
            continue;
        };
        let run = Path::new(&m.run)
            .file_name()
            .map_or("run".into(), |n| n.to_string_lossy());
        let name = format!(
            "{}-{run}-{}.robot.json",
            settings[m.setting].name,
            m.role.replace("front+", "")
        );
        let note = format!(
            "{} {}: {} of the final first front, objectives {:?}",
            settings[m.setting].name, m.run, m.role, m.objectives
        );
        match setup.genotypes.robot(genotype) {
            Ok(robot) => {
                let Some(description) = robot.description() else {
                    continue;
                };
                if written == 0 {
                    create_folder(dir)?;
                }
                write_output(&dir.join(name), description.to_json(Some(&note)).as_bytes())?;
                written += 1;
            }
            Err(e) => progress.note(&format!("warning: {}: {e}", m.run)),
        }
    }
    Ok(written)
}

/// `pareto.csv`: setting, run, index in the final population, the two objectives, role.
pub(crate) fn pareto_csv(settings: &[Setting], senses: &[ObjectiveSense], members: &[Member]) -> String {
    let mut text = format!("setting,run,index,{},{},role\n", senses[0].metric, senses[1].metric);
    for m in members {
        let _ = writeln!(
            text,
            "{},{},{},{},{},{}",
            settings[m.setting].name, m.run, m.index, m.objectives[0], m.objectives[1], m.role
        );
    }
    text
}

/// Per setting (indexed by its colour), objective `k` of every run's member with `role` (`knee`,
/// `specialist-<metric>`): the values of the per-setting boxplots.
pub(crate) fn role_values(settings: &[Setting], members: &[Member], role: &str, k: usize) -> Vec<Vec<f64>> {
    let mut values = vec![Vec::new(); settings.iter().map(|s| s.color + 1).max().unwrap_or(0)];
    for m in members.iter().filter(|m| m.role.split('+').any(|r| r == role)) {
        values[settings[m.setting].color].push(m.objectives[k]);
    }
    values
}

/// The scatter of every final population: front members larger, knees largest.
pub(crate) fn pareto_figure(settings: &[Setting], senses: &[ObjectiveSense], members: &[Member]) -> ScatterFigure {
    let label = |o: &ObjectiveSense| format!("{} ({})", o.metric, if o.minimize { "minimised" } else { "maximised" });
    let radius = |role: &str| {
        if role.contains("knee") {
            9.0
        } else if role.contains("front") {
            5.0
        } else {
            2.5
        }
    };
    ScatterFigure {
        title: "Final populations and their first fronts (large: front, largest: knee)".into(),
        x_label: label(&senses[0]),
        y_label: label(&senses[1]),
        groups: settings.iter().map(|s| s.name.clone()).collect(),
        legend_title: "setting".into(),
        points: members
            .iter()
            .filter(|m| m.objectives.iter().all(|v| v.is_finite()))
            .map(|m| ScatterPoint {
                x: m.objectives[0],
                y: m.objectives[1],
                radius: radius(&m.role),
                group: m.setting,
            })
            .collect(),
        x_range: None,
        y_range: None,
        size_legend: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn experiment(task: &str) -> ExperimentData {
        ExperimentData {
            dir: "x".into(),
            name: "x".into(),
            config: toml::from_str(task).unwrap(),
            runs: Vec::new(),
        }
    }

    #[test]
    fn role_values_pick_each_runs_member_with_the_role() {
        let setting = |name: &str, color| Setting {
            name: name.into(),
            color,
            experiments: Vec::new(),
        };
        let settings = [setting("flatworm", 0), setting("gecko", 1)];
        let member = |s, role: &str, o: [f64; 2]| Member {
            setting: s,
            experiment: s,
            run: "0".into(),
            index: 0,
            objectives: o.to_vec(),
            role: role.into(),
            genotype: None,
        };
        let members = [
            member(0, "front+knee", [0.1, 0.3]),
            member(0, "front+specialist-sensing", [0.2, 0.5]),
            member(0, "", [0.4, 0.9]),
            member(1, "front+knee+specialist-sensing", [0.3, 0.6]),
        ];
        assert_eq!(role_values(&settings, &members, "knee", 1), [vec![0.3], vec![0.6]]);
        assert_eq!(
            role_values(&settings, &members, "specialist-sensing", 1),
            [vec![0.5], vec![0.6]]
        );
        assert_eq!(
            role_values(&settings, &members, "front", 0),
            [vec![0.1, 0.2], vec![0.3]]
        );
    }

    #[test]
    fn objectives_are_read_from_the_resolved_fitness() {
        let two = experiment("[task]\nfitness = [{ metric = \"locomotion\", sense = \"minimize\" }, \"sensing\"]");
        assert_eq!(
            objectives(&two),
            vec![
                ObjectiveSense {
                    metric: "locomotion".into(),
                    minimize: true
                },
                ObjectiveSense {
                    metric: "sensing".into(),
                    minimize: false
                }
            ]
        );
        assert_eq!(objectives(&experiment("[task]\nfitness = \"velocity\"")).len(), 1);
        assert!(objectives(&experiment("[task]\nkind = \"jump\"")).is_empty());
    }
}
