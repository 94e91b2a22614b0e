//! `sightline selftest`: known answers, computed by hand, that sightline's own
//! code must reproduce on this machine. It is the "validation of the software
//! tool" evidence of a tool qualification (ISO 26262-8, 11.4.9; see
//! docs/qualification.md): each case names what it checks, the expected value
//! and where that value comes from. The engine and the oracles own their cases.

use crate::exit::Exit;
use crate::output::say;

/// Runs every case, prints one line each and a summary; exit 0 when all hold.
pub fn selftest() -> Exit {
    let cases: Vec<_> = sightline_engine::known_answers()
        .into_iter()
        .chain(sightline_oracles::known_answers())
        .collect();
    for case in &cases {
        say(format_args!(
            "{} {:<8} {} (expected {}, got {}, tolerance {})",
            if case.holds() { "PASS" } else { "FAIL" },
            case.id,
            case.what,
            case.expected,
            case.got,
            case.tolerance
        ));
    }
    let held = cases.iter().filter(|c| c.holds()).count();
    say(format_args!(
        "sightline {} (git {}) selftest: {held} of {} known answers hold",
        env!("CARGO_PKG_VERSION"),
        env!("SIGHTLINE_GIT"),
        cases.len()
    ));
    if held == cases.len() { Exit::Pass } else { Exit::Fail }
}
