//! Terminal input bytes to navdeck's keys: legacy xterm sequences and the kitty keyboard
//! protocol (press, repeat and release), through `terminput`'s parser, plus the replies
//! to navdeck's start-up probe.
//!
//! Pure: bytes in, inputs out, so tests feed the exact sequences terminals send.

use crate::app::KeyKind;
use crate::keymap::{Key, KeyCode};
use std::collections::VecDeque;
use terminput::{Event, KeyEventKind, KeyModifiers};

/// An escape sequence longer than this is garbage: dropped, and decoding starts afresh.
const MAX_SEQUENCE: usize = 64;

/// What a stretch of input meant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    Key(Key, KeyKind),
    /// The reply to `CSI ? u`: the terminal speaks the kitty keyboard protocol.
    KeyboardProtocol,
    /// The reply to `CSI c` (primary device attributes): every earlier reply is in.
    DeviceAttributes,
}

/// Bytes to inputs, keeping an unfinished sequence for the next read.
#[derive(Debug, Default)]
pub struct InputDecoder {
    pending: Vec<u8>,
}

impl InputDecoder {
    /// Decodes one read's bytes. A lone ESC at the end of a read is the Esc key, as
    /// terminals send an escape sequence in a single write.
    pub fn feed(&mut self, bytes: &[u8], out: &mut VecDeque<Input>) {
        for (i, &byte) in bytes.iter().enumerate() {
            let more = i + 1 < bytes.len();
            self.pending.push(byte);
            if self.pending == [0x1b] && more {
                continue;
            }
            match decode(&self.pending) {
                Decoded::Done(input) => {
                    out.extend(input);
                    self.pending.clear();
                }
                Decoded::Unfinished if self.pending.len() >= MAX_SEQUENCE => self.pending.clear(),
                Decoded::Unfinished => {}
            }
        }
    }
}

/// What the bytes so far amount to.
enum Decoded {
    /// A whole sequence: an input, or nothing navdeck uses (or garbage, dropped).
    Done(Option<Input>),
    /// The start of a sequence: wait for more bytes.
    Unfinished,
}

fn decode(pending: &[u8]) -> Decoded {
    match probe_reply(pending) {
        Some(Some(reply)) => Decoded::Done(Some(reply)),
        Some(None) => Decoded::Unfinished,
        None => match Event::parse_from(pending) {
            Ok(Some(event)) => {
                Decoded::Done(key_from_event(&event).map(|(key, kind)| Input::Key(key, kind)))
            }
            Ok(None) => Decoded::Unfinished,
            Err(_) => Decoded::Done(None),
        },
    }
}

/// `CSI ? flags u` and `CSI ? ... c`, the answers to the probe; `None` for anything else,
/// `Some(None)` for an unfinished reply.
fn probe_reply(bytes: &[u8]) -> Option<Option<Input>> {
    let body = bytes.strip_prefix(b"\x1b[?")?;
    match body.last() {
        None => Some(None),
        Some(b'u') => Some(Some(Input::KeyboardProtocol)),
        Some(b'c') => Some(Some(Input::DeviceAttributes)),
        Some(b'0'..=b'9' | b';') => Some(None),
        Some(_) => None,
    }
}

/// A parsed key event as navdeck's key; `None` for events and keys navdeck has no use for
/// (modifier keys alone, media keys, mouse, focus, paste).
pub fn key_from_event(event: &Event) -> Option<(Key, KeyKind)> {
    use terminput::KeyCode as C;
    let Event::Key(k) = event else {
        return None;
    };
    let shift = k.modifiers.contains(KeyModifiers::SHIFT);
    let code = match k.code {
        // The kitty protocol reports the unshifted key with a shift modifier when the
        // terminal does not send the shifted key itself.
        C::Char(c) if shift && c.is_ascii_lowercase() => KeyCode::Char(c.to_ascii_uppercase()),
        C::Char(c) => KeyCode::Char(c),
        C::Enter => KeyCode::Enter,
        C::Esc => KeyCode::Esc,
        C::Tab if shift => KeyCode::BackTab,
        C::Tab => KeyCode::Tab,
        C::Backspace => KeyCode::Backspace,
        C::Delete => KeyCode::Delete,
        C::Insert => KeyCode::Insert,
        C::Up => KeyCode::Up,
        C::Down => KeyCode::Down,
        C::Left => KeyCode::Left,
        C::Right => KeyCode::Right,
        C::Home => KeyCode::Home,
        C::End => KeyCode::End,
        C::PageUp => KeyCode::PageUp,
        C::PageDown => KeyCode::PageDown,
        C::F(n) => KeyCode::F(n),
        _ => return None,
    };
    let kind = match k.kind {
        KeyEventKind::Press => KeyKind::Press,
        KeyEventKind::Repeat => KeyKind::Repeat,
        KeyEventKind::Release => KeyKind::Release,
    };
    let key = Key {
        code,
        ctrl: k.modifiers.contains(KeyModifiers::CTRL),
        alt: k.modifiers.contains(KeyModifiers::ALT),
    };
    Some((key, kind))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decode(chunks: &[&[u8]]) -> Vec<Input> {
        let mut decoder = InputDecoder::default();
        let mut out = VecDeque::new();
        for chunk in chunks {
            decoder.feed(chunk, &mut out);
        }
        out.into_iter().collect()
    }

    fn key(c: char, kind: KeyKind) -> Input {
        Input::Key(Key::char(c), kind)
    }

    #[test]
    fn plain_letters_in_one_read_are_separate_presses() {
        assert_eq!(
            decode(&[b"wwd"]),
            vec![
                key('w', KeyKind::Press),
                key('w', KeyKind::Press),
                key('d', KeyKind::Press)
            ]
        );
    }

    #[test]
    fn kitty_press_repeat_and_release_of_a_letter() {
        // REPORT_ALL_KEYS_AS_ESCAPE_CODES | REPORT_EVENT_TYPES: CSI code ; mods:event u
        assert_eq!(
            decode(&[b"\x1b[119u\x1b[119;1:2u", b"\x1b[119;1:3u"]),
            vec![
                key('w', KeyKind::Press),
                key('w', KeyKind::Repeat),
                key('w', KeyKind::Release)
            ]
        );
    }

    #[test]
    fn enter_tab_and_backspace_releases_are_releases_not_presses() {
        let out = decode(&[b"\x1b[13u\x1b[13;1:3u\x1b[9;1:3u\x1b[127;1:3u"]);
        let kinds: Vec<KeyKind> = out
            .iter()
            .map(|i| match i {
                Input::Key(_, kind) => *kind,
                other => panic!("not a key: {other:?}"),
            })
            .collect();
        assert_eq!(
            kinds,
            [
                KeyKind::Press,
                KeyKind::Release,
                KeyKind::Release,
                KeyKind::Release
            ]
        );
        assert_eq!(out[0], Input::Key(Key::new(KeyCode::Enter), KeyKind::Press));
        assert_eq!(
            out[3],
            Input::Key(Key::new(KeyCode::Backspace), KeyKind::Release)
        );
    }

    #[test]
    fn shifted_keys_come_out_shifted_with_or_without_alternate_keys() {
        // Without REPORT_ALTERNATE_KEYS: the base key and shift.
        assert_eq!(decode(&[b"\x1b[119;2u"]), vec![key('W', KeyKind::Press)]);
        // With it: base:shifted ; shift.
        assert_eq!(decode(&[b"\x1b[59:58;2u"]), vec![key(':', KeyKind::Press)]);
        // Legacy: the character itself.
        assert_eq!(
            decode(&[b"W:"]),
            vec![key('W', KeyKind::Press), key(':', KeyKind::Press)]
        );
    }

    #[test]
    fn ctrl_c_legacy_and_kitty() {
        let ctrl_c = Input::Key(
            Key {
                code: KeyCode::Char('c'),
                ctrl: true,
                alt: false,
            },
            KeyKind::Press,
        );
        assert_eq!(decode(&[b"\x03"]), vec![ctrl_c]);
        assert_eq!(decode(&[b"\x1b[99;5u"]), vec![ctrl_c]);
    }

    #[test]
    fn arrows_legacy_and_kitty_with_event_types() {
        let up = |kind| Input::Key(Key::new(KeyCode::Up), kind);
        assert_eq!(decode(&[b"\x1b[A\x1bOA"]), vec![up(KeyKind::Press); 2]);
        assert_eq!(
            decode(&[b"\x1b[1;1:2A\x1b[1;1:3A"]),
            vec![up(KeyKind::Repeat), up(KeyKind::Release)]
        );
    }

    #[test]
    fn lone_escape_is_the_esc_key_and_split_sequences_join() {
        assert_eq!(
            decode(&[b"\x1b"]),
            vec![Input::Key(Key::new(KeyCode::Esc), KeyKind::Press)]
        );
        assert_eq!(
            decode(&[b"\x1b[11", b"9;1:3u"]),
            vec![key('w', KeyKind::Release)]
        );
    }

    #[test]
    fn modifier_keys_alone_are_ignored() {
        // Left shift pressed and released (kitty's functional key 57441).
        assert!(decode(&[b"\x1b[57441;2u\x1b[57441;1:3u"]).is_empty());
    }

    #[test]
    fn probe_replies_are_recognised() {
        assert_eq!(
            decode(&[b"\x1b[?0u\x1b[?62;22c"]),
            vec![Input::KeyboardProtocol, Input::DeviceAttributes]
        );
        assert_eq!(decode(&[b"\x1b[?62;", b"c"]), vec![Input::DeviceAttributes]);
    }

    #[test]
    fn garbage_never_grows_the_buffer_and_decoding_recovers() {
        let mut decoder = InputDecoder::default();
        let mut out = VecDeque::new();
        let mut junk = b"\x1b[".to_vec();
        junk.extend(std::iter::repeat_n(b'1', 10_000));
        decoder.feed(&junk, &mut out);
        assert!(decoder.pending.len() < MAX_SEQUENCE);
        decoder.feed(b"\x1bq", &mut out);
        decoder.feed(b"q", &mut out);
        assert_eq!(out.back(), Some(&key('q', KeyKind::Press)));
    }

    /// Sequences of every kind the decoder knows, as terminals send them.
    const SEQUENCES: &[&[u8]] = &[
        b"w",
        b"\x03",
        b"\x1b[A",
        b"\x1bOA",
        b"\x1b[1;1:3A",
        b"\x1b[119u",
        b"\x1b[119;1:2u",
        b"\x1b[119;1:3u",
        b"\x1b[59:58;2u",
        b"\x1b[13;1:3u",
        b"\x1b[99;5u",
        b"\x1b[5~",
        b"\x1b[?0u",
        b"\x1b[?62;22c",
    ];

    #[test]
    fn every_sequence_split_anywhere_between_two_reads_decodes_as_whole() {
        for seq in SEQUENCES {
            let whole = decode(&[seq]);
            assert_eq!(whole.len(), 1, "{seq:?} gives {whole:?}");
            // A split right after a lone ESC is the Esc key by design (see `feed`).
            for at in 2..seq.len() {
                let (a, b) = seq.split_at(at);
                assert_eq!(decode(&[a, b]), whole, "{seq:?} split at {at}");
            }
        }
    }

    #[test]
    fn random_bytes_never_panic_never_grow_the_buffer_and_decoding_recovers() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(15);
        for _ in 0..500 {
            let mut decoder = InputDecoder::default();
            let mut out = VecDeque::new();
            for _ in 0..rng.random_range(1..20) {
                let len = rng.random_range(1..40);
                // Escape-heavy noise: ESC, '[', '?', digits, ';', ':' and any byte.
                let chunk: Vec<u8> = (0..len)
                    .map(|_| match rng.random_range(0..6) {
                        0 => 0x1b,
                        1 => b'[',
                        2 => b"?;:"[rng.random_range(0..3)],
                        3 => b'0' + rng.random_range(0..10u8),
                        _ => rng.random(),
                    })
                    .collect();
                decoder.feed(&chunk, &mut out);
                assert!(decoder.pending.len() < MAX_SEQUENCE);
            }
            out.clear();
            // Whatever was left unfinished completes or is dropped within MAX_SEQUENCE
            // bytes; after that a plain key reads as itself.
            for _ in 0..=MAX_SEQUENCE {
                decoder.feed(b"q", &mut out);
            }
            assert_eq!(out.back(), Some(&key('q', KeyKind::Press)), "{out:?}");
        }
    }
}
