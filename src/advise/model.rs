//! The cost models, written by `cargo xtask calibrate` from the firmware's counts under
//! QEMU (`docs/calibration.md` holds every frame): do not edit.

use super::Model;

/// Every core × format calibrated: instructions per frame = Σ coefficient × count.
pub const MODELS: &[Model] = &[
    Model {
        core: "cortex-m0",
        format: "i16f16",
        coefficients: [
            1.042671e2, 0.000000e0, 2.585534e2, 4.305580e2, 2.930744e3, 0.000000e0, 0.000000e0,
            1.975481e4, 2.249839e2, 2.416817e3, 1.912901e3, 1.187391e4, 0.000000e0, 2.487866e3,
            1.292583e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3566, 2.4004),
    },
    Model {
        core: "cortex-m0",
        format: "i20f12",
        coefficients: [
            1.061028e2, 0.000000e0, 3.752452e2, 4.960782e2, 2.862962e3, 0.000000e0, 0.000000e0,
            2.141346e4, 0.000000e0, 2.685495e3, 1.895735e3, 1.218502e4, 0.000000e0, 2.269168e3,
            1.369188e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.2929, 1.2969),
    },
    Model {
        core: "cortex-m0",
        format: "i32f32",
        coefficients: [
            3.345106e2, 0.000000e0, 1.088272e3, 3.153545e3, 2.443956e4, 0.000000e0, 0.000000e0,
            5.405272e4, 3.556691e3, 1.450315e4, 1.214651e4, 1.029534e5, 0.000000e0, 0.000000e0,
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
            2.665901e2, 4.857883e1, 9.635815e2, 1.898662e3, 5.456793e3, 0.000000e0, 3.494215e3,
            1.107494e4, 2.964058e3, 3.990259e3, 4.129802e3, 1.987004e4, 0.000000e0, 6.078853e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3263, 1.5964),
    },
    Model {
        core: "cortex-m4f",
        format: "i16f16",
        coefficients: [
            5.507071e1, 0.000000e0, 9.160768e1, 2.497052e2, 9.615316e2, 0.000000e0, 2.866304e2,
            4.364250e3, 9.776282e1, 7.711024e2, 6.803047e2, 4.568005e3, 0.000000e0, 8.846957e2,
            4.481979e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2556, 1.2898),
    },
    Model {
        core: "cortex-m4f",
        format: "i20f12",
        coefficients: [
            5.545666e1, 0.000000e0, 2.118062e2, 3.049214e2, 1.085264e3, 0.000000e0, 0.000000e0,
            5.545065e3, 0.000000e0, 9.041672e2, 8.770776e2, 5.959083e3, 0.000000e0, 8.410760e2,
            4.602393e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2002, 1.1452),
    },
    Model {
        core: "cortex-m4f",
        format: "i32f32",
        coefficients: [
            1.065805e2, 0.000000e0, 4.842473e2, 1.475824e3, 1.185798e4, 0.000000e0, 0.000000e0,
            1.815410e4, 1.970617e3, 6.130655e3, 5.024311e3, 5.134057e4, 0.000000e0, 0.000000e0,
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
            5.705287e1, 0.000000e0, 1.114682e2, 2.352427e2, 3.736062e2, 0.000000e0, 5.883436e2,
            0.000000e0, 3.757125e2, 2.264807e2, 3.640370e2, 1.180367e3, 0.000000e0, 6.515044e2,
            3.745386e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2255, 1.3777),
    },
    Model {
        core: "riscv32imc",
        format: "i16f16",
        coefficients: [
            7.593472e1, 0.000000e0, 1.230865e2, 2.588362e2, 1.393233e3, 0.000000e0, 2.393779e2,
            8.477360e3, 1.647891e2, 1.147284e3, 9.474490e2, 5.770719e3, 0.000000e0, 1.228202e3,
            4.393472e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.3060, 1.1538),
    },
    Model {
        core: "riscv32imc",
        format: "i20f12",
        coefficients: [
            7.682693e1, 0.000000e0, 2.328165e2, 3.142644e2, 1.479758e3, 0.000000e0, 0.000000e0,
            8.637827e3, 1.352723e1, 1.286833e3, 1.095162e3, 6.952085e3, 0.000000e0, 1.150131e3,
            4.690499e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2301, 1.1117),
    },
    Model {
        core: "riscv32imc",
        format: "i32f32",
        coefficients: [
            1.546860e2, 0.000000e0, 5.731907e2, 1.304843e3, 1.350984e4, 0.000000e0, 1.289479e3,
            4.472380e4, 2.384982e3, 8.483066e3, 5.877085e3, 5.770942e4, 0.000000e0, 6.517147e3,
            1.562783e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3503, 1.3650),
    },
    Model {
        core: "riscv32imc",
        format: "f32",
        coefficients: [
            1.540103e2, 6.350390e1, 6.177955e2, 1.190467e3, 3.357585e3, 0.000000e0, 2.110379e3,
            5.243247e3, 2.012160e3, 2.264360e3, 2.695905e3, 1.184447e4, 0.000000e0, 3.911780e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3239, 1.6029),
    },
];

/// Cycles per instruction of the RP2040's Cortex-M0+ on this code: the emulated board's
/// whole exact frame of the boing ball at 240×240 (989.4 cycles per pixel at 200 MHz)
/// over the Cortex-M0's count of `scenes/boing-240x240.scene` in I16F16 (805.3
/// instructions per pixel).
pub const RP2040_CYCLES_PER_INSTRUCTION: f64 = 1.2287;
