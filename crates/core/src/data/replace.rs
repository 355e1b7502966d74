//! Writing files the way a map save does, for every file navdeck writes over a user's:
//! all of a set or none (each under a temporary name beside it first, then renamed into
//! place), never through a symbolic link planted at either name, the previous version
//! kept as `NAME.bak`, and no temporary file left behind on any failure.

use std::io::Write;
use std::path::{Path, PathBuf};

/// A file name navdeck creates may not hold control characters: the name would carry an
/// escape sequence to every terminal that lists the folder. `what` names the file's role;
/// the caller's message names the path.
pub fn check_name(path: &Path, what: &str) -> std::io::Result<()> {
    if path.to_string_lossy().chars().any(char::is_control) {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("the {what}'s name holds control characters: not created"),
        ));
    }
    Ok(())
}

/// Makes the folder `dir` and those above it, as `create_dir_all` does, refusing a name
/// with control characters and saying plainly when a file stands where a folder must.
pub fn create_folder(dir: &Path) -> std::io::Result<()> {
    check_name(dir, "folder")?;
    std::fs::create_dir_all(dir).map_err(|e| {
        let file = dir
            .ancestors()
            .find(|a| std::fs::metadata(a).is_ok_and(|m| !m.is_dir()));
        match file {
            Some(file) => std::io::Error::new(
                std::io::ErrorKind::AlreadyExists,
                format!("{} is a file, not a folder", file.display()),
            ),
            None => e,
        }
    })
}

/// Writes each (target, bytes) of `files` through `write` under `target.tmp`, then
/// renames the targets already there to `target.bak` and the temporary files into place.
/// On failure the error names the target at fault, and every temporary file is removed.
pub fn replace_files(
    files: &[(PathBuf, Vec<u8>)],
    write: &mut dyn FnMut(&Path, &[u8]) -> std::io::Result<()>,
) -> Result<(), (PathBuf, std::io::Error)> {
    for (target, _) in files {
        check_target(target).map_err(|e| (target.clone(), e))?;
    }
    let temporaries: Vec<PathBuf> = files.iter().map(|(t, _)| with_suffix(t, ".tmp")).collect();
    let clean_up = || {
        for tmp in &temporaries {
            // Only a regular file of ours: a folder or pipe someone put there stays.
            if std::fs::symlink_metadata(tmp).is_ok_and(|m| !m.is_dir()) {
                let _ = std::fs::remove_file(tmp);
            }
        }
    };
    for ((target, bytes), tmp) in files.iter().zip(&temporaries) {
        if let Err(e) = write(tmp, bytes) {
            clean_up();
            return Err((target.clone(), e));
        }
    }
    for ((target, _), tmp) in files.iter().zip(&temporaries) {
        let moved = (|| {
            // The link itself, not what it points to: a planted link is moved aside.
            if std::fs::symlink_metadata(target).is_ok() {
                std::fs::rename(target, with_suffix(target, ".bak"))?;
            }
            std::fs::rename(tmp, target)
        })();
        if let Err(e) = moved {
            clean_up();
            return Err((target.clone(), e));
        }
    }
    Ok(())
}

/// `replace_files` for one file, written with `write_synced`.
pub fn replace_file(target: &Path, bytes: Vec<u8>) -> Result<(), (PathBuf, std::io::Error)> {
    replace_files(&[(target.to_path_buf(), bytes)], &mut write_synced)
}

/// A target a save may replace: a regular file, a symbolic link (moved aside, not
/// followed) or nothing; not a folder or a device; and a name without control characters.
fn check_target(target: &Path) -> std::io::Result<()> {
    check_name(target, "file")?;
    let refuse = |why: &str| Err(std::io::Error::new(std::io::ErrorKind::InvalidInput, why));
    match std::fs::symlink_metadata(target) {
        Ok(meta) if meta.is_dir() => refuse("it is a folder, not a file"),
        // A device, pipe or socket is not replaced (nor moved aside: not /dev/null).
        Ok(meta) if !(meta.is_file() || meta.is_symlink()) => {
            refuse("it is not a regular file (a device, pipe or socket)")
        }
        _ => Ok(()),
    }
}

pub fn with_suffix(path: &Path, suffix: &str) -> PathBuf {
    let mut name = path.as_os_str().to_owned();
    name.push(suffix);
    PathBuf::from(name)
}

/// Writes a new file at `path` (a temporary name), never through what is already there:
/// a regular file left by an interrupted save is removed first; anything else (a symbolic
/// link planted to redirect the save, a folder, a pipe) is refused. The file is created
/// exclusively, so nothing put there meanwhile is followed either.
pub fn write_synced(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    match std::fs::symlink_metadata(path) {
        Ok(meta) if meta.file_type().is_file() => std::fs::remove_file(path)?,
        Ok(meta) => {
            let what = if meta.file_type().is_symlink() {
                "a symbolic link"
            } else {
                "not a regular file"
            };
            return Err(std::io::Error::new(
                std::io::ErrorKind::AlreadyExists,
                format!("{} is {what}: not writing through it", path.display()),
            ));
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        Err(e) => return Err(e),
    }
    let mut file = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(path)?;
    file.write_all(bytes)?;
    file.sync_all()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("navdeck-replace-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_planted_link_is_moved_aside_not_written_through() {
        let dir = scratch("link");
        let victim = dir.join("victim");
        std::fs::write(&victim, "keep").unwrap();
        let target = dir.join("out.toml");
        std::os::unix::fs::symlink(&victim, &target).unwrap();
        replace_file(&target, b"new".to_vec()).unwrap();
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep");
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new");
        assert!(
            std::fs::symlink_metadata(dir.join("out.toml.bak"))
                .unwrap()
                .is_symlink()
        );
        // A dangling link too.
        let dangling = dir.join("d.toml");
        std::os::unix::fs::symlink(dir.join("nowhere"), &dangling).unwrap();
        replace_file(&dangling, b"x".to_vec()).unwrap();
        assert!(!dir.join("nowhere").exists());
        assert_eq!(std::fs::read_to_string(&dangling).unwrap(), "x");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_failure_after_the_first_file_leaves_no_temporary_file() {
        let dir = scratch("fail");
        let (a, b) = (dir.join("m.pgm"), dir.join("m.yaml"));
        // A link planted at the second file's temporary name: that write is refused.
        std::os::unix::fs::symlink(dir.join("elsewhere"), with_suffix(&b, ".tmp")).unwrap();
        let files = [(a.clone(), b"img".to_vec()), (b.clone(), b"yaml".to_vec())];
        let (at, _) = replace_files(&files, &mut write_synced).unwrap_err();
        assert_eq!(at, b);
        let left: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert!(left.is_empty(), "{left:?}");
        assert!(!dir.join("elsewhere").exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_folder_where_a_file_stands_is_refused_plainly() {
        let dir = scratch("folder");
        std::fs::write(dir.join("f"), "").unwrap();
        let err = create_folder(&dir.join("f").join("sub"))
            .unwrap_err()
            .to_string();
        assert!(err.ends_with("f is a file, not a folder"), "{err}");
        let err = create_folder(&dir.join("a\u{1b}]0;pwn\u{7}dir"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("control characters"), "{err}");
        assert!(std::fs::read_dir(&dir).unwrap().count() == 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn names_with_control_characters_and_folders_are_refused() {
        let dir = scratch("names");
        let err = replace_file(&dir.join("a\u{1b}]0;x\u{7}.toml"), Vec::new()).unwrap_err();
        assert!(
            err.1.to_string().contains("control characters"),
            "{}",
            err.1
        );
        let err = replace_file(&dir, Vec::new()).unwrap_err();
        assert!(err.1.to_string().contains("folder"), "{}", err.1);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
