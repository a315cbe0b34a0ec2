//! `cli`: not yet implemented.
pub fn main() -> i32 { eprintln!("recipe: not yet implemented"); 2 }
