//! 32-bit division on the RP2040's divider in the `emulated` build too.
//!
//! That build turns on rp2040-hal's `disable-intrinsics` (the emulator has no boot ROM for
//! the memory and bit intrinsics the HAL routes there), which also stops the HAL from
//! exporting its divider routines as `__aeabi_uidiv` and `__aeabi_idiv`. These entry
//! points jump to the same routines, so that both builds divide alike: the emulated one
//! pays one load and one jump more per division. Memory and bit intrinsics stay Rust's.

core::arch::global_asm!(
    ".section .text.fixray_divide, \"ax\", %progbits",
    ".balign 4",
    ".global __aeabi_uidiv",
    ".global __aeabi_uidivmod",
    ".type __aeabi_uidiv, %function",
    ".type __aeabi_uidivmod, %function",
    ".thumb_func",
    "__aeabi_uidiv:",
    ".thumb_func",
    "__aeabi_uidivmod:",
    "    ldr r3, 1f",
    "    bx r3",
    ".size __aeabi_uidiv, 4",
    ".size __aeabi_uidivmod, 4",
    ".global __aeabi_idiv",
    ".global __aeabi_idivmod",
    ".type __aeabi_idiv, %function",
    ".type __aeabi_idivmod, %function",
    ".thumb_func",
    "__aeabi_idiv:",
    ".thumb_func",
    "__aeabi_idivmod:",
    "    ldr r3, 2f",
    "    bx r3",
    ".size __aeabi_idiv, 4",
    ".size __aeabi_idivmod, 4",
    ".balign 4",
    // The divider routines' addresses (with the Thumb bit, set by the linker).
    "1: .word _rphal_unsigned_divmod",
    "2: .word _rphal_signed_divmod",
);
