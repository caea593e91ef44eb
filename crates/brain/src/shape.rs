//! [`BrainShape`]: what a brain is built for, whatever the robot kind.

use crate::layout::{GridLayout, UnitLayout};
use std::sync::Arc;
use vsrlab_body::Morphology;

/// The body as its brain sees it: the units it actuates, how many readings each unit's sensors
/// give, and how the units are arranged ([`UnitLayout`]: positions and neighbours).
///
/// Every robot kind makes one for its body (a voxel grid: [`BrainShape::grid`]); brains ask it,
/// never the body, so a brain works on any kind whose layout answers its questions.
#[derive(Debug, Clone)]
pub struct BrainShape {
    layout: Arc<dyn UnitLayout>,
    readings: Vec<usize>,
}

impl BrainShape {
    /// A shape with this layout and these readings counts, one per unit in unit order (a count
    /// that does not match the layout's units is an error when a brain is built on it).
    pub fn new(layout: impl UnitLayout + 'static, readings_per_unit: Vec<usize>) -> BrainShape {
        BrainShape {
            layout: Arc::new(layout),
            readings: readings_per_unit,
        }
    }

    /// The shape of a 2D voxel grid body whose voxels (grid order) have these readings counts.
    pub fn grid(morphology: &Morphology, readings_per_voxel: &[usize]) -> BrainShape {
        BrainShape::new(GridLayout::new(morphology), readings_per_voxel.to_vec())
    }

    /// Number of units (the layout's).
    pub fn units(&self) -> usize {
        self.layout.units()
    }

    /// Readings count of every unit, in unit order.
    pub fn readings(&self) -> &[usize] {
        &self.readings
    }

    /// How the units are arranged.
    pub fn layout(&self) -> &dyn UnitLayout {
        self.layout.as_ref()
    }
}
