//! The lighting a colour frame is rendered under (seed 000 §6.2.1's bright, normal and
//! dark, and §6.4.2's shadows and glare): a level, hard shadows across the lane, and
//! specular glare of ceiling lamps on the floor.

use serde::Serialize;

/// How much light falls on the scene (seed 000 §6.2.1: bright > 500 lux, normal 200-500,
/// dark < 200).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LightingLevel {
    Bright,
    Normal,
    Dark,
}

impl LightingLevel {
    /// The factor on every lit colour: bright 1.2, normal 1, dark 0.5 (navdeck's figures
    /// for the seed's bands, 600, 350 and 150 lux, taken against 350 lux; a camera's
    /// auto-exposure recovers part of the difference, so the factors are milder than the
    /// lux ratios).
    pub fn brightness(self) -> f64 {
        match self {
            Self::Bright => 1.2,
            Self::Normal => 1.0,
            Self::Dark => 0.5,
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            Self::Bright => "bright",
            Self::Normal => "normal",
            Self::Dark => "dark",
        }
    }
}

/// A lighting variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub struct Lighting {
    pub level: LightingLevel,
    /// Hard shadows of furniture falling across the lane.
    pub shadows: bool,
    /// Ceiling lamps reflected on the floor (seed 000 §2.1.3: V 245 +- 8).
    pub glare: bool,
}

impl Default for Lighting {
    fn default() -> Self {
        Self::NORMAL
    }
}

impl Lighting {
    pub const NORMAL: Lighting = Lighting {
        level: LightingLevel::Normal,
        shadows: false,
        glare: false,
    };

    /// The variants a sweep runs: the three levels, then shadows and glare at normal.
    pub const VARIANTS: [&'static str; 5] = ["bright", "normal", "dark", "shadows", "glare"];

    /// The variant called `name` (one of `VARIANTS`, or `all`'s parts joined by `+`, such
    /// as `dark+shadows+glare`).
    pub fn parse(name: &str) -> Result<Self, String> {
        let mut lighting = Self::NORMAL;
        for part in name.split('+') {
            match part.trim() {
                "bright" => lighting.level = LightingLevel::Bright,
                "normal" => lighting.level = LightingLevel::Normal,
                "dark" => lighting.level = LightingLevel::Dark,
                "shadows" => lighting.shadows = true,
                "glare" => lighting.glare = true,
                other => {
                    return Err(format!(
                        "lighting `{other}`: expected one of {} (joined by +)",
                        Self::VARIANTS.join(", ")
                    ));
                }
            }
        }
        Ok(lighting)
    }

    /// The name `parse` reads back.
    pub fn name(self) -> String {
        let mut name = self.level.label().to_string();
        if self.shadows {
            name.push_str("+shadows");
        }
        if self.glare {
            name.push_str("+glare");
        }
        name
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn variants_read_back_and_bad_names_are_named() {
        for v in Lighting::VARIANTS {
            let l = Lighting::parse(v).unwrap();
            assert_eq!(Lighting::parse(&l.name()).unwrap(), l);
        }
        let l = Lighting::parse("dark+glare").unwrap();
        assert!(l.glare && l.level == LightingLevel::Dark && !l.shadows);
        let e = Lighting::parse("dusk").unwrap_err();
        assert!(e.contains("`dusk`"), "{e}");
    }
}
