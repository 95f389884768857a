//! Standard output for the commands. A write that fails (a full disk, a
//! closed file) is remembered and turns the command's exit status into 1
//! with one line on stderr; a closed pipe (`oxcover … | head`) stays quiet,
//! as a reader that has seen enough is no error.

use std::io::{self, Write};
use std::sync::Mutex;

static FAILED: Mutex<Option<String>> = Mutex::new(None);

/// Standard output, remembering write errors instead of returning them.
pub(crate) struct Out(io::StdoutLock<'static>);

/// The commands' standard output.
pub(crate) fn stdout() -> Out {
    Out(io::stdout().lock())
}

fn note(e: &io::Error) {
    if e.kind() == io::ErrorKind::BrokenPipe {
        return;
    }
    if let Ok(mut f) = FAILED.lock() {
        f.get_or_insert_with(|| e.to_string());
    }
}

impl Write for Out {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if let Err(e) = self.0.write_all(buf) {
            note(&e);
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        if let Err(e) = self.0.flush() {
            note(&e);
        }
        Ok(())
    }
}

/// The first write error on standard output, if any (after a last flush).
pub(crate) fn failure() -> Option<String> {
    let _ = stdout().flush();
    FAILED.lock().ok().and_then(|mut f| f.take())
}
