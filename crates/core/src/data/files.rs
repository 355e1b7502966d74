//! Reading an input file without trusting it: only a regular file (not a device, FIFO or
//! folder, which could be read for ever), and only up to a size limit given per kind of
//! file, checked before and while reading.

use std::io::Read;
use std::path::Path;

/// Most bytes of a config, keymap or calibration file.
pub const TEXT_LIMIT: u64 = 1 << 20;
/// Most bytes of a world file.
pub const WORLD_LIMIT: u64 = 4 << 20;
/// Most bytes of a map's YAML header (a Nav2 map YAML is a few hundred bytes).
pub const MAP_YAML_LIMIT: u64 = 64 << 10;
/// Most bytes of a map image: a 8192 x 8192 binary PGM with room for its header.
pub const MAP_IMAGE_LIMIT: u64 = (8192 * 8192) + (64 << 10);

/// The metadata of `path` when it is a regular file (a link to one counts).
fn regular_file(path: &Path) -> std::io::Result<std::fs::Metadata> {
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "not a regular file (a folder, device or pipe is not read)",
        ));
    }
    Ok(meta)
}

/// The size of the regular file at `path`, refused over `limit` bytes, for a reader that
/// opens the file itself (OpenCV's): nothing is read here.
pub fn check_limited(path: &Path, limit: u64) -> std::io::Result<u64> {
    let meta = regular_file(path)?;
    if meta.len() > limit {
        return Err(too_big(meta.len(), limit));
    }
    Ok(meta.len())
}

/// The bytes of the regular file at `path`, refused over `limit` bytes.
pub fn read_limited(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    let size = check_limited(path, limit)?;
    let mut bytes = Vec::with_capacity(size as usize);
    // The file may grow while read: never more than the limit.
    std::fs::File::open(path)?
        .take(limit + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_big(bytes.len() as u64, limit));
    }
    Ok(bytes)
}

/// The first `n` bytes (or fewer) of the regular file at `path`: enough for a header.
pub fn read_head(path: &Path, n: u64) -> std::io::Result<Vec<u8>> {
    regular_file(path)?;
    let mut bytes = Vec::new();
    std::fs::File::open(path)?.take(n).read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// `read_limited` as UTF-8 text.
pub fn read_text_limited(path: &Path, limit: u64) -> std::io::Result<String> {
    String::from_utf8(read_limited(path, limit)?).map_err(|e| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "not UTF-8 text (byte {} is not)",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

fn too_big(size: u64, limit: u64) -> std::io::Error {
    std::io::Error::new(
        std::io::ErrorKind::InvalidInput,
        format!("{size} bytes or more, over the limit of {limit} bytes"),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_device_a_folder_and_a_file_over_the_limit_are_refused() {
        let dir = std::env::temp_dir().join(format!("navdeck-files-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("a.toml");
        std::fs::write(&file, "x = 1\n").unwrap();
        assert_eq!(read_text_limited(&file, 100).unwrap(), "x = 1\n");
        let err = read_limited(&file, 3).unwrap_err().to_string();
        assert!(err.contains("over the limit of 3 bytes"), "{err}");
        let err = read_limited(&dir, 100).unwrap_err().to_string();
        assert!(err.contains("not a regular file"), "{err}");
        if Path::new("/dev/zero").exists() {
            let err = read_limited(Path::new("/dev/zero"), 100)
                .unwrap_err()
                .to_string();
            assert!(err.contains("not a regular file"), "{err}");
        }
        std::fs::write(&file, [0xff, 0xfe]).unwrap();
        assert!(
            read_text_limited(&file, 100)
                .unwrap_err()
                .to_string()
                .contains("UTF-8")
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
