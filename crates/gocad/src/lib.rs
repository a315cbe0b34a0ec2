//! gOcad ASCII import (`import`: TSurf, Model3d and group files to typed surfaces, PLine and Well
//! objects to lines and well paths) and the validation of the surfaces read (`validate`: the
//! seed's black-list of surface defects, reported with entity ids, source lines and coordinates).
//! Pure functions of the file bytes.

pub mod import;
pub mod validate;
