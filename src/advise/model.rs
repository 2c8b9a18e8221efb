//! The cost models, written by `cargo xtask calibrate` from the firmware's counts under
//! QEMU (`docs/calibration.md` holds every frame): do not edit.

use super::Model;

/// Every core × format calibrated: instructions per frame = Σ coefficient × count.
pub const MODELS: &[Model] = &[
    Model {
        core: "cortex-m0",
        format: "i16f16",
        coefficients: [
            1.042762e2, 0.000000e0, 2.612639e2, 4.307389e2, 2.930737e3, 0.000000e0, 0.000000e0,
            1.974164e4, 2.074150e2, 2.425949e3, 1.912530e3, 1.187393e4, 0.000000e0, 2.489274e3,
            1.291651e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3564, 2.4576),
    },
    Model {
        core: "cortex-m0",
        format: "i20f12",
        coefficients: [
            1.060887e2, 0.000000e0, 3.732445e2, 4.960937e2, 2.862971e3, 0.000000e0, 0.000000e0,
            2.141380e4, 0.000000e0, 2.685499e3, 1.895715e3, 1.218501e4, 0.000000e0, 2.268858e3,
            1.369488e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.2955, 1.3073),
    },
    Model {
        core: "cortex-m0",
        format: "i32f32",
        coefficients: [
            3.345105e2, 0.000000e0, 1.088664e3, 3.153534e3, 2.443956e4, 0.000000e0, 0.000000e0,
            5.406428e4, 3.556866e3, 1.450357e4, 1.214653e4, 1.029534e5, 0.000000e0, 0.000000e0,
            0.000000e0,
        ],
        sampled: false,
        frames: 13,
        error: (0.5467, 1.4496),
    },
    Model {
        core: "cortex-m0",
        format: "f32",
        coefficients: [
            2.665593e2, 4.860578e1, 9.677220e2, 1.898856e3, 5.456999e3, 0.000000e0, 3.493868e3,
            1.123562e4, 2.955097e3, 4.002510e3, 4.129786e3, 1.987166e4, 0.000000e0, 6.079354e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3284, 1.5922),
    },
    Model {
        core: "cortex-m4f",
        format: "i16f16",
        coefficients: [
            5.507123e1, 0.000000e0, 9.220897e1, 2.497215e2, 9.616074e2, 0.000000e0, 2.864911e2,
            4.372962e3, 9.803282e1, 7.713485e2, 6.804152e2, 4.568675e3, 0.000000e0, 8.847533e2,
            4.480288e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2552, 1.2883),
    },
    Model {
        core: "cortex-m4f",
        format: "i20f12",
        coefficients: [
            5.546075e1, 0.000000e0, 2.122490e2, 3.049193e2, 1.085262e3, 0.000000e0, 0.000000e0,
            5.545656e3, 0.000000e0, 9.043674e2, 8.770777e2, 5.959078e3, 0.000000e0, 8.411161e2,
            4.601243e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2002, 1.1418),
    },
    Model {
        core: "cortex-m4f",
        format: "i32f32",
        coefficients: [
            1.065805e2, 0.000000e0, 4.844345e2, 1.475839e3, 1.185798e4, 0.000000e0, 0.000000e0,
            1.816060e4, 1.970346e3, 6.131101e3, 5.024281e3, 5.134058e4, 0.000000e0, 0.000000e0,
            0.000000e0,
        ],
        sampled: false,
        frames: 13,
        error: (0.5004, 1.2960),
    },
    Model {
        core: "cortex-m4f",
        format: "f32",
        coefficients: [
            5.705060e1, 0.000000e0, 1.115472e2, 2.352412e2, 3.736077e2, 0.000000e0, 5.883429e2,
            0.000000e0, 3.757923e2, 2.264330e2, 3.640410e2, 1.180370e3, 0.000000e0, 6.515076e2,
            3.745556e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2255, 1.3773),
    },
    Model {
        core: "riscv32imc",
        format: "i16f16",
        coefficients: [
            7.593491e1, 0.000000e0, 1.235134e2, 2.588816e2, 1.393370e3, 0.000000e0, 2.391284e2,
            8.486256e3, 1.645285e2, 1.147839e3, 9.476153e2, 5.771896e3, 0.000000e0, 1.228295e3,
            4.392463e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.3056, 1.1547),
    },
    Model {
        core: "riscv32imc",
        format: "i20f12",
        coefficients: [
            7.682683e1, 0.000000e0, 2.330008e2, 3.142587e2, 1.479758e3, 0.000000e0, 0.000000e0,
            8.638871e3, 1.364788e1, 1.287019e3, 1.095173e3, 6.952085e3, 0.000000e0, 1.150207e3,
            4.689773e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2301, 1.1118),
    },
    Model {
        core: "riscv32imc",
        format: "i32f32",
        coefficients: [
            1.546859e2, 0.000000e0, 5.736289e2, 1.304932e3, 1.351012e4, 0.000000e0, 1.288963e3,
            4.473091e4, 2.384891e3, 8.483462e3, 5.877440e3, 5.771184e4, 0.000000e0, 6.517317e3,
            1.562668e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3503, 1.3643),
    },
    Model {
        core: "riscv32imc",
        format: "f32",
        coefficients: [
            1.539943e2, 6.351990e1, 6.198339e2, 1.190539e3, 3.357672e3, 0.000000e0, 2.110237e3,
            5.312602e3, 2.008642e3, 2.269505e3, 2.695910e3, 1.184513e4, 0.000000e0, 3.912044e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3235, 1.5998),
    },
];

/// Cycles per instruction of the RP2040's Cortex-M0+ on this code: the emulated board's
/// whole exact frame of the boing ball at 240×240 (868.7 cycles per pixel at 200 MHz)
/// over the Cortex-M0's count of `scenes/boing-240x240.scene` in I16F16 (799.4
/// instructions per pixel).
pub const RP2040_CYCLES_PER_INSTRUCTION: f64 = 1.0867;
