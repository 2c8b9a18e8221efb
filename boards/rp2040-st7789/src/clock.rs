//! The system clock: 125 MHz (the RP2040's nominal clock, rp2040-hal's default) or 200 MHz
//! (its rated maximum at a core voltage of 1.15 V), chosen by [`SYS_HZ`](crate::SYS_HZ).
//!
//! At 200 MHz the set-up follows the datasheet's condition and the Pico SDK's order: both
//! PLLs locked, clk_ref on the crystal, the core voltage raised to 1.15 V while clk_sys
//! still runs at 12 MHz, 1 ms for the regulator to settle, then clk_sys on PLL_SYS
//! (1200 MHz VCO / 6 / 1). The flash needs nothing: boot2 divides clk_sys by 2 for the
//! QSPI clock, 100 MHz at 200 MHz, within the W25Q16JV's 133 MHz.

use rp2040_hal::clocks::{Clock, ClocksManager, InitError};
use rp2040_hal::fugit::{HertzU32, RateExtU32};
use rp2040_hal::pac;
use rp2040_hal::pac::vreg_and_chip_reset::vreg::VSEL_A;
use rp2040_hal::pll::common_configs::{PLL_SYS_125MHZ, PLL_USB_48MHZ};
use rp2040_hal::pll::{PLLConfig, setup_pll_blocking};
use rp2040_hal::xosc::setup_xosc_blocking;
use rp2040_hal::{Watchdog, vreg};

/// PLL_SYS for 200 MHz: 12 MHz × 100 = 1200 MHz, / 6 / 1 (the Pico SDK's values).
const PLL_SYS_200MHZ: PLLConfig = PLLConfig {
    vco_freq: HertzU32::MHz(1200),
    refdiv: 1,
    post_div1: 6,
    post_div2: 1,
};

/// The hardware the clocks are made from.
pub struct Parts<'a> {
    pub xosc: pac::XOSC,
    pub clocks: pac::CLOCKS,
    pub pll_sys: pac::PLL_SYS,
    pub pll_usb: pac::PLL_USB,
    pub vreg: &'a mut pac::VREG_AND_CHIP_RESET,
    pub resets: &'a mut pac::RESETS,
    pub watchdog: &'a mut Watchdog,
}

/// Starts the crystal and the PLLs and runs clk_sys and clk_peri at `sys_hz` (125 or
/// 200 MHz), clk_usb and clk_adc at 48 MHz, the watchdog's tick (the 1 MHz timer) from
/// the crystal.
pub fn init(xtal_hz: u32, sys_hz: u32, parts: Parts<'_>) -> Result<ClocksManager, InitError> {
    let pll_sys_config = if sys_hz == 200_000_000 {
        PLL_SYS_200MHZ
    } else {
        PLL_SYS_125MHZ
    };
    let xosc = setup_xosc_blocking(parts.xosc, xtal_hz.Hz()).map_err(InitError::XoscErr)?;
    // The 12 MHz crystal fits the tick divider's 8 bits.
    parts
        .watchdog
        .enable_tick_generation((xtal_hz / 1_000_000) as u8);
    let mut clocks = ClocksManager::new(parts.clocks);
    let xosc_hz = xosc.operating_frequency();
    let pll_sys = setup_pll_blocking(
        parts.pll_sys,
        xosc_hz,
        pll_sys_config,
        &mut clocks,
        parts.resets,
    )
    .map_err(InitError::PllError)?;
    let pll_usb = setup_pll_blocking(
        parts.pll_usb,
        xosc_hz,
        PLL_USB_48MHZ,
        &mut clocks,
        parts.resets,
    )
    .map_err(InitError::PllError)?;
    clocks
        .reference_clock
        .configure_clock(&xosc, xosc_hz)
        .map_err(InitError::ClockError)?;
    if sys_hz > 133_000_000 {
        // Above the 133 MHz rated at any voltage: 1.15 V first (VSEL 0..=4 read as None,
        // all 0.80 V), while clk_sys runs from the 12 MHz clk_ref.
        let below = vreg::get_voltage(parts.vreg)
            .is_none_or(|v| u8::from(v) < u8::from(VSEL_A::VOLTAGE1_15));
        if below {
            vreg::set_voltage(parts.vreg, VSEL_A::VOLTAGE1_15);
            // At least 1 ms at 12 MHz (each loop iteration takes more than one cycle).
            cortex_m::asm::delay(xtal_hz / 1_000);
        }
    }
    clocks
        .system_clock
        .configure_clock(&pll_sys, pll_sys.operating_frequency())
        .map_err(InitError::ClockError)?;
    clocks
        .usb_clock
        .configure_clock(&pll_usb, pll_usb.operating_frequency())
        .map_err(InitError::ClockError)?;
    clocks
        .adc_clock
        .configure_clock(&pll_usb, pll_usb.operating_frequency())
        .map_err(InitError::ClockError)?;
    clocks
        .rtc_clock
        .configure_clock(&pll_usb, 46_875u32.Hz())
        .map_err(InitError::ClockError)?;
    let sys = clocks.system_clock.freq();
    clocks
        .peripheral_clock
        .configure_clock(&clocks.system_clock, sys)
        .map_err(InitError::ClockError)?;
    Ok(clocks)
}
