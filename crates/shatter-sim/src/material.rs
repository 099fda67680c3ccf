//! Material presets: density, friction, restitution, bond strength and the fracture method
//! and pattern they look best with. Every value can be overridden.

use serde::{Deserialize, Serialize};

use crate::error::SimError;

/// How a material's objects are cut by default.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FractureMethod {
    /// The thesis's Delaunay tetrahedra.
    Tetra,
    /// Voronoi cells clipped to the mesh.
    Voronoi,
    /// Plane slices.
    Slice,
    /// A regular grid of boxes (bricks); only for box-shaped objects (see
    /// [`crate::testing::box_grid_fracture`]).
    Grid,
}

/// Seed pattern for Voronoi fracture.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Pattern {
    /// Uniform seeds.
    Uniform,
    /// Seeds clustered around a few centres.
    Clustered,
    /// Dense near an impact point (glass).
    Radial,
    /// Cells stretched along an axis (wood).
    Splinter,
}

/// Physical and fracture properties of a breakable object.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Density in kg/m³.
    pub density: f32,
    /// Coulomb friction coefficient.
    pub friction: f32,
    /// Restitution (bounciness), 0..=1.
    pub restitution: f32,
    /// Default break force of a bond, in newtons (see [`crate::BondModel`] for how each
    /// model compares it).
    pub strength: f32,
    /// Default fracture method.
    pub method: FractureMethod,
    /// Default Voronoi seed pattern.
    pub pattern: Pattern,
}

/// The names of the presets, in a fixed order.
pub const MATERIAL_NAMES: [&str; 6] = ["glass", "stone", "concrete", "wood", "ceramic", "ice"];

impl Material {
    /// The preset called `name` (glass, stone, concrete, wood, ceramic, ice).
    ///
    /// ```
    /// let glass = shatter_sim::Material::preset("glass").expect("a preset");
    /// assert!(glass.density > 2000.0);
    /// assert!(shatter_sim::Material::preset("cheese").is_none());
    /// ```
    pub fn preset(name: &str) -> Option<Material> {
        let (density, friction, restitution, strength, method, pattern) = match name {
            "glass" => (
                2500.0,
                0.4,
                0.2,
                2_000.0,
                FractureMethod::Voronoi,
                Pattern::Radial,
            ),
            "stone" => (
                2600.0,
                0.7,
                0.1,
                20_000.0,
                FractureMethod::Voronoi,
                Pattern::Uniform,
            ),
            "concrete" => (
                2400.0,
                0.8,
                0.05,
                12_000.0,
                FractureMethod::Voronoi,
                Pattern::Clustered,
            ),
            "wood" => (
                700.0,
                0.5,
                0.2,
                6_000.0,
                FractureMethod::Voronoi,
                Pattern::Splinter,
            ),
            "ceramic" => (
                2300.0,
                0.5,
                0.15,
                3_000.0,
                FractureMethod::Voronoi,
                Pattern::Radial,
            ),
            "ice" => (
                917.0,
                0.05,
                0.1,
                1_500.0,
                FractureMethod::Voronoi,
                Pattern::Uniform,
            ),
            _ => return None,
        };
        Some(Material {
            density,
            friction,
            restitution,
            strength,
            method,
            pattern,
        })
    }

    /// The preset called `name`, or [`SimError::UnknownMaterial`] naming `key`.
    pub fn preset_or_error(name: &str, key: &str) -> Result<Material, SimError> {
        Material::preset(name).ok_or_else(|| SimError::UnknownMaterial {
            key: key.to_string(),
            name: name.to_string(),
        })
    }

    /// Checks every value: positive finite density and strength, friction ≥ 0, restitution
    /// in 0..=1. `key` prefixes the error.
    pub fn validate(&self, key: &str) -> Result<(), SimError> {
        let positive = |v: f32, name: &str| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(SimError::invalid(
                    format!("{key}.{name}"),
                    format!("must be a positive number, got {v}"),
                ))
            }
        };
        positive(self.density, "density")?;
        positive(self.strength, "strength")?;
        if !(self.friction.is_finite() && self.friction >= 0.0) {
            return Err(SimError::invalid(
                format!("{key}.friction"),
                format!("must be >= 0, got {}", self.friction),
            ));
        }
        if !(0.0..=1.0).contains(&self.restitution) {
            return Err(SimError::invalid(
                format!("{key}.restitution"),
                format!("must be in 0..=1, got {}", self.restitution),
            ));
        }
        Ok(())
    }
}

impl Default for Material {
    fn default() -> Self {
        Material::preset("stone").expect("stone is a preset")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_is_valid() {
        for name in MATERIAL_NAMES {
            let m = Material::preset(name).expect("listed preset");
            m.validate(name).expect("preset values are valid");
        }
    }

    #[test]
    fn unknown_preset_names_the_key() {
        let err = Material::preset_or_error("cheese", "objects[0].material").unwrap_err();
        assert!(err.to_string().contains("objects[0].material"));
        assert!(err.to_string().contains("cheese"));
    }
}
