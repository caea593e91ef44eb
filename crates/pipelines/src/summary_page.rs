//! `summary.md`: what was analysed, the summary table, the classifiers and the list of figures
//! and tables.

use crate::analyze::FigureNote;
use crate::settings::Setting;
use std::fmt::Write as _;
use std::path::PathBuf;
use vsrlab_analysis::report::Summary;
use vsrlab_analysis::results::ExperimentData;

/// What `summary.md` reports.
pub(crate) struct SummaryPage<'a> {
    /// The results folders analysed, as given.
    pub results: &'a [PathBuf],
    /// The settings.
    pub settings: &'a [Setting],
    /// The experiments.
    pub experiments: &'a [ExperimentData],
    /// The summary table.
    pub summary: &'a Summary,
    /// The classifiers' table, or why there are none.
    pub classifiers: &'a str,
    /// The figures written.
    pub figures: &'a [FigureNote],
    /// Whether species were analysed (`isi.csv` was written).
    pub species: bool,
    /// Whether `best.csv` was written (some run's best robot was replayed).
    pub best_table: bool,
}

impl SummaryPage<'_> {
    /// The page as Markdown.
    pub fn to_markdown(&self) -> String {
        let mut md = String::from("# vsrlab analysis\n\n");
        let results: Vec<String> = self.results.iter().map(|p| format!("`{}`", p.display())).collect();
        let _ = writeln!(md, "Results: {}\n", results.join(", "));
        let _ = writeln!(md, "Settings and their experiment folders:\n");
        for s in self.settings {
            let dirs: Vec<String> = s
                .experiments
                .iter()
                .map(|&e| {
                    let exp = &self.experiments[e];
                    format!("`{}` ({} runs)", exp.dir.display(), exp.runs.len())
                })
                .collect();
            let _ = writeln!(md, "- **{}**: {}", s.name, dirs.join(", "));
        }
        let _ = writeln!(md, "\n{}", self.summary.to_markdown());
        let _ = writeln!(md, "\n{}", self.classifiers);
        let _ = writeln!(md, "Figures (PNG and SVG):\n");
        for f in self.figures {
            let _ = writeln!(md, "- `{}.png`: {}", f.name, f.description);
        }
        let mut tables = vec!["`summary.csv` (per setting)", "`pvalues.csv` (pairwise tests)"];
        if self.best_table {
            tables.push("`best.csv` (best robot of each run)");
        }
        if self.species {
            tables.push("`isi.csv` (ISI per snapshot)");
        }
        let _ = writeln!(md, "\nTables: {}.", tables.join(", "));
        md
    }
}
