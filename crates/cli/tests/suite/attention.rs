//! End to end, the attention chapter's tools: a tiny attention experiment → a transfer of its
//! attention module to a bigger body through `[transfer]`, pooled by `setting` → the
//! frozen-attention ablation through `vsrlab plasticity` → a video with attention maps.

use crate::common;

use common::{ok, vsrlab};
use std::path::Path;

fn config(body: &str, extra: &str) -> String {
    format!(
        r#"
{extra}
runs = 2
seed = 1

[representation]
body = "{body}"
sensors = "uniform-a+vxy+t-0"
brain = {{ kind = "step", period = 0.33, inner = {{ kind = "attention" }} }}

[task]
terrain = "hilly-1-10"
duration = 3.0
random_terrain_per_evaluation = true

[optimizer]
kind = "ga"
population_size = 6
offspring_size = 6
reevaluate_survivors = true

[stop]
evaluations = 18
"#
    )
}

fn write(path: &Path, text: &str) -> String {
    std::fs::write(path, text).unwrap();
    path.display().to_string()
}

#[test]
fn transfer_freeze_and_draw_attention() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let source = write(&d.join("source.toml"), &config("biped-4x3", "name = \"source\""));
    let out = d.join("out");
    let out_s = out.to_str().unwrap();
    ok(&["run", &source, "--out", &format!("{out_s}/source")]);
    let best = out.join("source/run-00/best.robot.json");
    let robot: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&best).unwrap()).unwrap();
    let genes: Vec<f64> = serde_json::from_value(robot["robot"]["brain"]["inner"]["parameters"].clone()).unwrap();
    assert_eq!(genes.len(), 73, "the thesis' 73 parameters on a biped-4x3");

    // transfer: two sources pooled into one setting by `setting`
    let transfer = format!(
        "{}\n[sweep.\"transfer.from\"]\na = \"{}\"\nb = \"{}\"\n",
        config("biped-6x4", "name = \"moved\"\nsetting = \"moved\"").replacen("runs = 2", "runs = 1", 1),
        best.display(),
        out.join("source/run-01/best.robot.json").display()
    );
    let transfer = write(&d.join("transfer.toml"), &transfer);
    ok(&["run", &transfer, "--out", &format!("{out_s}/moved")]);
    let resolved = std::fs::read_to_string(out.join("moved/moved-a/experiment.toml")).unwrap();
    assert!(resolved.contains("attention = ["), "{resolved}");
    assert!(
        !resolved.contains("[transfer]"),
        "the resolved file needs no source: {resolved}"
    );
    let moved = std::fs::read_to_string(out.join("moved/moved-a/run-00/best.robot.json")).unwrap();
    let moved: serde_json::Value = serde_json::from_str(&moved).unwrap();
    let fixed: Vec<f64> = serde_json::from_value(moved["robot"]["brain"]["inner"]["attention"].clone()).unwrap();
    assert_eq!(fixed, genes[..32], "the attention genes travel unchanged, in order");
    let rest: Vec<f64> = serde_json::from_value(moved["robot"]["brain"]["inner"]["parameters"].clone()).unwrap();
    assert_eq!(
        rest.len(),
        18 * 4 + 1,
        "only the downstream network of the 18-voxel body evolves"
    );
    let text = ok(&[
        "reassess",
        &format!("{out_s}/moved"),
        "--episodes",
        "1",
        "--out",
        d.join("re").to_str().unwrap(),
    ]);
    assert!(
        text.contains("| moved | 2 |"),
        "the two experiments pool into one setting:\n{text}"
    );

    // the frozen-attention ablation
    let text = ok(&[
        "plasticity",
        &format!("{out_s}/source"),
        "--freeze-at",
        "0,1,2",
        "--weights-at",
        "1",
        "--episodes",
        "1",
        "--out",
        d.join("frozen").to_str().unwrap(),
    ]);
    assert!(text.contains("| source | restart | 1 |"), "{text}");

    // a video frame with the attention maps
    let png = d.join("frame.png");
    ok(&[
        "simulate",
        "--robot",
        best.to_str().unwrap(),
        "--duration",
        "1",
        "--video",
        png.to_str().unwrap(),
    ]);
    assert!(png.is_file());

    // a source without an attention module is refused, naming the field
    let mlp = d.join("mlp.json");
    ok(&[
        "simulate",
        "--brain",
        "mlp",
        "--duration",
        "0.1",
        "--save-robot",
        mlp.to_str().unwrap(),
    ]);
    let bad = format!(
        "{}\n[transfer]\nfrom = \"{}\"\n",
        config("biped-6x4", "name = \"bad\""),
        mlp.display()
    );
    let bad = write(&d.join("bad.toml"), &bad);
    let (success, text) = vsrlab(&["run", &bad, "--out", &format!("{out_s}/bad")]);
    assert!(
        !success && text.contains("transfer.from") && text.contains("not an attention brain"),
        "{text}"
    );
}
