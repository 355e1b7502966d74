//! A config file's `[localization]` table, checked before it is read. Its keys are flat,
//! and `#[serde(flatten)]` shares them out to the groups of `LocalizationConfig`; but
//! flattening first reads the table into a buffer, so serde can neither refuse a key no
//! group takes (`deny_unknown_fields` is not supported together with `flatten`) nor place
//! a value a group cannot take on its line. This check does both, key by key in the order
//! the reader meets them, on the table as parsed with each key's place in the file.

use super::{
    LocalizationConfig, MeasurementModel, OdometryNoise, ParticleCount, Recovery, Spread,
    UpdateSchedule,
};
use serde::Deserialize;
use serde::de::{self, DeserializeSeed, Deserializer, IgnoredAny, MapAccess, Visitor};
use std::sync::OnceLock;
use toml::Spanned;
use toml::de::{DeTable, DeValue, ValueDeserializer};

impl LocalizationConfig {
    /// Every key `[localization]` takes: the ones the default config writes, in its order.
    pub fn keys() -> &'static [&'static str] {
        static KEYS: OnceLock<Vec<&'static str>> = OnceLock::new();
        KEYS.get_or_init(|| {
            let text = toml::to_string(&LocalizationConfig::default())
                .expect("the default localization settings serialise to TOML");
            let table = DeTable::parse(&text).expect("TOML that toml wrote parses");
            let mut keys: Vec<_> = table.get_ref().keys().collect();
            keys.sort_by_key(|k| k.span().start);
            // Made once, for the program's life, as serde's own field lists are.
            keys.into_iter()
                .map(|k| &*String::leak(k.get_ref().to_string()))
                .collect()
        })
    }

    /// Refuses what reading `section`, a config file's `[localization]` value, would let
    /// through or misplace: a key no group takes, named as serde names an unknown field,
    /// and a value its group cannot take, each at its place in the file. A value that is
    /// not a table is left to the reader, which refuses it.
    pub fn check_section(section: &Spanned<DeValue<'_>>) -> Result<(), toml::de::Error> {
        let Some(table) = section.get_ref().as_table() else {
            return Ok(());
        };
        for (key, value) in table {
            let entry = || {
                let mut one = DeTable::new();
                one.insert(key.clone(), value.clone());
                ValueDeserializer::from(Spanned::new(section.span(), DeValue::Table(one)))
            };
            entry().deserialize_map(KnownKeys)?;
            // The group that has the key reads it from the file (the others skip it), so a
            // bad value is reported at its line rather than at the table's header.
            ParticleCount::deserialize(entry())?;
            OdometryNoise::deserialize(entry())?;
            MeasurementModel::deserialize(entry())?;
            UpdateSchedule::deserialize(entry())?;
            Recovery::deserialize(entry())?;
            Spread::deserialize(entry())?;
            // The keys outside the groups (`estimator`).
            LocalizationConfig::deserialize(entry())?;
        }
        Ok(())
    }
}

/// Reads a table's keys, refusing one that `[localization]` does not take.
struct KnownKeys;

impl<'de> Visitor<'de> for KnownKeys {
    type Value = ();

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("the [localization] table")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        while map.next_key_seed(KnownKey)?.is_some() {
            map.next_value::<IgnoredAny>()?;
        }
        Ok(())
    }
}

/// One key of `[localization]`: an error, with the keys it could have been, unless known.
struct KnownKey;

impl<'de> DeserializeSeed<'de> for KnownKey {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<(), D::Error> {
        deserializer.deserialize_identifier(self)
    }
}

impl<'de> Visitor<'de> for KnownKey {
    type Value = ();

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a [localization] key")
    }

    fn visit_str<E: de::Error>(self, key: &str) -> Result<(), E> {
        let keys = LocalizationConfig::keys();
        if keys.contains(&key) {
            Ok(())
        } else {
            Err(E::unknown_field(key, keys))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `check_section` on the `[localization]` of `text`, its error as a file reader shows it.
    fn checked(text: &str) -> Result<(), String> {
        let doc = DeTable::parse(text).unwrap();
        let section = doc.get_ref().get("localization").expect("a [localization]");
        LocalizationConfig::check_section(section).map_err(|mut e| {
            e.set_input(Some(text));
            e.to_string()
        })
    }

    #[test]
    fn the_keys_are_the_flat_ones_a_file_writes() {
        let keys = LocalizationConfig::keys();
        assert_eq!(keys.len(), 30, "{keys:?}");
        for key in [
            "estimator",
            "model",
            "alpha1",
            "max_particles",
            "converged_std",
        ] {
            assert!(keys.contains(&key), "{key}: {keys:?}");
        }
        assert!(!keys.iter().any(|k| k.contains('.')), "{keys:?}");
    }

    #[test]
    fn an_unknown_key_is_refused_at_its_line_and_named() {
        for (text, line) in [
            ("[localization]\nalpha1 = 0.3\nalpha5 = 1\n", 3),
            ("[localization]\nalpha1 = 0.3\n[localization.alpha5]\n", 3),
            ("localization.alpha1 = 0.3\nlocalization.alpha5 = 1\n", 2),
            ("\nlocalization = { alpha1 = 0.3, alpha5 = 1 }\n", 2),
        ] {
            let e = checked(text).unwrap_err();
            assert!(
                e.contains("unknown field `alpha5`, expected one of `estimator`"),
                "{e}"
            );
            assert!(
                e.starts_with(&format!("TOML parse error at line {line}")),
                "{e}"
            );
        }
        // Every known key passes, in any group.
        let all: String = (LocalizationConfig::keys().iter())
            .map(|k| match *k {
                "estimator" => "estimator = \"mcl\"\n".to_string(),
                "model" => "model = \"beam\"\n".to_string(),
                k => format!("{k} = 1\n"),
            })
            .collect();
        assert_eq!(checked(&format!("[localization]\n{all}")), Ok(()));
    }

    #[test]
    fn a_value_of_the_wrong_kind_is_refused_at_its_own_line_in_every_group() {
        for key in LocalizationConfig::keys() {
            let text = format!("[localization]\n# A comment.\n{key} = [true]\n");
            let e = checked(&text).unwrap_err();
            assert!(
                e.starts_with("TOML parse error at line 3") && e.contains(&format!("3 | {key} =")),
                "{e}"
            );
        }
    }
}
