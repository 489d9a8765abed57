//! One measurement at a time on a machine: an exclusive lock on
//! [`STAGE_LOCK`], held from before the sources are staged at
//! [`STAGE`](super::STAGE) until the measurement ends.
//!
//! The staged copy lives at one fixed path on purpose (cargo hashes a path
//! dependency's absolute path into the symbols, so counts are only
//! reproducible from one path), so two measurements at once would delete
//! and rebuild each other's copy. The lock is an advisory file lock
//! (`flock` on Linux, [`File::lock`]): the kernel releases it when the
//! holder's file is closed, also when the process is killed, so a crashed
//! measurement never leaves a stale lock behind.

use std::fs::{File, OpenOptions, TryLockError};
use std::path::{Path, PathBuf};

use crate::report::Error;

/// The lock file of [`StageLock`] (beside [`STAGE`](super::STAGE)).
pub const STAGE_LOCK: &str = "/tmp/fixshade-measure-src.lock";

/// An exclusive lock on a lock file, released when dropped.
#[derive(Debug)]
pub struct StageLock {
    /// The open lock file (closing it releases the lock).
    _file: File,
    /// Its path.
    path: PathBuf,
}

impl StageLock {
    /// Takes the lock at `path` (creating the file), waiting while another
    /// measurement holds it; prints [`waiting_message`] on stderr once
    /// when it has to wait.
    ///
    /// # Errors
    /// [`Error::Lock`] when the lock file cannot be created or locked.
    pub fn acquire(path: &Path) -> Result<Self, Error> {
        Self::acquire_with(path, |p| eprintln!("{}", waiting_message(p)))
    }

    /// [`acquire`](Self::acquire), calling `waiting` (instead of printing)
    /// before it waits for another holder.
    ///
    /// # Errors
    /// As [`acquire`](Self::acquire).
    pub fn acquire_with(path: &Path, waiting: impl FnOnce(&Path)) -> Result<Self, Error> {
        let fail = |source| Error::Lock {
            path: path.to_path_buf(),
            source,
        };
        let file = OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(path)
            .map_err(fail)?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                waiting(path);
                file.lock().map_err(fail)?;
            }
            Err(TryLockError::Error(e)) => return Err(fail(e)),
        }
        Ok(Self {
            _file: file,
            path: path.to_path_buf(),
        })
    }

    /// The lock file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

/// What a measurement prints while another one holds the lock at `path`.
pub fn waiting_message(path: &Path) -> String {
    format!("waiting for another measurement (lock {})", path.display())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::mpsc;
    use std::time::Duration;

    fn temp_lock(tag: &str) -> PathBuf {
        std::env::temp_dir().join(format!("fixshade-lock-{tag}-{}.lock", std::process::id()))
    }

    #[test]
    fn a_second_measurement_waits_for_the_first() {
        let path = temp_lock("wait");
        let first = StageLock::acquire_with(&path, |_| panic!("nobody holds it yet")).unwrap();
        assert_eq!(first.path(), path);
        let (waiting_tx, waiting_rx) = mpsc::channel();
        let (got_tx, got_rx) = mpsc::channel();
        let second = {
            let path = path.clone();
            std::thread::spawn(move || {
                let lock = StageLock::acquire_with(&path, |p| {
                    waiting_tx.send(waiting_message(p)).unwrap();
                })
                .unwrap();
                got_tx.send(()).unwrap();
                drop(lock);
            })
        };
        // The second one finds the lock held and says so...
        let said = waiting_rx.recv_timeout(Duration::from_secs(30)).unwrap();
        assert_eq!(
            said,
            format!("waiting for another measurement (lock {})", path.display())
        );
        // ...and does not get it while the first holds it.
        std::thread::sleep(Duration::from_millis(200));
        assert!(got_rx.try_recv().is_err(), "both held the lock");
        drop(first);
        got_rx.recv_timeout(Duration::from_secs(30)).unwrap();
        second.join().unwrap();
        // Released again: taken without waiting.
        let again = StageLock::acquire_with(&path, |_| panic!("released")).unwrap();
        drop(again);
        let _ = std::fs::remove_file(&path);
    }

    #[test]
    fn a_lock_file_that_cannot_be_created_is_bad_input_naming_it() {
        let path = Path::new("/nonexistent-fixshade-dir/measure.lock");
        let e = StageLock::acquire(path).unwrap_err();
        assert!(matches!(e, Error::Lock { .. }), "{e:?}");
        assert!(e.is_input());
        let m = e.to_string();
        assert!(
            m.starts_with("/nonexistent-fixshade-dir/measure.lock: cannot "),
            "{m}"
        );
        assert!(m.contains("No such file or directory"), "{m}");
    }
}
