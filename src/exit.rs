//! The exit statuses of `sightline`, the contract CI jobs gate on. This is the
//! only place they are defined.

use std::process::ExitCode;

/// How a command ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Exit {
    /// 0: every requirement holds (or, for `check`, every file is valid).
    Pass,
    /// 1: at least one requirement fails or could not be checked.
    Fail,
    /// 2: invalid input or usage (a scenario error, a missing file, a bad flag).
    Invalid,
    /// 3: internal error (a defect in sightline, or output that could not be written).
    Internal,
}

impl From<Exit> for ExitCode {
    fn from(exit: Exit) -> Self {
        ExitCode::from(match exit {
            Exit::Pass => 0,
            Exit::Fail => 1,
            Exit::Invalid => 2,
            Exit::Internal => 3,
        })
    }
}
