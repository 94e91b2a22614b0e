//! `run --shard K/N` and `merge` (issue 5 §3): the merged evidence is the
//! unsharded run's, byte for byte but for where, when and how long it ran; a
//! campaign that does not add up is refused with exit 2 and nothing written.

use std::path::{Path, PathBuf};

use crate::support::{SEED_SWEEP, arg, files_under, normalise_execution, read, sightline, temp_dir};

/// A world with a shared-data group, replicates and a recording.
const JUNCTION: &str = "tests/fixtures/valid/small-junction.yaml";

/// Runs `files` as shard `k` of `n` into `dir`; panics unless it exits 0.
fn shard(files: &[&str], k: u32, n: u32, dir: &Path) {
    let spec = format!("{k}/{n}");
    let mut args = vec!["run", "--shard", &spec, "--out", arg(dir)];
    args.extend_from_slice(files);
    sightline(args).assert_exit(0);
}

/// Shards 1 to `n` of `files`, each into its own directory under `dir`.
fn shards(files: &[&str], n: u32, dir: &Path) -> Vec<PathBuf> {
    (1..=n)
        .map(|k| {
            let out = dir.join(format!("s{k}"));
            shard(files, k, n, &out);
            out
        })
        .collect()
}

#[test]
fn three_shards_merge_into_the_unsharded_evidence() {
    let tmp = temp_dir();
    let files = [JUNCTION, SEED_SWEEP];
    let whole = tmp.path().join("whole");
    let run = sightline(["run", JUNCTION, SEED_SWEEP, "--out", arg(&whole)]);
    run.assert_exit(0);
    let parts = shards(&files, 3, tmp.path());
    for (k, part) in parts.iter().enumerate() {
        let name = PathBuf::from(format!("shard-{}-of-3.cbor", k + 1));
        assert_eq!(
            files_under(part),
            [
                Path::new("seed-sweep").join(&name),
                Path::new("small-junction").join(&name)
            ],
            "a shard writes only its shard files"
        );
    }
    let merged = tmp.path().join("merged");
    let mut args = vec!["merge".to_string(), "--out".into(), arg(&merged).into()];
    args.extend(parts.iter().map(|p| arg(p).to_string()));
    let merge = sightline(&args);
    merge.assert_exit(0);
    assert_eq!(
        merge.stdout,
        run.stdout.replace(arg(&whole), arg(&merged)),
        "merge prints what run prints"
    );
    assert_eq!(files_under(&merged), files_under(&whole));
    // Where, when and how long the work ran differ; nothing else may.
    let normalised = |dir: &Path, file: &Path| {
        let bytes = std::fs::read(dir.join(file)).unwrap();
        match file.extension().and_then(|e| e.to_str()) {
            Some("json" | "html") => normalise_execution(std::str::from_utf8(&bytes).unwrap()).into_bytes(),
            _ => bytes,
        }
    };
    for file in files_under(&whole) {
        let (a, b) = (normalised(&whole, &file), normalised(&merged, &file));
        assert!(a == b, "{} differs between the run and the merge", file.display());
    }
}

/// A failing requirement fails the merge, rendered with an organisation's templates.
#[test]
fn a_failing_requirement_fails_the_merge_too() {
    let tmp = temp_dir();
    let failing = "tests/fixtures/failing/accuracy-under-noise.yaml";
    let parts = shards(&[failing], 2, tmp.path());
    let out = tmp.path().join("merged");
    let template = "docs/report-templates/example";
    let merge = sightline([
        "merge",
        arg(&parts[0]),
        arg(&parts[1]),
        "--out",
        arg(&out),
        "--template",
        template,
    ]);
    merge.assert_exit(1);
    assert!(merge.stdout.starts_with("FAIL "), "{merge}");
    assert!(
        read(&out.join("report.html")).contains("ACME SAFETY"),
        "the merge renders with --template"
    );
}

/// Runs `merge` on `paths` into a fresh directory; panics unless it exits 2
/// with `message` in stderr and writes nothing.
#[track_caller]
fn assert_refused(paths: &[&Path], message: &str) {
    let tmp = temp_dir();
    let out = tmp.path().join("merged");
    let mut args = vec!["merge", "--out", arg(&out)];
    args.extend(paths.iter().map(|p| arg(p)));
    let merge = sightline(args);
    merge.assert_exit(2);
    assert!(
        merge.stderr.contains(message),
        "expected `{message}` in stderr\n{merge}"
    );
    assert!(!out.exists(), "nothing is written");
}

#[test]
fn a_campaign_that_does_not_add_up_is_refused() {
    let tmp = temp_dir();
    let parts = shards(&[SEED_SWEEP], 3, tmp.path());
    let file = |k: usize| parts[k - 1].join(format!("shard-{k}-of-3.cbor"));

    assert_refused(
        &[&parts[0], &parts[2]],
        "tests/fixtures/valid/seed-sweep.yaml: error: shard 2/3 is missing",
    );

    let copy = tmp.path().join("copy");
    std::fs::create_dir(&copy).unwrap();
    std::fs::copy(file(2), copy.join("shard-2-of-3.cbor")).unwrap();
    assert_refused(
        &[&parts[0], &parts[1], &parts[2], &copy],
        "shard 2/3 of tests/fixtures/valid/seed-sweep.yaml is also in",
    );

    let other = tmp.path().join("other");
    shard(&[SEED_SWEEP], 1, 2, &other);
    assert_refused(&[&parts[0], &parts[1], &parts[2], &other], "from another campaign than");

    let damaged = tmp.path().join("damaged.cbor");
    let bytes = std::fs::read(file(3)).unwrap();
    std::fs::write(&damaged, &bytes[..bytes.len() / 2]).unwrap();
    assert_refused(
        &[&file(1), &file(2), &damaged],
        "damaged.cbor: error: not a sightline shard file, or damaged",
    );

    let empty = tmp.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    assert_refused(&[&empty], "empty: error: no shard files");
}

#[test]
fn a_scenario_changed_since_its_shards_is_refused() {
    let tmp = temp_dir();
    let scenario = tmp.path().join("tiny.yaml");
    std::fs::copy(SEED_SWEEP, &scenario).unwrap();
    let parts = shards(&[arg(&scenario)], 2, tmp.path());
    let text = std::fs::read_to_string(&scenario).unwrap();
    std::fs::write(
        &scenario,
        text.replace("occupied_fraction: 0.2", "occupied_fraction: 0.3"),
    )
    .unwrap();
    assert_refused(
        &[&parts[0], &parts[1]],
        "or a file it imports changed since this shard was simulated",
    );
}

#[test]
fn a_shard_outside_one_to_n_is_a_usage_error() {
    for spec in ["0/3", "4/3", "1/0", "2", "a/b"] {
        let run = sightline(["run", SEED_SWEEP, "--shard", spec]);
        run.assert_exit(2);
        assert!(run.stderr.contains("expected K/N with 1 ≤ K ≤ N"), "{run}");
    }
}
