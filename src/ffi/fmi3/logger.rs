//! The importer's `fmi3LogMessageCallback` as a [`LogSink`]. Unlike FMI 2's logger it is not
//! variadic and takes no instance name: the message is passed as it is.

use super::types::{fmi3InstanceEnvironment, fmi3LogMessageCallback};
use crate::fmu::{Category, LogSink, Status};
use std::ffi::CString;

/// The copied callback and environment pointer of one FMI 3 instance.
pub struct C3Logger {
    log: fmi3LogMessageCallback,
    env: fmi3InstanceEnvironment,
}

// SAFETY: `env` is an opaque pointer that is only handed back to the importer's callback; an
// instance may be driven from any thread (one at a time), which is all Send claims.
unsafe impl Send for C3Logger {}

impl C3Logger {
    /// Wraps a callback (NULL: messages are dropped).
    #[must_use]
    pub fn new(log: fmi3LogMessageCallback, env: fmi3InstanceEnvironment) -> Self {
        Self { log, env }
    }
}

fn c_string(s: &str) -> CString {
    // interior NULs cannot be passed; replace them
    CString::new(s.replace('\0', "\u{fffd}")).unwrap_or_default()
}

impl LogSink for C3Logger {
    fn log(&self, _instance_name: &str, status: Status, category: Category, message: &str) {
        let Some(f) = self.log else { return };
        let cat = c_string(category.name());
        let msg = c_string(message);
        // SAFETY: the importer's callback has the fmi3LogMessageCallback signature; both strings
        // are valid, NUL-terminated and outlive the call.
        unsafe {
            f(
                self.env,
                crate::ffi::guard::code(status),
                cat.as_ptr(),
                msg.as_ptr(),
            )
        }
    }
}
