//! Append-only journals of JSON lines, as `stopscan serve --journal` and `roi --state` keep
//! them: a first line (a header, or a state), then one line per step, each written with one
//! `write` before the step's effect is shown to anyone. A crash leaves every line whole but
//! perhaps the last, torn at its end (no newline): [`read`] leaves it out and [`reopen`]
//! cuts it off before appending.

use std::fs::{File, OpenOptions};
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// A journal open for appending.
#[derive(Debug)]
pub struct Journal {
    path: PathBuf,
    file: File,
    fsync: bool,
    spent: Duration,
}

impl Journal {
    /// Opens the journal at `path` for appending; with `fsync`, every line is also synced to
    /// the disk.
    ///
    /// # Errors
    /// The file cannot be opened.
    pub fn append_to(path: &Path, fsync: bool) -> std::io::Result<Self> {
        let file = OpenOptions::new().create(true).append(true).open(path)?;
        Ok(Self { path: path.to_path_buf(), file, fsync, spent: Duration::ZERO })
    }

    /// The journal's file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Appends one line (`line` has no newline; one is added) with one `write`.
    ///
    /// # Errors
    /// The write (or the sync) failed.
    pub fn append(&mut self, line: &str) -> std::io::Result<()> {
        let t = Instant::now();
        let mut bytes = Vec::with_capacity(line.len() + 1);
        bytes.extend_from_slice(line.as_bytes());
        bytes.push(b'\n');
        self.file.write_all(&bytes)?;
        if self.fsync {
            self.file.sync_data()?;
        }
        self.spent += t.elapsed();
        Ok(())
    }

    /// Time spent appending so far.
    pub fn spent(&self) -> Duration {
        self.spent
    }
}

/// The complete lines of the journal at `path`, without their newlines; a last line torn by a
/// crash is left out. Also the length in bytes of the complete lines.
///
/// # Errors
/// The file cannot be read, or is not UTF-8.
pub fn read(path: &Path) -> std::io::Result<(Vec<String>, u64)> {
    let mut reader = BufReader::new(File::open(path)?);
    let (mut lines, mut whole) = (Vec::new(), 0u64);
    loop {
        let mut line = String::new();
        let n = reader.read_line(&mut line)?;
        if n == 0 || !line.ends_with('\n') {
            return Ok((lines, whole));
        }
        whole += n as u64;
        line.pop();
        lines.push(line);
    }
}

/// Opens the journal at `path` to go on with it: cut to its first `whole` bytes (the complete
/// lines [`read`] found), then open for appending.
///
/// # Errors
/// The file cannot be cut or opened.
pub fn reopen(path: &Path, whole: u64, fsync: bool) -> std::io::Result<Journal> {
    OpenOptions::new().write(true).open(path)?.set_len(whole)?;
    Journal::append_to(path, fsync)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_torn_last_line_is_left_out_and_cut_off() {
        let dir = std::env::temp_dir().join(format!("stopscan-journal-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("j.jsonl");
        let _ = std::fs::remove_file(&path);
        let mut j = Journal::append_to(&path, false).unwrap();
        j.append("{\"a\":1}").unwrap();
        j.append("{\"b\":2}").unwrap();
        drop(j);
        let mut f = OpenOptions::new().append(true).open(&path).unwrap();
        f.write_all(b"{\"c\":").unwrap();
        drop(f);
        let (lines, whole) = read(&path).unwrap();
        assert_eq!(lines, ["{\"a\":1}", "{\"b\":2}"]);
        assert_eq!(whole, 16);
        let mut j = reopen(&path, whole, true).unwrap();
        j.append("{\"c\":3}").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "{\"a\":1}\n{\"b\":2}\n{\"c\":3}\n");
    }
}
