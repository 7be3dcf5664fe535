//! Stable sorting of what a leap gathers: already in order, or a few runs
//! in order (the phases of a layer's two lanes, the fronts of a leap that
//! ends within one round trip of their last returns, the births of its
//! trains round by round). Merging the runs gives the stable sort's
//! result in a pass or two; `sort_by` took a fifth of the work of a leap
//! over a chatter's short contact (callgrind, the 20 hardest points of the
//! paper's grid).

/// Most runs merged; more go to `sort_by` (the input is then no longer
/// a few sorted runs, and merging gains nothing).
const MOST_RUNS: usize = 8;

/// Sorts `v` by `key` as a stable `sort_by` on `partial_cmp` would (equal
/// keys keep their order): by merging its non-decreasing runs, pair by
/// pair, where it has at most [`MOST_RUNS`] of them, else by `sort_by`.
/// `scratch` holds the left run of each merge. Keys are never NaN (times
/// and jumps of fronts).
pub(crate) fn sort_stably<T: Copy, K: PartialOrd>(
    v: &mut [T],
    scratch: &mut Vec<T>,
    key: impl Fn(&T) -> K,
) {
    // run boundaries: runs are bounds[j]..bounds[j + 1]
    let mut bounds = [0usize; MOST_RUNS + 1];
    let mut runs = 0;
    for i in 1..v.len() {
        if key(&v[i]) < key(&v[i - 1]) {
            runs += 1;
            if runs == MOST_RUNS {
                return sort_by_key(v, &key);
            }
            bounds[runs] = i;
        }
    }
    runs += 1;
    bounds[runs] = v.len();
    while runs > 1 {
        let mut merged = 0;
        let mut j = 0;
        while j < runs {
            let (a, b) = (bounds[j], bounds[j + 1]);
            let c = if j + 2 <= runs { bounds[j + 2] } else { b };
            if c > b {
                merge(&mut v[a..c], b - a, scratch, &key);
            }
            bounds[merged] = a;
            merged += 1;
            j += 2;
        }
        bounds[merged] = v.len();
        runs = merged;
    }
}

/// Most distinct keys [`sort_by_few_keys`] sorts by one pass each; more
/// go to `sort_by`.
const MOST_KEYS: usize = 8;

/// Sorts `v` by `key` as a stable `sort_by` on `partial_cmp` would, where
/// it holds at most [`MOST_KEYS`] distinct keys: a pass over a copy for
/// each key, in increasing order (else by `sort_by`). What it is for: the
/// trains a leap deposits together end in one of a few rounds, and sorted
/// by them, the library's sort finds few runs and partitions. Keys are
/// never NaN.
pub(crate) fn sort_by_few_keys<T: Copy, K: PartialOrd + Copy>(
    v: &mut [T],
    scratch: &mut Vec<T>,
    key: impl Fn(&T) -> K,
) {
    let mut keys = [None; MOST_KEYS];
    let mut distinct = 0;
    for x in v.iter() {
        let k = key(x);
        if keys[..distinct].contains(&Some(k)) {
            continue;
        }
        if distinct == MOST_KEYS {
            return sort_by_key(v, &key);
        }
        keys[distinct] = Some(k);
        distinct += 1;
    }
    if distinct < 2 {
        return;
    }
    let keys = &mut keys[..distinct];
    keys.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
    scratch.clear();
    scratch.extend_from_slice(v);
    let mut out = 0;
    for k in keys.iter().flatten() {
        for x in scratch.iter() {
            if key(x) == *k {
                v[out] = *x;
                out += 1;
            }
        }
    }
}

/// The library's stable sort by `key` (never NaN): what both sorts fall
/// back on.
fn sort_by_key<T, K: PartialOrd>(v: &mut [T], key: &impl Fn(&T) -> K) {
    v.sort_by(|a, b| {
        key(a)
            .partial_cmp(&key(b))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
}

/// Merges the sorted `v[..split]` and `v[split..]` stably.
fn merge<T: Copy, K: PartialOrd>(
    v: &mut [T],
    split: usize,
    scratch: &mut Vec<T>,
    key: &impl Fn(&T) -> K,
) {
    scratch.clear();
    scratch.extend_from_slice(&v[..split]);
    // written from the front: at most as many written as read from the
    // second run, so its unread part is never overwritten
    let (mut a, mut b, mut out) = (0, split, 0);
    while a < scratch.len() && b < v.len() {
        // the first run's element on ties (stability)
        if key(&v[b]) < key(&scratch[a]) {
            v[out] = v[b];
            b += 1;
        } else {
            v[out] = scratch[a];
            a += 1;
        }
        out += 1;
    }
    while a < scratch.len() {
        v[out] = scratch[a];
        a += 1;
        out += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pair sorted by its first element, which the second tags.
    type Tagged = (f64, u32);

    /// A sort under test: the runs' or by few keys.
    type Sort = fn(&mut [Tagged], &mut Vec<Tagged>, fn(&Tagged) -> f64);

    /// `sort` on `v` gives the standard library's stable sort by the
    /// first element.
    fn check(sort: Sort, v: Vec<Tagged>) {
        let mut expected = v.clone();
        expected.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(std::cmp::Ordering::Equal));
        let mut got = v.clone();
        sort(&mut got, &mut Vec::new(), |x| x.0);
        assert_eq!(got, expected, "input {v:?}");
    }

    /// Against the standard library's stable sort: sorted input, runs
    /// with ties across them (stability), more runs than are merged (the
    /// fallback), and the empty and single cases; pseudo-random sequences
    /// of one to twelve runs.
    #[test]
    fn sorts_as_the_stable_sort_does() {
        let check = |v| check(sort_stably, v);
        check(vec![]);
        check(vec![(1.0, 0)]);
        check(vec![(1.0, 0), (2.0, 1), (2.0, 2), (3.0, 3)]);
        check(vec![
            (1.0, 0),
            (2.0, 1),
            (3.0, 2),
            (0.5, 3),
            (2.0, 4),
            (4.0, 5),
        ]);
        check(vec![(3.0, 0), (1.0, 1), (2.0, 2), (0.0, 3)]);
        check(vec![(2.0, 0), (2.0, 1), (1.0, 2), (2.0, 3), (2.0, 4)]);
        // xorshift: runs of random lengths, values with many ties
        let mut next = crate::test_random::xorshift(0x9e37_79b9_7f4a_7c15u64);
        for case in 0..600 {
            let runs = 1 + case % 12;
            let mut v = Vec::new();
            for _ in 0..runs {
                let len = (next() % 12) as usize;
                let mut x = (next() % 5) as f64;
                for _ in 0..len {
                    x += (next() % 3) as f64 * 0.5;
                    v.push((x, v.len() as u32));
                }
            }
            check(v);
        }
    }

    /// [`sort_by_few_keys`] against the standard library's stable sort:
    /// one to twelve distinct keys in random order (past eight, the
    /// fallback), ties everywhere (stability), empty and single.
    #[test]
    fn sorts_by_few_keys_as_the_stable_sort_does() {
        let check = |v| check(sort_by_few_keys, v);
        check(vec![]);
        check(vec![(1.0, 0)]);
        check(vec![(2.0, 0), (1.0, 1), (2.0, 2), (1.0, 3)]);
        let mut next = crate::test_random::xorshift(0x2545_f491_4f6c_dd1du64);
        for case in 0..600 {
            let keys = 1 + case % 12;
            let len = (next() % 40) as usize;
            let v = (0..len)
                .map(|n| ((next() % keys as u64) as f64 * 0.25 - 1.0, n as u32))
                .collect();
            check(v);
        }
    }
}
