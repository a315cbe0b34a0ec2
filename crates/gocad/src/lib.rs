//! gOcad ASCII import (`import`: TSurf, Model3d and group files to typed surfaces) and the
//! validation of what was read (`validate`: the seed's black-list of surface defects, reported
//! with entity ids, source lines and coordinates). Pure functions of the file bytes.

pub mod import;
pub mod validate;
