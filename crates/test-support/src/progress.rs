//! What a progress bar must be told by a stage that reports progress (`geom::progress`).

/// Asserts that `seen`, the `(done, total)` reports of one run that succeeded, make a good bar:
/// one total, `done` strictly growing from 0 to the total, at most a few hundred reports, and
/// no jump over more than a fifth of the bar (so it moves during the work, not only at its ends).
pub fn assert_a_good_bar(what: &str, seen: &[(u64, u64)]) {
    let total = seen
        .first()
        .unwrap_or_else(|| panic!("{what}: no report"))
        .1;
    assert!(total > 0, "{what}: {seen:?}");
    assert!(seen.iter().all(|&(_, t)| t == total), "{what}: {seen:?}");
    assert!(
        seen.windows(2).all(|w| w[0].0 < w[1].0),
        "{what}: done goes back or repeats: {seen:?}"
    );
    assert_eq!(seen[0].0, 0, "{what}: {seen:?}");
    assert_eq!(seen.last(), Some(&(total, total)), "{what}: {seen:?}");
    assert!(seen.len() <= 300, "{what}: {} reports", seen.len());
    let jump = seen
        .windows(2)
        .map(|w| w[1].0 - w[0].0)
        .max()
        .unwrap_or(total);
    assert!(
        5 * jump <= total,
        "{what}: a jump of {jump} of {total}: {seen:?}"
    );
}
