//! The importer's logger as a [`LogSink`]: the callback is variadic and printf-style, so it is
//! always called with the format `"%s"` and the message as the one variadic argument (never the
//! message as the format: a `%` in a variable name must not be interpreted).

use super::types::{fmi2CallbackLogger, fmi2ComponentEnvironment};
use crate::fmu::{Category, LogSink, Status};
use std::ffi::CString;

/// The copied logger callback and environment pointer of one instance.
pub struct CLogger {
    logger: fmi2CallbackLogger,
    env: fmi2ComponentEnvironment,
}

// SAFETY: `env` is an opaque pointer that is only handed back to the importer's logger; the
// standard lets an instance be driven from any thread (one at a time), which is all Send claims.
unsafe impl Send for CLogger {}

impl CLogger {
    /// Wraps a callback (NULL: messages are dropped).
    #[must_use]
    pub fn new(logger: fmi2CallbackLogger, env: fmi2ComponentEnvironment) -> Self {
        Self { logger, env }
    }
}

fn c_string(s: &str) -> CString {
    // interior NULs cannot be passed; replace them
    CString::new(s.replace('\0', "\u{fffd}")).unwrap_or_default()
}

impl LogSink for CLogger {
    fn log(&self, instance_name: &str, status: Status, category: Category, message: &str) {
        let Some(f) = self.logger else { return };
        let name = c_string(instance_name);
        let cat = c_string(category.name());
        let msg = c_string(message);
        // SAFETY: the importer's logger has the fmi2CallbackLogger signature; every pointer is a
        // valid NUL-terminated string that outlives the call, and the format "%s" consumes
        // exactly the one variadic `const char*` argument passed.
        unsafe {
            f(
                self.env,
                name.as_ptr(),
                super::guard::code(status),
                cat.as_ptr(),
                c"%s".as_ptr(),
                msg.as_ptr(),
            )
        }
    }
}
