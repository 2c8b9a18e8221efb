//! The cost models, written by `cargo xtask calibrate` from the firmware's counts under
//! QEMU (`docs/calibration.md` holds every frame): do not edit.

use super::Model;

/// Every core × format calibrated: instructions per frame = Σ coefficient × count.
pub const MODELS: &[Model] = &[
    Model {
        core: "cortex-m0",
        format: "i16f16",
        coefficients: [
            0.000000e0, 1.039999e2, 2.828794e2, 4.496890e2, 3.001570e3, 0.000000e0, 0.000000e0,
            2.106230e4, 3.914368e2, 2.388772e3, 2.004753e3, 1.180767e4, 0.000000e0, 2.498506e3,
            2.789509e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3089, 1.9729),
    },
    Model {
        core: "cortex-m0",
        format: "i20f12",
        coefficients: [
            0.000000e0, 1.057675e2, 4.571358e2, 5.203075e2, 2.934150e3, 0.000000e0, 0.000000e0,
            2.171955e4, 0.000000e0, 2.720006e3, 1.978913e3, 1.212368e4, 0.000000e0, 2.314590e3,
            2.926869e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3521, 1.3290),
    },
    Model {
        core: "cortex-m0",
        format: "i32f32",
        coefficients: [
            3.344294e2, 0.000000e0, 1.198931e3, 3.144289e3, 2.437148e4, 0.000000e0, 0.000000e0,
            5.532665e4, 3.661236e3, 1.450221e4, 1.216735e4, 1.037252e5, 0.000000e0, 0.000000e0,
            0.000000e0,
        ],
        sampled: false,
        frames: 13,
        error: (0.5472, 1.4494),
    },
    Model {
        core: "cortex-m0",
        format: "f32",
        coefficients: [
            2.336134e2, 8.153590e1, 9.458101e2, 1.865986e3, 5.265437e3, 0.000000e0, 3.887127e3,
            9.581046e3, 3.203419e3, 3.786007e3, 3.841688e3, 1.792563e4, 0.000000e0, 5.491686e3,
            3.671368e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.3689, 1.6386),
    },
    Model {
        core: "cortex-m4f",
        format: "i16f16",
        coefficients: [
            0.000000e0, 5.473804e1, 1.095775e2, 2.680326e2, 1.016723e3, 0.000000e0, 2.450996e2,
            4.760359e3, 1.901163e2, 7.390608e2, 7.378751e2, 4.595460e3, 0.000000e0, 8.386186e2,
            1.371201e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.2677, 1.0381),
    },
    Model {
        core: "cortex-m4f",
        format: "i20f12",
        coefficients: [
            0.000000e0, 5.518928e1, 2.497715e2, 3.174968e2, 1.118040e3, 0.000000e0, 0.000000e0,
            5.381313e3, 0.000000e0, 9.073189e2, 9.036835e2, 5.789261e3, 0.000000e0, 7.958320e2,
            1.404596e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.2001, 1.2464),
    },
    Model {
        core: "cortex-m4f",
        format: "i32f32",
        coefficients: [
            1.065611e2, 0.000000e0, 5.218570e2, 1.484178e3, 1.177418e4, 0.000000e0, 0.000000e0,
            1.788126e4, 1.975479e3, 6.114742e3, 5.026369e3, 5.209237e4, 0.000000e0, 0.000000e0,
            0.000000e0,
        ],
        sampled: false,
        frames: 13,
        error: (0.5029, 1.2961),
    },
    Model {
        core: "cortex-m4f",
        format: "f32",
        coefficients: [
            1.397567e1, 4.244619e1, 1.206984e2, 2.431858e2, 4.239814e2, 0.000000e0, 5.488050e2,
            9.846811e2, 4.450784e2, 2.398392e2, 4.409915e2, 1.314867e3, 0.000000e0, 5.417461e2,
            1.219641e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.2395, 1.3380),
    },
    Model {
        core: "riscv32imc",
        format: "i16f16",
        coefficients: [
            0.000000e0, 7.549051e1, 1.515381e2, 2.819118e2, 1.468440e3, 0.000000e0, 1.894117e2,
            9.277117e3, 2.745553e2, 1.124311e3, 1.031770e3, 5.909631e3, 0.000000e0, 1.177658e3,
            1.678960e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.2978, 0.9798),
    },
    Model {
        core: "riscv32imc",
        format: "i20f12",
        coefficients: [
            0.000000e0,
            7.626836e1,
            2.852930e2,
            3.292844e2,
            1.526767e3,
            0.000000e0,
            0.000000e0,
            8.991831e3,
            3.828429e-2,
            1.322095e3,
            1.147946e3,
            6.865591e3,
            0.000000e0,
            1.102514e3,
            1.755620e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.2346, 0.9513),
    },
    Model {
        core: "riscv32imc",
        format: "i32f32",
        coefficients: [
            0.000000e0, 1.544153e2, 6.366814e2, 1.431267e3, 1.354524e4, 0.000000e0, 1.252248e3,
            3.983594e4, 2.962344e3, 7.945633e3, 5.833310e3, 5.885765e4, 0.000000e0, 7.940828e3,
            2.788119e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.2989, 1.4047),
    },
    Model {
        core: "riscv32imc",
        format: "f32",
        coefficients: [
            1.202271e2, 9.727131e1, 6.138317e2, 1.172495e3, 3.278833e3, 0.000000e0, 2.290862e3,
            5.236006e3, 2.158530e3, 2.186667e3, 2.582059e3, 1.098565e4, 0.000000e0, 3.498173e3,
            5.331827e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.3610, 1.6289),
    },
];

/// Cycles per instruction of the RP2040's Cortex-M0+ on this code: the emulated board's
/// whole exact frame of the boing ball at 240×240 (1258.9 cycles per pixel at 200 MHz)
/// over the Cortex-M0's count of `scenes/boing-240x240.scene` in I16F16 (869.0
/// instructions per pixel).
pub const RP2040_CYCLES_PER_INSTRUCTION: f64 = 1.4487;
