//! Output: where evidence goes, and lines on stdout and progress on stderr.
//! (How the evidence is written, as a set: `staging`.)

use std::ffi::OsString;
use std::fmt::Display;
use std::io::{ErrorKind, Write};
use std::path::{Component, Path, PathBuf};
use std::time::Instant;

use crate::input::STDIN;
use crate::terminal::{printable, stderr};

/// The default output directory of a scenario file: `out/STEM/` (STEM: the file
/// name without its extension); `None` when its [`stem`] names no directory.
pub fn default_dir(file: &Path) -> Option<PathBuf> {
    Some(Path::new("out").join(stem(file)?))
}

/// A scenario file's name without its extension (`stdin` for `-`); `None` when
/// that is `.` or `..` (`...yaml`), which name a directory already there (the
/// evidence went into the folder above).
pub fn stem(file: &Path) -> Option<OsString> {
    if file == Path::new(STDIN) {
        return Some("stdin".into());
    }
    let stem = file.file_stem().map_or_else(|| "scenario".into(), |s| s.to_os_string());
    (!matches!(stem.to_str(), Some("" | "." | ".."))).then_some(stem)
}

/// The path of `to` seen from the directory `from_dir` (both absolute, or both
/// relative to the same directory): `../sumo/x.xml`.
pub fn relative(from_dir: &Path, to: &Path) -> PathBuf {
    let from: Vec<_> = from_dir.components().collect();
    let target: Vec<_> = to.components().collect();
    let common = from.iter().zip(&target).take_while(|(a, b)| a == b).count();
    let mut path: PathBuf = from[common..].iter().map(|_| Component::ParentDir).collect();
    path.extend(&target[common..]);
    path
}

/// Prints a line on stdout. A closed stdout (`sightline run … | head`) is not an
/// error: the evidence files and the exit status are what matter, so the run goes
/// on and exits with the status it earns.
pub fn say(line: impl Display) {
    if let Err(error) = writeln!(std::io::stdout().lock(), "{}", printable(&line.to_string()))
        && error.kind() != ErrorKind::BrokenPipe
    {
        stderr!("warning: failed to write to stdout: {error}");
    }
}

/// A progress bar over `len` sweep points of `name` on stderr, shown only on a
/// terminal outside CI (`CI` unset): logs and pipes stay quiet.
pub fn progress(len: usize, name: &str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if std::env::var_os("CI").is_some() || !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len as u64).with_message(printable(name).into_owned());
    if let Ok(style) = indicatif::ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} points, {elapsed}") {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

/// The wall-clock time each sweep point takes, from the engine's reports of
/// the points it has simulated: the time since the previous report is shared
/// among the points just reported (a group that shares its data, with its
/// replicates). What junit.xml's case times are made of.
pub struct PointClock {
    last: Instant,
    seconds: Vec<f64>,
}

impl PointClock {
    /// A clock over `points` sweep points, started now.
    pub fn new(points: usize) -> Self {
        Self {
            last: Instant::now(),
            seconds: vec![0.0; points],
        }
    }

    /// `points` are simulated: the time since the last report is theirs.
    pub fn done(&mut self, points: &[usize]) {
        self.done_at(points, Instant::now());
    }

    /// `points` were simulated by `now`.
    fn done_at(&mut self, points: &[usize], now: Instant) {
        let share = now.duration_since(self.last).as_secs_f64() / points.len().max(1) as f64;
        for &point in points {
            if let Some(seconds) = self.seconds.get_mut(point) {
                *seconds += share;
            }
        }
        self.last = now;
    }

    /// Seconds per point.
    pub fn seconds(self) -> Vec<f64> {
        self.seconds
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_group_shares_its_time_and_every_point_is_timed() {
        let mut clock = PointClock::new(3);
        let start = clock.last;
        let at = |ms: u64| start + std::time::Duration::from_millis(ms);
        clock.done_at(&[0, 2], at(40));
        clock.done_at(&[1], at(50));
        clock.done_at(&[], at(60));
        assert_eq!(clock.seconds(), [0.02, 0.01, 0.02]);
    }

    #[test]
    fn relative_paths_climb_to_the_common_directory() {
        let path = relative(Path::new("/work/out/grid"), Path::new("/work/scenarios/sumo/x.xml"));
        assert_eq!(path, Path::new("../../scenarios/sumo/x.xml"));
        assert_eq!(relative(Path::new("/a"), Path::new("/a/b.xml")), Path::new("b.xml"));
    }
}

/// `path` as one word of a POSIX shell command: as it is when it holds only
/// characters no shell treats specially, else in single quotes (a `'` inside
/// written `'\''`), so that a reproduce command pasted into a shell runs the
/// same file and nothing else.
pub fn shell_word(path: &Path) -> String {
    let text = path.to_string_lossy();
    let plain = |c: char| c.is_ascii_alphanumeric() || "-_./=:,+@%".contains(c);
    if !text.is_empty() && text.chars().all(plain) {
        text.into_owned()
    } else {
        format!("'{}'", text.replace('\'', r"'\''"))
    }
}

#[cfg(test)]
mod shell_tests {
    use super::*;

    #[test]
    fn a_path_a_shell_would_split_or_run_is_quoted() {
        assert_eq!(shell_word(Path::new("scenarios/urban.yaml")), "scenarios/urban.yaml");
        assert_eq!(
            shell_word(Path::new("my run $(id) it's.yaml")),
            r"'my run $(id) it'\''s.yaml'"
        );
        assert_eq!(shell_word(Path::new("")), "''");
    }
}
