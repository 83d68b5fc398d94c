//! Writing output files atomically: each file is written to a hidden temporary sibling
//! (`.NAME.PID.tmp`) and renamed over its name, so that a crash never leaves a half-written
//! file in place of a good one, and the temporary file is removed on every failure. What is
//! not a regular file (`/dev/null`, `/dev/stdout`, a FIFO) is written in place instead, since
//! a rename would replace the device itself, and a symbolic link to a regular file stays a
//! link: the file it leads to is replaced. Also the checks on output targets that run before
//! any work: a file's directory must exist, an output directory is created one level deep.

use std::io::Write;
use std::path::{Path, PathBuf};

/// Why an output could not be written (every message names the file or directory).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum WriteError {
    /// The path has no file name (`/`, `..`).
    #[error("cannot write {}: not a file name", .0.display())]
    NotAFileName(PathBuf),
    /// A file output names a directory.
    #[error("cannot write {}: it is a directory", .0.display())]
    IsDirectory(PathBuf),
    /// A file output's directory does not exist (it is never created).
    #[error("cannot write {}: directory {} does not exist", .path.display(), .dir.display())]
    NoDirectory {
        /// The file.
        path: PathBuf,
        /// Its missing directory.
        dir: PathBuf,
    },
    /// Writing or renaming failed.
    #[error("cannot write {}", .path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The system error.
        source: std::io::Error,
    },
    /// An output directory's path exists and is not a directory.
    #[error("cannot use {} as the output directory: it exists and is not a directory", .0.display())]
    NotADirectory(PathBuf),
    /// An output directory's parent does not exist (only one level is created).
    #[error("cannot create output directory {}: {} does not exist", .path.display(), .parent.display())]
    NoParent {
        /// The directory.
        path: PathBuf,
        /// Its missing parent.
        parent: PathBuf,
    },
    /// An output directory could not be created.
    #[error("cannot create output directory {}", .path.display())]
    CreateDir {
        /// The directory.
        path: PathBuf,
        /// The system error.
        source: std::io::Error,
    },
    /// A writer of several files ([`write_stem`]) failed; its message names the final files.
    #[error("{0}")]
    Writer(String),
}

/// The directory a file path lives in (`.` for a bare file name).
fn parent_of(path: &Path) -> &Path {
    path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."))
}

/// The temporary sibling of `path` written first: hidden, the whole file name kept
/// (`.run.json.PID.tmp`), unique per process.
fn temp_sibling(path: &Path, pid: u32) -> Option<PathBuf> {
    let name = path.file_name()?.to_string_lossy();
    Some(parent_of(path).join(format!(".{name}.{pid}.tmp")))
}

/// Removes a temporary file unless it was renamed into place (on errors and panics alike).
struct TempGuard(Option<PathBuf>);

impl Drop for TempGuard {
    fn drop(&mut self) {
        if let Some(p) = self.0.take() {
            let _ = std::fs::remove_file(p);
        }
    }
}

/// Removes temporary siblings of `path` left by processes that no longer run (a SIGKILL cannot
/// be cleaned up after). Only where `/proc` tells which processes run.
fn remove_stale_temps(path: &Path) {
    let (Some(name), true) = (path.file_name(), Path::new("/proc/self").exists()) else {
        return;
    };
    let prefix = format!(".{}.", name.to_string_lossy());
    let Ok(entries) = std::fs::read_dir(parent_of(path)) else { return };
    for e in entries.flatten() {
        let file = e.file_name();
        let file = file.to_string_lossy();
        let Some(pid) = file.strip_prefix(&prefix).and_then(|r| r.strip_suffix(".tmp")) else {
            continue;
        };
        if pid.parse::<u32>().is_ok_and(|p| !Path::new(&format!("/proc/{p}")).exists()) {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

/// A file output (`--out FILE`, `-o`, `--svg`, `--state`, `--trace`) can be written: it is not
/// a directory and its directory exists. Directories of files are never created.
///
/// # Errors
/// [`WriteError::IsDirectory`] or [`WriteError::NoDirectory`].
pub fn check_file(path: &Path) -> Result<(), WriteError> {
    if path.is_dir() {
        return Err(WriteError::IsDirectory(path.to_path_buf()));
    }
    let dir = parent_of(path);
    if !dir.is_dir() {
        return Err(WriteError::NoDirectory { path: path.to_path_buf(), dir: dir.to_path_buf() });
    }
    Ok(())
}

/// A directory output: created if it is missing, as one level only (like `mkdir DIR`); its
/// parent must exist.
///
/// # Errors
/// [`WriteError::NotADirectory`], [`WriteError::NoParent`] or [`WriteError::CreateDir`].
pub fn ensure_dir(path: &Path) -> Result<(), WriteError> {
    if path.is_dir() {
        return Ok(());
    }
    if path.exists() {
        return Err(WriteError::NotADirectory(path.to_path_buf()));
    }
    let parent = parent_of(path);
    if !parent.is_dir() {
        return Err(WriteError::NoParent {
            path: path.to_path_buf(),
            parent: parent.to_path_buf(),
        });
    }
    std::fs::create_dir(path)
        .map_err(|source| WriteError::CreateDir { path: path.to_path_buf(), source })
}

/// How a file output is written.
#[derive(Debug, PartialEq)]
enum Target {
    /// Atomically, by renaming a temporary sibling over this path: the output's own path, or
    /// the regular file its symbolic link leads to (so the link stays a link).
    Replace(PathBuf),
    /// In place, like a shell's `>`: the output is not a regular file (a device such as
    /// `/dev/null`, a FIFO, a socket, a terminal), is reached through the kernel's `/dev` or
    /// `/proc` (`/dev/stdout` may lead to a regular file, which a rename would detach from the
    /// shell that opened it), or is a dangling link (written through, creating its file).
    InPlace,
}

fn target(path: &Path) -> Target {
    if path.starts_with("/dev") || path.starts_with("/proc") {
        return Target::InPlace;
    }
    let link = std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink());
    match std::fs::metadata(path) {
        Ok(m) if !m.is_file() => Target::InPlace,
        Ok(_) if link => std::fs::canonicalize(path).map_or(Target::InPlace, Target::Replace),
        Err(_) if link => Target::InPlace,
        _ => Target::Replace(path.to_path_buf()),
    }
}

/// Writes a file atomically: `write` fills a temporary sibling, which is then renamed over
/// `path`. The temporary file is removed on every failure, and temporary files of processes
/// that no longer run are removed first. Not fsync'ed: a power cut may lose the newest write,
/// never mix two. A path that is not a regular file (`/dev/null`, `/dev/stdout`, a FIFO) is
/// written in place, and a symbolic link's file is replaced, not the link (see the module).
///
/// # Errors
/// [`WriteError`] naming `path`: its directory is missing, or writing failed.
pub fn write(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), WriteError> {
    check_file(path)?;
    let failed = |source| WriteError::Io { path: path.to_path_buf(), source };
    let real = match target(path) {
        Target::Replace(real) => real,
        Target::InPlace => {
            return std::fs::File::create(path).and_then(|f| fill(f, write)).map_err(failed);
        }
    };
    remove_stale_temps(&real);
    let tmp = temp_sibling(&real, std::process::id())
        .ok_or_else(|| WriteError::NotAFileName(path.to_path_buf()))?;
    let mut guard = TempGuard(Some(tmp.clone()));
    std::fs::File::create(&tmp)
        .and_then(|f| fill(f, write))
        .and_then(|()| std::fs::rename(&tmp, &real))
        .map_err(failed)?;
    guard.0 = None;
    Ok(())
}

/// Runs `write` on `file` through a buffer, and flushes it.
fn fill(
    file: std::fs::File,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut w = std::io::BufWriter::new(file);
    write(&mut w)?;
    w.into_inner().map_err(std::io::IntoInnerError::into_error)?;
    Ok(())
}

/// Writes `bytes` to `path` atomically ([`write()`]).
///
/// # Errors
/// As [`write()`].
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    write(path, |w| w.write_all(bytes))
}

/// Writes `value` as pretty JSON, with a final newline, to `path` atomically ([`write()`]).
///
/// # Errors
/// As [`write()`]; a value that does not serialise is an I/O error.
pub fn write_json<T: serde::Serialize + ?Sized>(path: &Path, value: &T) -> Result<(), WriteError> {
    write(path, |w| {
        serde_json::to_writer_pretty(&mut *w, value)?;
        w.write_all(b"\n")
    })
}

/// Runs a writer that writes `STEM.svg`, `STEM.png`, … (a chart, an image) atomically: it
/// writes beside them under a temporary stem, and each file is then renamed to `final_stem`
/// with its extension. Returns the final paths.
///
/// # Errors
/// [`WriteError::Writer`] with the writer's message, naming the final files rather than the
/// temporary ones; [`WriteError::Io`] if a rename fails.
pub fn write_stem<E: std::fmt::Display>(
    final_stem: &Path,
    write: impl FnOnce(&Path) -> Result<Vec<PathBuf>, E>,
) -> Result<Vec<PathBuf>, WriteError> {
    let tmp_stem = temp_sibling(final_stem, std::process::id())
        .ok_or_else(|| WriteError::NotAFileName(final_stem.to_path_buf()))?;
    let written = write(&tmp_stem);
    let mut guards: Vec<TempGuard> =
        ["svg", "png"].iter().map(|e| TempGuard(Some(tmp_stem.with_extension(e)))).collect();
    // Errors name the final files, not the temporary ones.
    let written = written.map_err(|e| {
        let tmp = tmp_stem.with_extension("").display().to_string();
        let fin = final_stem.with_extension("").display().to_string();
        WriteError::Writer(e.to_string().replace(&tmp, &fin))
    })?;
    let mut out = Vec::new();
    for tmp in written {
        let fin = match tmp.extension() {
            Some(e) => final_stem.with_extension(e),
            None => final_stem.to_path_buf(),
        };
        guards.push(TempGuard(Some(tmp.clone())));
        std::fs::rename(&tmp, &fin)
            .map_err(|source| WriteError::Io { path: fin.clone(), source })?;
        out.push(fin);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("stopscan-atomic-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn leftovers(dir: &Path) -> Vec<String> {
        std::fs::read_dir(dir)
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains(".tmp"))
            .collect()
    }

    #[test]
    fn a_failed_write_leaves_the_old_file_and_no_temporary_file() {
        let dir = temp("fail");
        let path = dir.join("run.json");
        write_bytes(&path, b"old").unwrap();
        let e = write(&path, |w| {
            w.write_all(b"half")?;
            Err(std::io::Error::other("disk full"))
        })
        .unwrap_err();
        assert_eq!(e.to_string(), format!("cannot write {}", path.display()));
        assert_eq!(std::fs::read(&path).unwrap(), b"old");
        assert!(leftovers(&dir).is_empty());
        write_json(&path, &[1, 2]).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "[\n  1,\n  2\n]\n");
    }

    #[test]
    fn targets_are_checked() {
        let dir = temp("targets");
        let missing = dir.join("no/such/run.json");
        assert!(matches!(check_file(&missing), Err(WriteError::NoDirectory { .. })));
        assert!(matches!(check_file(&dir), Err(WriteError::IsDirectory(_))));
        assert!(matches!(ensure_dir(&dir.join("a/b")), Err(WriteError::NoParent { .. })));
        ensure_dir(&dir.join("a")).unwrap();
        assert!(dir.join("a").is_dir());
        write_bytes(&dir.join("f"), b"").unwrap();
        assert!(matches!(ensure_dir(&dir.join("f")), Err(WriteError::NotADirectory(_))));
    }

    /// `/dev/null`'s own kind of file, without touching it: a FIFO is not a regular file
    /// either, and a rename over it would replace it just as it replaced `/dev/null` once
    /// (when run as root, `-o /dev/null` made `/dev/null` a regular file, which then kept
    /// whatever was written to it).
    #[cfg(unix)]
    #[test]
    fn what_is_not_a_regular_file_is_written_in_place_not_replaced() {
        use std::os::unix::fs::FileTypeExt;
        let dir = temp("fifo");
        let fifo = dir.join("pipe");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if !made.is_ok_and(|s| s.success()) {
            // No mkfifo (not a POSIX system after all): nothing to check.
            return;
        }
        let reader = {
            let fifo = fifo.clone();
            // Opening a FIFO blocks until the other end is opened too.
            std::thread::spawn(move || std::fs::read(fifo).unwrap())
        };
        write_bytes(&fifo, b"through the pipe").unwrap();
        let kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
        // Checked before joining: a replaced FIFO would leave the reader waiting.
        assert!(kind.is_fifo(), "the FIFO was replaced by a {kind:?}");
        assert_eq!(reader.join().unwrap(), b"through the pipe");
        assert!(leftovers(&dir).is_empty());
        assert_eq!(target(Path::new("/dev/null")), Target::InPlace);
        assert_eq!(target(Path::new("/dev/stdout")), Target::InPlace);
    }

    #[cfg(unix)]
    #[test]
    fn a_symbolic_link_stays_a_link_and_its_file_is_replaced() {
        let dir = temp("link");
        let (real, link) = (dir.join("real.json"), dir.join("link.json"));
        std::fs::create_dir(dir.join("sub")).unwrap();
        write_bytes(&real, b"old").unwrap();
        std::os::unix::fs::symlink(&real, &link).unwrap();
        write_bytes(&link, b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        assert_eq!(std::fs::read(&real).unwrap(), b"new");
        assert!(leftovers(&dir).is_empty());
        // A dangling link is written through, creating its file.
        let (later, dangling) = (dir.join("sub/later.json"), dir.join("dangling.json"));
        std::os::unix::fs::symlink(&later, &dangling).unwrap();
        write_bytes(&dangling, b"made").unwrap();
        assert!(std::fs::symlink_metadata(&dangling).unwrap().file_type().is_symlink());
        assert_eq!(std::fs::read(&later).unwrap(), b"made");
    }

    #[test]
    fn stale_temporary_files_of_dead_processes_are_removed() {
        if !Path::new("/proc/self").exists() {
            return;
        }
        let dir = temp("stale");
        // No process has a pid this large (Linux caps them at 2^22).
        let stale = dir.join(".run.json.99999999.tmp");
        std::fs::write(&stale, b"x").unwrap();
        write_bytes(&dir.join("run.json"), b"new").unwrap();
        assert!(!stale.exists());
    }

    #[test]
    fn several_files_under_one_stem_get_their_final_names() {
        let dir = temp("stem");
        let stem = dir.join("chart");
        let files = write_stem(&stem, |tmp| -> Result<Vec<PathBuf>, String> {
            let (svg, png) = (tmp.with_extension("svg"), tmp.with_extension("png"));
            std::fs::write(&svg, b"<svg/>").map_err(|e| e.to_string())?;
            std::fs::write(&png, b"png").map_err(|e| e.to_string())?;
            Ok(vec![svg, png])
        })
        .unwrap();
        assert_eq!(files, vec![dir.join("chart.svg"), dir.join("chart.png")]);
        assert!(leftovers(&dir).is_empty());
        let e = write_stem(&stem, |tmp| -> Result<Vec<PathBuf>, String> {
            Err(format!("cannot draw {}", tmp.with_extension("svg").display()))
        })
        .unwrap_err();
        assert_eq!(e.to_string(), format!("cannot draw {}", dir.join("chart.svg").display()));
    }
}
