//! Exact double-width products of the fixed formats' bit patterns: one long multiply where
//! the core has it, 16-bit halves where it does not (Cortex-M0: no `SMULL`; the build
//! script sets `no_long_multiply` for such targets).

/// The exact product of two `i32`s, from four 16 × 16 → 32 multiplications: what a core
/// without a long multiply (Cortex-M0: no `SMULL`) does far faster than the 64-bit
/// multiply helper (per-operation costs: `docs/performance.md`).
/// Bit-identical to `i64::from(a) * i64::from(b)` (tested on every sign and size).
#[inline(always)]
#[cfg_attr(
    any(not(no_long_multiply), all(target_arch = "arm", feature = "kernels")),
    allow(dead_code)
)]
pub(crate) fn mul_wide_halves(a: i32, b: i32) -> i64 {
    // a = ah·2¹⁶ + al with ah signed and al in [0, 2¹⁶); the same for b.
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    // |ah·bh| ≤ 2³⁰; |ah·bl|, |al·bh| < 2³¹; al·bl < 2³² (u32).
    let high = i64::from(ah * bh);
    let middle = i64::from(ah * bl) + i64::from(al * bh);
    let low = i64::from(al.cast_unsigned() * bl.cast_unsigned());
    (high << 32) + (middle << 16) + low
}

/// The exact product of two `i32`s: one long multiply where the core has it, otherwise
/// [`mul_wide_halves`] (chosen by the build script for the target, not by the format).
#[inline(always)]
pub(crate) fn mul_wide_i32(a: i32, b: i32) -> i64 {
    #[cfg(no_long_multiply)]
    {
        mul_wide_halves_call(a, b)
    }
    #[cfg(not(no_long_multiply))]
    {
        i64::from(a) * i64::from(b)
    }
}

/// [`mul_wide_halves`] as one function (a call, as the 64-bit helper is, but about a third
/// of its instructions): inlined at every product it would add kilobytes of flash. On
/// ARMv6-M with the kernels (the crate's speed, `kernels`) the leaf below instead; without
/// them this one, whose callers the compiler sees through and keep their registers
/// (about 400 bytes less flash, the reference path's build fitting 64 KB).
#[cfg(all(no_long_multiply, not(all(target_arch = "arm", feature = "kernels"))))]
#[inline(never)]
fn mul_wide_halves_call(a: i32, b: i32) -> i64 {
    mul_wide_halves(a, b)
}

/// [`mul_wide_halves`] on ARMv6-M in 25 instructions that save two registers only (the
/// compiled function saves five and keeps a frame): the unsigned product of the halves,
/// then the high word less `b` where `a < 0` and `a` where `b < 0` (two's complement).
/// Bit for bit the same product: the firmware's frames, whose hashes are checked against
/// the host's, take every product through it. About 3 % fewer cycles for a whole frame
/// on the emulated RP2040; its callers cannot see which registers it keeps, and save
/// more (a few hundred bytes of flash).
#[cfg(all(no_long_multiply, target_arch = "arm", feature = "kernels"))]
#[unsafe(naked)]
extern "C" fn mul_wide_halves_call(a: i32, b: i32) -> i64 {
    core::arch::naked_asm!(
        "push {{r4, r5}}",
        // The high word's correction: (a < 0 ? b : 0) + (b < 0 ? a : 0).
        "asrs r2, r0, #31",
        "ands r2, r1",
        "asrs r3, r1, #31",
        "ands r3, r0",
        "adds r5, r2, r3",
        // The halves, unsigned: r2 = a.lo, r0 = a.hi, r3 = b.lo, r1 = b.hi.
        "uxth r2, r0",
        "lsrs r0, r0, #16",
        "uxth r3, r1",
        "lsrs r1, r1, #16",
        "movs r4, r2",
        "muls r4, r3", // a.lo·b.lo
        "muls r2, r1", // a.lo·b.hi
        "muls r3, r0", // a.hi·b.lo
        "muls r1, r0", // a.hi·b.hi
        // The middle sum, its carry in r0 (below 2³³).
        "movs r0, #0",
        "adds r2, r2, r3",
        "adcs r0, r0",
        "lsls r0, r0, #16",
        "lsls r3, r2, #16",
        "lsrs r2, r2, #16",
        "adds r2, r2, r0",
        // Low word, and the high word with its carry; then the correction.
        "adds r0, r4, r3",
        "adcs r1, r2",
        "subs r1, r1, r5",
        "pop {{r4, r5}}",
        "bx lr",
    )
}

/// The exact product of two `u32`s: one long multiply where the core has it, otherwise
/// from 16-bit halves as [`mul_wide_halves`].
#[inline(always)]
pub(crate) fn mul_wide_u32(a: u32, b: u32) -> u64 {
    #[cfg(no_long_multiply)]
    {
        let (ah, al) = (a >> 16, a & 0xFFFF);
        let (bh, bl) = (b >> 16, b & 0xFFFF);
        let middle = u64::from(ah * bl) + u64::from(al * bh);
        (u64::from(ah * bh) << 32) + (middle << 16) + u64::from(al * bl)
    }
    #[cfg(not(no_long_multiply))]
    {
        u64::from(a) * u64::from(b)
    }
}

/// The exact product of two `i64`s (`I32F32`'s double width). One shared function: a
/// 128-bit product inlined at every use would double I32F32's flash on a 32-bit core.
#[inline(never)]
pub(crate) fn mul_wide_i64(a: i64, b: i64) -> i128 {
    i128::from(a) * i128::from(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_from_halves_are_exact() {
        let edges = [
            i32::MIN,
            i32::MIN + 1,
            -65_537,
            -65_536,
            -65_535,
            -1,
            0,
            1,
            0xFFFF,
            0x1_0000,
            0x1_0001,
            i32::MAX - 1,
            i32::MAX,
        ];
        for a in edges {
            for b in edges {
                assert_eq!(
                    mul_wide_halves(a, b),
                    i64::from(a) * i64::from(b),
                    "{a} {b}"
                );
            }
        }
        // A seeded sweep (xorshift) over every size.
        let mut x: u32 = 0x2026_1124;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            let a = x.cast_signed() >> (x % 31);
            let b = x.rotate_left(11).cast_signed() >> (x % 29);
            assert_eq!(
                mul_wide_halves(a, b),
                i64::from(a) * i64::from(b),
                "{a} {b}"
            );
        }
    }
}
