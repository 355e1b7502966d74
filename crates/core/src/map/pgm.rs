//! PGM images (netpbm P5 binary and P2 plain), the pixel files of Nav2 maps. Hand-written
//! because a map file's errors must name what is wrong (a truncated file, a bad maxval, a
//! size beyond the limit, checked before anything is allocated), and the format is small.

/// The largest side navdeck reads, pixels: 8192 x 8192 at 5 cm is 410 m square, and its
/// grid stays within a few hundred megabytes.
pub const MAX_SIDE: usize = 8192;

/// A greyscale image, rows top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct Pgm {
    pub width: usize,
    pub height: usize,
    pub maxval: u16,
    pub pixels: Vec<u16>,
}

/// What is wrong with a PGM file.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PgmError {
    #[error("not a PGM file: magic number {0:?} is neither P5 nor P2")]
    Magic(String),
    #[error("header field `{field}` is missing or not a number")]
    Header { field: &'static str },
    #[error("header field `{field}` = {value}: {reason}")]
    Value {
        field: &'static str,
        value: u64,
        reason: &'static str,
    },
    #[error("truncated: {width} x {height} pixels need {needed} values, the file has {found}")]
    Truncated {
        width: usize,
        height: usize,
        needed: usize,
        found: usize,
    },
    #[error("pixel {index} = {value} exceeds maxval {maxval}")]
    Pixel {
        index: usize,
        value: u64,
        maxval: u16,
    },
}

/// The header: binary or plain, width, height and maxval, checked; `at` ends after it.
fn header(bytes: &[u8], at: &mut usize) -> Result<(bool, usize, usize, u16), PgmError> {
    let magic = token(bytes, at).unwrap_or_default();
    let binary = match magic.as_str() {
        "P5" => true,
        "P2" => false,
        // Only the start of what was found: the file may be anything at all.
        _ => {
            let start: String = magic.chars().take(8).collect();
            return Err(PgmError::Magic(crate::data::printable::printable(
                &start, None,
            )));
        }
    };
    let mut number = |field| {
        token(bytes, at)
            .and_then(|t| t.parse::<u64>().ok())
            .ok_or(PgmError::Header { field })
    };
    let (width, height, maxval) = (number("width")?, number("height")?, number("maxval")?);
    for (field, value) in [("width", width), ("height", height)] {
        if value == 0 || value > MAX_SIDE as u64 {
            return Err(PgmError::Value {
                field,
                value,
                reason: "must lie in 1..=8192",
            });
        }
    }
    if maxval == 0 || maxval > 65535 {
        return Err(PgmError::Value {
            field: "maxval",
            value: maxval,
            reason: "must lie in 1..=65535",
        });
    }
    Ok((binary, width as usize, height as usize, maxval as u16))
}

/// The width and height a P5 or P2 image's header gives, from its first bytes alone.
pub fn dimensions(bytes: &[u8]) -> Result<(usize, usize), PgmError> {
    header(bytes, &mut 0).map(|(_, w, h, _)| (w, h))
}

/// Reads a P5 or P2 image.
pub fn decode(bytes: &[u8]) -> Result<Pgm, PgmError> {
    let mut at = 0;
    let (binary, width, height, maxval) = header(bytes, &mut at)?;
    let needed = width * height;
    let pixels = if binary {
        // Exactly one whitespace byte separates the header from the raster.
        let start = at + 1;
        let size = if maxval < 256 { 1 } else { 2 };
        let raster = bytes.get(start..).unwrap_or_default();
        if raster.len() < needed * size {
            return Err(PgmError::Truncated {
                width,
                height,
                needed,
                found: raster.len() / size,
            });
        }
        if size == 1 {
            raster[..needed].iter().map(|&b| u16::from(b)).collect()
        } else {
            raster[..2 * needed]
                .chunks_exact(2)
                .map(|p| u16::from_be_bytes([p[0], p[1]]))
                .collect()
        }
    } else {
        // A plain pixel takes at least two bytes: never reserve more than the file holds.
        let mut pixels = Vec::with_capacity(needed.min(bytes.len() / 2 + 1));
        while pixels.len() < needed {
            let Some(t) = token(bytes, &mut at) else {
                break;
            };
            let value: u64 = t.parse().map_err(|_| PgmError::Header { field: "pixel" })?;
            pixels.push(value as u16);
            if value > u64::from(maxval) {
                return Err(PgmError::Pixel {
                    index: pixels.len() - 1,
                    value,
                    maxval,
                });
            }
        }
        if pixels.len() < needed {
            return Err(PgmError::Truncated {
                width,
                height,
                needed,
                found: pixels.len(),
            });
        }
        pixels
    };
    if let Some((index, &value)) = pixels.iter().enumerate().find(|(_, v)| **v > maxval) {
        return Err(PgmError::Pixel {
            index,
            value: u64::from(value),
            maxval,
        });
    }
    Ok(Pgm {
        width,
        height,
        maxval,
        pixels,
    })
}

/// Writes a P5 image with maxval 255 (every value must fit a byte).
pub fn encode(width: usize, height: usize, pixels: &[u8]) -> Vec<u8> {
    let mut out = format!("P5\n# written by navdeck\n{width} {height}\n255\n").into_bytes();
    out.extend_from_slice(pixels);
    out
}

/// The next whitespace-separated token from `at`, skipping `#` comments to the line end.
fn token(bytes: &[u8], at: &mut usize) -> Option<String> {
    loop {
        while *at < bytes.len() && bytes[*at].is_ascii_whitespace() {
            *at += 1;
        }
        if *at < bytes.len() && bytes[*at] == b'#' {
            while *at < bytes.len() && bytes[*at] != b'\n' {
                *at += 1;
            }
            continue;
        }
        break;
    }
    let start = *at;
    while *at < bytes.len() && !bytes[*at].is_ascii_whitespace() && bytes[*at] != b'#' {
        *at += 1;
    }
    (*at > start).then(|| String::from_utf8_lossy(&bytes[start..*at]).into_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn binary_and_plain_read_alike() {
        let p5 = encode(3, 2, &[0, 128, 255, 10, 20, 30]);
        let p2 = b"P2\n# a comment\n3 2\n255\n0 128 255\n10 20 30\n";
        assert_eq!(decode(&p5).unwrap(), decode(p2).unwrap());
        assert_eq!(decode(p2).unwrap().pixels, [0, 128, 255, 10, 20, 30]);
    }

    #[test]
    fn sixteen_bit_pixels_are_big_endian() {
        let mut bytes = b"P5 2 1 1000\n".to_vec();
        bytes.extend_from_slice(&[0x03, 0xE8, 0x00, 0x01]);
        assert_eq!(decode(&bytes).unwrap().pixels, [1000, 1]);
    }

    #[test]
    fn bad_files_say_what_is_wrong() {
        assert!(matches!(decode(b"P6 1 1 255\n\0"), Err(PgmError::Magic(_))));
        assert_eq!(
            decode(b"P5 4 4 255\n\0\0\0"),
            Err(PgmError::Truncated {
                width: 4,
                height: 4,
                needed: 16,
                found: 3
            })
        );
        let huge = decode(b"P5 100000 100000 255\n").unwrap_err();
        assert!(huge.to_string().contains("width") && huge.to_string().contains("100000"));
        assert!(
            decode(b"P5 1 1 70000\n\0\0")
                .unwrap_err()
                .to_string()
                .contains("maxval")
        );
        assert!(
            decode(b"P2 2 1 10\n5 11\n")
                .unwrap_err()
                .to_string()
                .contains("exceeds")
        );
        assert!(decode(b"P5 x").unwrap_err().to_string().contains("width"));
    }
}
