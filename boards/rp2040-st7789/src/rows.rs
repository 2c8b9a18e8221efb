//! Which core draws which row, and the order in which the rows go to the panel.
//!
//! The rows are dealt out in turn: row `r` is drawn by core `r mod cores`. The panel takes
//! them top to bottom, so each core is at most one row ahead of the other, and the ball,
//! the costliest part of a frame, is shared between the cores whatever its height.
//!
//! This file has no dependency: the host's tests (`tests/board.rs` in the crate's
//! repository) include it and check that rows drawn by separate cores, each with its own
//! copy of the scene, assemble the frame one core draws.

/// The core that draws `row` of a frame drawn by `cores` cores (1 or 2).
pub const fn core_of(row: u16, cores: u16) -> u16 {
    if cores <= 1 { 0 } else { row % cores }
}

/// The rows of a `height`-row frame that `core` draws, top to bottom.
pub fn rows_of(core: u16, cores: u16, height: u16) -> impl Iterator<Item = u16> {
    (0..height).filter(move |&row| core_of(row, cores) == core)
}
