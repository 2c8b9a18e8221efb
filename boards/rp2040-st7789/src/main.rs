//! fixray's animated boing ball on a Raspberry Pi Pico (RP2040, two Cortex-M0+ cores at
//! 200 MHz) with an ST7789 SPI display, the whole 240×240 panel (a 240×320 one: set
//! [`PANEL_HEIGHT`] to 320).
//!
//! At run time the program parses `scenes/boing-240x240.scene` (a red, lit sphere over a
//! checkered floor and back wall at the panel's resolution) with fixray's parser, in the
//! `I16F16` fixed-point format, then loops forever over the ball's 16-frame bounce
//! ([`fixray::anim::Bounce::boing`]), seen by a camera circling it (the default program,
//! below) or before a still camera (the `bounce` feature). In the still camera's program
//! each frame is ray-cast one scanline at a time,
//! only where it differs from the frame before: the rows are dealt out between the two
//! cores ([`rows`]), and each finished row goes to the panel by DMA while the next one is
//! drawn ([`panel`]). There is no framebuffer and no
//! allocator: four line buffers of 480 bytes, two copies of the parsed scene (the frame and
//! the frame before) on each core's stack.
//!
//! # Wiring
//!
//! | ST7789 module | Pico pin | RP2040 function |
//! |---------------|----------|-----------------|
//! | SCL / SCK     | GP18     | SPI0 SCK        |
//! | SDA / MOSI    | GP19     | SPI0 TX         |
//! | CS            | GP17     | output (chip select, held low) |
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
//! # The emulated board
//!
//! `cargo build --release --features emulated` builds the firmware for rp2040js, the
//! RP2040 emulator in `emulator/` (`node emulator/run.mjs ELF`): it has no boot ROM, so
//! memory and bit intrinsics are Rust's instead of the ROM's (32-bit division still uses
//! the RP2040's divider: [`divide`]), and it emulates one core, so core 0 draws every row.
//!
//! # What you should see
//!
//! The panel turns black, then the ball bounces twice over a pale/plum checkerboard
//! floor in front of a checkered wall, swaying right and back, with its shadow on the
//! floor, looping every 16 frames, while the camera swings round it and back (with
//! `bounce`, the camera stands still). On the serial port (e.g.
//! `picocom -b 115200 /dev/ttyUSB0`) a start line and then one line per frame:
//!
//! ```text
//! fixray boing: 240x240 at (0,0) on a 240x240 panel, 200 MHz, 1 core, SPI 50000 kHz, orbit, 8x8 blocks, bound 8
//! frame=0 us=… pixels=57600
//! frame=1 us=… pixels=57600
//! ```
//!
//! With `bounce` the start line says `2 cores, SPI 50000 kHz, changes only`, and each
//! frame's `pixels` are those sent.
//!
//! `us` is the frame's time from the RP2040's 1 MHz timer: ray casting its pixels, with
//! the display transfer overlapped, up to the last row's transfer. `pixels` are the
//! pixels sent: the first frame whole, then only those that may differ from the frame
//! before ([`fixray::Changes`]: the ball's box, old and new, and the rows its shadow can
//! reach), while the panel keeps the rest; the panel shows each frame bit for bit as if
//! it were sent whole ([`CHANGES_ONLY`] sends every frame whole).
//!
//! If the scene cannot be parsed or does not fit the panel, the panel turns red and the
//! error is printed on the serial port (`error: …`); the program then halts. If the
//! colours look inverted (a cyan ball), your panel does not need the inversion command:
//! remove `INVON` in `panel.rs`. If the picture is garbled, lower [`SPI_HZ`] (e.g. to
//! 31.25 MHz) or shorten the wires.
//!
//! # The two programs
//!
//! The default program ([`PROGRAM`]) is the orbit: the ball bouncing before a camera that
//! circles it ([`fixray::anim::Orbit`]). Every pixel changes, so each frame is sent whole;
//! core 0 draws it in bands of eight rows ([`fixray::Frame::bands`]: each band's bottom
//! corners kept for the next) in 8×8 blocks filled where a certificate bounds the error
//! by 8 levels ([`ORBIT_SAMPLING`], the fastest setting measured within the orbit's
//! budget; exact with the `exact` feature),
//! each band sent by DMA while the next is drawn. Its start line ends `orbit, 8x8 blocks,
//! bound 8` (or `orbit, exact`).
//!
//! `cargo build --release --features bounce` builds the other: the ball bouncing before
//! a still camera, exact, as described below; its start line ends `changes only` (or
//! `whole frames`).
//!
//! # Other panels
//!
//! An ST7789 of another size: a scene at its resolution (the camera's `pixeldim`), and
//! [`PANEL_WIDTH`] and [`PANEL_HEIGHT`]. A smaller scene is drawn centred on black.
//! Another controller: its commands in `panel.rs` (the window, `RAMWR`, the init
//! sequence); the DMA streaming stays as it is.

#![no_std]
#![no_main]

mod clock;
#[cfg(feature = "emulated")]
mod divide;
mod panel;
mod rows;

use core::fmt::{self, Write};
use core::ops::Range;
use core::sync::atomic::{Ordering, compiler_fence};

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use embedded_graphics_core::prelude::IntoStorage;
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::MODE_3;
use fixray::anim::{AnimError, Bounce, Orbit};
use fixray::{BlockSize, Depth, Frame, I16F16, Sampling, Scene, SceneError};
use panic_halt as _;
use rp2040_hal::dma::DMAExt;
use rp2040_hal::fugit::RateExtU32;
use rp2040_hal::gpio::{self, PinState};
use rp2040_hal::multicore::{Multicore, Stack};
use rp2040_hal::sio::SioFifo;
use rp2040_hal::uart::{DataBits, StopBits, UartConfig, UartPeripheral};
use rp2040_hal::{Clock, Sio, Spi, Timer, Watchdog, pac};

use panel::{LINE_BYTES, Line, Panel};

/// The second-stage bootloader for the Pico's W25Q080-compatible flash: the first 256
/// bytes of flash (`.boot2`, placed by `memory.x`), which the boot ROM runs to set up
/// execute-in-place before jumping to the vector table.
#[unsafe(link_section = ".boot2")]
#[used]
pub static BOOT2_FIRMWARE: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The Pico's crystal: 12 MHz.
const XTAL_HZ: u32 = 12_000_000;

/// The system clock: 200 MHz (the RP2040's rated maximum, at 1.15 V: see [`clock`]) or
/// 125 MHz (its nominal clock; also the `clock-125mhz` feature, for measuring both).
pub const SYS_HZ: u32 = if cfg!(feature = "clock-125mhz") {
    125_000_000
} else {
    200_000_000
};
const _: () = assert!(SYS_HZ == 200_000_000 || SYS_HZ == 125_000_000);

/// The panel's width in pixels.
pub const PANEL_WIDTH: u16 = 240;
/// The panel's height: 240, or 320 for a 240×320 panel (the scene follows).
pub const PANEL_HEIGHT: u16 = 240;

/// The scene, as text in flash, parsed on the chip: the boing ball at the panel's size.
const TEXT: &str = if PANEL_HEIGHT == 320 {
    include_str!("../../../scenes/boing-240x320.scene")
} else {
    include_str!("../../../scenes/boing-240x240.scene")
};
/// The scene's name in error messages.
const SCENE_NAME: &str = if PANEL_HEIGHT == 320 {
    "scenes/boing-240x320.scene"
} else {
    "scenes/boing-240x240.scene"
};

/// The SPI clock asked for: the ST7789's rated write clock. The RP2040 divides clk_peri
/// by an even number: 62.5 MHz at 125 MHz, 50 MHz at 200 MHz (the start line says which).
const SPI_HZ: u32 = 62_500_000;

/// The serial port's speed (UART0, GP0 TX).
const BAUD: u32 = 115_200;

/// The cores that draw: both, or core 0 alone in the emulator (which runs one core).
const CORES: u16 = if cfg!(feature = "emulated") { 1 } else { 2 };

/// Whether a frame sends only the pixels that may differ from the frame before it (the
/// panel keeps the rest: [`fixray::Changes`], bit for bit the whole frame) or every
/// pixel (also the `whole-frames` feature, for measuring both).
const CHANGES_ONLY: bool = !cfg!(feature = "whole-frames");

/// Which animation the board shows.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Program {
    /// The ball bouncing before a still camera, exact: each frame bit for bit the exact
    /// frame, sent where it may differ from the frame before ([`CHANGES_ONLY`]), on both
    /// cores.
    Bounce,
    /// The ball bouncing before a camera circling it ([`Orbit::boing`]): every pixel
    /// changes, each frame drawn in bands of [`BAND`] rows with [`ORBIT_SAMPLING`], sent
    /// whole, on core 0.
    Orbit,
}

/// The animation: the orbit, or the bounce before a still camera with the cargo feature
/// `bounce`.
pub const PROGRAM: Program = if cfg!(feature = "bounce") {
    Program::Bounce
} else {
    Program::Orbit
};

/// How the orbit's frames are drawn: 8×8 blocks traced at their corners and filled where
/// the colour strays by at most 8 levels by the certificate (the orbit's budget, within
/// 1 % of pixels beyond 2 levels of the exact frame and 40 dB, holds with room to spare:
/// `tests/sampling.rs`, `docs/accuracy.md`); every pixel traced with the feature `exact`.
pub const ORBIT_SAMPLING: Sampling = if cfg!(feature = "exact") {
    Sampling::Exact
} else {
    Sampling::blocks(BlockSize::Eight, 8)
};

/// The orbit's band: the rows drawn at once (a block's side; each band traces its top and
/// bottom rows of corners, so a row of corners between two bands is traced twice).
const BAND: u16 = 8;

/// A band as the DMA reads it: [`BAND`] panel rows.
const BAND_BYTES: usize = BAND as usize * LINE_BYTES;

/// The orbit's two band buffers: one drawn while the other is sent.
static mut BANDS: [[u8; BAND_BYTES]; 2] = [[0; BAND_BYTES]; 2];

/// The band buffer `slot`.
fn band(slot: usize) -> *mut [u8; BAND_BYTES] {
    // SAFETY: only the address is formed; `draw_bands` alternates the slots so that the
    // one written is never the one in flight.
    unsafe { &raw mut BANDS[slot] }
}

/// The panel's colour after an error: red (RGB565).
const ERROR_COLOUR: u16 = 0xf800;

/// The line buffers: slots 0 and 1 are core 0's, 2 and 3 core 1's. Who may touch a slot
/// passes between the cores and the DMA with the messages of [`draw_frame`]: a slot is
/// written by one core while no transfer reads it.
static mut LINES: [Line; 4] = [[0; LINE_BYTES]; 4];

/// Core 1's stack: 32 KB (the parsed scene and a frame's state live on it).
static CORE1_STACK: Stack<8192> = Stack::new();

/// A message from core 0 to core 1: a line buffer of core 1's has been sent. Any other
/// message starts a frame: its number.
const FREED: u32 = u32::MAX;

/// The line buffer `slot`.
fn line(slot: usize) -> *mut Line {
    // SAFETY: only the address is formed; the slot protocol decides who dereferences it.
    unsafe { &raw mut LINES[slot] }
}

/// Why the animation cannot start.
enum Failure {
    /// The scene file could not be read.
    Scene(SceneError),
    /// The bounce could not be made or applied to the scene.
    Anim(AnimError),
    /// The scene's picture is larger than the panel.
    TooBig { width: u16, height: u16 },
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Failure::Scene(e) => write!(f, "{SCENE_NAME}:{e}"),
            Failure::Anim(e) => write!(f, "animation: {e}"),
            Failure::TooBig { width, height } => write!(
                f,
                "the scene is {width}x{height}, the panel {PANEL_WIDTH}x{PANEL_HEIGHT}: \
                 give the camera a pixeldim that fits"
            ),
        }
    }
}

/// Parses the scene in place (no temporary copy on the stack; there are no texture files
/// to look up), checks that it fits the panel and makes its bounce.
fn load(scene: &mut Scene<I16F16>) -> Result<Bounce<I16F16>, Failure> {
    scene
        .read_with(TEXT, None, &mut |_| None)
        .map_err(Failure::Scene)?;
    let (width, height) = (scene.camera.width, scene.camera.height);
    if width > PANEL_WIDTH || height > PANEL_HEIGHT {
        return Err(Failure::TooBig { width, height });
    }
    let bounce = Bounce::boing(&scene.objects).map_err(Failure::Anim)?;
    // Every frame of the loop is placed once here, so that drawing cannot fail.
    for k in 0..bounce.frames() {
        bounce.centre(k).map_err(Failure::Anim)?;
    }
    if PROGRAM == Program::Orbit {
        // Every turn of the loop fits (`Orbit::new`), and frame 0's turns nothing: what
        // fails here is an object or light the orbit cannot turn.
        let orbit = Orbit::boing(&scene.objects).map_err(Failure::Anim)?;
        orbit.apply(scene, 0).map_err(Failure::Anim)?;
    }
    Ok(bounce)
}

/// Draws `frame` (`width` × `height`) on the panel at `(x, y)` band by band
/// ([`Frame::bands`], a band at a time), each band sent by DMA while the next is
/// drawn. Returns the pixels sent.
fn draw_bands(
    frame: &Frame<'_, I16F16, Rgb888>,
    (width, height): (u16, u16),
    (x, y): (u16, u16),
    panel: &mut Panel,
) -> u32 {
    let mut pixels = [Rgb888::BLACK; BAND as usize * PANEL_WIDTH as usize];
    let mut slot = 0;
    let mut sent = 0;
    // Each band's bottom corners are the next band's top ones: traced once.
    let mut bands = frame.bands();
    for top in (0..height).step_by(usize::from(BAND)) {
        let rows = BAND.min(height - top);
        let n = usize::from(rows) * usize::from(width);
        bands.render_rows(top..top + rows, &mut pixels[..n]);
        // SAFETY: the band in flight is the previous one, from the other slot.
        to_panel(&pixels[..n], unsafe { &mut *band(slot) });
        // SAFETY: the slot is drawn and is read by this one transfer until the next band's
        // `send_rows` has waited for it.
        let band: &'static [u8] = unsafe { &(&*band(slot))[..2 * n] };
        panel.send_rows((x, y + top), width, slot, band);
        slot ^= 1;
        sent += n as u32;
    }
    panel.finish();
    sent
}

/// Draws `columns` of row `row` of `frame` into `line` as big-endian RGB565 (the panel's
/// byte order); returns the bytes written.
fn draw_row(
    frame: &Frame<'_, I16F16, Rgb888>,
    row: u16,
    columns: Range<u16>,
    line: &mut Line,
) -> usize {
    let mut pixels = [Rgb888::BLACK; PANEL_WIDTH as usize];
    let n = usize::from(columns.end - columns.start);
    frame.render_columns(row, columns, &mut pixels[..n]);
    to_panel(&pixels[..n], line);
    2 * n
}

/// Writes `pixels` into `bytes` as big-endian RGB565 (the panel's byte order), each
/// converted as `Rgb565::from` converts it, once for a run of one colour: the frame is
/// exact in RGB565 (`panel_frame`), so runs of one colour are most of its pixels.
fn to_panel(pixels: &[Rgb888], bytes: &mut [u8]) {
    let mut last: Option<(Rgb888, [u8; 2])> = None;
    for (pair, &pixel) in bytes.chunks_exact_mut(2).zip(pixels) {
        let converted = match last {
            Some((colour, converted)) if colour == pixel => converted,
            _ => {
                let converted = Rgb565::from(pixel).into_storage().to_be_bytes();
                last = Some((pixel, converted));
                converted
            }
        };
        pair.copy_from_slice(&converted);
    }
}

/// The columns of `row` a frame sends: every one, or with the frame shown before it
/// (`before`) and [`CHANGES_ONLY`], those that may differ ([`fixray::Changes`]).
fn columns_to_send<'f>(
    frame: &'f Frame<'_, I16F16, Rgb888>,
    before: Option<&'f Frame<'_, I16F16, Rgb888>>,
    width: u16,
) -> impl Fn(u16) -> Option<Range<u16>> + 'f {
    let changes = before
        .filter(|_| CHANGES_ONLY)
        .map(|b| frame.changes_since(b));
    move |row| match &changes {
        Some(changes) => changes.columns(row),
        None => Some(0..width),
    }
}

/// Draws `frame` (`width` × `height`) on the panel at `(x, y)` with `cores` cores, the
/// columns [`columns_to_send`] gives: core 0's rows here, core 1's from the FIFO (it
/// sends each row as [`row_drawn`] when the row is in one of its line buffers, and gets
/// [`FREED`] back when that buffer has been sent). Returns the pixels sent.
fn draw_frame(
    frame: &Frame<'_, I16F16, Rgb888>,
    before: Option<&Frame<'_, I16F16, Rgb888>>,
    (width, height): (u16, u16),
    (x, y): (u16, u16),
    cores: u16,
    panel: &mut Panel,
    fifo: &mut SioFifo,
) -> u32 {
    let send = columns_to_send(frame, before, width);
    let mut own = 0;
    let mut pixels = 0;
    for row in 0..height {
        let Some(columns) = send(row) else {
            continue;
        };
        let start = columns.start;
        let (slot, bytes) = if rows::core_of(row, cores) == 0 {
            let slot = own;
            own ^= 1;
            // SAFETY: slot `own` is core 0's, and not in flight: the transfer in flight
            // is the previous row's, from the other slot.
            (
                slot,
                draw_row(frame, row, columns, unsafe { &mut *line(slot) }),
            )
        } else {
            // Core 1 sends its rows in order, each with its slot: another row or slot
            // would be a broken protocol, which stops the board rather than draw it.
            let message = fifo.read_blocking();
            compiler_fence(Ordering::Acquire);
            let slot = (message >> 16) as usize;
            assert!(
                message & 0xffff == u32::from(row) && (slot == 2 || slot == 3),
                "core 1's rows arrive in order, from its slots"
            );
            (slot, 2 * columns.len())
        };
        pixels += (bytes / 2) as u32;
        // SAFETY: the slot is drawn and is read by this one transfer until it is freed.
        let sent: &'static [u8] = unsafe { &(&*line(slot))[..bytes] };
        if panel
            .send((x + start, y + row), slot, sent)
            .is_some_and(|freed| freed >= 2)
        {
            fifo.write_blocking(FREED);
        }
    }
    if panel.finish().is_some_and(|freed| freed >= 2) {
        fifo.write_blocking(FREED);
    }
    pixels
}

/// Core 1's message to core 0: `row` is drawn, in the line buffer `slot`.
const fn row_drawn(row: u16, slot: usize) -> u32 {
    (slot as u32) << 16 | row as u32
}

/// Core 0's message to core 1 that starts frame `k` (`whole`: with no frame shown before
/// it, every column).
const fn frame_start(k: u16, whole: bool) -> u32 {
    (whole as u32) << 16 | k as u32
}

/// Core 1: its own two copies of the scene, drawn on in turn as core 0's are
/// ([`in_turn`]); it draws its rows of each frame whose number it is sent.
fn core1() -> ! {
    // SAFETY: core 1 uses only its own side of the SIO (the FIFO); core 0 set up the rest.
    let pac = unsafe { pac::Peripherals::steal() };
    let fifo = Sio::new(pac.SIO).fifo;
    let (mut scene, mut shown) = (Scene::<I16F16>::empty(), Scene::<I16F16>::empty());
    // Core 0 loaded the same text without error before it started this core.
    let (Ok(bounce), Ok(_)) = (load(&mut scene), load(&mut shown)) else {
        loop {
            cortex_m::asm::wfi();
        }
    };
    let (width, height) = (scene.camera.width, scene.camera.height);
    // Core 1's side of the FIFO, and how many of its two slots are free.
    let mut state = (fifo, 2u32);
    let mut last = None;
    in_turn(
        &bounce,
        (&mut scene, &mut shown),
        &mut state,
        |(fifo, free)| {
            let message = loop {
                match fifo.read_blocking() {
                    FREED => *free += 1,
                    message => break message,
                }
            };
            let (k, whole) = ((message & 0xffff) as u16, message >> 16 != 0);
            // Core 0 starts its frames in order: another would be a broken protocol,
            // which stops the board rather than draw it.
            assert!(
                whole || last.map(|j| next_frame(&bounce, j)) == Some(k),
                "core 0's frames arrive in order"
            );
            last = Some(k);
            (k, whole, ())
        },
        |(fifo, free), (), frame, before| {
            // Every slot sent in the last frame was freed before this frame's number (the
            // FIFO keeps order): each frame starts with both slots free, from slot 2.
            let mut slot = 2;
            let send = columns_to_send(frame, before, width);
            for row in rows::rows_of(1, 2, height) {
                let Some(columns) = send(row) else {
                    continue;
                };
                while *free == 0 {
                    if fifo.read_blocking() == FREED {
                        *free += 1;
                    }
                }
                *free -= 1;
                // SAFETY: slots 2 and 3 are core 1's, used in turn; core 0 sends them in
                // the order they are drawn, so the one `free` counted is this one.
                draw_row(frame, row, columns, unsafe { &mut *line(slot) });
                compiler_fence(Ordering::Release);
                cortex_m::asm::dmb();
                fifo.write_blocking(row_drawn(row, slot));
                slot ^= 1;
            }
        },
    )
}

/// The bounce's frame after frame `k` (the loop closes).
fn next_frame(bounce: &Bounce<I16F16>, k: u16) -> u16 {
    if k + 1 >= bounce.frames() { 0 } else { k + 1 }
}

/// Draws the bounce's frames in the order `start` gives them, forever, on the two scenes
/// `a` and `b` in turn. `start(ctx)` gives the next frame's number, whether it is drawn
/// whole (with no frame shown before it) and what `draw` needs of its start; `draw(ctx,
/// started, frame, before)` draws it, with the frame shown before it. That frame is the
/// one drawn last, kept with its per-frame part, not formed again from a scene moved one
/// frame behind; it is given where the frame is not whole and comes right after it (a
/// `start` out of order draws the frame whole).
fn in_turn<C, T>(
    bounce: &Bounce<I16F16>,
    (a, b): (&mut Scene<I16F16>, &mut Scene<I16F16>),
    ctx: &mut C,
    mut start: impl FnMut(&mut C) -> (u16, bool, T),
    mut draw: impl FnMut(&mut C, T, &Frame<'_, I16F16, Rgb888>, Option<&Frame<'_, I16F16, Rgb888>>),
) -> ! {
    // Whether frame `k`, drawn whole or not, comes right after frame `last`.
    let follows = |last: u16, k: u16, whole: bool| !whole && next_frame(bounce, last) == k;
    // The frame drawn last (of `b`), with its number.
    let mut kept: Option<(u16, Frame<'_, I16F16, Rgb888>)> = None;
    loop {
        let (k, whole, started) = start(ctx);
        // `load` placed every frame of the loop.
        let _ = bounce.apply(a, k);
        let frame = panel_frame(a);
        let before = kept.as_ref().filter(|(j, _)| follows(*j, k, whole));
        draw(ctx, started, &frame, before.map(|(_, f)| f));
        let (j, whole, started) = start(ctx);
        let _ = bounce.apply(b, j);
        let next = panel_frame(b);
        draw(ctx, started, &next, follows(k, j, whole).then_some(&frame));
        kept = Some((j, next));
    }
}

/// A frame of `scene` for the panel: exact in its Rgb565 colours (`Frame::with_depth`),
/// the colours the exact frame's pixels convert to, so that runs of the floor and the wall
/// whose ends convert to one colour are drawn from their ends.
fn panel_frame(scene: &Scene<I16F16>) -> Frame<'_, I16F16, Rgb888> {
    Frame::new(scene).with_depth(Depth::of::<Rgb565>())
}

/// The orbit's loop: each frame the scene as parsed (`base`, kept here; `scene` is
/// drawn), the ball moved by `bounce`, the whole scene turned by the orbit, then drawn
/// band by band with [`ORBIT_SAMPLING`] and sent whole.
fn orbit(
    scene: &mut Scene<I16F16>,
    bounce: Bounce<I16F16>,
    at: (u16, u16),
    panel: &mut Panel,
    serial: &mut impl Write,
    timer: &Timer,
) -> ! {
    let mut base = Scene::<I16F16>::empty();
    // `load` read the same text without error.
    let _ = load(&mut base);
    let size = (scene.camera.width, scene.camera.height);
    // `load` made the orbit and checked every object and light turns.
    let Ok(orbit) = Orbit::boing(&base.objects) else {
        halt(serial, "the orbit cannot be made")
    };
    loop {
        for k in 0..bounce.frames() {
            let start = timer.get_counter();
            scene.clone_from(&base);
            // `load` placed every frame of the bounce and checked the orbit's turns.
            let _ = bounce.apply(scene, k);
            let _ = orbit.apply(scene, k);
            let frame = panel_frame(scene).with_sampling(ORBIT_SAMPLING);
            let pixels = draw_bands(&frame, size, at, panel);
            let us = (timer.get_counter() - start).to_micros();
            let _ = write!(serial, "frame={k} us={us} pixels={pixels}\r\n");
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
    // A debugger's reset restarts core 0 only: hold core 1 until it is launched.
    if CORES == 2 {
        pac.PSM.frce_off().modify(|_, w| w.proc1().set_bit());
    }
    let mut watchdog = Watchdog::new(pac.WATCHDOG);
    let clocks = clock::init(
        XTAL_HZ,
        SYS_HZ,
        clock::Parts {
            xosc: pac.XOSC,
            clocks: pac.CLOCKS,
            pll_sys: pac.PLL_SYS,
            pll_usb: pac.PLL_USB,
            vreg: &mut pac.VREG_AND_CHIP_RESET,
            resets: &mut pac.RESETS,
            watchdog: &mut watchdog,
        },
    )
    .expect("the clocks start from the Pico's 12 MHz crystal");
    // The 1 MHz timer: frame times, and the delays of the display's reset and init.
    let timer = Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);
    let mut sio = Sio::new(pac.SIO);
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
        // 115200 baud is well within the dividers' range at 125 and 200 MHz.
        .expect("115200 baud from the peripheral clock");

    // SPI0 on GP18 (SCK) and GP19 (MOSI), write-only; CS, DC, reset and backlight as
    // plain outputs (reset starts high: inactive).
    let sck = pins.gpio18.into_function::<gpio::FunctionSpi>();
    let mosi = pins.gpio19.into_function::<gpio::FunctionSpi>();
    let mut bus = Spi::<_, _, _, 8>::new(pac.SPI0, (mosi, sck));
    let spi_hz = bus.set_baudrate(clocks.peripheral_clock.freq(), SPI_HZ.Hz());
    let bus = bus.init(
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
    let dma = pac.DMA.split(&mut pac.RESETS);
    let mut delay = timer;
    let mut panel = Panel::init(bus, dma.ch0, dc, cs, reset, &mut delay);
    // SAFETY: before any frame, slot 0 is core 0's and nothing is in flight.
    let blank = unsafe { &mut *line(0) };

    let mut scene = Scene::<I16F16>::empty();
    let bounce = match load(&mut scene) {
        Ok(bounce) => bounce,
        Err(e) => {
            panel.fill(ERROR_COLOUR, blank);
            panel.on(&mut delay);
            halt(&mut serial, e)
        }
    };
    panel.fill(0x0000, blank);
    panel.on(&mut delay);
    let (width, height) = (scene.camera.width, scene.camera.height);
    let (x, y) = ((PANEL_WIDTH - width) / 2, (PANEL_HEIGHT - height) / 2);

    // Core 1 draws every other row once it has answered the launch handshake; if it does
    // not, core 0 draws them all.
    let mut cores = 1;
    if CORES == 2 && PROGRAM == Program::Bounce {
        let mut multicore = Multicore::new(&mut pac.PSM, &mut pac.PPB, &mut sio.fifo);
        if let Some(stack) = CORE1_STACK.take()
            && multicore.cores()[1].spawn(stack, || core1()).is_ok()
        {
            cores = 2;
        }
    }
    let cores_named = if cores == 1 { "1 core" } else { "2 cores" };
    // The serial report is informational: a failed write (the blocking UART does not
    // fail) must not stop the animation, so its result is ignored here and below.
    let _ = write!(
        serial,
        "fixray boing: {width}x{height} at ({x},{y}) on a {PANEL_WIDTH}x{PANEL_HEIGHT} panel, \
         {} MHz, {cores_named}, SPI {} kHz, {}\r\n",
        SYS_HZ / 1_000_000,
        spi_hz.to_kHz(),
        match (PROGRAM, ORBIT_SAMPLING) {
            (Program::Bounce, _) if CHANGES_ONLY => "changes only",
            (Program::Bounce, _) => "whole frames",
            (Program::Orbit, Sampling::Exact) => "orbit, exact",
            (Program::Orbit, Sampling::Blocks { .. }) => "orbit, 8x8 blocks, bound 8",
        },
    );
    if PROGRAM == Program::Orbit {
        orbit(&mut scene, bounce, (x, y), &mut panel, &mut serial, &timer);
    }

    // The second scene: frames are drawn on it and on `scene` in turn ([`in_turn`]), the
    // one drawn last being the next one's frame shown before.
    let mut shown = Scene::<I16F16>::empty();
    let _ = load(&mut shown);
    let mut k = 0;
    let mut first = true;
    let mut ctx = (panel, sio.fifo, serial);
    in_turn(
        &bounce,
        (&mut scene, &mut shown),
        &mut ctx,
        |(_, fifo, _)| {
            let started = (k, timer.get_counter());
            if cores == 2 {
                fifo.write_blocking(frame_start(k, first));
            }
            let whole = first;
            first = false;
            k = next_frame(&bounce, k);
            (started.0, whole, started)
        },
        |(panel, fifo, serial), (k, start), frame, before| {
            let pixels = draw_frame(frame, before, (width, height), (x, y), cores, panel, fifo);
            let us = (timer.get_counter() - start).to_micros();
            let _ = write!(serial, "frame={k} us={us} pixels={pixels}\r\n");
        },
    )
}
