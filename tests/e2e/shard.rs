//! `run --shard K/N` and `merge` (issue 5 §3): the merged evidence is the
//! unsharded run's, byte for byte but for where, when and how long it ran; a
//! campaign that does not add up, a damaged shard or a file given twice is
//! refused with exit 2 (issue 13), a measured value outside its domain or a
//! recorded run that differs from its shard's with exit 3, and nothing is
//! written.

use std::path::{Path, PathBuf};

use sightline_engine::Outcome;
use sightline_reports::{Shard, read_shard, shard_bytes};

use crate::support::{
    FAILING, SEED_SWEEP, arg, caps_available, files_under, normalise_execution, normalise_junit_times, read, root,
    sightline, sightline_capped, temp_dir,
};

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
            Some("xml") => normalise_junit_times(std::str::from_utf8(&bytes).unwrap()).into_bytes(),
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

/// Runs `merge` on `paths`; panics unless it exits `code` with stderr
/// starting with `message`, and writes nothing: into a fresh `--out` (not
/// created), nor into one that holds earlier evidence (left as it was).
#[track_caller]
fn assert_refused_with(code: i32, paths: &[&Path], message: &str) {
    let tmp = temp_dir();
    let fresh = tmp.path().join("fresh");
    let earlier = tmp.path().join("earlier");
    std::fs::create_dir(&earlier).unwrap();
    std::fs::write(earlier.join("results.json"), "earlier evidence").unwrap();
    for out in [&fresh, &earlier] {
        let mut args = vec!["merge", "--out", arg(out)];
        args.extend(paths.iter().map(|p| arg(p)));
        let merge = sightline(args);
        merge.assert_exit(code);
        assert!(
            merge.stderr.starts_with(message),
            "expected stderr to start with `{message}`\n{merge}"
        );
        assert_eq!(merge.stdout, "", "{merge}");
    }
    assert!(!fresh.exists(), "a fresh --out is not created");
    assert_eq!(
        files_under(&earlier),
        [PathBuf::from("results.json")],
        "nothing is added"
    );
    assert_eq!(
        read(&earlier.join("results.json")),
        "earlier evidence",
        "nothing is changed"
    );
}

/// [`assert_refused_with`] exit 2: invalid input.
#[track_caller]
fn assert_refused(paths: &[&Path], message: &str) {
    assert_refused_with(2, paths, message);
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

    // Shard 2 again, copied under another name: its units would count twice.
    let copy = tmp.path().join("copy.cbor");
    std::fs::copy(file(2), &copy).unwrap();
    assert_refused(
        &[&parts[0], &parts[1], &parts[2], &copy],
        &format!(
            "{}: error: shard 2/3 of tests/fixtures/valid/seed-sweep.yaml is also in {}",
            file(2).display(),
            copy.display()
        ),
    );

    // N differs.
    let other = tmp.path().join("other");
    shard(&[SEED_SWEEP], 1, 2, &other);
    let other = other.join("shard-1-of-2.cbor");
    assert_refused(
        &[&other, &file(1), &file(2), &file(3)],
        &format!(
            "{}: error: from another campaign than {}",
            file(1).display(),
            other.display()
        ),
    );

    let empty = tmp.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    assert_refused(&[&empty], &format!("{}: error: no shard files", empty.display()));
}

/// A shard of the same files and N simulated with another `--seed` belongs to
/// another campaign: its campaign id differs.
#[test]
fn a_shard_of_another_seed_is_of_another_campaign() {
    let tmp = temp_dir();
    let parts = shards(&[FAILING], 2, tmp.path());
    let reseeded = tmp.path().join("reseeded");
    sightline(["run", FAILING, "--seed", "4", "--shard", "2/2", "--out", arg(&reseeded)]).assert_exit(0);
    // Merge reads the files in path order: `reseeded` before `s1`.
    let theirs = reseeded.join("shard-2-of-2.cbor");
    let ours = parts[0].join("shard-1-of-2.cbor");
    assert_refused(
        &[&ours, &theirs],
        &format!(
            "{}: error: from another campaign than {} (campaign ",
            ours.display(),
            theirs.display()
        ),
    );
}

/// The same file given twice is refused, whether spelled alike or not (before
/// issue 13 the repeat was silently dropped).
#[test]
fn a_shard_file_given_twice_is_refused() {
    let tmp = temp_dir();
    let parts = shards(&[SEED_SWEEP], 3, tmp.path());
    let file = |k: usize| parts[k - 1].join(format!("shard-{k}-of-3.cbor"));
    assert_refused(
        &[&file(1), &file(2), &file(3), &file(1)],
        &format!(
            "{}: error: given twice (each shard file counts once)",
            file(1).display()
        ),
    );
    // A directory and a file found in it.
    assert_refused(
        &[&parts[0], &file(2), &file(3), &file(1)],
        &format!(
            "{}: error: given twice (each shard file counts once)",
            file(1).display()
        ),
    );
    let respelled = parts[0].join(".").join("shard-1-of-3.cbor");
    assert_refused(
        &[&file(1), &file(2), &file(3), &respelled],
        &format!(
            "{}: error: the same file as {}, given twice (each shard file counts once)",
            respelled.display(),
            file(1).display()
        ),
    );
}

/// Links to directories above are followed once each: a directory holding the
/// shards and links back to itself and to its parent merges (the search went
/// round for ever, its memory growing), and one holding only links to itself
/// has no shard files.
#[cfg(unix)]
#[test]
fn links_to_a_directory_above_are_searched_once() {
    if !caps_available() {
        return;
    }
    let tmp = temp_dir();
    let campaign = tmp.path().join("campaign");
    shards(&[SEED_SWEEP], 2, &campaign);
    let link = |from: PathBuf, to: &str| std::os::unix::fs::symlink(to, from).expect("a link");
    for name in ["a", "b", "c"] {
        link(campaign.join(name), ".");
    }
    link(campaign.join("s1").join("up"), "..");
    // Run where the shards ran: the scenarios' paths are relative to it.
    let merged = tmp.path().join("merged");
    let merge = sightline_capped(root(), ["merge", arg(&campaign), "--out", arg(&merged)]);
    merge.assert_exit(0);
    let lone = tmp.path().join("lone");
    std::fs::create_dir(&lone).unwrap();
    for name in ["a", "b", "c"] {
        link(lone.join(name), ".");
    }
    let none = tmp.path().join("none");
    let merge = sightline_capped(root(), ["merge", arg(&lone), "--out", arg(&none)]);
    merge.assert_exit(2);
    let message = format!("{}: error: no shard files", lone.display());
    assert!(merge.stderr.starts_with(&message), "{merge}");
}

/// A flipped bit anywhere in a shard file (the header, the payload) and a
/// truncated file are refused by the seal before anything is decoded.
#[test]
fn a_damaged_shard_is_refused() {
    let tmp = temp_dir();
    let parts = shards(&[SEED_SWEEP], 3, tmp.path());
    let file = |k: usize| parts[k - 1].join(format!("shard-{k}-of-3.cbor"));
    let bytes = std::fs::read(file(3)).unwrap();
    let damaged = tmp.path().join("damaged.cbor");
    for at in [0, 20, 100, bytes.len() / 2, bytes.len() - 1] {
        let mut flipped = bytes.clone();
        flipped[at] ^= 0x04;
        std::fs::write(&damaged, &flipped).unwrap();
        let expected = if at < "sightline-shard/3\n".len() {
            format!("{}: error: not a sightline shard file", damaged.display())
        } else {
            format!(
                "{}: error: damaged or truncated: the SHA-256 of its payload is ",
                damaged.display()
            )
        };
        assert_refused(&[&file(1), &file(2), &damaged], &expected);
    }
    std::fs::write(&damaged, &bytes[..bytes.len() / 2]).unwrap();
    assert_refused(
        &[&file(1), &file(2), &damaged],
        &format!("{}: error: damaged or truncated", damaged.display()),
    );
}

/// Edits the shard file at `path` and seals it again, as only a forger (or a
/// defective sightline) would.
fn reseal(path: &Path, edit: impl FnOnce(&mut Shard)) {
    let mut shard = read_shard(&std::fs::read(path).unwrap()).unwrap();
    edit(&mut shard);
    std::fs::write(path, shard_bytes(&shard)).unwrap();
}

/// Shards that agree on a campaign id that their build, files, N, `--seed`
/// and `--record` do not make are refused.
#[test]
fn a_campaign_id_that_the_campaign_does_not_make_is_refused() {
    let tmp = temp_dir();
    let parts = shards(&[FAILING], 2, tmp.path());
    let files: Vec<PathBuf> = (1..=2)
        .map(|k| parts[k - 1].join(format!("shard-{k}-of-2.cbor")))
        .collect();
    for file in &files {
        reseal(file, |shard| shard.campaign = "0".repeat(64));
    }
    assert_refused(
        &[&parts[0], &parts[1]],
        &format!(
            "{}: error: its campaign id is 000000000000, and this build, the files, N, --seed and --record make ",
            files[0].display()
        ),
    );
}

/// A shard simulated by another build of sightline (here: one that says so)
/// may have simulated differently.
#[test]
fn a_shard_of_another_build_is_refused() {
    let tmp = temp_dir();
    let parts = shards(&[FAILING], 2, tmp.path());
    let other = parts[1].join("shard-2-of-2.cbor");
    reseal(&other, |shard| shard.tool.git = "v0.0.0-other".into());
    assert_refused(
        &[&parts[0], &parts[1]],
        &format!(
            "{}: error: simulated by sightline {v} (v0.0.0-other); this is {v} (",
            other.display(),
            v = env!("CARGO_PKG_VERSION")
        ),
    );
}

/// A shard that says accuracy = 1.11, sealed again so that it reads: without
/// the domain check the merge judged it (a FAIL turned PASS: the fixture's
/// γ = 30 point has 0.988 < 0.995); now it is an internal error, exit 3.
#[test]
fn a_value_outside_its_domain_is_an_internal_error_not_a_verdict() {
    let tmp = temp_dir();
    let parts = shards(&[FAILING], 2, tmp.path());
    let forged = parts[1].join("shard-2-of-2.cbor");
    reseal(&forged, |shard| {
        let (unit, outcomes) = &mut shard.units[0];
        assert_eq!(unit.group, [1], "shard 2 holds point 1 (γ = 30)");
        let Outcome::Field(field) = &mut outcomes[0] else {
            panic!("a field outcome")
        };
        field.metrics.correct = field.metrics.cells * 111 / 100;
    });
    assert_refused_with(
        3,
        &[&parts[0], &parts[1]],
        &format!(
            "{}: error: {FAILING}, point 1: accuracy = 1.11, outside its domain ([0, 1]): no simulation gives such a value",
            forged.display()
        ),
    );
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
        &format!(
            "{}: error: {} or a file it imports changed since this shard was simulated",
            parts[0].join("shard-1-of-2.cbor").display(),
            scenario.display()
        ),
    );
}

/// A shard writes no report, so a template given to it would be ignored:
/// `merge --template` renders it.
#[test]
fn a_shard_refuses_a_template() {
    let dir = temp_dir();
    let run = sightline([
        "run",
        SEED_SWEEP,
        "--shard",
        "1/2",
        "--template",
        "docs/report-templates",
        "--out",
        arg(dir.path()),
    ]);
    run.assert_exit(2);
    assert!(
        run.stderr
            .contains("the argument '--shard <K/N>' cannot be used with '--template <DIR>'"),
        "{run}"
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

/// `check --shards N` judges a run's work as `run --shard K/N` does: a
/// campaign too large for one process, refused by `check` as by one shard,
/// is valid split over two; zero shards is a usage error.
#[test]
fn check_judges_the_work_of_a_run_split_into_shards() {
    let file = "tests/fixtures/invalid/run-work-beyond-limit.yaml";
    let whole = sightline(["check", file]);
    whole.assert_exit(2);
    assert!(whole.stderr.contains("exceed the limit of 100"), "{whole}");
    for one in [
        sightline(["check", "--shards", "1", file]),
        sightline(["run", "--shard", "1/1", file]),
    ] {
        one.assert_exit(2);
        assert_eq!(one.stderr, whole.stderr);
    }
    let split = sightline(["check", "--shards", "2", file]);
    split.assert_exit(0);
    assert_eq!(
        split.stdout,
        format!("{file}: ok (1 sweep point, 1 requirement, run as 2 shards)\n")
    );
    let none = sightline(["check", "--shards", "0", file]);
    none.assert_exit(2);
    assert!(none.stderr.contains("--shards"), "{none}");
}

/// Shards are dealt units in turn, so an uneven sweep (heavy and light points
/// alternating) gives one shard all the heavy ones: each shard is held to the
/// limit, not the run's work divided by N.
#[test]
fn each_shard_of_an_uneven_sweep_is_held_to_the_limit() {
    let dir = temp_dir();
    let seeds: Vec<String> = (1..=150).map(|s| s.to_string()).collect();
    // The sweep gives the seed: the file's would be refused.
    let text = read(Path::new("scenarios/urban-falsify.yaml"))
        .replace("\nseed: 11\n", "\n")
        .replace("time: { duration: 10, step: 0.1 }", "time: { duration: 300, step: 0.1 }")
        .replace(
            "vary:\n  v2x.channel.sensitivity_dbm: [-100, -60]\n  traffic.pedestrians.per_minute: { one_of: [2, 0, 6] }\n",
            &format!("sweep:\n  seed: [{}]\n  semantic.runs: [64, 1]\n", seeds.join(", ")),
        );
    assert!(text.contains("semantic.runs: [64, 1]"));
    let file = dir.path().join("uneven.yaml");
    std::fs::write(&file, text).unwrap();
    // The run's work over two is within the limit; the shard with every
    // 64-run point is not.
    let two = sightline(["check", "--shards", "2", arg(&file)]);
    two.assert_exit(2);
    assert!(
        two.stderr
            .contains("error: one of 2 shards would do 131 points' worth of work"),
        "{two}"
    );
    sightline(["run", "--shard", "1/2", arg(&file), "--out", arg(&dir.path().join("o"))]).assert_exit(2);
    assert!(!dir.path().join("o").exists());
    sightline(["check", "--shards", "3", arg(&file)]).assert_exit(0);
    // More shards than units: one unit each, judged without a load per shard.
    sightline(["check", "--shards", "4000000000", arg(&file)]).assert_exit(0);
}

/// The urban junction cut to 70 s (the ego is served from about 50 s on),
/// pooling two runs at two densities; its recording, of a point chosen once
/// the run is judged, is made by the merge.
fn pooled_junction(dir: &Path) -> PathBuf {
    let text = read(Path::new("scenarios/urban-rsu-semantic.yaml"));
    let head = &text[..text.find("\nsweeps:").expect("the junction has sweeps")];
    let text = head
        .replace("duration: 120", "duration: 70")
        .replace("runs: 5 ", "runs: 2 ")
        // The sweep gives the density: the file's would be refused.
        .replace("    density_per_km: 10 ", "    # density_per_km ")
        + "\nsweep: { traffic.vehicles.density_per_km: [5, 15] }\nrequirements:\n  \
           - { id: PDR, text: Delivered., check: { metric: packet_delivery_ratio, at_least: 0.5 } }\n";
    let file = dir.join("pooled.yaml");
    std::fs::write(&file, text).unwrap();
    file
}

/// The merge records a pooled point by simulating its first run again, and
/// checks it against the first run its shard kept: one count off there (the
/// pooled measurements untouched) is an internal error, exit 3, nothing written.
#[test]
fn a_recorded_first_run_that_differs_from_its_shards_is_refused() {
    let tmp = temp_dir();
    let file = pooled_junction(tmp.path());
    let part = tmp.path().join("s1");
    sightline(["run", "--shard", "1/1", "--record", "--out", arg(&part), arg(&file)]).assert_exit(0);
    let merged = tmp.path().join("merged");
    sightline(["merge", "--out", arg(&merged), arg(&part)]).assert_exit(0);
    assert!(merged.join("run.mcap").is_file(), "the merge records");
    reseal(&part.join("shard-1-of-1.cbor"), |shard| {
        for (_, outcomes) in &mut shard.units {
            for outcome in outcomes {
                let Outcome::Semantic(metrics) = outcome else {
                    panic!("a semantic outcome")
                };
                metrics
                    .first_run
                    .as_mut()
                    .expect("a pooled point keeps its first run")
                    .bytes += 1;
            }
        }
    });
    let merge = sightline(["merge", "--out", arg(&tmp.path().join("forged")), arg(&part)]);
    merge.assert_exit(3);
    assert!(
        merge
            .stderr
            .contains("the recorded points, simulated again, differ from the run's outcomes"),
        "{merge}"
    );
    assert!(!tmp.path().join("forged").exists(), "nothing is written");
}
