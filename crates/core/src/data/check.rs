//! Range checks every config section validates with: each section's `validate()` returns
//! the first bad field (named within its section), its value and why. Values and bounds
//! are printed short (`super::number::short`): `1e308`, not 309 digits.

use super::number::short;
use std::borrow::Cow;

/// (field name within its section, value, reason).
pub type Invalid = (&'static str, f64, Cow<'static, str>);

/// Every value within its inclusive bounds (lo, hi): finite and physically sensible. The
/// reason names the bounds.
pub fn within(fields: &[(&'static str, f64, f64, f64)]) -> Result<(), Invalid> {
    match fields.iter().find(|(_, v, lo, hi)| !(lo..=hi).contains(&v)) {
        Some(&(field, value, lo, hi)) => Err((
            field,
            value,
            format!("must lie in {}..={}", short(lo), short(hi)).into(),
        )),
        None => Ok(()),
    }
}

/// Every count within its inclusive bounds.
pub fn counts_within(fields: &[(&'static str, u64, u64, u64)]) -> Result<(), Invalid> {
    match fields.iter().find(|(_, v, lo, hi)| !(lo..=hi).contains(&v)) {
        Some(&(field, value, lo, hi)) => Err((
            field,
            value as f64,
            format!("must lie in {lo}..={hi}").into(),
        )),
        None => Ok(()),
    }
}

/// Every value a positive finite number.
pub fn all_positive(fields: &[(&'static str, f64)]) -> Result<(), Invalid> {
    match fields.iter().find(|(_, v)| !(v.is_finite() && *v > 0.0)) {
        Some(&(field, value)) => Err((field, value, "must be a positive number".into())),
        None => Ok(()),
    }
}

/// Every value a finite number, zero or more.
pub fn all_non_negative(fields: &[(&'static str, f64)]) -> Result<(), Invalid> {
    match fields.iter().find(|(_, v)| !(v.is_finite() && *v >= 0.0)) {
        Some(&(field, value)) => Err((field, value, "must be zero or more".into())),
        None => Ok(()),
    }
}

/// Every value a probability, 0 to 1.
pub fn all_probabilities(fields: &[(&'static str, f64)]) -> Result<(), Invalid> {
    match fields.iter().find(|(_, v)| !(0.0..=1.0).contains(v)) {
        Some(&(field, value)) => Err((field, value, "must lie in 0..=1".into())),
        None => Ok(()),
    }
}
