//! ASAM OSI (Open Simulation Interface) 3.8.0's messages for sightline,
//! compiled with prost from the official descriptors.
//!
//! This crate owns the OSI message types ([`osi3`]), the descriptor set they
//! are compiled from ([`FILE_DESCRIPTOR_SET`], the schema an OSI trace in MCAP
//! embeds) and the versions a trace declares. It knows nothing of sightline's
//! scenarios or worlds: `sightline-reports` converts the engine's steps to
//! these messages.
//!
//! The descriptors (`proto/osi3.fds`) are those the official Python bindings,
//! PyPI's `osi-python` 3.8.0, embed: `proto/extract.py` gathers them, and
//! `proto/README.md` says why a descriptor set is vendored rather than the
//! `.proto` files. They are ASAM's, under the Mozilla Public License 2.0
//! (`proto/LICENSE`); prost-build compiles them at build time, so no `protoc`
//! is needed.
//!
//! ```
//! use prost::Message;
//! use sightline_osi::osi3;
//!
//! let view = osi3::SensorView {
//!     sensor_id: Some(osi3::Identifier { value: Some(7) }),
//!     ..Default::default()
//! };
//! let bytes = view.encode_to_vec();
//! assert_eq!(osi3::SensorView::decode(bytes.as_slice()).unwrap(), view);
//! ```
#![warn(missing_docs)]

/// OSI's messages (package `osi3`), as prost generates them from the
/// descriptors: every message of `osi_sensordata.proto` and the files it
/// imports. The descriptors carry no comments: ASAM's documentation of each
/// field is at its published reference.
#[expect(missing_docs, reason = "generated from descriptors without source comments")]
#[expect(clippy::all, reason = "generated code")]
pub mod osi3 {
    include!(concat!(env!("OUT_DIR"), "/osi3.rs"));
}

/// The descriptor set the messages are compiled from: `osi_sensordata.proto`
/// and every file it imports, dependencies first, as `protoc --include_imports
/// --descriptor_set_out` writes it. An OSI trace in MCAP embeds it as each
/// OSI channel's schema.
pub const FILE_DESCRIPTOR_SET: &[u8] = include_bytes!("../proto/osi3.fds");

/// The OSI release the messages are: major, minor and patch.
pub const OSI_VERSION: (u32, u32, u32) = (3, 8, 0);

/// The protobuf release whose `protoc` compiled the descriptors (osi-python
/// 3.8.0's `_pb2` modules name it), as `major.minor.patch`.
pub const PROTOBUF_VERSION: &str = "6.30.2";

/// The OSI release as an [`osi3::InterfaceVersion`], for each message's `version`.
pub fn interface_version() -> osi3::InterfaceVersion {
    let (major, minor, patch) = OSI_VERSION;
    osi3::InterfaceVersion {
        version_major: Some(major),
        version_minor: Some(minor),
        version_patch: Some(patch),
    }
}

/// The OSI release as `major.minor.patch`.
pub fn osi_version() -> String {
    let (major, minor, patch) = OSI_VERSION;
    format!("{major}.{minor}.{patch}")
}
