//! Helpers shared by the end-to-end tests: running the real binary, comparing
//! output with expected files (or rewriting them under `SIGHTLINE_BLESS=1`),
//! reading evidence and redacting what changes from build to build.

use std::collections::BTreeMap;
use std::ffi::OsStr;
use std::fmt;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Output, Stdio};
use std::sync::OnceLock;

use sha2::{Digest, Sha256};

/// Set to `1` to rewrite expected files from the actual output instead of
/// comparing with them.
pub const BLESS_VAR: &str = "SIGHTLINE_BLESS";

/// The names of the evidence files `run` writes into its directory.
pub const EVIDENCE_FILES: [&str; 3] = ["results.json", "junit.xml", "report.html"];

/// The recording `run` writes beside them when it records.
pub const RECORDING: &str = "run.mcap";

/// The main valid fixture (small, every requirement passes).
pub const SMALL_FIELD: &str = "tests/fixtures/valid/small-field.yaml";

/// A valid fixture that sweeps `seed`.
pub const SEED_SWEEP: &str = "tests/fixtures/valid/seed-sweep.yaml";

/// A valid fixture whose two sweeps meet at one configuration.
pub const SHARED_POINT: &str = "tests/fixtures/valid/shared-point.yaml";

/// A valid fixture with a requirement that fails at one of its two sweep points.
pub const FAILING: &str = "tests/fixtures/failing/accuracy-under-noise.yaml";

/// The package root. Every command runs there, so scenario paths in evidence
/// and messages are the stable relative paths the tests pass.
pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Whether expected files are being rewritten.
pub fn blessing() -> bool {
    std::env::var_os(BLESS_VAR).is_some_and(|v| v == "1")
}

/// How one invocation of `sightline` ended.
pub struct Outcome {
    /// The command line, for failure messages.
    pub command: String,
    /// The exit code (`None` when killed by a signal).
    pub code: Option<i32>,
    /// The signal that ended the process, if one did.
    pub signal: Option<i32>,
    /// Standard output.
    pub stdout: String,
    /// Standard error.
    pub stderr: String,
}

impl Outcome {
    /// Panics, showing both streams, unless the exit code is `code`.
    #[track_caller]
    pub fn assert_exit(&self, code: i32) -> &Self {
        assert_eq!(self.code, Some(code), "unexpected exit status\n{self}");
        self
    }
}

impl fmt::Display for Outcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "$ {}", self.command)?;
        match self.signal {
            Some(signal) => writeln!(f, "signal: {signal}")?,
            None => writeln!(f, "exit: {:?}", self.code)?,
        }
        writeln!(f, "--- stdout\n{}", self.stdout)?;
        write!(f, "--- stderr\n{}", self.stderr)
    }
}

/// Runs the real `sightline` binary with `args` in the package root.
pub fn sightline<I, S>(args: I) -> Outcome
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    sightline_in(root(), args)
}

/// Runs the real `sightline` binary with `args` in `dir`.
pub fn sightline_in<I, S>(dir: &Path, args: I) -> Outcome
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    sightline_fed(dir, args, Stdio::null())
}

/// Runs the real `sightline` binary with `args` in `dir`, `stdin` its standard input.
pub fn sightline_fed<I, S>(dir: &Path, args: I, stdin: impl Into<Stdio>) -> Outcome
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    let args: Vec<S> = args.into_iter().collect();
    let command = std::iter::once("sightline".to_string())
        .chain(args.iter().map(|a| a.as_ref().to_string_lossy().into_owned()))
        .collect::<Vec<_>>()
        .join(" ");
    let output = Command::new(env!("CARGO_BIN_EXE_sightline"))
        .args(&args)
        .current_dir(dir)
        .stdin(stdin)
        .output()
        .unwrap_or_else(|e| panic!("failed to start {command}: {e}"));
    let text = |bytes: Vec<u8>, stream: &str| {
        String::from_utf8(bytes).unwrap_or_else(|e| panic!("{command}: {stream} is not UTF-8: {e}"))
    };
    Outcome {
        code: output.status.code(),
        signal: signal(output.status),
        stdout: text(output.stdout, "stdout"),
        stderr: text(output.stderr, "stderr"),
        command,
    }
}

/// The signal that ended a process, if one did.
fn signal(status: ExitStatus) -> Option<i32> {
    #[cfg(unix)]
    return std::os::unix::process::ExitStatusExt::signal(&status);
    #[cfg(not(unix))]
    return None;
}

/// The memory cap of a run on hostile input (issue 15): 2 GiB of address space.
pub const MEMORY_CAP_BYTES: u64 = 2 << 30;

/// The real tool named by the environment variable `var` that a test checks
/// output with (`ci/tools.sh` installs each and sets its variable): `None`,
/// after saying on stderr what to set it to (`what`), when it is not set; a
/// panic instead when `CI` is set, since CI must run every such check.
pub fn tool(var: &str, what: &str) -> Option<PathBuf> {
    match std::env::var_os(var) {
        Some(path) => Some(PathBuf::from(path)),
        None => {
            assert!(
                std::env::var_os("CI").is_none(),
                "CI is set but {var} is not: `source ci/tools.sh` installs {what} and sets it"
            );
            eprintln!("skipped: {var} is not set; set it to {what}, as `source ci/tools.sh` does");
            None
        }
    }
}

/// The time cap of a run on hostile input, in seconds of wall-clock time; then
/// the run is killed (SIGKILL).
pub const TIME_CAP_SECONDS: u32 = 20;

/// The tools that impose the caps: `prlimit` (util-linux) and `timeout` (coreutils).
const CAP_TOOLS: [&str; 2] = ["prlimit", "timeout"];

/// Whether the tools that impose the caps are on PATH. When one is not, says
/// once on the terminal that the capped tests are skipped, and panics instead
/// when `CI` is set: CI must run them (`.ci/run` installs the tools).
pub fn caps_available() -> bool {
    static MISSING: OnceLock<Vec<&str>> = OnceLock::new();
    let missing = MISSING.get_or_init(|| {
        let missing: Vec<&str> = CAP_TOOLS
            .into_iter()
            .filter(|tool| Command::new(tool).arg("--version").output().is_err())
            .collect();
        if !missing.is_empty() && std::env::var_os("CI").is_none() {
            // Straight to the terminal, past the test harness's capture, so
            // that a passing run still says what it did not test.
            let _ = writeln!(
                std::io::stderr(),
                "skipped: the tests of hostile input need {} on PATH (util-linux, coreutils)",
                missing.join(" and ")
            );
        }
        missing
    });
    assert!(
        missing.is_empty() || std::env::var_os("CI").is_none(),
        "CI is set but {} is not on PATH: the tests of hostile input cannot run",
        missing.join(" and ")
    );
    missing.is_empty()
}

/// Runs the real `sightline` binary with `args` in `dir` under the caps:
/// `prlimit --as=2147483648 -- timeout --signal=KILL 20 sightline ARGS`. Its
/// streams are read lossily, so that a run on damaged input is judged rather
/// than the harness stopped. Call [`caps_available`] first. `timeout` ends
/// itself with the signal that ended sightline (SIGKILL at the time cap), so
/// the outcome's `signal` is sightline's.
pub fn sightline_capped<I, S>(dir: &Path, args: I) -> Outcome
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    let args: Vec<S> = args.into_iter().collect();
    let limit = format!("--as={MEMORY_CAP_BYTES}");
    let seconds = TIME_CAP_SECONDS.to_string();
    let prefix = [limit.as_str(), "--", "timeout", "--signal=KILL", seconds.as_str()];
    let command = ["prlimit"]
        .into_iter()
        .chain(prefix)
        .map(str::to_string)
        .chain(std::iter::once("sightline".to_string()))
        .chain(args.iter().map(|a| a.as_ref().to_string_lossy().into_owned()))
        .collect::<Vec<_>>()
        .join(" ");
    let output: Output = Command::new("prlimit")
        .args(prefix)
        .arg(env!("CARGO_BIN_EXE_sightline"))
        .args(&args)
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("failed to start {command}: {e}"));
    Outcome {
        code: output.status.code(),
        signal: signal(output.status),
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
        command,
    }
}

impl Outcome {
    /// What a run under the caps did that no input may make it do: end by a
    /// signal (an abort, a crash, or SIGKILL at the time cap), exit with
    /// another code than 0, 1 or 2, panic, or refuse without saying where
    /// (exit 2 without a `file:line:col: error:` or `file: error:` line).
    /// `None` when it kept to that contract.
    pub fn broken_contract(&self) -> Option<String> {
        let broken = match (self.code, self.signal) {
            (Some(0 | 1), _) => String::new(),
            (Some(2), _) if self.stderr.lines().any(is_located_error) => String::new(),
            (Some(2), _) => "exit 2 without a `file:line:col: error:` or `file: error:` line".to_string(),
            (Some(3), _) => "exit 3: an internal error".to_string(),
            (_, Some(9)) => format!("SIGKILL: over the time cap of {TIME_CAP_SECONDS} s"),
            (_, Some(6)) => "SIGABRT: an abort (an allocation refused under the memory cap?)".to_string(),
            (_, Some(signal)) => format!("ended by signal {signal}"),
            (code, None) => format!("exit {code:?}"),
        };
        let broken = match (broken.is_empty(), self.stderr.contains("panicked at")) {
            (true, false) => return None,
            (true, true) => "a panic on stderr".to_string(),
            (false, true) => format!("{broken}, and a panic on stderr"),
            (false, false) => broken,
        };
        Some(broken)
    }
}

/// Whether `line` is a located error: `file:line:col: error: …` (1-based
/// numbers) or `file: error: …`, for any file (the scenario or one it imports).
pub fn is_located_error(line: &str) -> bool {
    let Some((place, _)) = line.split_once(": error: ") else {
        return false;
    };
    let mut parts = place.rsplitn(3, ':');
    let (col, row, file) = (parts.next(), parts.next(), parts.next());
    let number = |n: Option<&str>| n.and_then(|n| n.parse::<u64>().ok()).is_some_and(|n| n >= 1);
    match file {
        Some(file) if number(row) && number(col) => !file.is_empty(),
        _ => !place.is_empty() && !place.starts_with("error"),
    }
}

/// Why the evidence folder `out` breaks the contract after an exit `code`:
/// a whole set (with or without the recording) after 0 or 1, nothing
/// otherwise, and never a temporary file beside them.
pub fn evidence_problem(out: &Path, code: Option<i32>) -> Option<String> {
    let found = files_under(out);
    let mut whole: Vec<PathBuf> = EVIDENCE_FILES.iter().map(PathBuf::from).collect();
    let mut recorded = whole.clone();
    recorded.push(RECORDING.into());
    whole.sort();
    recorded.sort();
    let fine = match code {
        Some(0 | 1) => found == whole || found == recorded,
        _ => found.is_empty(),
    };
    (!fine).then(|| format!("the evidence folder holds {found:?} after exit {code:?}"))
}

/// The hidden temporary entries (`.sightline-*`) a run left in `dir`.
pub fn leftovers(dir: &Path) -> Vec<String> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut found: Vec<String> = entries
        .map(|entry| entry.expect("failed to read a directory entry").file_name())
        .map(|name| name.to_string_lossy().into_owned())
        .filter(|name| name.starts_with(".sightline-"))
        .collect();
    found.sort();
    found
}

/// A path as a command-line argument (temporary paths are UTF-8 here).
#[track_caller]
pub fn arg(path: &Path) -> &str {
    path.to_str().expect("the path is UTF-8")
}

/// A fresh temporary directory, removed when dropped.
pub fn temp_dir() -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix("sightline-e2e-")
        .tempdir()
        .expect("failed to create a temporary directory")
}

/// Every file below `dir` (recursively), relative to it and sorted; empty when
/// `dir` does not exist.
pub fn files_under(dir: &Path) -> Vec<PathBuf> {
    fn walk(base: &Path, dir: &Path, found: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for entry in entries {
            let path = entry.expect("failed to read a directory entry").path();
            if path.is_dir() {
                walk(base, &path, found);
            } else {
                found.push(path.strip_prefix(base).expect("below base").to_path_buf());
            }
        }
    }
    let mut found = Vec::new();
    walk(dir, dir, &mut found);
    found.sort();
    found
}

/// Panics unless `dir` holds exactly the three evidence files.
#[track_caller]
pub fn assert_evidence_files(dir: &Path) {
    assert_files(dir, &EVIDENCE_FILES);
}

/// Panics unless `dir` holds exactly the three evidence files and the recording.
#[track_caller]
pub fn assert_recorded_evidence_files(dir: &Path) {
    assert_files(
        dir,
        &[EVIDENCE_FILES[0], EVIDENCE_FILES[1], EVIDENCE_FILES[2], RECORDING],
    );
}

#[track_caller]
fn assert_files(dir: &Path, names: &[&str]) {
    let mut expected: Vec<PathBuf> = names.iter().map(PathBuf::from).collect();
    expected.sort();
    assert_eq!(files_under(dir), expected, "evidence files in {}", dir.display());
}

/// The bundled roundabout cut to its first few seconds (`time.duration`
/// becomes `duration`, at most 4 s): the agents that would start later (cav5
/// at 4 s, ped2 at 6 s, car2 at 8 s) start within the first two seconds, since
/// one that never enters is refused.
pub fn short_roundabout(duration: &str) -> String {
    read(&root().join("scenarios/roundabout-six-agents.yaml"))
        .replace("duration: 30, step: 0.1", &format!("duration: {duration}, step: 0.1"))
        .replace("offset: 20, time: 4 }", "offset: 20, time: 1 }")
        .replace("offset: 40, time: 8 }", "offset: 40, time: 2 }")
        .replace("start: { time: 6 }", "start: { time: 1 }")
}

/// Reads a file as UTF-8 text.
#[track_caller]
pub fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("failed to read {}: {e}", path.display()))
}

/// Reads and parses a JSON file.
#[track_caller]
pub fn read_json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&read(path)).unwrap_or_else(|e| panic!("{} is not JSON: {e}", path.display()))
}

/// The requirement `id` of a results.json.
#[track_caller]
pub fn requirement<'a>(results: &'a serde_json::Value, id: &str) -> &'a serde_json::Value {
    results["requirements"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["id"] == id)
        .unwrap_or_else(|| panic!("no requirement {id}"))
}

/// Requirement `id`'s verdict in `results`: its status, measured value and n.
pub fn verdict(results: &serde_json::Value, id: &str) -> (String, Option<f64>, Option<u64>) {
    let r = requirement(results, id);
    (
        r["verdict"].as_str().unwrap().to_string(),
        r["value"].as_f64(),
        r["n"].as_u64(),
    )
}

/// The ids of the requirements that fail in `results`, in file order.
pub fn failing(results: &serde_json::Value) -> Vec<&str> {
    results["requirements"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["verdict"] == "fail")
        .map(|r| r["id"].as_str().unwrap())
        .collect()
}

/// The `name: value` lines of a JUnit case's `<system-out>`, as a map.
pub fn case_output(case: &quick_junit::TestCase) -> BTreeMap<String, String> {
    let out = case.system_out.as_ref().map_or("", |o| o.as_str());
    out.lines()
        .filter_map(|line| line.split_once(": "))
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect()
}

/// Reads and parses a JUnit XML file.
#[track_caller]
pub fn read_junit(path: &Path) -> quick_junit::Report {
    quick_junit::Report::deserialize_from_str(&read(path))
        .unwrap_or_else(|e| panic!("{} is not JUnit XML: {e}", path.display()))
}

/// The value of the swept setting `path` at a point of results.json's `sweep`,
/// from the first of its labels that sets it.
pub fn setting<'a>(point: &'a serde_json::Value, path: &str) -> Option<&'a serde_json::Value> {
    point["labels"]
        .as_array()?
        .iter()
        .find_map(|label| label["settings"].get(path))
}

/// Whether a point of results.json's `sweep` belongs to sweep `sweep`.
pub fn in_sweep(point: &serde_json::Value, sweep: u64) -> bool {
    point["labels"]
        .as_array()
        .is_some_and(|labels| labels.iter().any(|label| label["sweep"] == sweep))
}

/// The text of HTML: the entities minijinja's auto-escaping writes, decoded.
pub fn unescape_html(html: &str) -> String {
    html.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&#x27;", "'")
        .replace("&#x2f;", "/")
        .replace("&amp;", "&")
}

/// SHA-256 of `bytes` as lowercase hex, computed here rather than by sightline.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes).iter().map(|b| format!("{b:02x}")).collect()
}

/// Compares `actual` with the file at `expected` (relative to the package root),
/// or writes it there when blessing.
#[track_caller]
pub fn assert_matches_file(expected: &str, actual: &str) {
    let path = root().join(expected);
    if blessing() {
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).unwrap_or_else(|e| panic!("failed to create {}: {e}", parent.display()));
        }
        std::fs::write(&path, actual).unwrap_or_else(|e| panic!("failed to write {}: {e}", path.display()));
        return;
    }
    let wanted = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("failed to read {expected} ({e}); create it with {BLESS_VAR}=1"));
    if wanted != actual {
        panic!(
            "{expected} differs from the actual output; if the change is intended, refresh it with {BLESS_VAR}=1\n{}",
            first_difference(&wanted, actual)
        );
    }
}

/// The first line where two texts differ, for a readable failure.
fn first_difference(expected: &str, actual: &str) -> String {
    let mut expected_lines = expected.split_inclusive('\n');
    let mut actual_lines = actual.split_inclusive('\n');
    for line in 1.. {
        match (expected_lines.next(), actual_lines.next()) {
            (Some(e), Some(a)) if e == a => continue,
            (None, None) => break,
            (e, a) => return format!("first difference at line {line}:\n  expected: {e:?}\n  actual:   {a:?}"),
        }
    }
    "the texts differ".into()
}

/// Replaces exactly one occurrence of `from` in `text` by `to`; panics when
/// `from` occurs zero or several times, so a redaction never silently misses.
#[track_caller]
fn replace_once(text: &str, from: &str, to: &str) -> String {
    let count = text.matches(from).count();
    assert_eq!(count, 1, "expected exactly one `{from}` to redact, found {count}");
    text.replacen(from, to, 1)
}

/// The keys of `execution` in results.json and falsify.json, and the report's
/// provenance rows that show them: the only fields that differ between two
/// runs of the same scenario and seed.
const EXECUTION_KEYS: [&str; 5] = ["os", "arch", "threads", "started", "duration_seconds"];
const EXECUTION_ROWS: [&str; 4] = ["Date", "Platform", "Started", "Duration"];

/// Evidence (results.json, falsify.json or a report.html) with the fields that
/// differ from run to run (the platform, the worker threads, the start time and
/// the duration) replaced by placeholders, after checking their form. Every
/// other byte is kept, so two normalised files of equivalent runs are equal.
#[track_caller]
pub fn normalise_execution(text: &str) -> String {
    if text.starts_with('{') {
        normalise_execution_json(text)
    } else {
        normalise_execution_html(text)
    }
}

#[track_caller]
fn normalise_execution_json(text: &str) -> String {
    let json: serde_json::Value = serde_json::from_str(text).expect("the evidence is JSON");
    let execution = json["execution"].as_object().expect("`execution` is an object");
    let mut keys: Vec<&str> = execution.keys().map(String::as_str).collect();
    let mut expected = EXECUTION_KEYS;
    keys.sort();
    expected.sort();
    assert_eq!(keys, expected, "the keys of `execution`");
    assert_eq!(execution["os"], std::env::consts::OS);
    assert_eq!(execution["arch"], std::env::consts::ARCH);
    assert!(execution["threads"].as_u64().is_some_and(|n| n >= 1), "threads");
    assert_started(execution["started"].as_str().expect("started is a string"));
    assert!(
        execution["duration_seconds"].as_f64().is_some_and(|s| s >= 0.0),
        "duration_seconds"
    );
    let mut text = text.to_string();
    for key in EXECUTION_KEYS {
        let value = serde_json::to_string(&execution[key]).expect("a JSON value");
        text = replace_once(
            &text,
            &format!("\"{key}\": {value}"),
            &format!("\"{key}\": \"[{}]\"", key.to_uppercase()),
        );
    }
    text
}

#[track_caller]
fn normalise_execution_html(text: &str) -> String {
    let mut text = text.to_string();
    for row in EXECUTION_ROWS {
        let start = format!("<th scope=\"row\">{row}</th><td class=\"mono\">");
        let count = text.matches(&start).count();
        // Only a run's report has document control, and so a date.
        if row == "Date" && count == 0 {
            continue;
        }
        assert_eq!(count, 1, "expected exactly one `{row}` provenance row, found {count}");
        let begin = text.find(&start).expect("counted above") + start.len();
        let end = begin + text[begin..].find("</td>").expect("the cell is closed");
        let value = &text[begin..end];
        match row {
            "Platform" => assert!(
                value.starts_with(&format!("{} {}, ", std::env::consts::OS, std::env::consts::ARCH))
                    && value.contains(" worker thread"),
                "platform {value:?}"
            ),
            "Started" => assert_started(value),
            "Date" => assert_started(&format!("{value}T00:00:00Z")),
            _ => assert!(
                value
                    .strip_suffix(" s")
                    .and_then(|s| s.parse::<f64>().ok())
                    .is_some_and(|s| s >= 0.0),
                "duration {value:?}"
            ),
        }
        text = format!("{}[{}]{}", &text[..begin], row.to_uppercase(), &text[end..]);
    }
    text
}

/// Panics unless `started` is an RFC 3339 UTC time to the second.
#[track_caller]
fn assert_started(started: &str) {
    let shape: String = started
        .chars()
        .map(|c| if c.is_ascii_digit() { '9' } else { c })
        .collect();
    assert_eq!(shape, "9999-99-99T99:99:99Z", "started {started:?}");
}

/// results.json with the tool version and git revision redacted (they change
/// with every build) and its execution normalised ([`normalise_execution`]);
/// everything else must not change. Checks that the version is this package's
/// and the revision is not empty.
#[track_caller]
pub fn redact_results_json(text: &str) -> String {
    let text = &normalise_execution(text);
    let json: serde_json::Value = serde_json::from_str(text).expect("results.json is JSON");
    let tool = &json["tool"];
    assert_eq!(tool["name"], "sightline");
    let version = tool["version"].as_str().expect("tool.version is a string");
    let git = tool["git"].as_str().expect("tool.git is a string");
    assert_eq!(version, env!("CARGO_PKG_VERSION"), "tool.version");
    assert_build_id(git);
    let text = replace_once(
        text,
        &format!("\"version\": \"{version}\""),
        "\"version\": \"[VERSION]\"",
    );
    replace_once(&text, &format!("\"git\": \"{git}\""), "\"git\": \"[GIT]\"")
}

/// Checks that `git` names this checkout as build.rs does: `git describe`'s
/// revision, and for a modified tree 12 hex digits of the modifications' hash.
#[track_caller]
fn assert_build_id(git: &str) {
    let describe = std::process::Command::new("git")
        .args(["describe", "--always", "--dirty", "--abbrev=12"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string());
    match describe {
        Some(describe) if describe.ends_with("-dirty") => {
            let hash = git.strip_prefix(&format!("{describe}-")).unwrap_or_default();
            assert!(
                hash.len() == 12 && hash.bytes().all(|b| b.is_ascii_hexdigit()),
                "tool.git {git:?} does not name the modifications of {describe}"
            );
        }
        Some(describe) => assert_eq!(git, describe, "tool.git"),
        None => assert_eq!(git, "unknown", "tool.git outside a checkout"),
    }
}

/// report.html with the tool row (name, version and git revision) redacted and
/// its execution normalised ([`normalise_execution`]).
#[track_caller]
pub fn redact_report(text: &str) -> String {
    let text = normalise_execution(text);
    let start = format!(
        "<th scope=\"row\">Tool</th><td class=\"mono\">sightline {} (git ",
        env!("CARGO_PKG_VERSION")
    );
    let count = text.matches(&start).count();
    assert_eq!(count, 1, "expected exactly one `{start}…` row to redact, found {count}");
    let begin = text.find(&start).expect("counted above") + start.len();
    let end = begin + text[begin..].find(")</td>").expect("the cell is closed");
    assert!(end > begin, "the tool row names no git revision");
    let text = format!("{}[GIT]{}", &text[..begin], &text[end..]);
    // The document id hashes results.json, which names the git revision.
    let start = "<th scope=\"row\">Document id</th><td class=\"mono\">SL-";
    let begin = text.find(start).expect("the report has a document id") + start.len();
    let end = begin + text[begin..].find("</td>").expect("the cell is closed");
    assert!(
        end - begin == 16 && text[begin..end].chars().all(|c| c.is_ascii_hexdigit()),
        "document id {:?}",
        &text[begin..end]
    );
    format!("{}[ID]{}", &text[..begin], &text[end..])
}

/// junit.xml with the times that differ from run to run (every `time`
/// attribute, in seconds, and the suite's `timestamp`, RFC 3339 in UTC)
/// replaced by placeholders, after checking their form.
#[track_caller]
pub fn normalise_junit_times(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    let next = |rest: &str| {
        [rest.find(" time=\""), rest.find(" timestamp=\"")]
            .into_iter()
            .flatten()
            .min()
    };
    while let Some(at) = next(rest) {
        let (key, placeholder) = if rest[at..].starts_with(" time=") {
            (" time=\"", "[TIME]")
        } else {
            (" timestamp=\"", "[STARTED]")
        };
        let begin = at + key.len();
        let end = begin + rest[begin..].find('"').expect("the attribute value is closed");
        let value = &rest[begin..end];
        if placeholder == "[TIME]" {
            assert!(value.parse::<f64>().is_ok_and(|t| t >= 0.0), "time {value:?}");
        } else {
            assert_started(value);
        }
        out.push_str(&rest[..begin]);
        out.push_str(placeholder);
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// junit.xml with the `tool` property (name, version and git revision)
/// redacted and its times normalised ([`normalise_junit_times`]).
#[track_caller]
pub fn redact_junit(text: &str) -> String {
    let text = &normalise_junit_times(text);
    let value = format!("sightline {} (", env!("CARGO_PKG_VERSION"));
    let start = format!("<property name=\"tool\" value=\"{value}");
    let count = text.matches(&start).count();
    assert_eq!(
        count, 1,
        "expected exactly one `{start}…` property to redact, found {count}"
    );
    let begin = text.find(&start).expect("counted above") + start.len() - value.len();
    let end = begin + text[begin..].find('"').expect("the attribute value is closed");
    let revision = &text[begin + value.len()..end];
    assert!(
        revision.ends_with(')') && revision.len() > 1,
        "tool property {:?} does not end in a git revision",
        &text[begin..end]
    );
    format!("{}[TOOL]{}", &text[..begin], &text[end..])
}
