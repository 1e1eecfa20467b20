//! The one exception type of the bindings, and the conversion of library errors into it.

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::PyErr;

create_exception!(
    swarmplan,
    SwarmplanError,
    PyValueError,
    "Bad input to swarmplan (a scenario, plan, terrain or argument): the message names the \
     file or field, as the command-line tool does."
);

/// `e` as a [`SwarmplanError`] with its message (and its causes, joined as the CLI joins
/// them).
pub fn to_py(e: impl std::error::Error) -> PyErr {
    SwarmplanError::new_err(message(&e))
}

/// `e`'s message and its causes, joined as the CLI joins them.
pub fn message(e: &dyn std::error::Error) -> String {
    let mut out = e.to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        let text = c.to_string();
        if !out.contains(&text) {
            out.push_str(": ");
            out.push_str(&text);
        }
        cause = c.source();
    }
    out
}

/// A CLI message with its advice (the part after the last `; `, which names the CLI's
/// flags) replaced by `advice` in Python's terms; a message without one as it is.
pub fn with_advice(text: String, advice: &str) -> String {
    match text.rsplit_once("; ") {
        Some((head, _)) => format!("{head}; {advice}"),
        None => text,
    }
}

/// A [`SwarmplanError`] with `message`.
pub fn bad(message: impl Into<String>) -> PyErr {
    SwarmplanError::new_err(message.into())
}
