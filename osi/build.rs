//! Compiles OSI's messages from the vendored descriptor set (proto/osi3.fds)
//! with prost-build: no protoc, no .proto parser.

use prost::Message;

fn main() -> std::io::Result<()> {
    println!("cargo:rerun-if-changed=proto/osi3.fds");
    let bytes = std::fs::read("proto/osi3.fds")?;
    let descriptors = prost_types::FileDescriptorSet::decode(bytes.as_slice())
        .map_err(|error| std::io::Error::new(std::io::ErrorKind::InvalidData, error))?;
    prost_build::Config::new().compile_fds(descriptors)
}
