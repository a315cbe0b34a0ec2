//! Stage `import`: not yet implemented (see the issue that introduces it).
