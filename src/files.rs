//! Reading input files: only regular files (or standard input, piped), and no
//! more than a limit, so that a FIFO, a device (`/dev/zero`), a symbolic link
//! loop or a huge file is refused at once with a clear message instead of
//! blocking `check` or filling memory.

use std::collections::HashSet;
use std::fs::File;
use std::io::{self, ErrorKind, IsTerminal, Read};
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
    let kind = match std::fs::metadata(path) {
        Ok(metadata) => metadata.file_type(),
        Err(_) if is_link_loop(path) => return Err(refused("a symbolic link loop, not a regular file")),
        Err(error) => return Err(error),
    };
    if !kind.is_file() {
        let what = if kind.is_dir() {
            "a directory"
        } else {
            not_regular(&kind)
        };
        return Err(refused(&format!("{what}, not a regular file")));
    }
    read_limited(File::open(path)?, limit)
}

/// The bytes of the regular file `name` (segments joined by `/`) beneath the
/// folder `root`, following no symbolic link on the way nor at the end: a link
/// is refused as such (`` `parts` is a symbolic link``). On Unix each segment
/// is opened from the one before without following a link, so a link swapped
/// in between a check and the read cannot lead out of `root`.
pub fn read_beneath(root: &Path, name: &str, limit: u64) -> io::Result<Vec<u8>> {
    #[cfg(unix)]
    {
        use rustix::fs::{AtFlags, CWD, FileType, Mode, OFlags, fstat, openat, statat};
        let mut at = openat(
            CWD,
            root,
            OFlags::RDONLY | OFlags::CLOEXEC | OFlags::DIRECTORY,
            Mode::empty(),
        )?;
        for (end, segment, last) in segments(name) {
            let kind = if last { OFlags::NONBLOCK } else { OFlags::DIRECTORY };
            let flags = OFlags::RDONLY | OFlags::CLOEXEC | OFlags::NOFOLLOW | kind;
            at = match openat(&at, segment, flags, Mode::empty()) {
                Ok(next) => next,
                // Refused for being a link (ELOOP at the end, ENOTDIR on the way).
                Err(_)
                    if statat(&at, segment, AtFlags::SYMLINK_NOFOLLOW)
                        .is_ok_and(|stat| FileType::from_raw_mode(stat.st_mode) == FileType::Symlink) =>
                {
                    return Err(linked(&name[..end]));
                }
                Err(errno) => return Err(errno.into()),
            };
        }
        match FileType::from_raw_mode(fstat(&at)?.st_mode) {
            FileType::RegularFile => read_limited(File::from(at), limit),
            FileType::Directory => Err(refused("a directory, not a regular file")),
            _ => Err(refused("a special file, not a regular file")),
        }
    }
    #[cfg(not(unix))]
    {
        let mut path = root.to_path_buf();
        for (end, segment, _) in segments(name) {
            path.push(segment);
            if std::fs::symlink_metadata(&path)?.file_type().is_symlink() {
                return Err(linked(&name[..end]));
            }
        }
        read_regular(&path, limit)
    }
}

/// Each segment of `name`, with where it ends in `name` and whether it is the last.
fn segments(name: &str) -> impl Iterator<Item = (usize, &str, bool)> {
    let mut end = 0;
    name.split('/').map(move |segment| {
        end += segment.len() + usize::from(end > 0);
        (end, segment, end == name.len())
    })
}

/// The error of a path through a symbolic link, at `prefix`.
fn linked(prefix: &str) -> io::Error {
    refused(&format!("`{prefix}` is a symbolic link, never read through"))
}

/// The bytes of standard input (`-` on the command line), within `limit`;
/// refused when it is a terminal (nothing was piped in, and a read would wait
/// for typing) or a directory (`< dir`).
pub fn read_stdin(limit: u64) -> io::Result<Vec<u8>> {
    let stdin = io::stdin();
    if stdin.is_terminal() {
        return Err(refused(
            "it is a terminal; pipe a scenario into it (`sightline check - < FILE`) or name the file",
        ));
    }
    #[cfg(unix)]
    {
        use std::os::fd::AsFd;
        let file = File::from(stdin.as_fd().try_clone_to_owned()?);
        if file.metadata()?.is_dir() {
            return Err(refused("a directory, not a regular file"));
        }
    }
    read_limited(stdin.lock(), limit)
}

/// Everything `reader` holds, refused past `limit` bytes (reading at most one
/// more), so a source that never ends is cut off.
fn read_limited(reader: impl Read, limit: u64) -> io::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    reader.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(refused(&format!("larger than the limit of {} MiB", limit / MIB)));
    }
    Ok(bytes)
}

/// An input refused for what it is.
fn refused(why: &str) -> io::Error {
    io::Error::new(ErrorKind::InvalidInput, why)
}

/// Whether `path` is a symbolic link whose chain of links comes back on itself
/// (or is longer than the 40 links Linux follows).
fn is_link_loop(path: &Path) -> bool {
    let mut seen = HashSet::new();
    let mut at = path.to_path_buf();
    while let Ok(target) = std::fs::read_link(&at) {
        if !seen.insert(at.clone()) || seen.len() > 40 {
            return true;
        }
        at = at.parent().unwrap_or(Path::new("")).join(target);
    }
    false
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
    fn a_symbolic_link_loop_is_named() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.yaml"), dir.path().join("b.yaml"));
        std::os::unix::fs::symlink("b.yaml", &a).unwrap();
        std::os::unix::fs::symlink("a.yaml", &b).unwrap();
        let error = read_regular(&a, TEXT_LIMIT).unwrap_err();
        assert_eq!(error.to_string(), "a symbolic link loop, not a regular file");
        // A link to a missing file is no loop: the system's own message stays.
        let dangling = dir.path().join("c.yaml");
        std::os::unix::fs::symlink("missing.yaml", &dangling).unwrap();
        let error = read_regular(&dangling, TEXT_LIMIT).unwrap_err();
        assert_eq!(error.kind(), ErrorKind::NotFound);
    }

    #[cfg(unix)]
    #[test]
    fn a_device_is_refused_without_reading_it() {
        let error = read_regular(Path::new("/dev/zero"), TEXT_LIMIT).unwrap_err();
        assert_eq!(error.to_string(), "a device, not a regular file");
    }

    /// Beneath a folder, a file is read only where it is: a link at the end or
    /// on the way is refused by name; a FIFO is refused without waiting for a
    /// writer; a missing file is `NotFound`.
    #[cfg(unix)]
    #[test]
    fn a_file_beneath_a_folder_is_read_through_no_link() {
        let dir = tempfile::tempdir().unwrap();
        let (root, outside) = (dir.path().join("set"), dir.path().join("outside"));
        std::fs::create_dir_all(root.join("parts")).unwrap();
        std::fs::create_dir_all(&outside).unwrap();
        std::fs::write(root.join("parts/a.html"), "A").unwrap();
        std::fs::write(outside.join("b.html"), "B").unwrap();
        std::os::unix::fs::symlink(outside.join("b.html"), root.join("parts/b.html")).unwrap();
        std::os::unix::fs::symlink(&outside, root.join("linked")).unwrap();
        assert_eq!(read_beneath(&root, "parts/a.html", TEXT_LIMIT).unwrap(), b"A");
        for (name, link) in [("parts/b.html", "parts/b.html"), ("linked/b.html", "linked")] {
            let error = read_beneath(&root, name, TEXT_LIMIT).unwrap_err();
            assert_eq!(
                error.to_string(),
                format!("`{link}` is a symbolic link, never read through")
            );
        }
        assert!(rustix::fs::mkfifoat(rustix::fs::CWD, root.join("fifo"), rustix::fs::Mode::RUSR).is_ok());
        let error = read_beneath(&root, "fifo", TEXT_LIMIT).unwrap_err();
        assert_eq!(error.to_string(), "a special file, not a regular file");
        let error = read_beneath(&root, "parts", TEXT_LIMIT).unwrap_err();
        assert_eq!(error.to_string(), "a directory, not a regular file");
        let error = read_beneath(&root, "parts/missing.html", TEXT_LIMIT).unwrap_err();
        assert_eq!(error.kind(), ErrorKind::NotFound);
    }
}
