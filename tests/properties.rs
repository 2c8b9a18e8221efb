//! Seeded property tests of the plane test against f64, per format:
//! (a) on the same quantised inputs the arithmetic error stays inside the documented bound;
//! (b) on the exact inputs the hit/miss decision agrees except inside the documented bands
//!     around the epsilon, t = 0 and the format's range;
//! (c) a secondary ray spawned off a hit (offset by the computed residual bound) never
//!     hits the same plane again.
//!
//! One million cases per format per run, in every format of the one list
//! (`fixray::num::formats::FORMATS`), in debug builds (every operation overflow-checked)
//! and in release builds (`.ci/run` runs both).

mod common;

use common::probes::dot_rounds_once;
use common::sampling;

use fixray::Scalar;
use fixray::num::formats::FORMATS;

const CASES: u64 = 1_000_000;

fn check<S: Scalar>() {
    let st = sampling::run::<S>(CASES, 0xF1C5_2026);
    println!("{}: {st:?}", S::NAME);
    let fail = |i: usize| st.first_failure[i].clone().unwrap_or_default();
    assert_eq!(st.cases, CASES);
    // Not vacuous: plenty of hits, spawns and near-epsilon disagreements exercised.
    assert!(st.same_input_hits > CASES / 4, "{}: {st:?}", S::NAME);
    assert!(st.spawned > CASES / 4, "{}: {st:?}", S::NAME);
    // The decisions (b) must agree outside the bands in every format.
    assert_eq!(st.disagree_outside_band, 0, "{}: {}", S::NAME, fail(1));
    if !dot_rounds_once::<S>() {
        // Neither the wide arithmetic bound (a) nor the residual bound behind the spawn
        // offset (c) covers products rounded one by one (measured in docs/numerics.md:
        // one reason the narrow variant is not the default).
        return;
    }
    assert_eq!(st.over_bound, 0, "{}: {}", S::NAME, fail(0));
    assert_eq!(st.rehits, 0, "{}: {}", S::NAME, fail(2));
    assert!(
        st.max_residual_ratio <= 1.0,
        "{}: residual over its bound",
        S::NAME
    );
}

/// Every format on its own thread (as many cases as one test per format, side by side).
#[test]
fn the_plane_test_keeps_its_properties_in_every_format() {
    std::thread::scope(|threads| {
        for name in FORMATS {
            threads.spawn(move || fixray::with_format!(name, check()).unwrap());
        }
    });
    // Not vacuous: the bounds (a) and (c) apply to the main formats.
    for name in fixray::num::formats::MAIN {
        assert!(
            fixray::with_format!(name, dot_rounds_once()).unwrap(),
            "{name}"
        );
    }
}
