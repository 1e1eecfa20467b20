//! Statistical tests (in progress).
