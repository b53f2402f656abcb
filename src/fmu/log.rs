//! Log categories (declared in `<LogCategories>`) and the sink the FFI layer provides.

use super::status::Status;

/// The declared log categories (FMI 2.0.4 §2.2.4 standard names).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Category {
    /// Informational messages: instantiation, mode changes, parameter changes.
    LogEvents,
    /// Messages with status `fmi2Warning`.
    LogStatusWarning,
    /// Messages with status `fmi2Discard` (a step that could not be completed).
    LogStatusDiscard,
    /// Messages with status `fmi2Error`.
    LogStatusError,
    /// Messages with status `fmi2Fatal` (a caught panic).
    LogStatusFatal,
    /// Everything.
    LogAll,
}

impl Category {
    /// Every category, in the order of `<LogCategories>`.
    pub const ALL: [Category; 6] = [
        Self::LogEvents,
        Self::LogStatusWarning,
        Self::LogStatusDiscard,
        Self::LogStatusError,
        Self::LogStatusFatal,
        Self::LogAll,
    ];

    /// The category name used in the XML and passed to the logger.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::LogEvents => "logEvents",
            Self::LogStatusWarning => "logStatusWarning",
            Self::LogStatusDiscard => "logStatusDiscard",
            Self::LogStatusError => "logStatusError",
            Self::LogStatusFatal => "logStatusFatal",
            Self::LogAll => "logAll",
        }
    }

    /// The description written to `<LogCategories>`.
    #[must_use]
    pub fn description(self) -> &'static str {
        match self {
            Self::LogEvents => "Instantiation, mode changes and parameter changes",
            Self::LogStatusWarning => "Messages with status fmi2Warning",
            Self::LogStatusDiscard => {
                "Communication steps that could not be completed (fmi2Discard)"
            }
            Self::LogStatusError => "Rejected calls and failures (fmi2Error)",
            Self::LogStatusFatal => "Internal errors (fmi2Fatal)",
            Self::LogAll => "All of the above",
        }
    }

    /// Looks a category up by name.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Category> {
        Self::ALL.into_iter().find(|c| c.name() == name)
    }

    /// The category of a message with `status`.
    #[must_use]
    pub fn of_status(status: Status) -> Category {
        match status {
            Status::Ok => Self::LogEvents,
            Status::Warning => Self::LogStatusWarning,
            Status::Discard => Self::LogStatusDiscard,
            Status::Error => Self::LogStatusError,
            Status::Fatal => Self::LogStatusFatal,
        }
    }

    fn bit(self) -> u8 {
        1 << (self as u8)
    }
}

/// Where an instance's messages go (the FFI wraps the importer's logger callback).
pub trait LogSink: Send {
    /// Delivers one already formatted message.
    fn log(&self, instance_name: &str, status: Status, category: Category, message: &str);
}

/// A sink that drops everything (no logger callback given).
#[derive(Debug, Default)]
pub struct NoLog;

impl LogSink for NoLog {
    fn log(&self, _: &str, _: Status, _: Category, _: &str) {}
}

/// Which categories are enabled.
///
/// `fmi2Instantiate(loggingOn)` enables `logEvents` when true; warnings, discards, errors and
/// fatal errors are enabled by default (a rejected call should always say why), and
/// `fmi2SetDebugLogging` switches any of them. `logAll` enables everything.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Filter(u8);

impl Filter {
    /// The default filter for `fmi2Instantiate(loggingOn)`.
    #[must_use]
    pub fn new(logging_on: bool) -> Self {
        let mut f = Self(0);
        for c in [
            Category::LogStatusWarning,
            Category::LogStatusDiscard,
            Category::LogStatusError,
            Category::LogStatusFatal,
        ] {
            f.set(c, true);
        }
        f.set(Category::LogEvents, logging_on);
        f
    }

    /// Switches one category.
    pub fn set(&mut self, c: Category, on: bool) {
        if on {
            self.0 |= c.bit();
        } else {
            self.0 &= !c.bit();
        }
    }

    /// Switches every category.
    pub fn set_all(&mut self, on: bool) {
        for c in Category::ALL {
            self.set(c, on);
        }
    }

    /// Whether a message of category `c` is delivered.
    #[must_use]
    pub fn enabled(&self, c: Category) -> bool {
        self.0 & (c.bit() | Category::LogAll.bit()) != 0
    }
}
