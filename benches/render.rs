//! How long one full frame takes to render: the 200x60 frame must stay under 1 ms.

use criterion::{Criterion, criterion_group, criterion_main};
use navdeck::app::KeyKind;
use navdeck::keymap::Key;
use navdeck::session::{LinkChoice, Session, SessionSpec};
use navdeck::tui::draw::draw;
use navdeck::tui::theme::Theme;
use ratatui::Terminal;
use ratatui::backend::TestBackend;

fn frame(c: &mut Criterion) {
    let spec = SessionSpec {
        world: None,
        seed: 1,
        start: None,
        config: None,
        keymap: None,
        link: LinkChoice::Sim,
        localize: Default::default(),
    };
    for (braille, name) in [
        (false, "render_200x60_ascii"),
        (true, "render_200x60_braille"),
    ] {
        let mut app = Session::load(&spec).unwrap().into_app(0.0);
        app.resize(200, 60);
        if braille {
            app.apply(navdeck::keymap::Action::ToggleBraille);
        }
        // Drive a little so the frame has motion, sightings and log lines in it.
        for i in 0..20 {
            app.handle_key(Key::char('w'), KeyKind::Press, f64::from(i) * 0.05);
        }
        app.update(1.5);
        let mut terminal = Terminal::new(TestBackend::new(200, 60)).unwrap();
        let theme = Theme { color: true };
        c.bench_function(name, |b| {
            b.iter(|| {
                // A fresh buffer each time: the whole frame is drawn, not a diff.
                terminal.clear().unwrap();
                terminal.draw(|f| draw(f, &app, theme)).unwrap();
            })
        });
    }
}

criterion_group!(benches, frame);
criterion_main!(benches);
