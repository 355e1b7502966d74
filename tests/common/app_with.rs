//! A console session loaded as the command line loads it.

use navdeck::app::App;
use navdeck::session::{Session, SessionSpec};

/// The console of the session `spec` describes, at time 0.
pub fn app_with(spec: SessionSpec) -> App {
    Session::load(&spec).expect("session loads").into_app(0.0)
}
