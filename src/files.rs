//! Reading input files: only regular files, and no more than a limit, so that a
//! FIFO, a device (`/dev/zero`) or a huge file is refused at once with a clear
//! message instead of blocking `check` or filling memory.

use std::fs::File;
use std::io::{self, ErrorKind, Read};
use std::path::Path;

/// A mebibyte.
const MIB: u64 = 1 << 20;

/// The most a scenario file or a page template may hold.
pub const TEXT_LIMIT: u64 = 16 * MIB;

/// The most a file a scenario imports (a SUMO network, polygons, a trace), a
/// shard file or a recording may hold.
pub const DATA_LIMIT: u64 = 512 * MIB;

/// The bytes of the regular file at `path` (symbolic links followed), refused
/// when it is anything else (a directory, a FIFO, a device, a socket) or holds
/// more than `limit` bytes, even if it grows while it is read.
pub fn read_regular(path: &Path, limit: u64) -> io::Result<Vec<u8>> {
    let kind = std::fs::metadata(path)?.file_type();
    if !kind.is_file() {
        let what = if kind.is_dir() {
            "a directory"
        } else {
            not_regular(&kind)
        };
        return Err(io::Error::new(
            ErrorKind::InvalidInput,
            format!("{what}, not a regular file"),
        ));
    }
    let mut bytes = Vec::new();
    File::open(path)?.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(io::Error::new(
            ErrorKind::InvalidInput,
            format!("larger than the limit of {} MiB", limit / MIB),
        ));
    }
    Ok(bytes)
}

/// What a file that is neither regular nor a directory is.
#[cfg(unix)]
fn not_regular(kind: &std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if kind.is_fifo() {
        "a FIFO"
    } else if kind.is_char_device() || kind.is_block_device() {
        "a device"
    } else if kind.is_socket() {
        "a socket"
    } else {
        "a special file"
    }
}

/// What a file that is neither regular nor a directory is.
#[cfg(not(unix))]
fn not_regular(_: &std::fs::FileType) -> &'static str {
    "a special file"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_regular_file_within_the_limit_is_read_whole() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.yaml");
        let bytes = vec![b'x'; MIB as usize + 1];
        std::fs::write(&path, &bytes).unwrap();
        assert_eq!(read_regular(&path, 2 * MIB).unwrap(), bytes);
        let error = read_regular(&path, MIB).unwrap_err();
        assert_eq!(error.to_string(), "larger than the limit of 1 MiB");
    }

    #[test]
    fn a_directory_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let error = read_regular(dir.path(), TEXT_LIMIT).unwrap_err();
        assert_eq!(error.to_string(), "a directory, not a regular file");
    }

    #[cfg(unix)]
    #[test]
    fn a_device_is_refused_without_reading_it() {
        let error = read_regular(Path::new("/dev/zero"), TEXT_LIMIT).unwrap_err();
        assert_eq!(error.to_string(), "a device, not a regular file");
    }
}
