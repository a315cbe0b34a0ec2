//! Writes the corpus of geological situations (`test_support::geology`: faults with throw, a
//! fault dying out in a layer, an erosional unconformity, X and Y fault junctions, a recumbent
//! fold, a vertical tube, a salt stock, a closed salt diapir, a lens, a raft inside salt, a
//! chevron fold, an intrusion, a fault splay), one folder per case holding its recipe and TSurf
//! files, and under `known_gaps/` any situation that does not mesh yet, or not to the corpus's
//! quality bars, to try or to show: `cargo run --example geology_corpus -- /tmp/corpus`, then
//! `recipe build /tmp/corpus/<case>/<case>.toml`.

fn main() {
    let out = std::env::args()
        .nth(1)
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| "corpus".into());
    for case in test_support::geology::cases() {
        let path = case.write(&out.join(case.name));
        println!("wrote {} ({} regions)", path.display(), case.regions);
    }
    for case in test_support::geology::known_gaps() {
        let path = case.write(&out.join("known_gaps").join(case.name));
        println!("wrote {} (a known gap)", path.display());
    }
}
