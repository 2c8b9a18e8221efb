//! The cost models, written by `cargo xtask calibrate` from the firmware's counts under
//! QEMU (`docs/calibration.md` holds every frame): do not edit.

use super::Model;

/// Every core × format calibrated: instructions per frame = Σ coefficient × count.
pub const MODELS: &[Model] = &[
    Model {
        core: "cortex-m0",
        format: "i16f16",
        coefficients: [
            1.042450e2, 0.000000e0, 2.553556e2, 4.295829e2, 2.906296e3, 0.000000e0, 4.566684e1,
            1.910024e4, 2.783824e2, 2.356005e3, 1.867672e3, 1.165308e4, 0.000000e0, 2.533712e3,
            1.198317e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3383, 2.3596),
    },
    Model {
        core: "cortex-m0",
        format: "i20f12",
        coefficients: [
            1.061153e2, 0.000000e0, 3.950218e2, 5.034952e2, 2.862667e3, 0.000000e0, 0.000000e0,
            1.988935e4, 0.000000e0, 2.634348e3, 1.880657e3, 1.218747e4, 0.000000e0, 2.332496e3,
            1.261628e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3304, 1.2645),
    },
    Model {
        core: "cortex-m0",
        format: "i32f32",
        coefficients: [
            3.345014e2, 0.000000e0, 1.120066e3, 3.146858e3, 2.443839e4, 0.000000e0, 0.000000e0,
            5.492948e4, 3.624281e3, 1.450568e4, 1.214772e4, 1.029633e5, 0.000000e0, 0.000000e0,
            0.000000e0,
        ],
        sampled: false,
        frames: 13,
        error: (0.5467, 1.4492),
    },
    Model {
        core: "cortex-m0",
        format: "f32",
        coefficients: [
            2.465148e2, 6.865415e1, 9.113113e2, 1.857342e3, 5.270369e3, 0.000000e0, 3.858937e3,
            1.021843e4, 3.170226e3, 3.823443e3, 3.856190e3, 1.811586e4, 0.000000e0, 5.643546e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3268, 1.6560),
    },
    Model {
        core: "cortex-m4f",
        format: "i16f16",
        coefficients: [
            5.520932e1, 0.000000e0, 8.630679e1, 2.470036e2, 9.559934e2, 0.000000e0, 2.986735e2,
            4.295341e3, 1.366808e2, 7.459976e2, 6.681344e2, 4.501431e3, 0.000000e0, 8.466448e2,
            3.850779e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2831, 1.2173),
    },
    Model {
        core: "cortex-m4f",
        format: "i20f12",
        coefficients: [
            5.562750e1, 0.000000e0, 2.133927e2, 3.086610e2, 1.086329e3, 0.000000e0, 0.000000e0,
            4.635040e3, 0.000000e0, 8.741022e2, 8.644193e2, 5.949335e3, 0.000000e0, 7.992567e2,
            4.064276e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.1742, 1.1810),
    },
    Model {
        core: "cortex-m4f",
        format: "i32f32",
        coefficients: [
            1.065759e2, 0.000000e0, 4.890026e2, 1.484516e3, 1.185631e4, 0.000000e0, 0.000000e0,
            1.781514e4, 1.969619e3, 6.115989e3, 5.020703e3, 5.135910e4, 0.000000e0, 0.000000e0,
            0.000000e0,
        ],
        sampled: false,
        frames: 13,
        error: (0.5005, 1.2959),
    },
    Model {
        core: "cortex-m4f",
        format: "f32",
        coefficients: [
            5.745930e1, 0.000000e0, 1.072562e2, 2.294053e2, 3.740605e2, 0.000000e0, 5.871214e2,
            3.550436e2, 4.201892e2, 2.222887e2, 3.765665e2, 1.186252e3, 0.000000e0, 5.387893e2,
            3.055971e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2269, 1.3609),
    },
    Model {
        core: "riscv32imc",
        format: "i16f16",
        coefficients: [
            7.597129e1, 0.000000e0, 1.167894e2, 2.542733e2, 1.366724e3, 0.000000e0, 2.899432e2,
            8.200318e3, 1.997528e2, 1.113411e3, 9.043632e2, 5.521174e3, 0.000000e0, 1.170488e3,
            4.843848e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.3051, 1.1244),
    },
    Model {
        core: "riscv32imc",
        format: "i20f12",
        coefficients: [
            7.678193e1, 0.000000e0, 2.381143e2, 3.178594e2, 1.479814e3, 0.000000e0, 0.000000e0,
            7.897988e3, 4.424566e1, 1.248537e3, 1.091033e3, 6.951793e3, 0.000000e0, 1.096112e3,
            5.192616e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2185, 0.9405),
    },
    Model {
        core: "riscv32imc",
        format: "i32f32",
        coefficients: [
            0.000000e0, 1.544521e2, 5.555548e2, 1.348451e3, 1.336980e4, 0.000000e0, 1.710373e3,
            4.046613e4, 2.732496e3, 8.082368e3, 5.521269e3, 5.560531e4, 0.000000e0, 8.167068e3,
            2.111674e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3460, 1.6712),
    },
    Model {
        core: "riscv32imc",
        format: "f32",
        coefficients: [
            1.506668e2, 6.684647e1, 5.875472e2, 1.163145e3, 3.242808e3, 0.000000e0, 2.323542e3,
            4.774924e3, 2.112525e3, 2.179394e3, 2.533944e3, 1.083305e4, 0.000000e0, 3.577082e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3097, 1.6463),
    },
];

/// Cycles per instruction of the RP2040's Cortex-M0+ on this code: the emulated board's
/// whole exact frame of the boing ball at 240×240 (1048.9 cycles per pixel at 200 MHz)
/// over the Cortex-M0's count of `scenes/boing-240x240.scene` in I16F16 (817.3
/// instructions per pixel).
pub const RP2040_CYCLES_PER_INSTRUCTION: f64 = 1.2834;
