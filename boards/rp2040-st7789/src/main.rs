//! fixray's animated boing ball on a Raspberry Pi Pico (RP2040, Cortex-M0+ at 125 MHz)
//! with an ST7789 SPI display (a 240×240 panel; for a 240×320 one set [`PANEL_HEIGHT`] to
//! 320).
//!
//! At run time the program parses `scenes/boing.scene` (a red, lit sphere over a
//! checkered floor and back wall, 128×64 pixels) with fixray's parser, in the `I16F16`
//! fixed-point format, then loops forever over the ball's 16-frame bounce
//! ([`fixray::anim::Bounce::boing`]): each frame is ray-cast one scanline at a time into a
//! 240-pixel line buffer and every scanline is sent straight to the display. There is
//! no framebuffer and no allocator: the parsed scene, the line buffer (480 bytes) and the
//! SPI driver's 512-byte buffer all live on the stack.
//!
//! # Wiring
//!
//! | ST7789 module | Pico pin | RP2040 function |
//! |---------------|----------|-----------------|
//! | SCL / SCK     | GP18     | SPI0 SCK        |
//! | SDA / MOSI    | GP19     | SPI0 TX         |
//! | CS            | GP17     | output (chip select, active low) |
//! | DC / RS       | GP16     | output (data/command) |
//! | RES / RST     | GP20     | output (reset, active low) |
//! | BL / BLK      | GP21     | output (backlight, driven high) |
//! | VCC           | 3V3 (OUT)|                 |
//! | GND           | GND      |                 |
//!
//! The frame counter goes out on UART0 at 115200 baud, 8N1: **GP0 (UART0 TX)** to your
//! USB-serial adapter's RX (and GND to GND). GP1 is UART0 RX (unused).
//!
//! Modules without a CS pin work too (SPI mode 3 is used for that reason); leave GP17
//! unconnected.
//!
//! # Build and flash
//!
//! ```text
//! rustup target add thumbv6m-none-eabi     # once
//! cd boards/rp2040-st7789
//! cargo build --release                    # target/thumbv6m-none-eabi/release/fixray-rp2040-st7789
//! ```
//!
//! Then either
//! - over USB, no extra hardware: hold BOOTSEL while plugging the Pico in (it shows up as
//!   a USB drive `RPI-RP2`), then `cargo install elf2uf2-rs` (once) and
//!   `elf2uf2-rs -d target/thumbv6m-none-eabi/release/fixray-rp2040-st7789`
//!   (or `picotool load -x target/thumbv6m-none-eabi/release/fixray-rp2040-st7789 -t elf`);
//! - or through an SWD debug probe (e.g. a second Pico running debugprobe), with
//!   `cargo install probe-rs-tools` (once):
//!   `probe-rs run --chip RP2040 target/thumbv6m-none-eabi/release/fixray-rp2040-st7789`.
//!
//! `cargo run --release` runs `elf2uf2-rs -d` (the `runner` in `.cargo/config.toml`; the
//! probe-rs line beside it is the other way).
//!
//! # What you should see
//!
//! The panel turns black, then the 128×64 scene appears centred on it (at x = 56,
//! y = 88 on a 240×240 panel, y = 128 on a 240×320 one): a red ball bouncing twice
//! over a pale/plum checkerboard floor in front of a checkered wall, swaying right and
//! back, with its shadow on the floor, looping every 16 frames. On the serial port (e.g.
//! `picocom -b 115200 /dev/ttyUSB0`) a start line and then one line per frame:
//!
//! ```text
//! fixray boing: 128x64 at (56,88) on a 240x240 panel
//! frame=0 ms=…
//! frame=1 ms=…
//! ```
//!
//! `ms` is the frame's time from the RP2040's 1 MHz timer: ray casting the 8192 pixels
//! plus sending them over SPI (16 KB at 62.5 MHz: at least 2 ms of it).
//!
//! If the scene cannot be parsed or the display fails, the error is printed on the
//! serial port (`error: …`) and the program halts. If the colours look inverted (a cyan
//! ball), your panel does not need [`ColorInversion::Inverted`]: use `Normal`. If the
//! picture is garbled, lower [`SPI_HZ`] (e.g. to 31.25 MHz) or shorten the wires.

#![no_std]
#![no_main]

use core::convert::Infallible;
use core::fmt::{self, Write};

use embedded_graphics::prelude::{Point, Size};
use embedded_graphics::primitives::Rectangle;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::MODE_3;
use embedded_hal_bus::spi::ExclusiveDevice;
use fixray::anim::{AnimError, Bounce};
use fixray::{Frame, I16F16, Scene, SceneError};
use mipidsi::Builder;
use mipidsi::interface::SpiInterface;
use mipidsi::models::ST7789;
use mipidsi::options::ColorInversion;
use panic_halt as _;
use rp2040_hal::fugit::RateExtU32;
use rp2040_hal::gpio::{self, PinState};
use rp2040_hal::uart::{DataBits, StopBits, UartConfig, UartPeripheral};
use rp2040_hal::{Clock, Sio, Spi, Timer, Watchdog, pac};

/// The second-stage bootloader for the Pico's W25Q080-compatible flash: the first 256
/// bytes of flash (`.boot2`, placed by `memory.x`), which the boot ROM runs to set up
/// execute-in-place before jumping to the vector table.
#[unsafe(link_section = ".boot2")]
#[used]
pub static BOOT2_FIRMWARE: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The Pico's crystal: 12 MHz (the clocks are set up from it to the default 125 MHz).
const XTAL_HZ: u32 = 12_000_000;

/// The panel's size in pixels (the ST7789's controller has a 240×320 framebuffer; a
/// 240×240 panel shows its top 240 rows in the default orientation).
const PANEL_WIDTH: u16 = 240;
/// The panel's height: 240, or 320 for a 240×320 panel.
const PANEL_HEIGHT: u16 = 240;

/// The SPI clock: 62.5 MHz, the RP2040's fastest (half the 125 MHz peripheral clock)
/// and the ST7789's rated write clock.
const SPI_HZ: u32 = 62_500_000;

/// The serial port's speed (UART0, GP0 TX).
const BAUD: u32 = 115_200;

/// The line buffer's capacity: one panel row.
const LINE: usize = PANEL_WIDTH as usize;

/// The scene, as text in flash, parsed on the chip.
const TEXT: &str = include_str!("../../../scenes/boing.scene");

/// Why the animation stopped.
enum Failure<E> {
    /// The scene file could not be read.
    Scene(SceneError),
    /// The bounce could not be made or applied to the scene.
    Anim(AnimError),
    /// The scene's picture does not fit the panel or the line buffer.
    TooBig { width: u16, height: u16 },
    /// Drawing on the display failed.
    Display(E),
}

impl<E: fmt::Debug> fmt::Display for Failure<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Failure::Scene(e) => write!(f, "scenes/boing.scene:{e}"),
            Failure::Anim(e) => write!(f, "animation: {e}"),
            Failure::TooBig { width, height } => write!(
                f,
                "the scene is {width}x{height}, the panel {PANEL_WIDTH}x{PANEL_HEIGHT}"
            ),
            Failure::Display(e) => write!(f, "display: {e:?}"),
        }
    }
}

/// Parses the scene and draws the bouncing ball on `display`, forever, with one line per
/// frame on `serial`. Returns only on an error.
fn run<D>(
    display: &mut D,
    serial: &mut impl Write,
    timer: &Timer,
) -> Result<Infallible, Failure<D::Error>>
where
    D: DrawTarget<Color = Rgb565>,
{
    display.clear(Rgb565::BLACK).map_err(Failure::Display)?;

    // The scene is parsed in place (no temporary copy on the stack); there are no
    // texture files to look up.
    let mut scene = Scene::<I16F16>::empty();
    scene
        .read_with(TEXT, None, &mut |_| None)
        .map_err(Failure::Scene)?;
    let (width, height) = (scene.camera.width, scene.camera.height);
    if width > PANEL_WIDTH || height > PANEL_HEIGHT || usize::from(width) > LINE {
        return Err(Failure::TooBig { width, height });
    }
    // Centred on the panel.
    let top_left = Point::new(
        i32::from((PANEL_WIDTH - width) / 2),
        i32::from((PANEL_HEIGHT - height) / 2),
    );
    // The serial report is informational: a failed write (the blocking UART does not
    // fail) must not stop the animation, so its result is ignored here and below.
    let _ = write!(
        serial,
        "fixray boing: {width}x{height} at ({},{}) on a {PANEL_WIDTH}x{PANEL_HEIGHT} panel\r\n",
        top_left.x, top_left.y
    );

    let bounce = Bounce::boing(&scene.objects).map_err(Failure::Anim)?;
    let mut buffer = [Rgb565::BLACK; LINE];
    let line = &mut buffer[..usize::from(width)];
    let row_size = Size::new(u32::from(width), 1);
    loop {
        for k in 0..bounce.frames() {
            let start = timer.get_counter();
            // The sphere moves in the parsed scene (no re-parsing).
            bounce.apply(&mut scene, k).map_err(Failure::Anim)?;
            // What is constant for the frame is computed once, then line by line.
            let frame = Frame::new(&scene);
            for row in 0..height {
                frame.render_line(row, line);
                let area = Rectangle::new(top_left + Point::new(0, i32::from(row)), row_size);
                display
                    .fill_contiguous(&area, line.iter().copied())
                    .map_err(Failure::Display)?;
            }
            let ms = (timer.get_counter() - start).to_millis();
            let _ = write!(serial, "frame={k} ms={ms}\r\n");
        }
    }
}

/// Prints `error: {message}` on the serial port and stops (sleeping).
fn halt(serial: &mut impl Write, message: impl fmt::Display) -> ! {
    // Nothing is left to report a failed write to.
    let _ = write!(serial, "error: {message}\r\n");
    loop {
        cortex_m::asm::wfi();
    }
}

#[rp2040_hal::entry]
fn main() -> ! {
    // Board init. `take` succeeds on its first and only call; the clocks fail to start
    // only on broken hardware (no crystal), before the serial port exists: that panics,
    // i.e. halts (`panic-halt`).
    let mut pac = pac::Peripherals::take().unwrap();
    let mut watchdog = Watchdog::new(pac.WATCHDOG);
    let clocks = rp2040_hal::clocks::init_clocks_and_plls(
        XTAL_HZ,
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    )
    .expect("the clocks start from the Pico's 12 MHz crystal");
    // The 1 MHz timer: frame times, and the delays of the display's reset and init.
    let timer = Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);
    let sio = Sio::new(pac.SIO);
    let pins = gpio::Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );

    // UART0 on GP0 (TX) and GP1 (RX): the frame counter.
    let uart_pins = (
        pins.gpio0.into_function::<gpio::FunctionUart>(),
        pins.gpio1.into_function::<gpio::FunctionUart>(),
    );
    let mut serial = UartPeripheral::new(pac.UART0, uart_pins, &mut pac.RESETS)
        .enable(
            UartConfig::new(BAUD.Hz(), DataBits::Eight, None, StopBits::One),
            clocks.peripheral_clock.freq(),
        )
        // 115200 baud is well within the dividers' range at 125 MHz: this cannot fail.
        .expect("115200 baud from the 125 MHz peripheral clock");

    // SPI0 on GP18 (SCK) and GP19 (MOSI), write-only; CS, DC, reset and backlight as
    // plain outputs (CS and reset start high: inactive).
    let sck = pins.gpio18.into_function::<gpio::FunctionSpi>();
    let mosi = pins.gpio19.into_function::<gpio::FunctionSpi>();
    let bus = Spi::<_, _, _, 8>::new(pac.SPI0, (mosi, sck)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        SPI_HZ.Hz(),
        MODE_3,
    );
    let cs = pins.gpio17.into_push_pull_output_in_state(PinState::High);
    let dc = pins.gpio16.into_push_pull_output();
    let reset = pins.gpio20.into_push_pull_output_in_state(PinState::High);
    let mut backlight = pins.gpio21.into_push_pull_output();
    // The RP2040's pins cannot fail (their error type is `Infallible`).
    let Ok(()) = backlight.set_high();
    let Ok(device) = ExclusiveDevice::new(bus, cs, timer);

    // The driver gathers pixels in this buffer before each SPI write.
    let mut spi_buffer = [0u8; 512];
    let interface = SpiInterface::new(device, dc, &mut spi_buffer);
    let mut delay = timer;
    let mut display = match Builder::new(ST7789, interface)
        .display_size(PANEL_WIDTH, PANEL_HEIGHT)
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(reset)
        .init(&mut delay)
    {
        Ok(display) => display,
        Err(e) => halt(&mut serial, format_args!("display init: {e:?}")),
    };

    let Err(e) = run(&mut display, &mut serial, &timer);
    halt(&mut serial, e)
}
