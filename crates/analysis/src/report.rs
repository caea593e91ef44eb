//! The summary table of `vsrlab analyze`: per setting, the median (and sd) of the runs' best
//! fitness and final Inverse Simpson Index, and two-sided Mann–Whitney p-values between every
//! pair of settings, as CSV and Markdown.

use crate::stats::{mann_whitney_u, median, std_dev, MannWhitney};
use serde::Serialize;
use std::fmt::Write;

/// Per-setting values, one per run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SettingSummary {
    /// Setting name.
    pub name: String,
    /// Best fitness of each run.
    pub best: Vec<f64>,
    /// Final-population ISI of each run (empty without species).
    pub final_isi: Vec<f64>,
}

/// A Mann–Whitney comparison of two settings on one metric.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Comparison {
    /// "best" or "isi".
    pub metric: String,
    /// First setting (index into the settings).
    pub a: usize,
    /// Second setting.
    pub b: usize,
    /// The test (None when a side has no values).
    pub test: Option<MannWhitney>,
}

/// Every pairwise comparison of `values` (one vector per setting).
pub fn pairwise(metric: &str, values: &[Vec<f64>]) -> Vec<Comparison> {
    let mut out = Vec::new();
    for a in 0..values.len() {
        for b in a + 1..values.len() {
            let clean = |v: &Vec<f64>| v.iter().copied().filter(|x| x.is_finite()).collect::<Vec<f64>>();
            out.push(Comparison {
                metric: metric.into(),
                a,
                b,
                test: mann_whitney_u(&clean(&values[a]), &clean(&values[b])),
            });
        }
    }
    out
}

/// The whole summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// What the fitness is (velocity or distance).
    pub fitness: String,
    /// One entry per setting.
    pub settings: Vec<SettingSummary>,
    /// Pairwise comparisons of best fitness, then of final ISI.
    pub comparisons: Vec<Comparison>,
}

fn finite(v: &[f64]) -> Vec<f64> {
    v.iter().copied().filter(|x| x.is_finite()).collect()
}

fn num(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.4}")
    } else {
        String::new()
    }
}

fn p_text(t: &Option<MannWhitney>) -> String {
    t.map_or_else(
        || "n/a".into(),
        |t| {
            if t.p < 1e-4 {
                format!("{:.1e}", t.p)
            } else {
                format!("{:.4}", t.p)
            }
        },
    )
}

impl Summary {
    /// Builds the summary and its comparisons.
    pub fn new(fitness: &str, settings: Vec<SettingSummary>) -> Summary {
        let best: Vec<Vec<f64>> = settings.iter().map(|s| s.best.clone()).collect();
        let mut comparisons = pairwise("best", &best);
        if settings.iter().any(|s| !s.final_isi.is_empty()) {
            let isi: Vec<Vec<f64>> = settings.iter().map(|s| s.final_isi.clone()).collect();
            comparisons.extend(pairwise("isi", &isi));
        }
        Summary {
            fitness: fitness.into(),
            settings,
            comparisons,
        }
    }

    /// One row per setting: setting, runs, median_best, sd_best, median_final_isi, sd_final_isi.
    pub fn settings_csv(&self) -> String {
        let mut s = String::from("setting,runs,median_best,sd_best,median_final_isi,sd_final_isi\n");
        for x in &self.settings {
            let (b, i) = (finite(&x.best), finite(&x.final_isi));
            let _ = writeln!(
                s,
                "{},{},{},{},{},{}",
                csv_field(&x.name),
                x.best.len(),
                num(median(&b)),
                num(std_dev(&b)),
                num(median(&i)),
                num(std_dev(&i))
            );
        }
        s
    }

    /// One row per comparison: metric, setting_a, setting_b, u, p, method.
    pub fn pvalues_csv(&self) -> String {
        let mut s = String::from("metric,setting_a,setting_b,u,p,method\n");
        for c in &self.comparisons {
            let (u, p, m) = match c.test {
                Some(t) => (
                    format!("{}", t.u),
                    format!("{}", t.p),
                    format!("{:?}", t.method).to_lowercase(),
                ),
                None => (String::new(), String::new(), String::new()),
            };
            let _ = writeln!(
                s,
                "{},{},{},{u},{p},{m}",
                c.metric,
                csv_field(&self.settings[c.a].name),
                csv_field(&self.settings[c.b].name)
            );
        }
        s
    }

    /// Markdown: the per-setting table (its ISI columns only when some run has a final ISI, that
    /// is, when species were analysed), then a matrix of p-values per metric.
    pub fn to_markdown(&self) -> String {
        let mut s = String::new();
        let with_isi = self.settings.iter().any(|x| !x.final_isi.is_empty());
        let (isi_head, isi_rule) = match with_isi {
            true => (" median final ISI | sd final ISI |", "---:|---:|"),
            false => ("", ""),
        };
        let _ = writeln!(
            s,
            "| setting | runs | median best {f} | sd best {f} |{isi_head}",
            f = self.fitness
        );
        let _ = writeln!(s, "|---|---:|---:|---:|{isi_rule}");
        for x in &self.settings {
            let (b, i) = (finite(&x.best), finite(&x.final_isi));
            let dash = |v: f64| if v.is_finite() { format!("{v:.4}") } else { "–".into() };
            let isi = match with_isi {
                true => format!(" {} | {} |", dash(median(&i)), dash(std_dev(&i))),
                false => String::new(),
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} |{isi}",
                x.name,
                x.best.len(),
                dash(median(&b)),
                dash(std_dev(&b)),
            );
        }
        for (metric, title) in [
            ("best", format!("best {}", self.fitness)),
            ("isi", "final ISI".to_string()),
        ] {
            let cs: Vec<&Comparison> = self.comparisons.iter().filter(|c| c.metric == metric).collect();
            if cs.is_empty() {
                continue;
            }
            let _ = writeln!(s, "\nTwo-sided Mann–Whitney U p-values, {title}:\n");
            let names: Vec<&str> = self.settings.iter().map(|x| x.name.as_str()).collect();
            let _ = writeln!(s, "| | {} |", names.join(" | "));
            let _ = writeln!(s, "|---|{}", "---:|".repeat(names.len()));
            for (i, n) in names.iter().enumerate() {
                let cells: Vec<String> = (0..names.len())
                    .map(|j| {
                        if i == j {
                            "–".into()
                        } else {
                            cs.iter()
                                .find(|c| (c.a, c.b) == (i.min(j), i.max(j)))
                                .map_or("".into(), |c| p_text(&c.test))
                        }
                    })
                    .collect();
                let _ = writeln!(s, "| {n} | {} |", cells.join(" | "));
            }
        }
        s
    }
}

/// Quotes a CSV field when needed.
pub fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_tables() {
        let s = Summary::new(
            "velocity",
            vec![
                SettingSummary {
                    name: "es".into(),
                    best: vec![1.0, 2.0, 3.0],
                    final_isi: vec![1.0, 1.5, 2.0],
                },
                SettingSummary {
                    name: "ga".into(),
                    best: vec![4.0, 5.0, 6.0],
                    final_isi: vec![2.0, 3.0, 4.0],
                },
            ],
        );
        assert_eq!(s.comparisons.len(), 2);
        assert!((s.comparisons[0].test.unwrap().p - 0.1).abs() < 1e-12);
        let csv = s.settings_csv();
        assert!(csv.contains("es,3,2.0000,1.0000,1.5000,0.5000"), "{csv}");
        let md = s.to_markdown();
        assert!(
            md.contains("| es | 3 | 2.0000 |") && md.contains("| ga | 0.1000 | – |"),
            "{md}"
        );
        assert!(s.pvalues_csv().contains("best,es,ga,0,0.1,exact"));
        assert!(md.contains("| es | 3 | 2.0000 | 1.0000 | 1.5000 | 0.5000 |"), "{md}");
        assert_eq!(csv_field("a,b"), "\"a,b\"");
        // without species, no ISI columns (not a column of dashes)
        let plain = Summary::new(
            "velocity",
            vec![SettingSummary {
                name: "es".into(),
                best: vec![1.0, 2.0, 3.0],
                final_isi: vec![],
            }],
        );
        let md = plain.to_markdown();
        assert!(!md.contains("ISI"), "{md}");
        assert!(md.contains("| es | 3 | 2.0000 | 1.0000 |\n"), "{md}");
    }
}
