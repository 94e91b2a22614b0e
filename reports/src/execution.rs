//! How a piece of work ran: the platform, the worker threads, the wall-clock
//! start and duration.
//!
//! These are the only fields of the evidence (`execution` in results.json and
//! falsify.json, and three rows of a report's provenance) that differ between
//! two runs of the same scenario and seed. They are kept together here, apart
//! from what the scenario determines, so that whatever assembles evidence fills
//! them in one place. The recording never holds them.

use std::time::{Duration, SystemTime, UNIX_EPOCH};

use jiff::Timestamp;
use serde::{Deserialize, Serialize};

/// The platform a run ran on, when it started and how long it took.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Execution {
    /// Operating system, as Rust names it (`linux`, `macos`, `windows`, …).
    pub os: String,
    /// CPU architecture, as Rust names it (`x86_64`, `aarch64`, …).
    pub arch: String,
    /// Worker threads the work ran on (`--jobs`, or one per core).
    pub threads: usize,
    /// When the work started: UTC, RFC 3339 to the second (`2026-05-01T09:30:00Z`).
    pub started: String,
    /// Wall-clock duration of the work, seconds, to the millisecond.
    pub duration_seconds: f64,
    /// Per sweep point, the wall-clock seconds spent simulating it (a group of
    /// points that share their data shares its time equally, its replicates
    /// included), when the work measured them; empty otherwise (a merged
    /// campaign). junit.xml's case times come from them. Not written: they
    /// differ from run to run, and the duration says how long the work took.
    #[serde(skip)]
    #[schemars(skip)]
    pub points: Vec<f64>,
}

impl Execution {
    /// Work on this machine's OS and architecture, on `threads` worker threads,
    /// that started at `started` and lasted `duration`.
    pub fn on_this_machine(threads: usize, started: SystemTime, duration: Duration) -> Self {
        Self {
            os: std::env::consts::OS.into(),
            arch: std::env::consts::ARCH.into(),
            threads,
            started: rfc3339(started),
            duration_seconds: (duration.as_secs_f64() * 1000.0).round() / 1000.0,
            points: Vec::new(),
        }
    }

    /// The same work, with the seconds each sweep point took (see
    /// [`points`](Self::points)).
    pub fn with_points(self, points: Vec<f64>) -> Self {
        Self { points, ..self }
    }

    /// A sharded campaign's: the shards' platforms (each distinct OS and
    /// architecture once, in shard order), their threads summed, the earliest
    /// start, and the shards' durations summed with the merge's (`merge`): the
    /// work done, not the wall-clock span.
    ///
    /// # Panics
    ///
    /// If `shards` is empty.
    pub fn campaign<'a>(shards: impl IntoIterator<Item = &'a Execution>, merge: &Execution) -> Self {
        let shards: Vec<&Execution> = shards.into_iter().collect();
        let distinct = |field: fn(&Execution) -> &str| {
            let mut seen: Vec<&str> = Vec::new();
            for value in shards.iter().map(|e| field(e)) {
                if !seen.contains(&value) {
                    seen.push(value);
                }
            }
            seen.join(", ")
        };
        let duration: f64 = shards.iter().map(|e| e.duration_seconds).sum::<f64>() + merge.duration_seconds;
        Self {
            os: distinct(|e| &e.os),
            arch: distinct(|e| &e.arch),
            threads: shards.iter().map(|e| e.threads).sum(),
            started: shards
                .iter()
                .map(|e| e.started.clone())
                .min()
                .expect("a campaign has shards"),
            duration_seconds: (duration * 1000.0).round() / 1000.0,
            points: Vec::new(),
        }
    }

    /// The platform in words: `linux x86_64, 2 worker threads`.
    pub fn platform(&self) -> String {
        let plural = if self.threads == 1 { "" } else { "s" };
        format!("{} {}, {} worker thread{plural}", self.os, self.arch, self.threads)
    }
}

/// `time` in UTC as RFC 3339 to the second (`1970-01-01T00:00:00Z`); the
/// fraction of a second is dropped (toward the past). A time outside jiff's
/// range (years -9999 to 9999) reads as the end of the range it lies beyond.
pub fn rfc3339(time: SystemTime) -> String {
    let timestamp = Timestamp::try_from(time).unwrap_or(if time < UNIX_EPOCH {
        Timestamp::MIN
    } else {
        Timestamp::MAX
    });
    // Precision 0 prints the civil time in UTC without its fraction of a
    // second, which is never negative: dropping it rounds toward the past.
    format!("{timestamp:.0}")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(seconds: i64) -> SystemTime {
        if seconds >= 0 {
            UNIX_EPOCH + Duration::from_secs(seconds as u64)
        } else {
            UNIX_EPOCH - Duration::from_secs(seconds.unsigned_abs())
        }
    }

    /// Instants checked with `date -u -d @SECONDS`.
    #[test]
    fn rfc3339_of_known_instants() {
        assert_eq!(rfc3339(at(0)), "1970-01-01T00:00:00Z");
        assert_eq!(rfc3339(at(951_782_400)), "2000-02-29T00:00:00Z");
        assert_eq!(rfc3339(at(4_107_542_400)), "2100-03-01T00:00:00Z");
        assert_eq!(rfc3339(at(1_700_000_000)), "2023-11-14T22:13:20Z");
        assert_eq!(rfc3339(at(-1)), "1969-12-31T23:59:59Z");
        // A fraction of a second is dropped toward the past, before 1970 too.
        assert_eq!(rfc3339(at(59) + Duration::from_millis(999)), "1970-01-01T00:00:59Z");
        assert_eq!(rfc3339(at(0) - Duration::from_millis(1)), "1969-12-31T23:59:59Z");
    }

    /// A clock beyond year 9999 (or before -9999) reads as the end of jiff's
    /// range rather than failing.
    #[test]
    fn rfc3339_beyond_the_range_reads_as_its_end() {
        let eons = Duration::from_secs(1 << 40);
        assert_eq!(rfc3339(UNIX_EPOCH + eons), "9999-12-30T22:00:00Z");
        assert_eq!(rfc3339(UNIX_EPOCH - eons), "-009999-01-02T01:59:59Z");
    }

    #[test]
    fn durations_keep_milliseconds_and_the_platform_reads_as_words() {
        let execution = Execution::on_this_machine(1, at(0), Duration::from_micros(3_251_600));
        assert_eq!(execution.duration_seconds, 3.252);
        assert_eq!(execution.started, "1970-01-01T00:00:00Z");
        assert_eq!(
            execution.platform(),
            format!("{} {}, 1 worker thread", std::env::consts::OS, std::env::consts::ARCH)
        );
        let two = Execution {
            threads: 2,
            ..execution
        };
        assert!(two.platform().ends_with(", 2 worker threads"));
    }

    #[test]
    fn a_campaign_sums_the_work_of_its_shards_and_starts_with_the_first() {
        let shard = |os: &str, threads, started: &str, duration_seconds| Execution {
            os: os.into(),
            arch: "x86_64".into(),
            threads,
            started: started.into(),
            duration_seconds,
            points: Vec::new(),
        };
        let shards = [
            shard("linux", 8, "2026-11-22T10:05:00Z", 10.5),
            shard("macos", 4, "2026-11-22T09:59:59Z", 20.25),
            shard("linux", 8, "2026-11-22T10:00:00Z", 0.125),
        ];
        let merge = shard("linux", 2, "2026-11-22T11:00:00Z", 1.0);
        let campaign = Execution::campaign(&shards, &merge);
        assert_eq!(campaign, shard("linux, macos", 20, "2026-11-22T09:59:59Z", 31.875));
    }
}
