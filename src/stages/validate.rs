//! Stage `validate`: not yet implemented (see the issue that introduces it).
