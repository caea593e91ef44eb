//! The votes of an episode over time (thesis §5.1.4.3 follows them frame by frame): at every
//! frame of a trace with a `vote` channel, the share of voxels voting "passable" (vote > 0), and
//! the collective decision it gives (passable at one half or more: ties count as passable).

use std::path::{Path, PathBuf};
use vsrlab_analysis::plot::{self, BandChart, BandFigure, BandSeries, PlotError};
use vsrlab_tasks::{channels, Trace};

/// The frames' times and the share of voxels voting "passable" at each, or `None` for a trace
/// without votes.
pub fn passable_share(trace: &Trace) -> Option<(Vec<f64>, Vec<f64>)> {
    let votes = trace.channel(channels::VOTE.name)?;
    if votes.fixed || votes.width == 0 {
        return None;
    }
    let (mut times, mut share) = (Vec::new(), Vec::new());
    for (step, &t) in trace.times.iter().enumerate() {
        let Some(row) = trace.at(channels::VOTE.name, step) else {
            break;
        };
        times.push(t);
        share.push(row.iter().filter(|&&v| v > 0.0).count() as f64 / row.len() as f64);
    }
    Some((times, share))
}

/// The figure of [`passable_share`] over time, titled `title`, with the tie line at one half.
pub fn votes_figure(trace: &Trace, title: &str) -> Option<BandFigure> {
    let (times, share) = passable_share(trace)?;
    let flat = |v: f64| vec![v; times.len()];
    Some(BandFigure {
        title: title.to_string(),
        panels: vec![BandChart {
            title: "share of voxels voting passable (vote > 0)".into(),
            x_label: "time (s)".into(),
            y_label: "share voting passable".into(),
            series: vec![
                BandSeries {
                    label: "voxels voting passable".into(),
                    color: 0,
                    x: times.clone(),
                    center: share.clone(),
                    spread: flat(0.0),
                },
                BandSeries {
                    label: "1/2: the decision is passable at or above".into(),
                    color: 7,
                    x: times.clone(),
                    center: flat(0.5),
                    spread: flat(0.0),
                },
            ],
        }],
        legend_title: "votes".into(),
        note: Vec::new(),
    })
}

/// Why the votes figure of `vsrlab simulate --votes` was not written.
#[derive(Debug, thiserror::Error)]
pub enum VotesError {
    /// The episode's trace has no votes channel.
    #[error("--votes: the episode has no votes (use a brain that votes, e.g. elman, on the affordance task)")]
    NoVotes,
    /// The figure could not be written.
    #[error("--votes: {0}")]
    Plot(#[from] PlotError),
}

/// Writes [`votes_figure`] as `path` (its stem `.png` and `.svg`).
pub fn save_votes(trace: &Trace, title: &str, path: &Path) -> Result<Vec<PathBuf>, VotesError> {
    let figure = votes_figure(trace, title).ok_or(VotesError::NoVotes)?;
    Ok(plot::save(&figure, &path.with_extension(""))?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use vsrlab_tasks::Probe;

    #[test]
    fn the_share_counts_votes_above_zero_at_every_frame() {
        let mut trace = Trace {
            dt: 0.1,
            times: vec![0.0, 0.1, 0.2],
            ..Trace::default()
        };
        for row in [[0.0, 0.0, 0.0, 0.0], [0.5, -0.5, 0.1, 0.0], [1.0, 1.0, 1.0, -1.0]] {
            trace.step(&channels::VOTE, &row);
        }
        let (times, share) = passable_share(&trace).unwrap();
        assert_eq!(times, [0.0, 0.1, 0.2]);
        assert_eq!(share, [0.0, 0.5, 0.75]);
        assert!(passable_share(&Trace::default()).is_none());
        let figure = votes_figure(&trace, "t").unwrap();
        assert_eq!(figure.panels[0].series[1].center, [0.5; 3]);
        let dir = std::env::temp_dir().join(format!("vsrlab-votes-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let files = save_votes(&trace, "t", &dir.join("votes.png")).unwrap();
        assert!(files.iter().all(|f| f.metadata().unwrap().len() > 1000), "{files:?}");
        let e = save_votes(&Trace::default(), "t", &dir.join("none.png")).unwrap_err();
        assert!(matches!(e, VotesError::NoVotes), "{e}");
        assert!(
            e.to_string().starts_with("--votes") && e.to_string().contains("elman"),
            "{e}"
        );
        std::fs::remove_dir_all(dir).unwrap();
    }
}
