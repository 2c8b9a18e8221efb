//! The fast kernel's invariants, each tested on its own.
