//! Evidence written as a set (#15): an output folder holds one run's whole set or
//! the previous one, never a mix; a failed or interrupted run leaves nothing
//! behind after the next run; a commit cut short is finished by the next run.
//! See: https://example.invalid/sightline/issues/15

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use crate::support::{
    RECORDING, SMALL_FIELD, arg, assert_evidence_files, assert_recorded_evidence_files, read, root, sightline, temp_dir,
};

/// A scenario that simulates for many seconds: long enough to be interrupted
/// once its staging folder appears.
const SLOW: &str = "scenarios/evidential-field.yaml";

/// Every entry below `dir`, hidden ones too: each file's bytes, `None` for a
/// directory.
fn snapshot(dir: &Path) -> BTreeMap<PathBuf, Option<Vec<u8>>> {
    fn walk(base: &Path, dir: &Path, found: &mut BTreeMap<PathBuf, Option<Vec<u8>>>) {
        for entry in fs::read_dir(dir).expect("the directory is readable") {
            let path = entry.expect("the entry is readable").path();
            let relative = path.strip_prefix(base).expect("below base").to_path_buf();
            if path.is_dir() {
                found.insert(relative, None);
                walk(base, &path, found);
            } else {
                found.insert(relative, Some(fs::read(&path).expect("the file is readable")));
            }
        }
    }
    let mut found = BTreeMap::new();
    walk(dir, dir, &mut found);
    found
}

/// The names in `dir` that sightline's staging and commit folders take.
fn temporaries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .map(|entries| {
            entries
                .map(|e| {
                    e.expect("the entry is readable")
                        .file_name()
                        .to_string_lossy()
                        .into_owned()
                })
                .filter(|name| name.starts_with(".sightline-"))
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    names
}

/// Starts `sightline run SLOW --out out` (with `extra`) and returns it once its
/// staging folder is in `out`, while it simulates.
fn started_and_staged(out: &Path, extra: &[&str]) -> Child {
    let mut child = Command::new(env!("CARGO_BIN_EXE_sightline"))
        .args(["run", SLOW, "--out", arg(out)])
        .args(extra)
        .current_dir(root())
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("sightline starts");
    let deadline = Instant::now() + Duration::from_secs(300);
    while temporaries(out).is_empty() {
        if let Some(status) = child.try_wait().expect("the child can be waited for") {
            panic!(
                "sightline ended ({status}) before its staging folder appeared in {}",
                out.display()
            );
        }
        assert!(
            Instant::now() < deadline,
            "no staging folder appeared in {}",
            out.display()
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    assert!(
        child.try_wait().unwrap().is_none(),
        "{SLOW} ended before it was interrupted"
    );
    child
}

/// Sends `signal` (a name: INT, TERM) to `child`.
fn send(child: &Child, signal: &str) {
    let sent = Command::new("kill")
        .args(["-s", signal, &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(sent.success(), "kill -s {signal}");
}

/// A run whose report.html cannot be put in place (a directory is there) fails
/// before anything is moved: the previous set stays byte for byte, and nothing
/// of the failed run is left. Before #15 its results.json and junit.xml were
/// already in place beside the previous report.
#[test]
fn a_report_that_cannot_be_written_leaves_the_previous_set_untouched() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    sightline(["run", SMALL_FIELD, "--out", arg(&out), "--record"]).assert_exit(0);
    fs::remove_file(out.join("report.html")).unwrap();
    fs::create_dir(out.join("report.html")).unwrap();
    let before = snapshot(&out);
    let failed = sightline(["run", SMALL_FIELD, "--out", arg(&out), "--seed", "7"]);
    failed.assert_exit(3);
    assert_eq!(
        failed.stderr,
        format!(
            "error: failed to write {}: a directory is in its place (nothing was changed)\n",
            out.join("report.html").display()
        ),
        "{failed}"
    );
    assert!(snapshot(&out) == before, "the previous set changed");
}

/// A custom template that fails on the data is found after the recording was
/// staged: exit 2, the previous set unchanged, the recording gone with its
/// staging folder.
#[test]
fn a_template_failing_at_render_time_leaves_the_previous_set_untouched() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    sightline(["run", SMALL_FIELD, "--out", arg(&out)]).assert_exit(0);
    let before = snapshot(&out);
    let set = tmp.path().join("org");
    fs::create_dir(&set).unwrap();
    fs::write(
        set.join("report.html"),
        "{% extends \"sightline/report.html\" %}\n{% block footer %}\n{{ report.nmae }}{% endblock %}\n",
    )
    .unwrap();
    let refused = sightline([
        "run",
        SMALL_FIELD,
        "--out",
        arg(&out),
        "--record",
        "--template",
        arg(&set),
    ]);
    refused.assert_exit(2);
    assert!(refused.stderr.contains("undefined value"), "{refused}");
    assert!(snapshot(&out) == before, "the previous set changed");
}

/// The names of the entries in `dir`, sorted.
fn names(dir: &Path) -> Vec<PathBuf> {
    snapshot(dir).into_keys().collect()
}

/// A new set replaces the previous one whole: a run that records nothing
/// removes the previous run's recording, a search removes a run's evidence
/// (its report.html would sit beside the run's results.json) and a run the
/// search's, and shard files (a set of one file each) replace nothing but
/// themselves.
#[test]
fn a_new_set_replaces_the_previous_one_whole() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    sightline(["run", SMALL_FIELD, "--out", arg(&out), "--record"]).assert_exit(0);
    assert_recorded_evidence_files(&out);
    sightline(["run", SMALL_FIELD, "--out", arg(&out)]).assert_exit(0);
    assert_evidence_files(&out);
    assert!(!out.join(RECORDING).exists());
    sightline(search_into(&out)).assert_exit(1);
    assert_eq!(
        names(&out),
        ["counterexample.yaml", "falsify.json", "junit.xml", "report.html"].map(PathBuf::from)
    );
    sightline(["run", SMALL_FIELD, "--out", arg(&out)]).assert_exit(0);
    assert_evidence_files(&out);
    sightline(["run", SMALL_FIELD, "--out", arg(&out), "--shard", "1/2"]).assert_exit(0);
    sightline(["run", SMALL_FIELD, "--out", arg(&out), "--shard", "2/2"]).assert_exit(0);
    let expected = [
        "junit.xml",
        "report.html",
        "results.json",
        "shard-1-of-2.cbor",
        "shard-2-of-2.cbor",
    ];
    assert_eq!(names(&out), expected.map(PathBuf::from));
}

/// A short search of the bundled falsify scenario writing into `out` (it
/// finds a counterexample: exit 1).
fn search_into(out: &Path) -> [&str; 6] {
    [
        "falsify",
        "scenarios/urban-falsify.yaml",
        "--cases",
        "4",
        "--out",
        arg(out),
    ]
}

/// A set never replaces a file the command reads: the counterexample of a
/// search, run with `--out` its own folder as its header's command invites,
/// would be removed by the run's commit (a search with `--budget` may not find
/// it again). Refused with exit 2 before anything runs, the folder untouched;
/// `--shard`, which writes only its shard file, and another `--out` run.
// See: session 17's outside check.
#[test]
fn a_set_that_would_replace_the_scenario_it_runs_is_refused() {
    let tmp = temp_dir();
    let out = tmp.path().join("search");
    sightline(search_into(&out)).assert_exit(1);
    let before = snapshot(&out);
    let counterexample = out.join("counterexample.yaml");
    for command in ["run", "merge"] {
        let refused = match command {
            "run" => sightline(["run", arg(&counterexample), "--out", arg(&out)]),
            _ => {
                let shards = tmp.path().join("shards");
                sightline(["run", arg(&counterexample), "--out", arg(&shards), "--shard", "1/1"]).assert_exit(0);
                sightline(["merge", arg(&shards), "--out", arg(&out)])
            }
        };
        refused.assert_exit(2);
        assert_eq!(
            refused.stderr,
            format!(
                "{}: error: the evidence written into {} would replace this file, which the command reads; give \
                 another --out\n",
                counterexample.display(),
                out.display()
            ),
            "{command}"
        );
        assert_eq!(snapshot(&out), before, "{command} leaves the folder as it was");
    }
    sightline(["run", arg(&counterexample), "--out", arg(&out), "--shard", "1/2"]).assert_exit(0);
    let elsewhere = tmp.path().join("elsewhere");
    sightline(["run", arg(&counterexample), "--out", arg(&elsewhere)]).assert_exit(1);
    assert!(counterexample.exists());
}

/// SIGKILL cannot be handled: a run killed while it simulates leaves its
/// staging folder, and nothing else; the next run into the folder removes it
/// with a note, and writes its set.
#[cfg(unix)]
#[test]
fn a_run_killed_while_it_simulates_leaves_a_staging_folder_the_next_run_removes() {
    use std::os::unix::process::ExitStatusExt;
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    sightline(["run", SMALL_FIELD, "--out", arg(&out)]).assert_exit(0);
    let before = snapshot(&out);
    let mut child = started_and_staged(&out, &["--record"]);
    child.kill().expect("sightline is killed");
    let status = child.wait().unwrap();
    assert_eq!(status.signal(), Some(9), "{status}");
    let left = temporaries(&out);
    assert_eq!(left.len(), 1, "{left:?}");
    assert!(left[0].starts_with(".sightline-staging-"), "{left:?}");
    let mut after = snapshot(&out);
    after.retain(|path, _| !path.starts_with(&left[0]));
    assert!(after == before, "the previous set changed");
    let next = sightline(["run", SMALL_FIELD, "--out", arg(&out)]);
    next.assert_exit(0);
    assert_eq!(
        next.stderr,
        format!(
            "note: {}: removed {}, left by an interrupted run\n",
            out.display(),
            left[0]
        ),
        "{next}"
    );
    assert_evidence_files(&out);
    assert!(temporaries(&out).is_empty());
}

/// SIGINT and SIGTERM while a run simulates (and records): exit 130 and 143,
/// the staging folder removed, and with it the directories the run created;
/// a previous set stays as it was.
#[cfg(unix)]
#[test]
fn sigint_and_sigterm_exit_130_and_143_and_leave_nothing() {
    let tmp = temp_dir();
    let fresh = tmp.path().join("new").join("evidence");
    let child = started_and_staged(&fresh, &["--record"]);
    send(&child, "INT");
    let ended = child.wait_with_output().unwrap();
    assert_eq!(
        ended.status.code(),
        Some(130),
        "{}",
        String::from_utf8_lossy(&ended.stderr)
    );
    assert!(
        !tmp.path().join("new").exists(),
        "the directories the run created are removed"
    );

    let out = tmp.path().join("evidence");
    sightline(["run", SMALL_FIELD, "--out", arg(&out)]).assert_exit(0);
    let before = snapshot(&out);
    let child = started_and_staged(&out, &[]);
    send(&child, "TERM");
    let ended = child.wait_with_output().unwrap();
    assert_eq!(
        ended.status.code(),
        Some(143),
        "{}",
        String::from_utf8_lossy(&ended.stderr)
    );
    assert!(snapshot(&out) == before, "the previous set changed");
}

/// A commit folder left by a run killed during its commit is finished by the
/// next run into the folder, as its manifest says; a folder whose owner still
/// holds its manifest's lock is that run's work in progress and is left alone.
#[test]
fn a_commit_cut_short_is_finished_by_the_next_run() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    sightline(["run", SMALL_FIELD, "--out", arg(&out), "--record"]).assert_exit(0);
    // Killed after results.json was moved: junit.xml and report.html are
    // still in the commit folder, run.mcap is still to be removed.
    let commit = out.join(".sightline-commit-1-planted");
    fs::create_dir(&commit).unwrap();
    fs::write(out.join("results.json"), "committed results").unwrap();
    fs::write(commit.join("junit.xml"), "committed junit").unwrap();
    fs::write(commit.join("report.html"), "committed report").unwrap();
    let manifest =
        "sightline-commit/1\nput results.json\nput junit.xml\nput report.html\nremove run.mcap\nremove falsify.json\n";
    fs::write(commit.join("manifest"), manifest).unwrap();
    // A live run's staging folder: its manifest locked by this test.
    let live = out.join(".sightline-staging-1-live");
    fs::create_dir(&live).unwrap();
    let lock = fs::File::create(live.join("manifest")).unwrap();
    lock.lock().unwrap();

    // A shard is a set of one file that replaces nothing: what the finished
    // commit put in place stays to be seen.
    let shard = sightline(["run", SMALL_FIELD, "--out", arg(&out), "--shard", "1/1"]);
    shard.assert_exit(0);
    assert_eq!(
        shard.stderr,
        format!(
            "note: {}: finished the evidence set an interrupted run had committed (.sightline-commit-1-planted)\n",
            out.display()
        ),
        "{shard}"
    );
    assert_eq!(read(&out.join("junit.xml")), "committed junit");
    assert_eq!(read(&out.join("report.html")), "committed report");
    assert_eq!(read(&out.join("results.json")), "committed results");
    assert!(!out.join(RECORDING).exists());
    assert_eq!(temporaries(&out), [".sightline-staging-1-live"]);

    drop(lock);
    let next = sightline(["run", SMALL_FIELD, "--out", arg(&out)]);
    next.assert_exit(0);
    assert_eq!(
        next.stderr,
        format!(
            "note: {}: removed .sightline-staging-1-live, left by an interrupted run\n",
            out.display()
        ),
        "{next}"
    );
    assert!(temporaries(&out).is_empty());
}

/// A commit folder whose manifest sightline did not write is not guessed at:
/// a located warning, the folder left, and the run's own set written whole.
#[test]
fn a_damaged_manifest_is_left_with_a_warning() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    let commit = out.join(".sightline-commit-1-damaged");
    fs::create_dir_all(&commit).unwrap();
    fs::write(commit.join("manifest"), "sightline-commit/1\nput ../outside.txt\n").unwrap();
    let outcome = sightline(["run", SMALL_FIELD, "--out", arg(&out)]);
    outcome.assert_exit(0);
    let warning = format!(
        "{}:2:1: warning: not a manifest sightline wrote (`../outside.txt` is not the name of a file in the \
         output folder); the interrupted commit is left as it is\n",
        commit.join("manifest").display()
    );
    assert_eq!(outcome.stderr, warning, "{outcome}");
    assert_eq!(temporaries(&out), [".sightline-commit-1-damaged"]);
    assert!(out.join("results.json").exists());
}
