//! What `label` writes for the person labelling: `manifest.csv` (every robot with its origin,
//! descriptors and suggestions) and `index.html`, a self-contained page (no network, works
//! from `file://`) that saves `labels.csv`.

use crate::candidates::Candidate;
use std::fmt::Write as _;
use vsrlab_analysis::labels::LabelRow;
use vsrlab_analysis::report::csv_field;

/// The page; `/*DATA*/null`, `{{TITLE}}` and `{{KEY}}` are filled in by [`page`].
const PAGE: &str = include_str!("label_page.html");

/// One robot on the page.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PageRobot {
    /// `r-0001`.
    pub id: String,
    /// Its robot file, relative to the page.
    pub robot: String,
    /// Its video, relative to the page.
    pub video: String,
    /// Terrain of its episode.
    pub terrain: String,
    /// Episode length (s).
    pub duration: f64,
    /// Transient (s).
    pub transient: f64,
    /// Episode seed.
    pub seed: u64,
    /// Its candidate (index into the pool).
    pub candidate: usize,
    /// Suggested (morphology, behaviour) classes.
    pub proposal: (String, String),
    /// What the behaviour proposal was made from, for the manifest.
    pub evidence: Evidence,
}

/// The features behind a behaviour proposal ([`vsrlab_analysis::diversity::propose_behaviour`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Evidence {
    /// Fraction of steps with the whole body off the ground.
    pub airborne: f64,
    /// Net rotation, in turns.
    pub turns: f64,
    /// Net x displacement of the centre, in voxel sides.
    pub displacement: f64,
    /// Occurrences of the main footprint n-gram.
    pub occurrences: usize,
    /// Purity of its intervals.
    pub purity: f64,
}

impl PageRobot {
    /// The robot as a labels row with the suggestions as its classes (`label --auto`).
    pub fn proposed_labels(&self) -> LabelRow {
        LabelRow {
            robot: self.robot.clone(),
            terrain: self.terrain.clone(),
            duration: self.duration,
            transient: self.transient,
            seed: self.seed,
            shape: self.proposal.0.clone(),
            behaviour: self.proposal.1.clone(),
        }
    }
}

/// `manifest.csv`: every robot on the page with its origin, descriptors and suggestions.
pub(crate) fn manifest_csv(robots: &[PageRobot], pool: &[Candidate]) -> String {
    let mut s = String::from("id,robot,video,terrain,duration,transient,seed,setting,run,evaluations,index,velocity,voxels,elongation,compactness,proposed_shape,proposed_behaviour,airborne,turns,displacement_sides,gait_occurrences,gait_purity\n");
    for e in robots {
        let c = &pool[e.candidate];
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{:.4},{:.4},{},{},{:.3},{:.3},{:.3},{},{:.3}",
            e.id,
            e.robot,
            e.video,
            e.terrain,
            e.duration,
            e.transient,
            e.seed,
            csv_field(&c.setting),
            c.run,
            c.row.evaluations,
            c.row.index,
            c.row.velocity().map_or(String::new(), |v| v.to_string()),
            c.descriptors.voxels,
            c.descriptors.elongation,
            c.descriptors.compactness,
            e.proposal.0,
            e.proposal.1,
            e.evidence.airborne,
            e.evidence.turns,
            e.evidence.displacement,
            e.evidence.occurrences,
            e.evidence.purity
        );
    }
    s
}

/// The robots' data, the classes and whether to pre-select the suggestions: embedded in
/// `index.html` and written as `labelling.json` for the replay viewer (`vsrlab view`), which
/// offers the same choices beside each robot's replay.
pub(crate) fn page_data(
    robots: &[PageRobot],
    pool: &[Candidate],
    shapes: &[String],
    behaviours: &[String],
    prefill: bool,
) -> serde_json::Value {
    let items: Vec<serde_json::Value> = robots
        .iter()
        .map(|e| {
            let c = &pool[e.candidate];
            serde_json::json!({
                "id": e.id, "robot": e.robot, "video": e.video, "terrain": e.terrain,
                "duration": e.duration, "transient": e.transient, "seed": e.seed,
                "setting": c.setting, "run": c.run, "evaluations": c.row.evaluations,
                "velocity": c.row.velocity(), "voxels": c.descriptors.voxels,
                "elongation": c.descriptors.elongation, "compactness": c.descriptors.compactness,
                "body": c.row.body(), "proposal": [e.proposal.0, e.proposal.1],
            })
        })
        .collect();
    serde_json::json!({ "items": items, "shapes": shapes, "behaviours": behaviours, "prefill": prefill })
}

/// `index.html`: the page with [`page_data`] embedded.
pub(crate) fn page(data: &serde_json::Value) -> String {
    let count = data["items"].as_array().map_or(0, Vec::len);
    // "</" cannot appear inside the script element.
    let text = data.to_string().replace("</", "<\\/");
    let key = serde_json::Value::from(format!("vsrlab-labels-{count}")).to_string();
    PAGE.replace("/*DATA*/null", &text)
        .replace("{{TITLE}}", &format!("vsrlab labelling: {count} robots"))
        .replace("{{KEY}}", &key)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn page_embeds_data_safely() {
        let html = page(&page_data(
            &[],
            &[],
            &["a</script>".into(), "b".into()],
            &["c".into(), "d".into()],
            true,
        ));
        assert!(html.starts_with("<!doctype html>"));
        assert!(html.contains("vsrlab labelling: 0 robots"));
        assert!(html.contains(r#"const KEY = "vsrlab-labels-0""#));
        assert!(html.contains(r#""prefill":true"#));
        assert!(!html.contains("a</script>") && html.contains("a<\\/script>"));
    }
}
