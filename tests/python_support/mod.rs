//! The Python the interop tests run their peers and readers with: `NAVDECK_PYTHON`
//! (./scripts/test makes a virtualenv with every package they need and sets it, with
//! NAVDECK_REQUIRE_INTEROP=1 so that a missing Python fails the run instead of skipping).

/// The Python to run `what` with, or None (the test is skipped) when none is set and
/// none is required. `packages` names the PyPI packages it needs, for the skip message.
pub fn python(what: &str, packages: &str) -> Option<String> {
    match std::env::var("NAVDECK_PYTHON") {
        Ok(p) if !p.is_empty() => Some(p),
        _ => {
            assert!(
                std::env::var_os("NAVDECK_REQUIRE_INTEROP").is_none(),
                "NAVDECK_PYTHON is not set: {what} cannot run"
            );
            eprintln!(
                "skipped: set NAVDECK_PYTHON to a Python with {packages} (./scripts/test does)"
            );
            None
        }
    }
}
