//! The default console session.

use super::app_with::app_with;
use navdeck::app::App;
use navdeck::session::SessionSpec;

/// The default session: the built-in arena, seed 1.
pub fn default_app() -> App {
    app_with(SessionSpec::twin(None))
}
