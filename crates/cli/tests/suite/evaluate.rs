//! `vsrlab evaluate`: fitness of given genotypes, in file order, independent of the thread count;
//! bad files are refused with the line named.

use crate::common;
use common::{ok, vsrlab};

const EXPERIMENT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../experiments/quickstart.toml");

fn genotypes(dir: &std::path::Path, rows: usize, genes: usize) -> String {
    let text: Vec<String> = (0..rows)
        .map(|r| {
            (0..genes)
                .map(|g| format!("{}", (((r * 31 + g * 17) % 41) as f64 / 20.0) - 1.0))
                .collect::<Vec<_>>()
                .join(",")
        })
        .collect();
    let path = dir.join("g.csv");
    std::fs::write(&path, text.join("\n") + "\n").unwrap();
    path.display().to_string()
}

#[test]
fn fitness_per_row_in_order_whatever_the_threads_and_the_same_as_records() {
    let dir = tempfile::tempdir().unwrap();
    let genes: usize = ok(&["evaluate", EXPERIMENT, "--genes"]).trim().parse().unwrap();
    assert_eq!(genes, 45, "the quickstart's distributed MLP has 45 weights");
    let file = genotypes(dir.path(), 6, genes);
    let one = ok(&["evaluate", EXPERIMENT, &file, "--threads", "1"]);
    let two = ok(&["evaluate", EXPERIMENT, &file, "--threads", "2"]);
    assert_eq!(one, two);
    let fitness: Vec<f64> = one.lines().map(|l| l.parse().unwrap()).collect();
    assert_eq!(fitness.len(), 6);
    assert!(fitness.iter().any(|&f| f != fitness[0]));
    let records = ok(&["evaluate", EXPERIMENT, &file, "--records"]);
    for (line, f) in records.lines().zip(&fitness) {
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        assert_eq!(v["fitness"].as_f64().unwrap(), *f);
    }
}

#[test]
fn short_rows_words_and_missing_seeds_are_refused_with_the_line() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.csv");
    std::fs::write(&path, "0.1,0.2\n").unwrap();
    let (success, text) = vsrlab(&["evaluate", EXPERIMENT, path.to_str().unwrap()]);
    assert!(!success);
    assert!(
        text.contains("line 1: 2 genes, the experiment's genotypes have 45"),
        "{text}"
    );
    let row = vec!["0.5"; 45].join(",");
    std::fs::write(&path, format!("{row}\n{}\n", row.replace("0.5,0.5", "0.5,x"))).unwrap();
    let (_, text) = vsrlab(&["evaluate", EXPERIMENT, path.to_str().unwrap()]);
    assert!(text.contains("line 2: 'x' is not a number"), "{text}");
    std::fs::write(&path, format!("{row}\n{row}\n")).unwrap();
    let (success, text) = vsrlab(&["evaluate", EXPERIMENT, path.to_str().unwrap(), "--seeds", "1"]);
    assert!(!success);
    assert!(text.contains("--seeds: 1 seeds for 2 genotypes"), "{text}");
}
