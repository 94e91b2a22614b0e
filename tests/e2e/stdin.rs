//! `-` reads the scenario from standard input (#15): `check`, `run` (with
//! `--out`) and `falsify` take it, within the size limit of a file; errors name
//! it `<stdin>`; the files it imports are found from the working directory.
//! See: https://example.invalid/sightline/issues/15

use std::fs::File;
use std::path::Path;

use crate::support::{SMALL_FIELD, arg, assert_evidence_files, read_json, root, sightline_fed, temp_dir};

/// The file at `path` (from the package root) as standard input.
fn fed(path: &str) -> File {
    File::open(root().join(path)).expect("the fixture opens")
}

#[test]
fn check_and_run_read_the_scenario_from_stdin() {
    let checked = sightline_fed(root(), ["check", "-"], fed(SMALL_FIELD));
    checked.assert_exit(0);
    assert_eq!(
        checked.stdout, "<stdin>: ok (3 sweep points, 3 requirements)\n",
        "{checked}"
    );

    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    let run = sightline_fed(root(), ["run", "-", "--out", arg(&out)], fed(SMALL_FIELD));
    run.assert_exit(0);
    assert!(
        run.stdout.starts_with("PASS <stdin>: 3 of 3 requirements hold"),
        "{run}"
    );
    assert_evidence_files(&out);
    let results = read_json(&out.join("results.json"));
    assert_eq!(results["scenario"]["path"], "<stdin>");
    // The report's command to reproduce the run is one `run` accepts: a
    // scenario on standard input needs `--out`.
    let report = crate::support::unescape_html(&crate::support::read(&out.join("report.html")));
    let reproduce = format!("sightline run - --seed 42 --out {}<", out.display());
    assert!(report.contains(&reproduce), "{reproduce}");
    // The same bytes as the file: the same hash.
    let by_file = sightline_fed(
        root(),
        ["run", SMALL_FIELD, "--out", arg(&tmp.path().join("file"))],
        fed(SMALL_FIELD),
    );
    by_file.assert_exit(0);
    let from_file = read_json(&tmp.path().join("file").join("results.json"));
    assert_eq!(results["scenario"]["sha256"], from_file["scenario"]["sha256"]);
}

/// A scenario's imports are relative to its file's directory; standard input
/// has none, so they are found from the working directory.
#[test]
fn imports_of_a_scenario_on_stdin_are_found_from_the_working_directory() {
    let scenario = "scenarios/sumo-grid-semantic.yaml";
    let here = sightline_fed(&root().join("scenarios"), ["check", "-"], fed(scenario));
    here.assert_exit(0);
    let elsewhere = sightline_fed(root(), ["check", "-"], fed(scenario));
    elsewhere.assert_exit(2);
    assert!(
        elsewhere
            .stderr
            .starts_with("<stdin>:28:8: error: traces.fcd: failed to read sumo/grid3x3.fcd.xml: "),
        "{elsewhere}"
    );
}

#[test]
fn errors_in_a_scenario_on_stdin_are_located_in_stdin() {
    let tmp = temp_dir();
    let file = tmp.path().join("bad.yaml");
    std::fs::write(&file, "sightline: 1\nname: x\nbogus: 1\n").unwrap();
    let outcome = sightline_fed(root(), ["check", "-"], File::open(&file).unwrap());
    outcome.assert_exit(2);
    assert!(outcome.stderr.starts_with("<stdin>:"), "{outcome}");
    assert!(outcome.stderr.contains(": error: "), "{outcome}");
}

/// What cannot work is refused with exit 2 before anything is written: no
/// `--out` to name the evidence directory after, `-` twice, a directory or
/// more than 16 MiB on standard input, a shard (merge reads its scenario again).
#[test]
fn stdin_is_refused_where_it_cannot_work() {
    let tmp = temp_dir();
    let no_out = sightline_fed(tmp.path(), ["run", "-"], File::open(root().join(SMALL_FIELD)).unwrap());
    no_out.assert_exit(2);
    assert_eq!(
        no_out.stderr,
        "<stdin>: error: a scenario read from standard input has no file name to name its evidence directory \
         after; give --out DIR\n",
        "{no_out}"
    );
    let twice = sightline_fed(root(), ["check", "-", "-"], fed(SMALL_FIELD));
    twice.assert_exit(2);
    assert_eq!(
        twice.stderr, "<stdin>: error: `-` is given more than once; standard input can be read only once\n",
        "{twice}"
    );
    let directory = sightline_fed(root(), ["check", "-"], File::open(root().join("tests")).unwrap());
    directory.assert_exit(2);
    assert_eq!(
        directory.stderr, "<stdin>: error: failed to read standard input: a directory, not a regular file\n",
        "{directory}"
    );
    let big = tmp.path().join("big.yaml");
    std::fs::write(&big, vec![b'#'; (16 << 20) + 1]).unwrap();
    let oversized = sightline_fed(root(), ["check", "-"], File::open(&big).unwrap());
    oversized.assert_exit(2);
    assert_eq!(
        oversized.stderr, "<stdin>: error: failed to read standard input: larger than the limit of 16 MiB\n",
        "{oversized}"
    );
    let out = tmp.path().join("shards");
    let shard = sightline_fed(
        root(),
        ["run", "-", "--shard", "1/2", "--out", arg(&out)],
        fed(SMALL_FIELD),
    );
    shard.assert_exit(2);
    assert_eq!(
        shard.stderr, "<stdin>: error: a shard's scenario must be a file: `sightline merge` reads it again\n",
        "{shard}"
    );
    assert!(!Path::new(&out).exists(), "nothing is written");
    assert_eq!(crate::support::files_under(tmp.path()), [Path::new("big.yaml")]);
}
