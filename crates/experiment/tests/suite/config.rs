//! Experiment files: the shipped ones parse; mistakes give errors naming the field and the line;
//! the resolved configuration round-trips.

use std::path::{Path, PathBuf};
use vsrlab_experiment::config;
use vsrlab_experiment::optimizers::{OptimizerConfig, SeFeatures};

const BASE: &str = r#"name = "demo"
runs = 2
seed = 7

[representation]
body = { kind = "direct", width = 5, height = 5 }
sensors = "uniform-vxy+a+t-0"
brain = { kind = "distributed-mlp", layout = "homogeneous", signals = 1, hidden = [] }

[task]
terrain = "flat"
duration = 5.0

[optimizer]
kind = "ga"
population_size = 10

[stop]
evaluations = 100
"#;

/// Parses BASE with `from` replaced by `to` and returns the error text.
fn error_of(from: &str, to: &str) -> String {
    assert!(BASE.contains(from), "{from}");
    let text = BASE.replacen(from, to, 1);
    match config::parse(&text, "demo.toml") {
        Ok(_) => panic!("expected an error for {to:?}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn errors_name_the_field_and_the_line() {
    let cases = [
        // wrong type
        ("duration = 5.0", "duration = \"long\"", "line 12", "'task.duration'"),
        // unknown top-level field
        ("seed = 7", "seed = 7\nrun = 3", "line 4", "'run'"),
        // unknown and wrongly typed fields inside the (tagged) optimizer table
        (
            "population_size = 10",
            "population_size = 10\nmutation_rate = 0.1",
            "line 17",
            "'optimizer.mutation_rate'",
        ),
        (
            "population_size = 10",
            "population_size = \"many\"",
            "line 16",
            "'optimizer.population_size'",
        ),
        // unknown optimizer
        ("kind = \"ga\"", "kind = \"pso\"", "line 15", "'optimizer.kind'"),
        // unknown field inside an inline table of the representation
        (
            "width = 5,",
            "width = 5, depth = 2,",
            "line 6",
            "'representation.body.depth'",
        ),
        // invalid values caught after parsing
        ("runs = 2", "runs = 0", "line 2", "'runs'"),
        (
            "duration = 5.0",
            "duration = 5.0\ntransient = 7.0",
            "line 13",
            "'task.transient'",
        ),
        (
            "population_size = 10",
            "population_size = 10\nmutation_probability = 1.5",
            "line 17",
            "'optimizer.mutation_probability'",
        ),
        (
            "sensors = \"uniform-vxy+a+t-0\"",
            "sensors = \"uniform-vz+a-0\"",
            "line 7",
            "'representation.sensors'",
        ),
        ("evaluations = 100", "target_fitness = 3.0", "line 18", "'stop'"),
        // CMA-ES termination thresholds
        (
            "kind = \"ga\"\npopulation_size = 10",
            "kind = \"cma-es\"\ntolfun = -1.0",
            "line 16",
            "'optimizer.tolfun'",
        ),
        (
            "kind = \"ga\"\npopulation_size = 10",
            "kind = \"cma-es\"\ntermination = \"off\"",
            "line 16",
            "'optimizer.termination'",
        ),
        // IPOP restarts need the criteria, and a factor ≥ 1
        (
            "kind = \"ga\"\npopulation_size = 10",
            "kind = \"cma-es\"\ntermination = false\nrestarts = 3",
            "",
            "'optimizer.restarts'",
        ),
        (
            "kind = \"ga\"\npopulation_size = 10",
            "kind = \"cma-es\"\nrestarts = 3\nrestart_increase = 0.5",
            "",
            "'optimizer.restart_increase'",
        ),
        (
            "kind = \"ga\"\npopulation_size = 10",
            "kind = \"cma-es\"\nupdatecovwait = -2.0",
            "",
            "'optimizer.updatecovwait'",
        ),
        (
            "kind = \"ga\"\npopulation_size = 10",
            "kind = \"cma-es\"\nrestarts = 3\nrestart_strategy = \"tripop\"",
            "",
            "'optimizer.restart_strategy'",
        ),
        // syntax error
        ("[stop]", "[stop", "line 18", ""),
    ];
    for (from, to, line, field) in cases {
        let e = error_of(from, to);
        assert!(e.starts_with("demo.toml, "), "{e}");
        assert!(e.contains(line), "expected {line} in: {e}");
        assert!(e.contains(field), "expected {field} in: {e}");
    }
}

#[test]
fn bipop_restarts_are_read_and_written_only_when_set() {
    let text = BASE.replace(
        "kind = \"ga\"\npopulation_size = 10",
        "kind = \"cma-es\"\nrestarts = 4\nrestart_strategy = \"bipop\"",
    );
    assert_ne!(text, BASE, "the base file has the GA table this test replaces");
    let e = config::parse(&text, "demo.toml").unwrap();
    let resolved = e.to_toml();
    assert!(resolved.contains("restart_strategy = \"bipop\""), "{resolved}");
    let plain = BASE.replace("kind = \"ga\"\npopulation_size = 10", "kind = \"cma-es\"");
    let resolved = config::parse(&plain, "demo.toml").unwrap().to_toml();
    assert!(!resolved.contains("restart_strategy"), "{resolved}");
}

#[test]
fn defaults_are_resolved_and_round_trip() {
    let e = config::parse(BASE, "demo.toml").unwrap();
    assert_eq!(e.output.snapshot_every, 1000);
    let text = e.to_toml();
    assert!(
        text.contains("tournament_size = 5") && text.contains("mutation_sigma = 0.35"),
        "{text}"
    );
    assert_eq!(config::parse(&text, "resolved").unwrap(), e);
    // MAP-Elites gets the thesis' three descriptors, d_num over the whole grid.
    let me = config::parse(
        &BASE.replace("kind = \"ga\"\npopulation_size = 10", "kind = \"map-elites\""),
        "me",
    )
    .unwrap();
    match &me.optimizer {
        OptimizerConfig::MapElites(p) => {
            assert_eq!(p.axes.len(), 3);
            assert_eq!(p.axes[0].max, 25.0);
            assert!(p.axes.iter().all(|a| a.bins == 10));
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(config::parse(&me.to_toml(), "me").unwrap(), me);
    // Runs get distinct derived seeds.
    let seeds = e.run_seeds();
    assert_eq!(seeds.len(), 2);
    assert_ne!(seeds[0], seeds[1]);
}

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn shipped_experiments_parse_with_the_thesis_sizes() {
    let quick = config::load(&workspace().join("experiments/quickstart.toml")).unwrap();
    assert_eq!(quick.name.as_deref(), Some("quickstart"));
    let dir = workspace().join("experiments/ch3");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    assert_eq!(files.len(), 72, "2 brains × 2 bodies × 6 EAs × 3 terrains");
    for path in files {
        let e = config::load(&path).unwrap_or_else(|err| panic!("{err}"));
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let genes = e.representation.genotype_length().unwrap();
        let expected = match (name.starts_with("ho-"), name.contains("-direct-")) {
            (true, true) => 100 + 45,
            (true, false) => 25 + 45,
            (false, true) => 100 + 4500,
            (false, false) => 25 + 4500,
        };
        assert_eq!(genes, expected, "{name}");
        assert_eq!(e.runs, 10, "{name}");
        assert_eq!(e.stop.evaluations, Some(30_000), "{name}");
        assert_eq!(e.task.spec.task().duration(), 30.0, "{name}");
        let features = match &e.optimizer {
            OptimizerConfig::Se(p) => Some(p.features),
            _ => None,
        };
        let ea = name.split('-').nth(2).unwrap();
        match ea {
            "se" => {
                let suffix = name.split('-').nth(3).unwrap();
                let want = match suffix {
                    "g" => SeFeatures::Genotype,
                    "s" => SeFeatures::Shape,
                    _ => SeFeatures::Behaviour,
                };
                assert_eq!(features, Some(want), "{name}");
            }
            "es" => assert!(matches!(e.optimizer, OptimizerConfig::Es(_)), "{name}"),
            "ga" => assert!(matches!(e.optimizer, OptimizerConfig::Ga(_)), "{name}"),
            "me" => assert!(matches!(e.optimizer, OptimizerConfig::MapElites(_)), "{name}"),
            other => panic!("unexpected EA {other} in {name}"),
        }
    }
}

#[test]
fn names_that_could_leave_the_output_folder_are_refused() {
    for bad in ["../../escaped", "a/b", "a\\\\b", ".hidden", "..", "", "two words"] {
        let e = error_of("name = \"demo\"", &format!("name = \"{bad}\""));
        assert!(e.contains("line 1") && e.contains("'name'"), "{bad}: {e}");
    }
    for good in ["demo", "ho-direct-ga-flat", "run_2.b+c", "véhicule"] {
        let text = BASE.replacen("name = \"demo\"", &format!("name = \"{good}\""), 1);
        assert!(config::parse(&text, "demo.toml").is_ok(), "{good}");
    }
    // without a name, the file's name is used, and checked too
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("my experiment.toml");
    std::fs::write(&file, BASE.replacen("name = \"demo\"\n", "", 1)).unwrap();
    let e = config::load(&file).unwrap_err().to_string();
    assert!(e.contains("'name'") && e.contains("set `name"), "{e}");
}

#[test]
fn sizes_are_bounded_and_named() {
    let cases = [
        (
            "population_size = 10",
            "population_size = 1000000000000",
            "'optimizer.population_size'",
        ),
        ("runs = 2", "runs = 1000000000000", "'runs'"),
        ("evaluations = 100", "evaluations = 0", "'stop.evaluations'"),
        ("evaluations = 100", "generations = 0", "'stop.generations'"),
        (
            "kind = \"ga\"\npopulation_size = 10",
            "kind = \"se\"\npopulation_size = 10\nspecies = 500",
            "'optimizer.species'",
        ),
        (
            "brain = { kind = \"distributed-mlp\", layout = \"homogeneous\", signals = 1, hidden = [] }",
            "brain = { kind = \"distributed-mlp\", layout = \"homogeneous\", signals = 1000000000, hidden = [] }",
            "'representation.brain",
        ),
        (
            "brain = { kind = \"distributed-mlp\", layout = \"homogeneous\", signals = 1, hidden = [] }",
            "brain = { kind = \"distributed-mlp\", layout = \"homogeneous\", signals = 1, hidden = [1000000000] }",
            "'representation.brain",
        ),
    ];
    for (from, to, field) in cases {
        let e = error_of(from, to);
        assert!(e.contains(field), "expected {field} in: {e}");
    }
}

#[test]
fn the_ch3_sweep_expands_into_the_72_generated_files() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../experiments");
    let settings = vsrlab_experiment::config::load_all(&root.join("ch3.toml")).unwrap();
    assert_eq!(settings.len(), 72);
    let without_name = |e: &vsrlab_experiment::Experiment| {
        let mut e = e.clone();
        e.name = None;
        e.description = None;
        e.to_toml()
    };
    let mut compared = 0;
    for entry in std::fs::read_dir(root.join("ch3")).unwrap() {
        let path = entry.unwrap().path();
        let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
        let file = vsrlab_experiment::config::load(&path).unwrap();
        let setting = settings
            .iter()
            .find(|s| s.name.as_deref() == Some(&format!("ch3-{stem}")))
            .unwrap_or_else(|| panic!("no setting ch3-{stem}"));
        assert_eq!(without_name(setting), without_name(&file), "{stem}");
        compared += 1;
    }
    assert_eq!(compared, 72);
}

#[test]
fn nsga2_duplicate_elimination_is_read_and_written_only_when_set() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../experiments/two-objectives.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let plain = config::parse(&text, "two.toml").unwrap();
    assert!(
        !plain.to_toml().contains("eliminate_duplicates"),
        "unchanged resolved files"
    );
    let with = text.replace("kind = \"nsga2\"", "kind = \"nsga2\"\neliminate_duplicates = true");
    let e = config::parse(&with, "two.toml").unwrap();
    match &e.optimizer {
        OptimizerConfig::Nsga2(p) => assert!(p.eliminate_duplicates),
        other => panic!("{other:?}"),
    }
    assert_eq!(config::parse(&e.to_toml(), "resolved").unwrap(), e);
    let bad = text.replace("kind = \"nsga2\"", "kind = \"nsga2\"\neliminate_duplicates = \"yes\"");
    let err = config::parse(&bad, "two.toml").unwrap_err().to_string();
    assert!(err.contains("optimizer.eliminate_duplicates"), "{err}");
}

/// Optimizer tables are decoded from flattened parts (the optimizer's settings, the operators):
/// a field written at its default, which the resolved file leaves out, is still a known field,
/// and a misspelt one is still refused, naming it, for every optimizer.
#[test]
fn optimizer_fields_written_at_their_default_are_known_and_misspelt_ones_refused() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../experiments/two-objectives.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let explicit = text.replace("kind = \"nsga2\"", "kind = \"nsga2\"\neliminate_duplicates = false");
    assert!(config::parse(&explicit, "two.toml").is_ok());
    let quick = concat!(env!("CARGO_MANIFEST_DIR"), "/../../experiments/quickstart.toml");
    let quick = std::fs::read_to_string(quick).unwrap();
    let optimizer = |table: &str| {
        let start = quick.find("[optimizer]").unwrap();
        let end = quick[start + 1..].find("\n[").map_or(quick.len(), |e| start + 1 + e);
        format!("{}[optimizer]\n{table}\n{}", &quick[..start], &quick[end..])
    };
    let cases = [
        ("kind = \"cma-es\"\nrestarts = 0\nrestart_strategy = \"ipop\"", None),
        ("kind = \"cma-es\"\nupdatecovwait = 34", None),
        ("kind = \"es\"\nsigma = 0.35", None),
        ("kind = \"map-elites\"\nbatch_size = 20", None),
        ("kind = \"se\"\nalpha = 0.75", None),
        ("kind = \"ga\"\nreevaluate_survivors = false", None),
        ("kind = \"cma-es\"\nrestart = 1", Some("optimizer.restart")),
        ("kind = \"es\"\nparent = 3", Some("optimizer.parent")),
        ("kind = \"map-elites\"\nbatch = 3", Some("optimizer.batch")),
        ("kind = \"se\"\nalfa = 0.5", Some("optimizer.alfa")),
        ("kind = \"ga\"\npopulation = 3", Some("optimizer.population")),
        // inside a nested table of a flattened part, the path keeps the table's name
        (
            "kind = \"neat\"\nmutation = { bogus = 1 }",
            Some("optimizer.mutation.bogus"),
        ),
    ];
    for (table, refused) in cases {
        let parsed = config::parse(&optimizer(table), "q.toml");
        match refused {
            None => assert!(parsed.is_ok(), "{table}: {:?}", parsed.err()),
            Some(field) => {
                let err = parsed.expect_err(table).to_string();
                assert!(err.contains(field) && err.contains("unknown field"), "{table}: {err}");
            }
        }
    }
}

#[test]
fn values_that_mean_nothing_are_refused_naming_the_field() {
    let cases = [
        (
            "evaluations = 100",
            "evaluations = 100\ntarget_fitness = nan",
            "'stop.target_fitness'",
        ),
        (
            "evaluations = 100",
            "evaluations = 100\ntarget_fitness = inf",
            "'stop.target_fitness'",
        ),
        (
            "population_size = 10",
            "population_size = 10\ninit_range = [-1e308, 1e308]",
            "'optimizer.init_range'",
        ),
        (
            "population_size = 10",
            "population_size = 10\nmutation_sigma = 1e300",
            "'optimizer.mutation_sigma'",
        ),
        ("duration = 5.0", "duration = nan", "'task.duration'"),
        (
            "population_size = 10",
            "population_size = 10\ninit_range = [-1.0, inf]",
            "'optimizer.init_range'",
        ),
    ];
    for (from, to, field) in cases {
        let e = error_of(from, to);
        assert!(e.contains(field), "{to}: {e}");
        // a non-finite number is named as such, not as the `null` serde would read
        assert!(!e.contains("null"), "{to}: {e}");
    }
    // a finite target and ordinary ranges are fine
    let text = BASE.replacen("evaluations = 100", "evaluations = 100\ntarget_fitness = 1.5", 1);
    assert!(config::parse(&text, "demo.toml").is_ok());
}
