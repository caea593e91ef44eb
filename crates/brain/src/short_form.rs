//! Short forms of brains for the command line (`phase`, `mlp:16,8`, `step:0.33:distributed-mlp`, …):
//! the registry [`SHORT_FORMS`] from which [`crate::BrainSpec::parse`] dispatches and from which the
//! "unknown brain" message lists the accepted forms.

use crate::{controllers, BrainError, BrainSpec};

/// One short form: `name` or `name:<argument>`, parsed by the brain kind's module.
#[derive(Debug, Clone, Copy)]
pub struct ShortForm {
    /// The text before the first `:` (e.g. `mlp`).
    pub name: &'static str,
    /// How to write it, for messages (e.g. `mlp[:<hidden sizes, comma separated, or none>]`).
    pub usage: &'static str,
    /// Parses the text after `name:` (`None` when there is no `:`) into a brain whose parameters
    /// are empty; `None` when the argument does not fit this form.
    pub parse: fn(argument: Option<&str>) -> Option<BrainSpec>,
}

/// Every short form, in the order the "unknown brain" message lists them. Each brain kind's module
/// contributes its entries (`SHORT_FORM`).
pub static SHORT_FORMS: &[ShortForm] = &[
    controllers::phase::SHORT_FORM,
    controllers::phase_grid::SHORT_FORM,
    controllers::constant::SHORT_FORM,
    controllers::random::SHORT_FORM,
    controllers::centralized_mlp::SHORT_FORM,
    controllers::distributed_mlp::SHORT_FORM,
    controllers::distributed_mlp::HETEROGENEOUS_SHORT_FORM,
    controllers::distributed_mlp::LOCAL_SHORT_FORM,
    controllers::step::SHORT_FORM,
    controllers::smoothed::SHORT_FORM,
    controllers::hebbian::SHORT_FORM,
    controllers::attention::SHORT_FORM,
    controllers::graph::SHORT_FORM,
    controllers::heads::SHORT_FORM,
    controllers::elman::SHORT_FORM,
];

/// Parses `name[:argument]` with the [`SHORT_FORMS`] entry of that name; any failure is
/// [`BrainError::Unknown`] with the whole text.
pub(crate) fn parse(text: &str) -> Result<BrainSpec, BrainError> {
    let (name, argument) = text.split_once(':').map_or((text, None), |(a, b)| (a, Some(b)));
    SHORT_FORMS
        .iter()
        .find(|form| form.name == name)
        .and_then(|form| (form.parse)(argument))
        .ok_or_else(|| BrainError::Unknown(text.to_string()))
}

/// The usages of every short form: "a, b, … or z".
pub(crate) fn expected_forms() -> String {
    let usages: Vec<&str> = SHORT_FORMS.iter().map(|form| form.usage).collect();
    match usages.split_last() {
        Some((last, [])) => last.to_string(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => String::new(),
    }
}

/// A number argument (surrounding spaces allowed).
pub(crate) fn number(argument: &str) -> Option<f64> {
    argument.trim().parse().ok()
}

/// A count argument (surrounding spaces allowed).
pub(crate) fn count(argument: &str) -> Option<usize> {
    argument.trim().parse().ok()
}

/// The argument of a wrapper, `<number>:<inner brain's short form>`.
pub(crate) fn wrapped(argument: Option<&str>) -> Option<(f64, Box<BrainSpec>)> {
    let (value, inner) = argument?.split_once(':')?;
    let inner = BrainSpec::parse(inner).ok()?;
    Some((number(value)?, Box::new(inner)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Activation, ConstantSpec, DistributedMlpSpec, Layout, MlpSpec, RandomSpec, SmoothedSpec, StepSpec};

    #[test]
    fn parse_accepts_every_short_form_and_rejects_the_rest() {
        assert_eq!(BrainSpec::parse("phase"), Ok(BrainSpec::default()));
        assert_eq!(
            BrainSpec::parse("random:0.5"),
            Ok(BrainSpec::Random(RandomSpec { period: 0.5, seed: 0 }))
        );
        assert_eq!(
            BrainSpec::parse("random"),
            Ok(BrainSpec::Random(RandomSpec { period: 0.0, seed: 0 }))
        );
        assert_eq!(
            BrainSpec::parse("constant: -0.5"),
            Ok(BrainSpec::Constant(ConstantSpec { value: -0.5 }))
        );
        assert_eq!(
            BrainSpec::parse("mlp:16,8").unwrap(),
            BrainSpec::Mlp(MlpSpec {
                hidden: Some(vec![16, 8]),
                activation: Activation::Tanh,
                input_activation: true,
                weights: vec![]
            })
        );
        assert!(matches!(
            BrainSpec::parse("mlp"),
            Ok(BrainSpec::Mlp(MlpSpec { hidden: None, .. }))
        ));
        assert!(matches!(
            BrainSpec::parse("mlp:none"),
            Ok(BrainSpec::Mlp(MlpSpec { hidden: Some(h), .. })) if h.is_empty()
        ));
        assert!(matches!(
            BrainSpec::parse("distributed-mlp-hetero:3"),
            Ok(BrainSpec::DistributedMlp(DistributedMlpSpec {
                signals: 3,
                layout: Layout::Heterogeneous,
                ..
            }))
        ));
        assert!(matches!(
            BrainSpec::parse("distributed-mlp"),
            Ok(BrainSpec::DistributedMlp(DistributedMlpSpec {
                signals: 1,
                layout: Layout::Homogeneous,
                ..
            }))
        ));
        assert!(matches!(
            BrainSpec::parse("phase-grid:freq"),
            Ok(BrainSpec::PhaseGrid(crate::PhaseGridSpec {
                evolve_frequency: true,
                ..
            }))
        ));
        let nested = BrainSpec::parse("step:0.33:smoothed:5:random:0.1").unwrap();
        assert_eq!(
            nested,
            BrainSpec::Step(StepSpec {
                period: 0.33,
                inner: Box::new(BrainSpec::Smoothed(SmoothedSpec {
                    speed: 5.0,
                    inner: Box::new(BrainSpec::Random(RandomSpec { period: 0.1, seed: 0 }))
                }))
            })
        );
        for bad in [
            "",
            "brain",
            "constant",
            "phase:1",
            "mlp:a",
            "mlp:",
            "distributed-mlp:x",
            "step:0.33",
            "step:x:phase",
            "smoothed:1:nope",
            "phase-grid:x",
            "random:",
            "step",
        ] {
            let err = BrainSpec::parse(bad).unwrap_err();
            assert_eq!(err, BrainError::Unknown(bad.to_string()), "{bad}");
            assert!(err.to_string().contains("distributed-mlp-hetero[:<signals>]"), "{err}");
        }
    }

    #[test]
    fn the_unknown_brain_message_lists_every_form() {
        assert_eq!(
            BrainError::Unknown("neat".into()).to_string(),
            "unknown brain 'neat': expected phase, phase-grid[:freq], constant:<value>, random[:<period s>], \
             mlp[:<hidden sizes, comma separated, or none>], distributed-mlp[:<signals>], \
             distributed-mlp-hetero[:<signals>], local-mlp[:<signals>], step:<period s>:<brain>, smoothed:<speed>:<brain>, hebbian[:full|incoming|dew|l2], attention[:hetero|slow], graph[:<added hidden neurons>], heads[:<linear outputs>] or elman[:<memory units>]"
        );
    }

    #[test]
    fn each_form_has_its_own_name_and_usage_and_parses_its_example() {
        for (i, form) in SHORT_FORMS.iter().enumerate() {
            assert!(form.usage.starts_with(form.name), "{form:?}");
            assert!(!form.name.contains(':'), "{form:?}");
            assert!(
                SHORT_FORMS[i + 1..].iter().all(|other| other.name != form.name),
                "{} is registered twice",
                form.name
            );
        }
        for example in [
            "phase",
            "phase-grid:freq",
            "constant:1",
            "random:0.1",
            "mlp:4",
            "distributed-mlp:2",
            "distributed-mlp-hetero:2",
            "step:0.1:phase",
            "smoothed:1:phase",
        ] {
            assert!(BrainSpec::parse(example).is_ok(), "{example}");
        }
    }
}
