//! Task settings that replace an experiment's when its robots are replayed (`reassess`,
//! `plasticity`): `--duration`, `--terrain`, `--damage`.

use crate::simulate::damage_value;
use clap::Args;
use serde_json::json;

/// Options replacing settings of the experiments' tasks.
#[derive(Args, Debug, Clone)]
pub struct TaskOverrides {
    /// Episode length in simulated seconds (default: the experiment's).
    #[arg(long)]
    pub duration: Option<f64>,
    /// Terrain, e.g. hilly-3-30 (default: the experiment's; without a seed every episode has its
    /// own terrain).
    #[arg(long)]
    pub terrain: Option<String>,
    /// Damage: `<time s>:<probability>` (e.g. 30:0.5), or `none` to replay without the
    /// experiment's damage (default: the experiment's).
    #[arg(long)]
    pub damage: Option<String>,
}

impl TaskOverrides {
    /// The (dotted path, value) pairs to apply.
    pub fn settings(&self) -> Result<Vec<(String, serde_json::Value)>, String> {
        let mut out = Vec::new();
        if let Some(d) = self.duration {
            out.push(("duration".to_string(), json!(d)));
        }
        if let Some(t) = &self.terrain {
            out.push(("terrain".to_string(), json!(t)));
        }
        if let Some(d) = &self.damage {
            out.push((
                "damage".to_string(),
                damage_value(d).map_err(|e| format!("--damage: {e}"))?,
            ));
        }
        Ok(out)
    }
}
