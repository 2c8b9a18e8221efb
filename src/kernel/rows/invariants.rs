//! The level-plane kernel's invariants, each tested on its own.
