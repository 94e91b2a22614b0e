//! A system under test's process: started with its input and output as pipes,
//! fed and read by two threads so that every wait is bounded by a time limit,
//! and killed and reaped on every path: when it is dropped, and on SIGINT,
//! SIGTERM or SIGHUP (a clean-up registered with `signals`). On Unix it leads
//! a process group of its own, killed whole: what it started (a helper left
//! running, holding sightline's standard error) goes with it.

use std::io::{Read, Write};
use std::process::{Command, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender, TryRecvError};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use sightline_reports::osi::system::{ProtocolError, read_frame};

use crate::signals::{Ticket, with_pending};

/// What went wrong with the process.
#[derive(Debug, thiserror::Error)]
pub enum ChildError {
    /// It could not be started.
    #[error("failed to start it: {0}")]
    Start(std::io::Error),
    /// It did not answer in time.
    #[error("it did not answer within {0} s (its step_timeout)")]
    Timeout(f64),
    /// Its output ended: it closed it or exited.
    #[error("its output ended{0}")]
    Closed(String),
    /// Its output broke the framing.
    #[error("{0}")]
    Protocol(#[from] ProtocolError),
    /// It wrote to its output after the last step's answer: the bytes read.
    #[error("it wrote {0} bytes after the last step")]
    AfterEnd(u64),
    /// It failed after its input was closed: how it ended, in words.
    #[error("it {0} after the last step")]
    Exit(String),
}

/// The process, shared with the signal clean-up that kills it.
type Shared = Arc<Mutex<Option<std::process::Child>>>;

/// A running system under test.
pub struct Child {
    process: Shared,
    ticket: Ticket,
    input: Option<Sender<Vec<u8>>>,
    /// Each message or error read, with the bytes of its output read by then.
    output: Receiver<(Result<Vec<u8>, ChildError>, u64)>,
    /// The bytes of its output up to the end of the last message taken.
    read: u64,
}

/// A reader that counts the bytes read.
struct Counted<R> {
    inner: R,
    read: u64,
}

impl<R: Read> Read for Counted<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.read += n as u64;
        Ok(n)
    }
}

fn lock(process: &Shared) -> MutexGuard<'_, Option<std::process::Child>> {
    process.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Kills what the process started and left running: its process group
/// outlives it while one of them runs (on Unix; elsewhere nothing).
fn kill_group(child: &std::process::Child) {
    #[cfg(unix)]
    let _ = rustix::process::kill_process_group(rustix::process::Pid::from_child(child), rustix::process::Signal::KILL);
}

/// Kills the process if it still runs and waits for it: nothing is left.
fn reap(process: &Shared) {
    if let Some(mut child) = lock(process).take() {
        // It may have exited already; either way `wait` reaps it.
        kill_group(&child);
        let _ = child.kill();
        let _ = child.wait();
    }
}

impl Child {
    /// Starts `command` (program and arguments) with `env` added to its
    /// environment; its standard error is sightline's.
    pub fn start(command: &[String], env: &[(&str, String)]) -> Result<Self, ChildError> {
        let mut process = Command::new(&command[0]);
        process
            .args(&command[1..])
            .envs(env.iter().map(|(k, v)| (k, v)))
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit());
        #[cfg(unix)]
        std::os::unix::process::CommandExt::process_group(&mut process, 0);
        let mut child = process.spawn().map_err(ChildError::Start)?;
        let (mut stdin, mut stdout) = (child.stdin.take(), child.stdout.take());
        let process: Shared = Arc::new(Mutex::new(Some(child)));
        let shared = Arc::clone(&process);
        let ticket = with_pending(|pending| pending.add(move || reap(&shared)));
        let (input, to_write) = mpsc::channel::<Vec<u8>>();
        // Neither thread is joined: each ends when its pipe closes, which a
        // process the system started and left holding the pipe may delay.
        std::thread::spawn(move || {
            let Some(stdin) = stdin.as_mut() else { return };
            for bytes in to_write {
                // A system that stops reading shows as a closed output or a
                // timeout on the reading side; nothing to report from here.
                if stdin.write_all(&bytes).and_then(|()| stdin.flush()).is_err() {
                    return;
                }
            }
        });
        // One message at most waits in the channel: a system that floods its
        // output is read no faster than its answers are taken.
        let (send, output) = mpsc::sync_channel(0);
        std::thread::spawn(move || {
            let Some(stdout) = stdout.as_mut() else { return };
            let mut stdout = Counted { inner: stdout, read: 0 };
            loop {
                let message = match read_frame(&mut stdout) {
                    Ok(Some(message)) => Ok(message),
                    Ok(None) => Err(ChildError::Closed(String::new())),
                    Err(error) => Err(error.into()),
                };
                let last = message.is_err();
                if send.send((message, stdout.read)).is_err() || last {
                    return;
                }
            }
        });
        Ok(Self {
            process,
            ticket,
            input: Some(input),
            output,
            read: 0,
        })
    }

    /// Hands `bytes` to its input (written by the writer thread).
    pub fn send(&self, bytes: Vec<u8>) {
        if let Some(input) = &self.input {
            // The writer has ended only when the system stopped reading, which
            // the next `receive` reports.
            let _ = input.send(bytes);
        }
    }

    /// Its next message, waiting at most `limit` seconds.
    pub fn receive(&mut self, limit: f64) -> Result<Vec<u8>, ChildError> {
        match self.output.recv_timeout(Duration::from_secs_f64(limit)) {
            Ok((Ok(message), read)) => {
                self.read = read;
                Ok(message)
            }
            Ok((Err(ChildError::Closed(_)), _)) | Err(RecvTimeoutError::Disconnected) => {
                Err(ChildError::Closed(self.exit_status(limit)))
            }
            Ok((Err(error), _)) => Err(error),
            Err(RecvTimeoutError::Timeout) => Err(ChildError::Timeout(limit)),
        }
    }

    /// How it ended, if it ends within `limit` seconds of its output closing:
    /// ` (it exited with …)`, or nothing.
    fn exit_status(&self, limit: f64) -> String {
        match self.wait(limit) {
            Some(status) => format!(" (it {})", describe(status)),
            None => String::new(),
        }
    }

    /// Waits up to `limit` seconds for it to exit; its status, or `None` if it
    /// still runs (or was reaped already).
    fn wait(&self, limit: f64) -> Option<std::process::ExitStatus> {
        let deadline = Instant::now() + Duration::from_secs_f64(limit);
        loop {
            let status = lock(&self.process).as_mut().and_then(|c| c.try_wait().ok().flatten());
            if status.is_some() || Instant::now() >= deadline {
                return status;
            }
            std::thread::sleep(Duration::from_millis(2));
        }
    }

    /// Closes its input and waits up to `limit` seconds for it to exit with
    /// status 0, its output ending with the last answer: a byte more is an
    /// error. What it leaves running is killed when it exits, so that one
    /// holding its output open ends it. Whatever happens, it is reaped.
    pub fn finish(mut self, limit: f64) -> Result<(), ChildError> {
        self.input = None;
        let deadline = Instant::now() + Duration::from_secs_f64(limit);
        let (mut ended, mut stragglers_killed) = (false, false);
        loop {
            if !ended {
                match self.output.try_recv() {
                    // Its output ended, or failed, where its last answer did.
                    Ok((Err(_), read)) if read == self.read => ended = true,
                    Ok((_, read)) => return Err(ChildError::AfterEnd(read - self.read)),
                    Err(TryRecvError::Disconnected) => ended = true,
                    Err(TryRecvError::Empty) => {}
                }
            }
            let mut process = lock(&self.process);
            let status = process.as_mut().and_then(|c| c.try_wait().ok().flatten());
            let late = Instant::now() >= deadline;
            match status {
                Some(status) if !status.success() => return Err(ChildError::Exit(describe(status))),
                Some(_) if ended || late => return Ok(()),
                // A process it started holds its output open past its exit:
                // killed, its end closes the output (after what it wrote).
                Some(_) if !stragglers_killed => {
                    if let Some(child) = process.as_ref() {
                        kill_group(child);
                    }
                    stragglers_killed = true;
                }
                None if late => return Err(ChildError::Timeout(limit)),
                _ => {}
            }
            drop(process);
            std::thread::sleep(Duration::from_millis(2));
        }
    }
}

/// An exit status in words: `exited with status 3`, `was killed by signal 9`.
fn describe(status: std::process::ExitStatus) -> String {
    #[cfg(unix)]
    if let Some(signal) = std::os::unix::process::ExitStatusExt::signal(&status) {
        return format!("was killed by signal {signal}");
    }
    match status.code() {
        Some(code) => format!("exited with status {code}"),
        None => format!("ended ({status})"),
    }
}

impl Drop for Child {
    fn drop(&mut self) {
        self.input = None;
        reap(&self.process);
        if let Some(cleanup) = with_pending(|pending| pending.take(self.ticket)) {
            drop(cleanup);
        }
    }
}
