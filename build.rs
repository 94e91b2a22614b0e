//! Records the git revision of the build, for provenance in evidence files.
//!
//! A build from a modified tree is `<describe>-dirty-<12 hex>`: the hex is git's
//! hash of the changes to what is compiled in (the diff of [`BUILT`] against HEAD
//! and the untracked files there), so two builds of different modifications
//! never share an id (`merge` refuses shards of another build by it).

use std::io::Write;
use std::process::{Command, Stdio};

/// What the binary is built from: a change here is a change of build.
const BUILT: &[&str] = &[
    "Cargo.toml",
    "Cargo.lock",
    "build.rs",
    "src",
    "dsl/Cargo.toml",
    "dsl/src",
    "engine/Cargo.toml",
    "engine/src",
    "oracles/Cargo.toml",
    "oracles/src",
    "reports/Cargo.toml",
    "reports/src",
    "reports/templates",
    "osi/Cargo.toml",
    "osi/build.rs",
    "osi/src",
    "osi/proto",
];

fn main() {
    let revision = match git(&["describe", "--always", "--dirty", "--abbrev=12"], None) {
        Some(describe) if describe.ends_with("-dirty") => match changes() {
            Some(hash) => format!("{describe}-{}", &hash[..12]),
            None => describe,
        },
        Some(describe) => describe,
        None => "unknown".into(),
    };
    println!("cargo:rustc-env=SIGHTLINE_GIT={revision}");
    for path in [".git/HEAD", ".git/index", ".git/refs/heads"].iter().chain(BUILT) {
        println!("cargo:rerun-if-changed={path}");
    }
}

/// Git's hash of the tracked changes and untracked files under [`BUILT`].
fn changes() -> Option<String> {
    let mut bytes = git_bytes(&[&["diff", "HEAD", "--binary", "--"], BUILT].concat())?;
    let untracked = git_bytes(&[&["ls-files", "-z", "--others", "--exclude-standard", "--"], BUILT].concat())?;
    for path in untracked.split(|&b| b == 0).filter(|p| !p.is_empty()) {
        bytes.extend_from_slice(path);
        bytes.push(0);
        bytes.extend(std::fs::read(String::from_utf8_lossy(path).as_ref()).ok()?);
    }
    git(&["hash-object", "--stdin"], Some(&bytes)).filter(|h| h.len() >= 12)
}

/// `git args`, its trimmed output when it succeeds.
fn git(args: &[&str], stdin: Option<&[u8]>) -> Option<String> {
    let mut child = Command::new("git")
        .args(args)
        .stdin(if stdin.is_some() { Stdio::piped() } else { Stdio::null() })
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .ok()?;
    if let Some(bytes) = stdin {
        child.stdin.take()?.write_all(bytes).ok()?;
    }
    let output = child.wait_with_output().ok()?;
    let text = String::from_utf8(output.stdout).ok()?;
    (output.status.success() && !text.trim().is_empty()).then(|| text.trim().to_string())
}

/// `git args`, its raw output when it succeeds.
fn git_bytes(args: &[&str]) -> Option<Vec<u8>> {
    let output = Command::new("git").args(args).stderr(Stdio::null()).output().ok()?;
    output.status.success().then_some(output.stdout)
}
