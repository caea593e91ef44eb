//! [`BodySummary`]: what records, MAP-Elites descriptors and the Python robot know of a robot's
//! body, given by its kind, so that none of them needs to know the kind's body type.

use vsrlab_body::{Morphology, MorphologyDescriptors};

/// A robot's body summarised by its kind.
#[derive(Debug, Clone, PartialEq)]
pub struct BodySummary {
    /// Units of the body (voxels, masses): what a brain sees as units.
    pub units: usize,
    /// The body as text rows, top row first, joined by `/`, in the kind's own characters (the
    /// voxel grid: `#` for a voxel, `.` for an empty cell).
    pub text: String,
    /// Named morphology descriptors, for MAP-Elites axes and analyses (grid kinds: `voxels`,
    /// `elongation`, `compactness`; see [`MorphologyDescriptors`]).
    pub descriptors: Vec<(&'static str, f64)>,
}

impl BodySummary {
    /// The summary of a body that is an occupancy grid: its rows and the thesis' three
    /// morphology descriptors (d_num, d_elong, d_compact).
    pub fn of_grid(grid: &Morphology) -> BodySummary {
        let d = MorphologyDescriptors::of(grid);
        BodySummary {
            units: grid.voxel_count(),
            text: grid.to_rows().join("/"),
            descriptors: vec![
                ("voxels", d.voxels as f64),
                ("elongation", d.elongation),
                ("compactness", d.compactness),
            ],
        }
    }

    /// The descriptor called `name`, when the kind gives it.
    pub fn descriptor(&self, name: &str) -> Option<f64> {
        self.descriptors.iter().find(|(n, _)| *n == name).map(|&(_, v)| v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_is_summarised_by_its_rows_and_the_thesis_descriptors() {
        let square = BodySummary::of_grid(&Morphology::parse("box-3x3").unwrap());
        assert_eq!(square.units, 9);
        assert_eq!(square.text, "###/###/###");
        // a square's moment ellipse is a circle (eccentricity 0); its hull holds only voxels
        assert_eq!(square.descriptor("voxels"), Some(9.0));
        assert_eq!(square.descriptor("elongation"), Some(0.0));
        assert_eq!(square.descriptor("compactness"), Some(1.0));
        assert_eq!(square.descriptor("height"), None);
        let line = BodySummary::of_grid(&Morphology::parse("worm-5x1").unwrap());
        assert_eq!((line.units, line.text.as_str()), (5, "#####"));
        let elongation = line.descriptor("elongation").unwrap();
        assert!(elongation > 0.9, "a line is elongated: {elongation}");
        assert_eq!(line.descriptor("compactness"), Some(1.0));
    }
}
