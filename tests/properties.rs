//! Seeded property tests of the plane test against f64, per format:
//! (a) on the same quantised inputs the arithmetic error stays inside the documented bound;
//! (b) on the exact inputs the hit/miss decision agrees except inside the documented bands
//!     around the epsilon, t = 0 and the format's range;
//! (c) a secondary ray spawned off a hit (offset by the computed residual bound) never
//!     hits the same plane again.
//!
//! One million cases per format per run, in debug builds (every operation overflow-checked)
//! and in release builds (`.ci/run` runs both).

mod common;
use common::sampling;

use fixray::num::variants::I16F16Narrow;
use fixray::{I16F16, I20F12, I32F32, Scalar};

const CASES: u64 = 1_000_000;

fn check<S: Scalar>() {
    let st = sampling::run::<S>(CASES, 0xF1C5_2026);
    println!("{}: {st:?}", S::NAME);
    let fail = |i: usize| st.first_failure[i].clone().unwrap_or_default();
    assert_eq!(st.cases, CASES);
    // Not vacuous: plenty of hits, spawns and near-epsilon disagreements exercised.
    assert!(st.same_input_hits > CASES / 4, "{}: {st:?}", S::NAME);
    assert!(st.spawned > CASES / 4, "{}: {st:?}", S::NAME);
    assert_eq!(st.over_bound, 0, "{}: {}", S::NAME, fail(0));
    assert_eq!(st.disagree_outside_band, 0, "{}: {}", S::NAME, fail(1));
    assert_eq!(st.rehits, 0, "{}: {}", S::NAME, fail(2));
    assert!(
        st.max_residual_ratio <= 1.0,
        "{}: residual over its bound",
        S::NAME
    );
}

#[test]
fn i16f16() {
    check::<I16F16>();
}

#[test]
fn i16f16_narrow() {
    // The narrow variant rounds each product towards −∞: neither the wide arithmetic
    // bound (a) nor the residual bound behind the spawn offset (c) covers it (measured in
    // docs/numerics.md: that is one reason it is not the default). Its decisions (b) must
    // still agree outside the bands.
    let st = sampling::run::<I16F16Narrow>(CASES, 0xF1C5_2026);
    println!("i16f16n: {st:?}");
    assert_eq!(st.disagree_outside_band, 0, "{:?}", st.first_failure[1]);
}

#[test]
fn i20f12() {
    check::<I20F12>();
}

#[test]
fn i32f32() {
    check::<I32F32>();
}

#[test]
fn f32() {
    check::<f32>();
}

#[test]
fn f64() {
    check::<f64>();
}
