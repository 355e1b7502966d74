//! Range checks shared by the config sections: the first bad field, its value and why.

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
