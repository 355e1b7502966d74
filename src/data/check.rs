//! Range checks every config section validates with: each section's `validate()` returns
//! the first bad field (named within its section), its value and why.

/// (field name within its section, value, reason).
pub type Invalid = (&'static str, f64, &'static str);

/// Every value a positive finite number.
pub fn all_positive(fields: &[(&'static str, f64)]) -> Result<(), Invalid> {
    match fields.iter().find(|(_, v)| !(v.is_finite() && *v > 0.0)) {
        Some(&(field, value)) => Err((field, value, "must be a positive number")),
        None => Ok(()),
    }
}

/// Every value a finite number, zero or more.
pub fn all_non_negative(fields: &[(&'static str, f64)]) -> Result<(), Invalid> {
    match fields.iter().find(|(_, v)| !(v.is_finite() && *v >= 0.0)) {
        Some(&(field, value)) => Err((field, value, "must be zero or more")),
        None => Ok(()),
    }
}

/// Every value a probability, 0 to 1.
pub fn all_probabilities(fields: &[(&'static str, f64)]) -> Result<(), Invalid> {
    match fields.iter().find(|(_, v)| !(0.0..=1.0).contains(v)) {
        Some(&(field, value)) => Err((field, value, "must lie in 0..=1")),
        None => Ok(()),
    }
}

/// Every count at least one.
pub fn all_at_least_one(fields: &[(&'static str, u32)]) -> Result<(), Invalid> {
    match fields.iter().find(|(_, v)| *v == 0) {
        Some(&(field, value)) => Err((field, f64::from(value), "must be at least 1")),
        None => Ok(()),
    }
}
