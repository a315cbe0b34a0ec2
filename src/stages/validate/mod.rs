//! Stage `validate` (in progress).
