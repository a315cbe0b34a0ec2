//! Stage `topology` (in progress).
