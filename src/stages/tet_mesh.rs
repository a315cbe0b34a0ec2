//! Stage `tet_mesh`: not yet implemented (see the issue that introduces it).
