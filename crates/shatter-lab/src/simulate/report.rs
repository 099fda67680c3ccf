//! What a run measured, as `shatter simulate --json` reports it.
//!
//! To report something more, add a field to [`SimulateReport`] and fill it in
//! [`SimulateReport::new`] (from the world at the end of the run); the JSON follows.

use std::path::PathBuf;

use shatter_sim::World;

pub use super::export::ExportSummary;

/// What `--record` wrote.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RecordSummary {
    /// The CSV file.
    pub path: PathBuf,
    /// Rows after the header (one per step).
    pub rows: usize,
}

/// What a run measured.
#[derive(Debug, Clone, serde::Serialize)]
pub struct SimulateReport {
    /// Steps run.
    pub steps: u64,
    /// Rigid bodies at the end.
    pub bodies: usize,
    /// Fragments with a body at the end.
    pub fragments: usize,
    /// Bonds of all objects.
    pub bonds_total: usize,
    /// Broken bonds (never decreases during a run; the sum of the three causes).
    pub bonds_broken: usize,
    /// Bonds broken by a load over the break force (contacts, explosions, joints).
    pub bonds_broken_by_impact: usize,
    /// Bonds broken by the stress solver (stress over the material's limits).
    pub bonds_broken_by_stress: usize,
    /// Bonds broken when repeated weak hits wore their health to 0.
    pub bonds_broken_by_damage: usize,
    /// Runtime cuts applied (an `on_impact` object's first cut, fragments cut again).
    pub runtime_fractures: usize,
    /// The deepest fracture level a runtime cut reached (0: none).
    pub max_depth: u32,
    /// Intact bonds worn by weak hits (damage: health under 1).
    pub bonds_damaged: usize,
    /// The lowest health of an intact bond (1: none worn).
    pub min_bond_health: f32,
    /// Mean wall-clock milliseconds per step.
    pub millis_per_step: f64,
    /// Bodies removed because they diverged.
    pub diverged: usize,
    /// Bodies the contact speed cap slowed, summed over the steps (the `[world]` setting
    /// `contact_speed_cap`).
    pub speeds_capped: usize,
    /// Hash of the final state (hex).
    pub digest: String,
    /// The animated glTF written by `--export`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub export: Option<ExportSummary>,
    /// The statistics written by `--record`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub record: Option<RecordSummary>,
}

impl SimulateReport {
    /// The report of `world` after `steps` steps that took `total_ms` of wall-clock
    /// time (no export, no record yet).
    pub fn new(world: &World, steps: u64, total_ms: f64) -> Self {
        let stats = world.stats();
        Self {
            steps: stats.steps,
            bodies: stats.bodies,
            fragments: stats.fragments,
            bonds_total: stats.bonds_total,
            bonds_broken: stats.bonds_broken,
            bonds_broken_by_impact: stats.bonds_broken_by_impact,
            bonds_broken_by_stress: stats.bonds_broken_by_stress,
            bonds_broken_by_damage: stats.bonds_broken_by_damage,
            runtime_fractures: stats.runtime_fractures,
            max_depth: stats.max_depth,
            bonds_damaged: stats.bonds_damaged,
            min_bond_health: stats.min_bond_health,
            millis_per_step: if steps > 0 {
                total_ms / steps as f64
            } else {
                0.0
            },
            diverged: stats.diverged,
            speeds_capped: stats.speeds_capped,
            digest: format!("{:016x}", world.digest()),
            export: None,
            record: None,
        }
    }
}
