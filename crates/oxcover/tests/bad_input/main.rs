//! Bad input and the guarantees on outputs, through the command line:
//! every bad input exits with status 2 and one line on stderr naming what
//! was wrong, never a panic (contract, exit status); outputs are whole or
//! absent, never clobber an input, and endless or oversized inputs are
//! refused by size.

mod inputs;
mod limits;
mod outputs;
mod targets;

use std::path::{Path, PathBuf};

pub(crate) fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_oxcover")
}

pub(crate) fn fixtures() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/maps")
}

pub(crate) fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("oxcover-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create scratch dir");
    dir
}

pub(crate) fn write(dir: &Path, name: &str, bytes: &[u8]) -> String {
    let p = dir.join(name);
    std::fs::write(&p, bytes).expect("write fixture");
    p.display().to_string()
}

pub(crate) fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in data {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// A syntactically valid PNG whose header claims `w × h` pixels (no image data).
pub(crate) fn png_header_only(w: u32, h: u32) -> Vec<u8> {
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut chunk = b"IHDR".to_vec();
    chunk.extend(w.to_be_bytes());
    chunk.extend(h.to_be_bytes());
    chunk.extend([8, 0, 0, 0, 0]);
    out.extend(13u32.to_be_bytes());
    out.extend(&chunk);
    out.extend(crc32(&chunk).to_be_bytes());
    out
}

pub(crate) const GOOD_YAML: &str = "image: ok.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";

pub(crate) fn real_png_path() -> String {
    fixtures()
        .join("pythonrobotics/test.png")
        .display()
        .to_string()
}
