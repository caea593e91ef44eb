//! Class names of the labelling page: parsed from a comma-separated list, checked to be safe in
//! HTML, and the rule-of-thumb proposals mapped onto them.

use crate::error::AnalysisError;

/// The thesis' morphology classes.
pub const THESIS_SHAPES: [&str; 4] = ["blob", "limbed", "elongated", "other"];

/// The thesis' behaviour classes.
pub const THESIS_BEHAVIOURS: [&str; 4] = ["jumping", "walking", "rolling", "other"];

/// Class names from a comma-separated list (`"blob, limbed,,other"`): trimmed, empty ones
/// dropped; at least two, without quotes or `<>&`.
pub fn parse_classes(list: &str) -> Result<Vec<String>, AnalysisError> {
    let classes: Vec<String> = list
        .split(',')
        .map(|c| c.trim().to_string())
        .filter(|c| !c.is_empty())
        .collect();
    check_classes(&classes, list)?;
    Ok(classes)
}

/// Checks class names: at least two, none with quotes or `<>&`; `given` names the list in
/// errors.
pub(crate) fn check_classes(classes: &[String], given: &str) -> Result<(), AnalysisError> {
    if classes.len() < 2 {
        return Err(AnalysisError::TooFewClasses { given: given.into() });
    }
    if classes.iter().any(|c| c.contains(['"', '<', '>', '&'])) {
        return Err(AnalysisError::ClassNameCharacters { given: given.into() });
    }
    Ok(())
}

/// The proposal if it is one of the classes, else the last class (the "other" bin by convention).
pub(crate) fn nearest_class(proposal: &str, classes: &[String]) -> String {
    classes
        .iter()
        .find(|c| c.as_str() == proposal)
        .cloned()
        .unwrap_or_else(|| classes.last().cloned().unwrap_or_default())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_and_proposals() {
        assert_eq!(parse_classes("a, b,,c").unwrap(), vec!["a", "b", "c"]);
        assert!(parse_classes("only").is_err());
        assert!(parse_classes("a,<b>").is_err());
        let cls = vec!["block".to_string(), "legged".to_string(), "other".to_string()];
        assert_eq!(nearest_class("limbed", &cls), "other");
        assert_eq!(nearest_class("legged", &cls), "legged");
    }
}
