//! The recording's MCAP container, written on a thread of its own: the
//! recorder encodes each message into a batch, or hands the thread what it
//! needs to encode it ([`Container::deferred`]: the messages of every step,
//! encoded off the simulation's thread), and hands full batches to a writer
//! thread over a bounded channel; the thread registers the channels and
//! schemas, encodes the deferred messages, compresses the chunks (lz4),
//! computes their CRCs and writes the file, in the order the recorder gave
//! them, so the bytes are the ones writing in place gives.
//!
//! The thread writes without seeking back ([`NoSeek`]: each chunk is built in
//! memory and written whole), so what reaches the output is the file in order
//! and a writer can hash it as it passes
//! ([`Sha256Writer`](crate::Sha256Writer)).
//!
//! Memory stays bounded: at most [`QUEUED`] batches wait for the thread, each
//! about [`BATCH_BYTES`] (or one message, when larger; a deferred message
//! counts what it holds), and the thread hands each batch back emptied, to be
//! filled again.

use std::any::Any;
use std::borrow::Cow;
use std::collections::BTreeMap;
use std::io::Write;
use std::sync::mpsc::{Receiver, Sender, SyncSender, channel, sync_channel};
use std::thread::JoinHandle;

use mcap::records::MessageHeader;
use mcap::write::NoSeek;
use mcap::{Attachment, WriteOptions, Writer};

use super::WriteError;
use super::channel::SchemaSpec;

/// A batch is handed to the thread once it holds this many bytes.
const BATCH_BYTES: usize = 64 * 1024;

/// How many full batches may wait for the thread; the recorder waits beyond.
const QUEUED: usize = 4;

/// The recorder's end of the container: the batch being filled, and the
/// writer thread.
pub(super) struct Container<W> {
    batch: Batch,
    /// Topic → index of its channel, in the order of first use.
    channels: BTreeMap<String, usize>,
    /// `None` once the thread stopped on a failure (which
    /// [`finish`](Self::finish) reports) or the container finished.
    to_thread: Option<SyncSender<Batch>>,
    /// Batches the thread has written and emptied.
    recycled: Receiver<Batch>,
    /// The thread; `None` once joined.
    thread: Option<JoinHandle<Result<W, WriteError>>>,
    /// The first message that did not encode; once set, nothing more is
    /// written.
    failure: Option<WriteError>,
}

/// Messages and attachments, encoded or to encode, for the thread to write in
/// order.
#[derive(Default)]
struct Batch {
    /// The entries' bytes, one after the other.
    bytes: Vec<u8>,
    /// The bytes the deferred messages and their entries hold, about.
    held: usize,
    entries: Vec<Entry>,
}

/// How the thread encodes a deferred message: it owns what it needs.
type Encode = Box<dyn FnOnce(&mut Vec<u8>) -> serde_json::Result<()> + Send>;

/// What the thread writes; the ones with `len` take the next `len` bytes of
/// their batch.
enum Entry {
    /// A channel on `topic` (with `schema`, registered on its first use): the
    /// next channel index.
    Channel { topic: String, schema: SchemaSpec },
    /// A message on channel index `channel`.
    Message { channel: usize, log_time: u64, len: usize },
    /// A message on channel index `channel` that the thread encodes.
    Deferred {
        channel: usize,
        log_time: u64,
        encode: Encode,
    },
    /// A file attached.
    Attachment {
        name: String,
        media_type: &'static str,
        log_time: u64,
        len: usize,
    },
}

impl<W: Write + Send + 'static> Container<W> {
    /// Writes the MCAP header into `out` and starts the thread that writes the
    /// rest with `options`.
    pub(super) fn start(out: W, options: WriteOptions) -> Result<Self, WriteError> {
        let writer = options.disable_seeking(true).create(NoSeek::new(out))?;
        let (to_thread, batches) = sync_channel(QUEUED);
        let (recycle, recycled) = channel();
        let thread = std::thread::Builder::new()
            .name("sightline-recording".into())
            .spawn(move || write_batches(writer, &batches, &recycle))
            .map_err(WriteError::Thread)?;
        Ok(Self {
            batch: Batch::default(),
            channels: BTreeMap::new(),
            to_thread: Some(to_thread),
            recycled,
            thread: Some(thread),
            failure: None,
        })
    }

    /// Hands the last batch over, waits for the thread to write it and the
    /// MCAP summary, and gives the output back; the first message that did
    /// not encode, the thread's first failure, or its panic, as an error.
    pub(super) fn finish(mut self) -> Result<W, WriteError> {
        self.take_failure()?;
        self.send();
        self.to_thread = None;
        match self.thread.take() {
            Some(thread) => thread
                .join()
                .unwrap_or_else(|panic| Err(WriteError::Panicked(panic_message(panic.as_ref())))),
            None => unreachable!("the thread is joined only by `finish` and `drop`"),
        }
    }
}

impl<W> Container<W> {
    /// Adds a message on `topic` (created with `schema` on first use) at
    /// `log_time` nanoseconds, which `encode` appends; nothing once the thread
    /// has stopped or a message did not encode (the first such failure is
    /// kept for [`finish`](Self::finish)).
    pub(super) fn message(
        &mut self,
        topic: &str,
        schema: SchemaSpec,
        log_time: u64,
        encode: impl FnOnce(&mut Vec<u8>) -> serde_json::Result<()>,
    ) {
        if self.to_thread.is_none() || self.failure.is_some() {
            return;
        }
        let start = self.batch.bytes.len();
        if let Err(error) = encode(&mut self.batch.bytes) {
            self.batch.bytes.truncate(start);
            self.failure = Some(WriteError::Json(error));
            return;
        }
        let channel = self.channel(topic, schema);
        let len = self.batch.bytes.len() - start;
        self.batch.entries.push(Entry::Message { channel, log_time, len });
        self.sent_when_full();
    }

    /// [`message`](Self::message) of a message `write` appends, which cannot
    /// fail.
    pub(super) fn written(&mut self, topic: &str, schema: SchemaSpec, log_time: u64, write: impl FnOnce(&mut Vec<u8>)) {
        self.message(topic, schema, log_time, |out| {
            write(out);
            Ok(())
        });
    }

    /// Adds a message on `topic` (created with `schema` on first use) at
    /// `log_time` nanoseconds that the writer thread encodes with `encode`,
    /// in its place among the others: encoding off the caller's thread.
    /// `encode` owns what it needs, about `held` bytes (counted toward the
    /// batch's size); a failure to encode stops the recording, reported by
    /// [`finish`](Self::finish).
    pub(super) fn deferred(
        &mut self,
        topic: &str,
        schema: SchemaSpec,
        log_time: u64,
        held: usize,
        encode: impl FnOnce(&mut Vec<u8>) -> serde_json::Result<()> + Send + 'static,
    ) {
        if self.to_thread.is_none() || self.failure.is_some() {
            return;
        }
        let channel = self.channel(topic, schema);
        // The entry counts too, so that messages holding nothing still fill
        // a batch.
        self.batch.held += held + size_of::<Entry>();
        self.batch.entries.push(Entry::Deferred {
            channel,
            log_time,
            encode: Box::new(encode),
        });
        self.sent_when_full();
    }

    /// The first message that did not encode, taken.
    pub(super) fn take_failure(&mut self) -> Result<(), WriteError> {
        self.failure.take().map_or(Ok(()), Err)
    }

    /// Attaches `data` as the file `name` of type `media_type`, at `log_time`.
    pub(super) fn attach(&mut self, name: &str, media_type: &'static str, log_time: u64, data: &[u8]) {
        if self.to_thread.is_none() {
            return;
        }
        self.batch.bytes.extend_from_slice(data);
        self.batch.entries.push(Entry::Attachment {
            name: name.into(),
            media_type,
            log_time,
            len: data.len(),
        });
        self.sent_when_full();
    }

    /// The index of `topic`'s channel, registered with `schema` on first use.
    fn channel(&mut self, topic: &str, schema: SchemaSpec) -> usize {
        if let Some(&index) = self.channels.get(topic) {
            return index;
        }
        let index = self.channels.len();
        self.channels.insert(topic.into(), index);
        self.batch.entries.push(Entry::Channel {
            topic: topic.into(),
            schema,
        });
        index
    }

    fn sent_when_full(&mut self) {
        if self.batch.bytes.len() + self.batch.held >= BATCH_BYTES {
            self.send();
        }
    }

    /// Hands the batch to the thread (waiting while [`QUEUED`] wait) and
    /// takes an emptied one, or a new one, to fill.
    fn send(&mut self) {
        if self.batch.entries.is_empty() {
            return;
        }
        let next = self.recycled.try_recv().unwrap_or_default();
        let full = std::mem::replace(&mut self.batch, next);
        if let Some(to_thread) = &self.to_thread
            && to_thread.send(full).is_err()
        {
            // The thread stopped on a failure, which `finish` reports.
            self.to_thread = None;
        }
    }
}

impl<W> Drop for Container<W> {
    /// Unfinished (a recording discarded, or a run that failed): the thread
    /// writes what it was given, closes the output and ends before the
    /// container does, so that the output can be removed.
    fn drop(&mut self) {
        self.to_thread = None;
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

/// The writer thread: writes every batch `batches` brings into `out`, in
/// order, handing each back emptied through `recycle`; once the recorder has
/// finished (the channel closed), the MCAP summary. Stops at the first
/// failure.
fn write_batches<W: Write>(
    mut out: Writer<NoSeek<W>>,
    batches: &Receiver<Batch>,
    recycle: &Sender<Batch>,
) -> Result<W, WriteError> {
    // Schema name → id, channel index → id.
    let mut schemas: BTreeMap<&'static str, u16> = BTreeMap::new();
    let mut channels: Vec<u16> = Vec::new();
    let mut sequence = 0;
    // A deferred message's bytes, encoded.
    let mut encoded = Vec::new();
    for mut batch in batches {
        let Batch { bytes, held, entries } = &mut batch;
        let mut rest = bytes.as_slice();
        let mut take = |len: usize| {
            let (data, after) = rest.split_at(len);
            rest = after;
            data
        };
        for entry in entries.drain(..) {
            match entry {
                Entry::Channel { topic, schema } => {
                    let schema_id = match schemas.get(schema.name) {
                        Some(&id) => id,
                        None => {
                            let id = out.add_schema(schema.name, "jsonschema", &(schema.data)())?;
                            schemas.insert(schema.name, id);
                            id
                        }
                    };
                    channels.push(out.add_channel(schema_id, &topic, "json", &BTreeMap::new())?);
                }
                Entry::Message { channel, log_time, len } => {
                    sequence += 1;
                    out.write_to_known_channel(&header(channels[channel], sequence, log_time), take(len))?;
                }
                Entry::Deferred {
                    channel,
                    log_time,
                    encode,
                } => {
                    sequence += 1;
                    encoded.clear();
                    encode(&mut encoded)?;
                    out.write_to_known_channel(&header(channels[channel], sequence, log_time), &encoded)?;
                }
                Entry::Attachment {
                    name,
                    media_type,
                    log_time,
                    len,
                } => out.attach(&Attachment {
                    log_time,
                    create_time: log_time,
                    name,
                    media_type: media_type.into(),
                    data: Cow::Borrowed(take(len)),
                })?,
            }
        }
        bytes.clear();
        *held = 0;
        // The recorder may have gone (dropped unfinished); the batch then goes too.
        let _ = recycle.send(batch);
    }
    out.finish()?;
    Ok(out.into_inner().into_inner())
}

/// The header of message `sequence` on channel `channel_id`, published when
/// logged.
fn header(channel_id: u16, sequence: u32, log_time: u64) -> MessageHeader {
    MessageHeader {
        channel_id,
        sequence,
        log_time,
        publish_time: log_time,
    }
}

/// What a panic said, when it said it with a string.
fn panic_message(panic: &(dyn Any + Send)) -> String {
    panic
        .downcast_ref::<&str>()
        .map(|s| (*s).to_string())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "no message".into())
}

#[cfg(test)]
mod tests {
    use std::io::Cursor;

    use mcap::Compression;

    use super::super::channel::{LOG, SCENE, SIGNALS};
    use super::*;
    use crate::{Sha256Writer, sha256_hex};

    fn options() -> WriteOptions {
        WriteOptions::new()
            .compression(Some(Compression::Lz4))
            .library("sightline")
    }

    /// What a recording holds, in order: attachments (name, bytes) and
    /// messages (topic, schema, time, JSON), about 2.5 MB of JSON in all:
    /// several chunks and several dozen batches.
    enum Item {
        Attachment(String, Vec<u8>),
        Message(&'static str, SchemaSpec, u64, Vec<u8>),
    }

    fn items() -> Vec<Item> {
        let mut items = vec![Item::Attachment("net.xml".into(), b"<net/>".repeat(3_000))];
        let topics = [("/a", SCENE), ("/b", SIGNALS), ("/c", LOG), ("/d", SCENE)];
        for i in 0..30_000_u64 {
            let (topic, schema) = topics[(i * i % 7 % 4) as usize];
            let json = format!(
                r#"{{"i":{i},"x":{},"text":"{}"}}"#,
                i * 7919 % 1013,
                "ab".repeat((i % 29) as usize)
            );
            items.push(Item::Message(topic, schema, 1_000 + i / 3, json.into_bytes()));
            if i == 17_000 {
                items.push(Item::Attachment("poly.xml".into(), b"<poly/>".repeat(500)));
            }
        }
        items
    }

    /// `items` through a container into `out`: every third message deferred
    /// (encoded by the thread), the others encoded in the batch.
    fn contained<W: Write + Send + 'static>(out: W, items: &[Item]) -> Result<W, WriteError> {
        let mut container = Container::start(out, options())?;
        for (i, item) in items.iter().enumerate() {
            match item {
                Item::Attachment(name, data) => container.attach(name, "application/xml", 5, data),
                Item::Message(topic, schema, time, json) if i % 3 == 0 => {
                    let json = json.clone();
                    container.deferred(topic, *schema, *time, json.len(), move |out| {
                        out.extend_from_slice(&json);
                        Ok(())
                    });
                }
                Item::Message(topic, schema, time, json) => {
                    container.written(topic, *schema, *time, |out| out.extend_from_slice(json));
                }
            }
        }
        container.finish()
    }

    /// `items` written in place by the MCAP writer, seeking back to finish
    /// each chunk, as recordings were written before the thread.
    fn in_place(items: &[Item]) -> Vec<u8> {
        let mut out = options().create(Cursor::new(Vec::new())).unwrap();
        let (mut schemas, mut channels, mut sequence) = (BTreeMap::new(), BTreeMap::new(), 0);
        for item in items {
            match item {
                Item::Attachment(name, data) => out
                    .attach(&Attachment {
                        log_time: 5,
                        create_time: 5,
                        name: name.clone(),
                        media_type: "application/xml".into(),
                        data: Cow::Borrowed(data),
                    })
                    .unwrap(),
                Item::Message(topic, schema, time, json) => {
                    let schema_id = *schemas
                        .entry(schema.name)
                        .or_insert_with(|| out.add_schema(schema.name, "jsonschema", &(schema.data)()).unwrap());
                    let channel_id = *channels
                        .entry(*topic)
                        .or_insert_with(|| out.add_channel(schema_id, topic, "json", &BTreeMap::new()).unwrap());
                    sequence += 1;
                    let header = MessageHeader {
                        channel_id,
                        sequence,
                        log_time: *time,
                        publish_time: *time,
                    };
                    out.write_to_known_channel(&header, json).unwrap();
                }
            }
        }
        out.finish().unwrap();
        out.into_inner().into_inner()
    }

    /// The thread writes the bytes the MCAP writer writes in place, and the
    /// hash of what it wrote is the file's.
    #[test]
    fn the_thread_writes_the_bytes_written_in_place() {
        let items = items();
        let (written, hash) = contained(Sha256Writer::new(Vec::new()), &items).unwrap().finish();
        let expected = in_place(&items);
        assert!(expected.len() > 200_000, "{} bytes", expected.len());
        assert!(
            written == expected,
            "{} bytes, {} in place",
            written.len(),
            expected.len()
        );
        assert_eq!(hash, sha256_hex(&expected));
    }

    /// A deferred message that does not encode on the thread is the
    /// recording's error.
    #[test]
    fn a_deferred_message_that_does_not_encode_is_the_recordings_error() {
        let mut container = Container::start(Vec::new(), options()).unwrap();
        for (i, item) in items().into_iter().enumerate() {
            if let Item::Message(topic, schema, time, json) = item {
                container.deferred(topic, schema, time, json.len(), move |out| {
                    if i == 2_000 {
                        return Err(serde::ser::Error::custom("a value that does not encode"));
                    }
                    out.extend_from_slice(&json);
                    Ok(())
                });
            }
        }
        match container.finish() {
            Err(WriteError::Json(error)) => assert_eq!(error.to_string(), "a value that does not encode"),
            other => panic!("{:?}", other.map(|_| ())),
        }
    }

    /// Deferred messages that hold nothing still fill a batch: the one being
    /// filled never grows past a batch's worth of entries.
    #[test]
    fn deferred_messages_holding_nothing_still_fill_a_batch() {
        let mut container = Container::start(Vec::new(), options()).unwrap();
        let most = BATCH_BYTES / size_of::<Entry>() + 1;
        for i in 0..100_000 {
            container.deferred("/a", SCENE, i, 0, |out| {
                out.extend_from_slice(b"{}");
                Ok(())
            });
            assert!(
                container.batch.entries.len() <= most,
                "{} entries",
                container.batch.entries.len()
            );
        }
        container.finish().unwrap();
    }

    /// An output that fails, or panics, once it has taken `limit` bytes.
    struct Breaks {
        taken: usize,
        limit: usize,
        panics: bool,
    }

    impl Write for Breaks {
        fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
            if self.taken + bytes.len() > self.limit {
                assert!(!self.panics, "the output broke");
                return Err(std::io::Error::other("the disk is full"));
            }
            self.taken += bytes.len();
            Ok(bytes.len())
        }

        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    /// An output that fails on the thread is the recording's error, and a
    /// panic on the thread is one too, not an abort; the recorder goes on
    /// handing messages over until the end either way.
    #[test]
    fn the_threads_failure_or_panic_is_the_recordings_error() {
        let items = items();
        let failing = Breaks {
            taken: 0,
            limit: 10_000,
            panics: false,
        };
        match contained(failing, &items) {
            Err(WriteError::Mcap(mcap::McapError::Io(error))) => assert_eq!(error.to_string(), "the disk is full"),
            other => panic!("{:?}", other.map(|_| ())),
        }
        let panicking = Breaks {
            taken: 0,
            limit: 10_000,
            panics: true,
        };
        match contained(panicking, &items) {
            Err(WriteError::Panicked(message)) => assert_eq!(message, "the output broke"),
            other => panic!("{:?}", other.map(|_| ())),
        }
    }

    /// Takes every byte, and closes a channel when dropped.
    struct Closes {
        _on_drop: Sender<()>,
    }

    impl Write for Closes {
        fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
            Ok(bytes.len())
        }

        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    /// A container dropped unfinished has closed its output when the drop
    /// returns.
    #[test]
    fn a_container_dropped_has_closed_its_output() {
        let (closes, closed) = channel();
        let mut container = Container::start(Closes { _on_drop: closes }, options()).unwrap();
        for item in &items()[..5_000] {
            if let Item::Message(topic, schema, time, json) = item {
                container.written(topic, *schema, *time, |out| out.extend_from_slice(json));
            }
        }
        drop(container);
        assert_eq!(closed.try_recv(), Err(std::sync::mpsc::TryRecvError::Disconnected));
    }
}
