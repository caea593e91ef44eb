//! Sweeps: one experiment file that expands into a grid of settings.
//!
//! A `[sweep]` table maps dotted keys of the file to the values each takes, either a list
//! (`"task.terrain" = ["flat", "uphill-20"]`, each value naming itself, in the order written) or a
//! table of named values (`[sweep."representation.brain"]` with `ho = { … }` and `he = { … }`, in
//! label order). The file expands into one experiment per combination (the Cartesian product, keys
//! in the order they are written, the last varying fastest),
//! named `<name>-<label>-<label>…`, e.g. `ch3-ho-direct-ga-flat`. Each is checked like a file of
//! its own; errors name the combination.

use super::{check_name, parse, ConfigError, Experiment};
use vsrlab_field::FieldError;

/// Most settings one sweep may expand into.
pub const MAX_SETTINGS: usize = 10_000;

/// One swept key: its dotted path and its (label, value) pairs.
struct Axis {
    key: String,
    values: Vec<(String, toml::Value)>,
}

/// A label for a listed value: strings as they are, other values as TOML text, with characters
/// that cannot go into a folder name replaced by `_`.
fn label_of(value: &toml::Value) -> String {
    let text = match value {
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    };
    text.chars()
        .map(|c| {
            if c.is_alphanumeric() || matches!(c, '-' | '_' | '.' | '+') {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The axes of a `[sweep]` table, in the order their keys appear in `text`.
fn axes(sweep: toml::Table, text: &str) -> Result<Vec<Axis>, FieldError> {
    let mut axes = Vec::new();
    for (key, spec) in sweep {
        let field = format!("sweep.\"{key}\"");
        let values: Vec<(String, toml::Value)> = match spec {
            toml::Value::Array(items) => items.into_iter().map(|v| (label_of(&v), v)).collect(),
            toml::Value::Table(named) => named.into_iter().collect(),
            other => {
                return Err(FieldError::new(
                    field,
                    format!("expected a list of values or a table of named values, got {other}"),
                ))
            }
        };
        if values.is_empty() {
            return Err(FieldError::new(field, "needs at least one value"));
        }
        if let Some((label, _)) = values.iter().find(|(label, _)| check_name(label).is_err()) {
            return Err(FieldError::new(
                field,
                format!("label '{label}' cannot be part of a folder name"),
            ));
        }
        axes.push(Axis { key, values });
    }
    let sweep_text = &text[text.find("[sweep").unwrap_or(0)..];
    let position = |key: &str| sweep_text.find(&format!("\"{key}\"")).or_else(|| sweep_text.find(key));
    axes.sort_by_key(|a| position(&a.key).unwrap_or(usize::MAX));
    Ok(axes)
}

/// Why a swept key cannot be set.
#[derive(Debug, thiserror::Error)]
enum KeyProblem {
    #[error("empty key")]
    Empty,
    #[error("'{part}' in '{key}' is not a table")]
    NotATable { part: String, key: String },
}

/// Sets the dotted `key` of `table` to `value`, creating tables on the way.
fn set(table: &mut toml::Table, key: &str, value: toml::Value) -> Result<(), KeyProblem> {
    let mut parts: Vec<&str> = key.split('.').collect();
    let last = parts.pop().filter(|p| !p.is_empty()).ok_or(KeyProblem::Empty)?;
    let mut here = table;
    for part in parts {
        let next = here
            .entry(part.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        here = next.as_table_mut().ok_or_else(|| KeyProblem::NotATable {
            part: part.to_string(),
            key: key.to_string(),
        })?;
    }
    here.insert(last.to_string(), value);
    Ok(())
}

/// Expands an experiment file's text: one experiment without `[sweep]`, one per combination
/// with it. `stem` names the experiments when the file has no `name`.
pub fn expand(text: &str, origin: &str, stem: &str) -> Result<Vec<Experiment>, ConfigError> {
    let whole_file = |field: &str, message: String| ConfigError::at_field(origin, text, field, message);
    let mut table: toml::Table = match text.parse() {
        Ok(table) => table,
        // the plain parser reports TOML errors with their line
        Err(_) => return parse(text, origin).map(|e| vec![e]),
    };
    let Some(sweep) = table.remove("sweep") else {
        return parse(text, origin).map(|e| vec![e]);
    };
    let sweep = match sweep {
        toml::Value::Table(t) => t,
        other => return Err(whole_file("sweep", format!("expected a table, got {other}"))),
    };
    let axes = axes(sweep, text).map_err(|e| whole_file(&e.path, e.message))?;
    let count = axes
        .iter()
        .try_fold(1usize, |n, a| n.checked_mul(a.values.len()))
        .filter(|&n| n <= MAX_SETTINGS)
        .ok_or_else(|| whole_file("sweep", format!("expands into more than {MAX_SETTINGS} settings")))?;
    let base = match table.get("name") {
        Some(toml::Value::String(name)) => name.clone(),
        _ => stem.to_string(),
    };
    let mut experiments = Vec::with_capacity(count);
    // each setting runs in a folder of its name: two settings of one name would collide there
    let mut named: std::collections::HashMap<String, String> = std::collections::HashMap::new();
    for index in 0..count {
        let mut setting = table.clone();
        let mut rest = index;
        let mut labels = Vec::new();
        let mut assignments = Vec::new();
        // the last key varies fastest
        let picks: Vec<(&Axis, usize)> = axes
            .iter()
            .rev()
            .map(|a| {
                let pick = rest % a.values.len();
                rest /= a.values.len();
                (a, pick)
            })
            .collect();
        for (axis, pick) in picks.into_iter().rev() {
            let (label, value) = &axis.values[pick];
            set(&mut setting, &axis.key, value.clone())
                .map_err(|m| whole_file(&format!("sweep.\"{}\"", axis.key), m.to_string()))?;
            labels.push(label.clone());
            assignments.push(format!("{} = {label}", axis.key));
        }
        let name = format!("{base}-{}", labels.join("-"));
        if let Some(first) = named.insert(name.clone(), assignments.join(", ")) {
            return Err(whole_file(
                "sweep",
                format!(
                    "the settings ({first}) and ({}) are both named '{name}' and would share its folder: give them distinct labels",
                    assignments.join(", ")
                ),
            ));
        }
        setting.insert("name".into(), toml::Value::String(name.clone()));
        let setting_origin = format!("{origin} (sweep setting {})", assignments.join(", "));
        let generated = toml::to_string(&setting)
            .map_err(|e| whole_file("sweep", format!("cannot write the setting {name}: {e}")))?;
        let experiment = parse(&generated, &setting_origin).map_err(|mut e| {
            // lines of the generated text mean nothing to the user
            e.line = None;
            e.column = None;
            e
        })?;
        experiments.push(experiment);
    }
    Ok(experiments)
}

#[cfg(test)]
mod tests {
    use super::*;

    const BASE: &str = r#"
name = "demo"
[representation]
body = "biped-4x3"
sensors = "uniform-vxy+a+t-0"
brain = { kind = "distributed-mlp", layout = "homogeneous", signals = 1, hidden = [] }
[task]
duration = 5.0
[optimizer]
kind = "ga"
[stop]
evaluations = 100
"#;

    #[test]
    fn settings_that_expand_to_one_name_are_refused_naming_both() {
        let twice = format!("{BASE}[sweep]\nseed = [1, 1]\n");
        let e = expand(&twice, "demo.toml", "demo").unwrap_err();
        assert_eq!(e.field, "sweep");
        assert!(
            e.to_string().contains("(seed = 1) and (seed = 1)") && e.to_string().contains("'demo-1'"),
            "{e}"
        );
        // labels that join to the same string: "a-b" + "c" and "a" + "b-c"
        let joined = format!("{BASE}[sweep.seed]\n\"a-b\" = 1\na = 2\n[sweep.runs]\nc = 1\n\"b-c\" = 2\n");
        let e = expand(&joined, "demo.toml", "demo").unwrap_err();
        assert!(e.to_string().contains("'demo-a-b-c'"), "{e}");
    }

    #[test]
    fn a_file_without_sweep_is_one_experiment() {
        let all = expand(BASE, "demo.toml", "demo").unwrap();
        assert_eq!(all.len(), 1);
        assert_eq!(all[0].name.as_deref(), Some("demo"));
    }

    #[test]
    fn lists_and_named_tables_expand_into_the_product_in_written_order() {
        let text = format!(
            "{BASE}\n[sweep]\n\"task.terrain\" = [\"flat\", \"uphill-20\"]\n\"seed\" = [1, 2, 3]\n\
             [sweep.optimizer]\nga = {{ kind = \"ga\" }}\nes = {{ kind = \"es\", population_size = 10 }}\n"
        );
        let all = expand(&text, "demo.toml", "demo").unwrap();
        assert_eq!(all.len(), 12);
        let names: Vec<&str> = all.iter().map(|e| e.name.as_deref().unwrap()).collect();
        // lists keep their order, named values come in label order
        assert_eq!(names[0], "demo-flat-1-es");
        assert_eq!(names[1], "demo-flat-1-ga");
        assert_eq!(names[11], "demo-uphill-20-3-ga");
        assert_eq!(all[11].seed, 3);
        assert_eq!(all[10].optimizer.kind().name(), "es");
        let resolved = all[11].to_toml();
        assert!(resolved.contains("terrain = \"uphill-20\""), "{resolved}");
    }

    #[test]
    fn a_bad_setting_is_reported_with_its_combination() {
        let text = format!("{BASE}\n[sweep]\n\"task.duration\" = [1.0, -1.0]\n");
        let err = expand(&text, "demo.toml", "demo").unwrap_err().to_string();
        assert!(err.contains("sweep setting task.duration = -1.0"), "{err}");
        assert!(err.contains("task.duration"), "{err}");
        let text = format!("{BASE}\n[sweep]\n\"task.terrain\" = []\n");
        let err = expand(&text, "demo.toml", "demo").unwrap_err().to_string();
        assert!(
            err.contains("sweep.\"task.terrain\"") && err.contains("at least one"),
            "{err}"
        );
        let text = format!("{BASE}\n[sweep]\n\"seed\" = 5\n");
        assert!(expand(&text, "demo.toml", "demo").is_err());
    }
}
