// The scene language's reference: `docs/scene-format.md`, shown here by rustdoc. Its
// tables are generated from `parse/schema.rs` (`cargo xtask scene-format`), and
// `tests/scene_format.rs` checks them and parses every example.
#![doc = include_str!("../../docs/scene-format.md")]
