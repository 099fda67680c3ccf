//! Material presets: density, friction, restitution, bond strength, stress limits, wear,
//! and the fracture method and pattern they look best with. Every value can be overridden.
//!
//! The stress limits are the material's compressive, tensile and shear strengths in
//! pascals, from handbook ranges (rounded, at the low end where the range is wide, since
//! a fractured object's bonds are its weakest planes):
//!
//! | preset   | compression | tension | shear  | wear | source of the figures |
//! |----------|-------------|---------|--------|------|------------------------|
//! | glass    | 1000 MPa    | 40 MPa  | 30 MPa | 0.25 | annealed soda-lime glass: design tensile strength 30–60 MPa |
//! | stone    | 100 MPa     | 6 MPa   | 12 MPa | 0.2  | limestone / granite: compressive 60–250 MPa, tensile 5–25 MPa |
//! | concrete | 30 MPa      | 3 MPa   | 4 MPa  | 0.3  | C30 concrete: f_ck 30 MPa, f_ctm 2.9 MPa |
//! | wood     | 40 MPa      | 20 MPa  | 6 MPa  | 0.1  | softwood (C24): 21 MPa compression, 14–24 MPa tension, 4 MPa shear along the grain |
//! | ceramic  | 500 MPa     | 40 MPa  | 40 MPa | 0.3  | porcelain: compressive 300–1000 MPa, tensile 30–60 MPa |
//! | ice      | 5 MPa       | 1 MPa   | 0.8 MPa| 0.4  | freshwater ice near 0 °C: compressive 5–25 MPa, tensile 0.7–3 MPa |
//! | brick    | 8 MPa       | 0.1 MPa | 0.2 MPa| 0.3  | clay-brick masonry in general-purpose mortar (Eurocode 6): f_k 4–10 MPa, flexural bond f_xk1 0.1 MPa, initial shear f_vk0 0.1–0.3 MPa |
//!
//! `wear` is the health a bond loses to one hit at its full break force (see
//! [`Material::wear`]).

use serde::{Deserialize, Serialize};
use shatter_geom::fracture::Roughness;
pub use shatter_geom::fracture::{MethodKind, Pattern};

use crate::error::SimError;

shatter_geom::vocabulary! {
    /// A material preset: see the table above and [`MaterialPreset::material`].
    ///
    /// ```
    /// use shatter_sim::MaterialPreset;
    /// let glass: MaterialPreset = "glass".parse().expect("a preset");
    /// assert!(glass.material().density > 2000.0);
    /// assert!("cheese".parse::<MaterialPreset>().unwrap_err().to_string().contains("brick"));
    /// ```
    pub enum MaterialPreset: "material", default Stone {
        /// Annealed soda-lime glass.
        Glass = "glass",
        /// Limestone / granite.
        Stone = "stone",
        /// C30 concrete.
        Concrete = "concrete",
        /// Softwood (C24).
        Wood = "wood",
        /// Porcelain.
        Ceramic = "ceramic",
        /// Freshwater ice near 0 °C.
        Ice = "ice",
        /// Clay-brick masonry.
        Brick = "brick",
    }
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
    pub method: MethodKind,
    /// Default Voronoi seed pattern.
    pub pattern: Pattern,
    /// Compressive strength of a bond's face (Pa), for the stress solver.
    pub compression: f32,
    /// Tensile strength (Pa).
    pub tension: f32,
    /// Shear strength (Pa).
    pub shear: f32,
    /// Damage: a hit that loads a bond with a fraction `x < 1` of its break force, at
    /// least the endurance limit ([`crate::breaking::ENDURANCE`]), lowers the bond's
    /// health (1 when new) by `wear · x`; at health ≤ 0 it breaks. 0 turns damage off.
    pub wear: f32,
    /// Rough cut faces: fractal noise on the interior faces of precomputed Voronoi,
    /// tetra and slice fractures, in world units (stone and concrete by default; glass,
    /// wood, ceramic, ice and brick off). Grids stay flat (bricks are cut square), and
    /// runtime cuts too (roughening costs several times the cut itself).
    #[serde(default)]
    pub roughness: Roughness,
}

/// The names of the presets, in a fixed order (the words of [`MaterialPreset`]).
pub const MATERIAL_NAMES: &[&str] = MaterialPreset::NAMES;

impl MaterialPreset {
    /// The preset's material.
    pub fn material(self) -> Material {
        use MaterialPreset as P;
        let (compression, tension, shear, wear) = match self {
            P::Glass => (1000e6, 40e6, 30e6, 0.25),
            P::Stone => (100e6, 6e6, 12e6, 0.2),
            P::Concrete => (30e6, 3e6, 4e6, 0.3),
            P::Wood => (40e6, 20e6, 6e6, 0.1),
            P::Ceramic => (500e6, 40e6, 40e6, 0.3),
            P::Ice => (5e6, 1e6, 0.8e6, 0.4),
            P::Brick => (8e6, 0.1e6, 0.2e6, 0.3),
        };
        let (density, friction, restitution, strength, pattern) = match self {
            P::Glass => (2500.0, 0.4, 0.2, 2_000.0, Pattern::Radial),
            P::Stone => (2600.0, 0.7, 0.1, 20_000.0, Pattern::Uniform),
            P::Concrete => (2400.0, 0.8, 0.05, 12_000.0, Pattern::Clustered),
            P::Wood => (700.0, 0.5, 0.2, 6_000.0, Pattern::Splinter),
            P::Ceramic => (2300.0, 0.5, 0.15, 3_000.0, Pattern::Radial),
            P::Ice => (917.0, 0.05, 0.1, 1_500.0, Pattern::Uniform),
            P::Brick => (1800.0, 0.7, 0.05, 12_000.0, Pattern::Uniform),
        };
        Material {
            density,
            friction,
            restitution,
            strength,
            method: MethodKind::Voronoi,
            pattern,
            compression,
            tension,
            shear,
            wear,
            roughness: match self {
                P::Stone => Roughness::STONE,
                P::Concrete => Roughness::CONCRETE,
                P::Glass | P::Wood | P::Ceramic | P::Ice | P::Brick => Roughness::OFF,
            },
        }
    }

    /// The preset a material was made from: the one whose fixed properties match (the
    /// default method and pattern, the stress strengths and wear), which no scene key
    /// overrides; density, friction, restitution, strength and roughness may have been.
    ///
    /// ```
    /// use shatter_sim::{Material, MaterialPreset};
    /// let mut wood = MaterialPreset::Wood.material();
    /// wood.strength = 1.0;
    /// wood.density = 450.0;
    /// assert_eq!(MaterialPreset::of(&wood), Some(MaterialPreset::Wood));
    /// ```
    pub fn of(m: &Material) -> Option<MaterialPreset> {
        let fixed = |q: &Material| {
            let strengths = [q.compression, q.tension, q.shear, q.wear];
            (q.method, q.pattern, strengths)
        };
        MaterialPreset::ALL
            .iter()
            .copied()
            .find(|p| fixed(&p.material()) == fixed(m))
    }
}

impl Material {
    /// The preset called `name` (a word of [`MaterialPreset`]).
    ///
    /// ```
    /// let glass = shatter_sim::Material::preset("glass").expect("a preset");
    /// assert!(glass.density > 2000.0);
    /// assert!(shatter_sim::Material::preset("cheese").is_none());
    /// ```
    pub fn preset(name: &str) -> Option<Material> {
        name.parse::<MaterialPreset>()
            .ok()
            .map(MaterialPreset::material)
    }

    /// The stress limits of the material's bonds.
    ///
    /// ```
    /// let stone = shatter_sim::Material::preset("stone").expect("a preset");
    /// let limits = stone.limits();
    /// assert!(limits.tension < limits.shear && limits.shear < limits.compression);
    /// ```
    pub fn limits(&self) -> crate::stress::StressLimits {
        crate::stress::StressLimits {
            compression: f64::from(self.compression),
            tension: f64::from(self.tension),
            shear: f64::from(self.shear),
        }
    }

    /// The preset called `name`, or [`SimError::UnknownMaterial`] naming `key`.
    pub fn preset_or_error(name: &str, key: &str) -> Result<Material, SimError> {
        Material::preset(name).ok_or_else(|| SimError::UnknownMaterial {
            key: key.to_string(),
            name: name.to_string(),
            valid: MATERIAL_NAMES,
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
        positive(self.compression, "compression")?;
        positive(self.tension, "tension")?;
        positive(self.shear, "shear")?;
        if !(self.wear.is_finite() && self.wear >= 0.0) {
            return Err(SimError::invalid(
                format!("{key}.wear"),
                format!("must be >= 0, got {}", self.wear),
            ));
        }
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
        self.roughness
            .validate()
            .map_err(|e| SimError::invalid(format!("{key}.roughness"), e.to_string()))?;
        Ok(())
    }
}

impl Default for Material {
    fn default() -> Self {
        MaterialPreset::default().material()
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
    fn presets_round_trip_through_their_words() {
        for &p in MaterialPreset::ALL {
            assert_eq!(p.to_string().parse::<MaterialPreset>(), Ok(p));
            assert_eq!(Material::preset(p.name()), Some(p.material()));
            assert_eq!(MaterialPreset::of(&p.material()), Some(p), "{p}");
        }
    }

    #[test]
    fn unknown_preset_lists_every_preset() {
        let err = Material::preset_or_error("cheese", "objects[0].material").unwrap_err();
        for name in MATERIAL_NAMES {
            assert!(err.to_string().contains(name), "{err} lacks {name}");
        }
    }

    #[test]
    fn unknown_preset_names_the_key() {
        let err = Material::preset_or_error("cheese", "objects[0].material").unwrap_err();
        assert!(err.to_string().contains("objects[0].material"));
        assert!(err.to_string().contains("cheese"));
    }
}
