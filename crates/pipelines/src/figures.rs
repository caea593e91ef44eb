//! The figures of `analyze`, built from the runs, the best robots and the species (each is
//! described in `summary.md` and docs/analysis.md).

use crate::best_robots::BestRobot;
use crate::classifiers::Classifiers;
use crate::settings::Setting;
use crate::species::{Labelled, RunSpecies, SnapshotIsi};
use vsrlab_analysis::curves::{band, grid_for};
use vsrlab_analysis::pca::Pca;
use vsrlab_analysis::plot::{
    BandChart, BandFigure, BandSeries, BoxFigure, BoxGroup, Bubble, BubbleFigure, BubblePanel, ScatterFigure,
    ScatterPoint,
};
use vsrlab_analysis::report::pairwise;
use vsrlab_analysis::results::{ExperimentData, GenerationRow};
use vsrlab_experiment::genotypes::ColumnFigure;

/// Curves are resampled on a common grid of this many points before taking median and sd.
const GRID_POINTS: usize = 200;

/// Most p-value brackets drawn on a boxplot (more pairs are left to the tables).
const MAX_BRACKETS: usize = 6;

/// Best-so-far and population-median fitness vs evaluations, median ± sd across runs.
pub(crate) fn fitness_figure(settings: &[Setting], experiments: &[ExperimentData], fitness: &str) -> BandFigure {
    let panel = |title: &str, pick: &dyn Fn(&GenerationRow) -> f64| {
        evaluations_panel(title, fitness, settings, |s| {
            s.runs(experiments)
                .map(|(_, r)| {
                    r.generations
                        .iter()
                        .map(|g| (g.evaluations as f64, pick(g)))
                        .filter(|p| p.1.is_finite())
                        .collect()
                })
                .filter(|c: &Vec<(f64, f64)>| !c.is_empty())
                .collect()
        })
    };
    BandFigure {
        note: vsrlab_analysis::plot::band::median_sd_note(),
        title: format!("Fitness ({fitness}) during evolution"),
        legend_title: "setting".into(),
        panels: vec![
            panel("best so far (re-evaluated: of the population)", &|g| g.best_fitness),
            panel("population median", &|g| g.population_median),
        ],
    }
}

/// A column logged for the best genotype (`best_<column>`) vs evaluations, median ± sd across
/// runs, as its genotype kind describes it; `None` without data. Only the experiments of a kind
/// that declares the figure count.
pub(crate) fn column_figure(
    settings: &[Setting],
    experiments: &[ExperimentData],
    figure: &ColumnFigure,
) -> Option<BandFigure> {
    let declares = |e: &ExperimentData| column_figures(e).contains(figure);
    let curves_of = |s: &Setting| -> Vec<Vec<(f64, f64)>> {
        s.runs(experiments)
            .filter(|(e, _)| declares(e))
            .map(|(_, r)| {
                r.generations
                    .iter()
                    .map(|g| (g.evaluations as f64, g.best_stat(figure.column)))
                    .filter(|p| p.1.is_finite())
                    .collect()
            })
            .filter(|c: &Vec<(f64, f64)>| !c.is_empty())
            .collect()
    };
    if settings.iter().all(|s| curves_of(s).is_empty()) {
        return None;
    }
    Some(BandFigure {
        note: vsrlab_analysis::plot::band::median_sd_note(),
        title: figure.title.into(),
        legend_title: "setting".into(),
        panels: vec![evaluations_panel(figure.axis, figure.axis, settings, |s| curves_of(s))],
    })
}

/// The figures an experiment's genotype kind declares (none for flat vectors, or for a kind
/// this version does not know).
pub(crate) fn column_figures(experiment: &ExperimentData) -> Vec<ColumnFigure> {
    match experiment.config.get("genotype") {
        Some(toml::Value::Table(table)) => vsrlab_experiment::genotypes::decode_table(table.clone())
            .map(|kind| kind.column_figures())
            .unwrap_or_default(),
        _ => Vec::new(),
    }
}

/// ISI of species, morphology and behaviour classes vs evaluations, median ± sd across runs.
pub(crate) fn isi_figure(settings: &[Setting], runs: &[RunSpecies]) -> BandFigure {
    let panel = |title: &str, pick: &dyn Fn(&SnapshotIsi) -> f64| {
        evaluations_panel(title, "Inverse Simpson Index", settings, |s| {
            runs.iter()
                .filter(|r| r.setting == s.color)
                .map(|r| r.snapshots.iter().map(|x| (x.evaluations as f64, pick(x))).collect())
                .collect()
        })
    };
    BandFigure {
        note: vsrlab_analysis::plot::band::median_sd_note(),
        title: "Diversity of the population (Inverse Simpson Index)".into(),
        legend_title: "setting".into(),
        panels: vec![
            panel("species", &|x| x.species),
            panel("morphology", &|x| x.shape),
            panel("behaviour", &|x| x.behaviour),
        ],
    }
}

/// A panel of `y_label` vs fitness evaluations: per setting, the median ± sd band of the curves
/// (one per run) that `curves_of` gives for it.
fn evaluations_panel(
    title: &str,
    y_label: &str,
    settings: &[Setting],
    curves_of: impl Fn(&Setting) -> Vec<Vec<(f64, f64)>>,
) -> BandChart {
    BandChart {
        title: title.into(),
        x_label: "fitness evaluations".into(),
        y_label: y_label.into(),
        series: settings.iter().map(|s| median_band(s, &curves_of(s))).collect(),
    }
}

/// The median ± sd band across runs of one setting's curves, on a common grid.
fn median_band(setting: &Setting, curves: &[Vec<(f64, f64)>]) -> BandSeries {
    let grid = grid_for(curves, GRID_POINTS);
    let b = band(curves, &grid, true);
    BandSeries {
        label: setting.name.clone(),
        color: setting.color,
        x: b.x,
        center: b.median,
        spread: b.sd,
    }
}

/// The settings' names without the dash-separated words they all begin with (a sweep's
/// `affordance-reduced-flatworm`, `affordance-reduced-gecko` → `flatworm`, `gecko`), so that tick
/// labels fit; the names themselves when fewer than two or when nothing would be left.
pub(crate) fn short_names(settings: &[Setting]) -> Vec<String> {
    let names: Vec<&str> = settings.iter().map(|s| s.name.as_str()).collect();
    let shared = |cut: usize| {
        names
            .iter()
            .all(|n| n.len() > cut && n.as_bytes()[cut] == b'-' && n[..cut] == names[0][..cut])
    };
    let cut = match names.len() {
        0 | 1 => None,
        _ => names[0].match_indices('-').map(|(i, _)| i).rfind(|&i| shared(i)),
    };
    names
        .iter()
        .map(|n| cut.map_or(*n, |c| &n[c + 1..]).to_string())
        .collect()
}

/// One box per setting from `values[setting colour]`, with pairwise Mann–Whitney p-values; the
/// boxes are labelled by [`short_names`].
pub(crate) fn boxplot(title: String, y_label: String, settings: &[Setting], values: &[Vec<f64>]) -> BoxFigure {
    let labels = short_names(settings);
    BoxFigure {
        title,
        y_label,
        groups: settings
            .iter()
            .zip(labels)
            .map(|(s, label)| BoxGroup {
                label,
                color: s.color,
                values: values[s.color].clone(),
            })
            .collect(),
        pvalues: pairwise("", values)
            .into_iter()
            .filter_map(|c| c.test.map(|t| (c.a, c.b, t.p)))
            .collect(),
        max_brackets: MAX_BRACKETS,
    }
}

/// Elongation vs compactness of each run's best robot, marker area ∝ voxels.
pub(crate) fn descriptor_figure(settings: &[Setting], bests: &[BestRobot]) -> ScatterFigure {
    let max_voxels = bests.iter().map(|b| b.descriptors.voxels).max().unwrap_or(1).max(1) as f64;
    let radius = |v: f64| 4.0 + 16.0 * (v / max_voxels).sqrt();
    let size_entries: Vec<(String, f64)> = size_legend_values(max_voxels)
        .into_iter()
        .map(|v| (format!("{v}"), radius(v as f64)))
        .collect();
    ScatterFigure {
        title: "Morphology descriptors of the best robots".into(),
        x_label: "elongation".into(),
        y_label: "compactness".into(),
        groups: settings.iter().map(|s| s.name.clone()).collect(),
        legend_title: "setting".into(),
        points: bests
            .iter()
            .map(|b| ScatterPoint {
                x: b.descriptors.elongation,
                y: b.descriptors.compactness,
                radius: radius(b.descriptors.voxels as f64),
                group: b.setting,
            })
            .collect(),
        x_range: Some((-0.03, 1.03)),
        y_range: Some((0.0, 1.03)),
        size_legend: Some(("voxels".into(), size_entries)),
    }
}

/// Marker-size legend entries: 1, a quarter, half and all of the most voxels.
fn size_legend_values(max: f64) -> Vec<usize> {
    let max = max.max(1.0) as usize;
    let mut v: Vec<usize> = [1, max / 4, max / 2, max].into_iter().filter(|&x| x >= 1).collect();
    v.dedup();
    v
}

/// The best robots on the first two principal components of their standardised features
/// (dynamic pose + behaviour); None with fewer than 3 replayed best robots.
pub(crate) fn pca_figure(settings: &[Setting], bests: &[BestRobot]) -> Option<ScatterFigure> {
    let with_features: Vec<(usize, Vec<f64>)> = bests
        .iter()
        .filter_map(|b| {
            let f = b.features.as_ref()?;
            let mut v = f.morphology_vector();
            v.extend(f.behaviour_vector());
            Some((b.setting, v))
        })
        .collect();
    if with_features.len() < 3 {
        return None;
    }
    let rows: Vec<Vec<f64>> = with_features.iter().map(|(_, v)| v.clone()).collect();
    let pca = Pca::fit(&rows, true);
    let variance = |k: usize| 100.0 * pca.variance_ratio.get(k).copied().unwrap_or(0.0);
    Some(ScatterFigure {
        title: "PCA of the best robots (dynamic pose + behaviour features, standardised)".into(),
        x_label: format!("PC1 ({:.0}% of variance)", variance(0)),
        y_label: format!("PC2 ({:.0}% of variance)", variance(1)),
        groups: settings.iter().map(|s| s.name.clone()).collect(),
        legend_title: "setting".into(),
        points: with_features
            .iter()
            .map(|(setting, r)| {
                let z = pca.transform(r, 2);
                ScatterPoint {
                    x: z.first().copied().unwrap_or(0.0),
                    y: z.get(1).copied().unwrap_or(0.0),
                    radius: 9.0,
                    group: *setting,
                }
            })
            .collect(),
        x_range: None,
        y_range: None,
        size_legend: None,
    })
}

/// One panel per setting: the species of the final populations, bubble area ∝ share, colour =
/// best velocity of the species.
pub(crate) fn species_figure(settings: &[Setting], runs: &[RunSpecies], cls: &Classifiers) -> BubbleFigure {
    let panels = settings
        .iter()
        .map(|s| {
            let members: Vec<&Labelled> = runs
                .iter()
                .filter(|r| r.setting == s.color)
                .flat_map(|r| r.last.iter())
                .collect();
            BubblePanel {
                title: format!("{} ({} individuals)", s.name, members.len()),
                bubbles: bubbles(&members, cls),
            }
        })
        .collect();
    BubbleFigure {
        title: "Species of the final populations".into(),
        x_classes: cls.shape.classes.clone(),
        y_classes: cls.behaviour.classes.clone(),
        x_label: "morphology class".into(),
        y_label: "behaviour class".into(),
        value_label: "best velocity [length units/s]".into(),
        panels,
    }
}

/// One bubble per species present among `members`: its share and best velocity.
fn bubbles(members: &[&Labelled], cls: &Classifiers) -> Vec<Bubble> {
    let n = members.len().max(1) as f64;
    let mut bubbles = Vec::new();
    for x in 0..cls.shape.classes.len() {
        for y in 0..cls.behaviour.classes.len() {
            let of: Vec<&&Labelled> = members.iter().filter(|m| m.shape == x && m.behaviour == y).collect();
            if !of.is_empty() {
                let best = of
                    .iter()
                    .map(|m| m.velocity)
                    .filter(|v| v.is_finite())
                    .fold(f64::NAN, f64::max);
                bubbles.push(Bubble {
                    x,
                    y,
                    share: of.len() as f64 / n,
                    value: best,
                });
            }
        }
    }
    bubbles
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn size_legend_spans_the_voxel_counts() {
        assert_eq!(size_legend_values(40.0), vec![1, 10, 20, 40]);
        assert_eq!(size_legend_values(2.0), vec![1, 2]);
    }

    #[test]
    fn short_names_drop_the_words_every_setting_begins_with() {
        let settings = |names: &[&str]| -> Vec<Setting> {
            names
                .iter()
                .enumerate()
                .map(|(color, n)| Setting {
                    name: n.to_string(),
                    color,
                    experiments: Vec::new(),
                })
                .collect()
        };
        let short = |names: &[&str]| short_names(&settings(names));
        assert_eq!(short(&["aff-red-flatworm", "aff-red-gecko"]), ["flatworm", "gecko"]);
        // a shared prefix that is not whole words stays
        assert_eq!(short(&["ho-mlp", "he-mlp"]), ["ho-mlp", "he-mlp"]);
        assert_eq!(short(&["aff-x", "aff-xy"]), ["x", "xy"]);
        assert_eq!(short(&["demo"]), ["demo"]);
        assert_eq!(short(&["a-b", "a-b-c"]), ["b", "b-c"]);
    }
}
