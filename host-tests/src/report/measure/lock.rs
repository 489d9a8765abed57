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
//!
//! Every user of the machine shares the one lock file: it is created
//! readable and writable by all (mode 0666 whatever the umask), and an
//! existing one is opened read-only (`flock` needs no write access), so a
//! second user waits for the first instead of failing on the file's
//! permissions.
//!
//! A script that builds from the staged copy after the measurement (as
//! `.ci/firmware` does) holds the lock itself around both: it opens the
//! lock file on a descriptor, takes the lock with `flock`, and names the
//! descriptor in [`LOCK_FD_ENV`]. A measurement started under it finds its
//! inherited descriptor holding the exclusive lock on the same file (the
//! kernel says so in `/proc/self/fdinfo`) and runs inside that lock
//! instead of waiting for it; a wrong or stale variable changes nothing
//! (the lock is then taken as usual).

use std::fs::{File, OpenOptions, TryLockError};
use std::io;
use std::os::unix::fs::{MetadataExt, OpenOptionsExt, PermissionsExt};
use std::path::{Path, PathBuf};

use crate::report::Error;

/// The lock file of [`StageLock`] (beside [`STAGE`](super::STAGE)).
pub const STAGE_LOCK: &str = "/tmp/fixshade-measure-src.lock";

/// The environment variable naming an inherited file descriptor through
/// which a parent process holds the lock (see the [module docs](self)).
pub const LOCK_FD_ENV: &str = "FIXSHADE_MEASURE_LOCK_FD";

/// An exclusive lock on a lock file, released when dropped (or the lock
/// of a parent process, see [`LOCK_FD_ENV`], which it leaves alone).
#[derive(Debug)]
pub struct StageLock {
    /// The open lock file (closing it releases the lock).
    _file: File,
    /// Its path.
    path: PathBuf,
    /// Whether the lock is a parent's, held through an inherited
    /// descriptor, rather than taken here.
    inherited: bool,
}

impl StageLock {
    /// Takes the lock at `path` (creating the file), waiting while another
    /// measurement holds it; prints [`waiting_message`] on stderr once
    /// when it has to wait.
    ///
    /// # Errors
    /// [`Error::Lock`] when the lock file cannot be created, opened or
    /// locked.
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
        let file = open_shared(path).map_err(fail)?;
        let inherited = match file.try_lock() {
            Ok(()) => false,
            Err(TryLockError::WouldBlock) if held_by_parent(path) => true,
            Err(TryLockError::WouldBlock) => {
                waiting(path);
                file.lock().map_err(fail)?;
                false
            }
            Err(TryLockError::Error(e)) => return Err(fail(e)),
        };
        Ok(Self {
            _file: file,
            path: path.to_path_buf(),
            inherited,
        })
    }

    /// The lock file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Whether this measurement runs inside a parent's lock (see
    /// [`LOCK_FD_ENV`]) rather than its own.
    pub fn is_inherited(&self) -> bool {
        self.inherited
    }
}

/// Opens the lock file for every user: an existing one read-only (a lock
/// needs no write access, and another user's file may not be writable),
/// else created with mode 0666 (set again after creation: the umask
/// would take the others' write bits away).
fn open_shared(path: &Path) -> io::Result<File> {
    match File::open(path) {
        Ok(f) => return Ok(f),
        Err(e) if e.kind() != io::ErrorKind::NotFound => return Err(e),
        Err(_) => {}
    }
    let file = OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .mode(0o666)
        .open(path)?;
    // Only the owner may change the mode: another user who created the
    // file between our two calls has set it already.
    if file.metadata()?.permissions().mode() & 0o777 != 0o666 {
        let _ = file.set_permissions(std::fs::Permissions::from_mode(0o666));
    }
    Ok(file)
}

/// Whether the descriptor named by [`LOCK_FD_ENV`] (inherited from a
/// parent) is open on the lock file at `path` and holds its exclusive
/// lock.
fn held_by_parent(path: &Path) -> bool {
    let Some(fd) = std::env::var(LOCK_FD_ENV)
        .ok()
        .and_then(|v| v.trim().parse::<u32>().ok())
    else {
        return false;
    };
    let (Ok(lock), Ok(open)) = (
        std::fs::metadata(path),
        std::fs::metadata(format!("/proc/self/fd/{fd}")),
    ) else {
        return false;
    };
    if (lock.dev(), lock.ino()) != (open.dev(), open.ino()) {
        return false;
    }
    std::fs::read_to_string(format!("/proc/self/fdinfo/{fd}"))
        .is_ok_and(|info| holds_exclusive_flock(&info, lock.ino()))
}

/// Whether `/proc/self/fdinfo/N` text says that descriptor holds an
/// exclusive `flock` on the inode `ino` (a `lock:` line `FLOCK ADVISORY
/// WRITE PID MAJ:MIN:INODE ...`; waiters' lines, marked `->`, hold
/// nothing).
fn holds_exclusive_flock(fdinfo: &str, ino: u64) -> bool {
    fdinfo.lines().any(|l| {
        let Some(rest) = l.strip_prefix("lock:") else {
            return false;
        };
        let w: Vec<&str> = rest.split_whitespace().collect();
        !w.contains(&"->")
            && w.get(1) == Some(&"FLOCK")
            && w.get(3) == Some(&"WRITE")
            && w.get(5)
                .and_then(|id| id.rsplit(':').next())
                .and_then(|i| i.parse::<u64>().ok())
                == Some(ino)
    })
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

    /// The environment variable through which the tests below hand a
    /// lock file to the probes they run in a child process.
    const PROBE_ENV: &str = "FIXSHADE_LOCK_PROBE";

    /// Runs one `#[ignore]`d probe of this test binary in a child process
    /// (through `sh -c SCRIPT`, which ends with `exec "$0" ARGS`), with the
    /// lock file in [`PROBE_ENV`] and `env`; true when it passed.
    fn probe(name: &str, path: &Path, wrap: &[&str], script: &str, env: &[(&str, &str)]) -> bool {
        let exe = std::env::current_exe().unwrap();
        let test = format!("report::measure::lock::tests::{name}");
        let mut cmd = std::process::Command::new(wrap.first().copied().unwrap_or("sh"));
        cmd.args(wrap.iter().skip(1))
            .args(if wrap.is_empty() {
                &[][..]
            } else {
                &["sh"][..]
            })
            .args(["-c", script])
            .arg(exe)
            .args(["--exact", &test, "--ignored", "--quiet"])
            .env(PROBE_ENV, path);
        for (k, v) in env {
            cmd.env(k, v);
        }
        let out = cmd.output().unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        out.status.success() && text.contains("1 passed")
    }

    /// Probe: takes the lock of [`PROBE_ENV`] without waiting.
    #[test]
    #[ignore = "run by the tests above in a child process"]
    fn probe_takes_the_lock() {
        if let Some(path) = std::env::var_os(PROBE_ENV) {
            let lock = StageLock::acquire_with(Path::new(&path), |_| panic!("waited")).unwrap();
            assert!(!lock.is_inherited());
        }
    }

    /// Probe: finds the lock of [`PROBE_ENV`] held by its parent through
    /// the inherited descriptor of [`LOCK_FD_ENV`], and runs inside it.
    #[test]
    #[ignore = "run by the tests above in a child process"]
    fn probe_runs_inside_the_parents_lock() {
        if let Some(path) = std::env::var_os(PROBE_ENV) {
            let lock = StageLock::acquire_with(Path::new(&path), |_| panic!("waited")).unwrap();
            assert!(lock.is_inherited());
        }
    }

    #[test]
    fn the_lock_file_is_created_for_every_user() {
        let path = temp_lock("mode");
        let _ = std::fs::remove_file(&path);
        drop(StageLock::acquire_with(&path, |_| panic!("nobody holds it")).unwrap());
        let mode = std::fs::metadata(&path).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o666, "{mode:o}");
        let _ = std::fs::remove_file(&path);
    }

    /// Another user's lock file (0644, not writable for us) is taken
    /// read-only: measured as the unprivileged user `nobody` when the
    /// tests run as root (as CI does), else skipped.
    #[test]
    fn another_users_lock_file_is_taken_not_refused() {
        let path = temp_lock("user");
        std::fs::write(&path, b"").unwrap();
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o644)).unwrap();
        let root = std::fs::metadata("/proc/self")
            .map(|m| m.uid() == 0)
            .unwrap_or(false);
        let setpriv = std::process::Command::new("setpriv")
            .arg("--version")
            .output()
            .is_ok();
        if root && setpriv {
            let nobody = [
                "setpriv",
                "--reuid=65534",
                "--regid=65534",
                "--clear-groups",
            ];
            assert!(
                probe(
                    "probe_takes_the_lock",
                    &path,
                    &nobody,
                    r#"exec "$0" "$@""#,
                    &[]
                ),
                "user nobody could not take root's 0644 lock file"
            );
        } else {
            println!("skipped: needs root and setpriv to act as a second user");
        }
        // Read-only for its owner too: taken all the same.
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o444)).unwrap();
        drop(StageLock::acquire_with(&path, |_| panic!("nobody holds it")).unwrap());
        let _ = std::fs::remove_file(&path);
    }

    /// A script holding the lock on descriptor 9 (`flock 9`) and naming it
    /// in LOCK_FD_ENV: the measurement it starts runs inside that lock.
    /// Named wrongly (a descriptor that is not open), the child would
    /// wait: checked on the fdinfo reader below instead.
    #[test]
    fn a_measurement_inside_a_scripts_lock_does_not_wait_for_it() {
        if std::process::Command::new("flock")
            .arg("--version")
            .output()
            .is_err()
        {
            println!("skipped: no flock(1)");
            return;
        }
        let path = temp_lock("inherit");
        let script = format!(
            r#"exec 9>>"{}" && flock 9 && exec "$0" "$@""#,
            path.display()
        );
        assert!(probe(
            "probe_runs_inside_the_parents_lock",
            &path,
            &[],
            &script,
            &[(LOCK_FD_ENV, "9")],
        ));
        // Released with the child (its descriptor was the last one).
        drop(StageLock::acquire_with(&path, |_| panic!("released")).unwrap());
        let _ = std::fs::remove_file(&path);
    }

    #[test]
    fn fdinfo_lock_lines_are_read() {
        let held = "pos:\t0\nflags:\t0102001\nmnt_id:\t27\nino:\t385539\n\
                    lock:\t1: FLOCK  ADVISORY  WRITE 4602 fe:00:385539 0 EOF\n";
        assert!(holds_exclusive_flock(held, 385_539));
        assert!(!holds_exclusive_flock(held, 385_538), "another file");
        assert!(!holds_exclusive_flock(
            &held.replace("WRITE", "READ"),
            385_539
        ));
        assert!(!holds_exclusive_flock(
            &held.replace("1: FLOCK", "1: -> FLOCK"),
            385_539
        ));
        assert!(!holds_exclusive_flock(
            "pos:\t0\nflags:\t0102001\nino:\t385539\n",
            385_539
        ));
        // No variable, or one naming a descriptor that is not the lock's:
        // not held.
        let path = temp_lock("fdinfo");
        std::fs::write(&path, b"").unwrap();
        if std::env::var_os(LOCK_FD_ENV).is_none() {
            assert!(!held_by_parent(&path));
        }
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
