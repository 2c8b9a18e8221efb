//! The ST7789 on SPI0: commands written by the CPU, pixels streamed by DMA.
//!
//! Each row (or the part of it that changed) is a window (CASET, RASET) and a RAMWR
//! written by the CPU, then its pixels as big-endian RGB565 bytes with DC high, sent by
//! DMA from a line buffer while the CPU draws the next row into another: the CPU waits on
//! the display only when it has drawn a row before the previous one has left, and at the
//! frame's end. The panel keeps what it was sent: rows that did not change are not sent.

use embedded_hal::delay::DelayNs;
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::SpiBus;
use rp2040_hal::dma::{CH0, Channel, single_buffer};
use rp2040_hal::gpio::bank0::{Gpio16, Gpio17, Gpio18, Gpio19, Gpio20};
use rp2040_hal::gpio::{FunctionSioOutput, FunctionSpi, Pin, PullDown};
use rp2040_hal::pac;
use rp2040_hal::spi::{Enabled, Spi};

use crate::{PANEL_HEIGHT, PANEL_WIDTH};

/// One panel row: two bytes a pixel.
pub const LINE_BYTES: usize = 2 * PANEL_WIDTH as usize;
/// A line buffer as the DMA reads it.
pub type Line = [u8; LINE_BYTES];

/// SPI0 with GP19 as TX and GP18 as SCK, 8-bit frames.
pub type Bus = Spi<
    Enabled,
    pac::SPI0,
    (
        Pin<Gpio19, FunctionSpi, PullDown>,
        Pin<Gpio18, FunctionSpi, PullDown>,
    ),
    8,
>;
type Output<P> = Pin<P, FunctionSioOutput, PullDown>;
type Sending = single_buffer::Transfer<Channel<CH0>, &'static [u8], Bus>;

/// What the link between the CPU and the panel is doing.
enum Link {
    /// Nothing in flight: the channel and the bus are here.
    Idle(Channel<CH0>, Bus),
    /// A row in flight from the line buffer `slot`.
    Sending(Sending, usize),
}

/// The panel: its pins, the bus and the DMA channel.
pub struct Panel {
    link: Option<Link>,
    dc: Output<Gpio16>,
    /// Held low: the panel is the bus's only device.
    _cs: Output<Gpio17>,
    /// The window being filled: its columns and the row the next pixels go to.
    open: Option<(u16, u16, u16)>,
}

// ST7789 commands (its datasheet, section 9.1).
const SLPOUT: u8 = 0x11;
const NORON: u8 = 0x13;
const INVON: u8 = 0x21;
const DISPON: u8 = 0x29;
const CASET: u8 = 0x2a;
const RASET: u8 = 0x2b;
const RAMWR: u8 = 0x2c;
const MADCTL: u8 = 0x36;
const COLMOD: u8 = 0x3a;

impl Panel {
    /// Resets the controller and wakes it: 16-bit colour, top-left origin, colours
    /// inverted (the IPS modules' panels need it); [`Panel::on`] turns the display on.
    /// The same sequence and delays as the `mipidsi` driver's for the ST7789.
    pub fn init(
        bus: Bus,
        channel: Channel<CH0>,
        dc: Output<Gpio16>,
        mut cs: Output<Gpio17>,
        mut reset: Output<Gpio20>,
        delay: &mut impl DelayNs,
    ) -> Self {
        // The RP2040's pins cannot fail (their error type is `Infallible`). CS stays low:
        // the panel is the bus's only device.
        let Ok(()) = cs.set_low();
        let Ok(()) = reset.set_low();
        // At least the controller's 10 µs (the 1 MHz timer's first tick can come early).
        delay.delay_us(20);
        let Ok(()) = reset.set_high();
        let mut panel = Panel {
            link: Some(Link::Idle(channel, bus)),
            dc,
            _cs: cs,
            open: None,
        };
        delay.delay_ms(150);
        panel.command(SLPOUT, &[]);
        delay.delay_ms(10);
        panel.command(MADCTL, &[0x00]);
        panel.command(INVON, &[]);
        panel.command(COLMOD, &[0x55]);
        delay.delay_ms(10);
        panel.command(NORON, &[]);
        delay.delay_ms(10);
        panel
    }

    /// Turns the display on (after the first fill: the panel never shows its memory's
    /// power-on contents).
    pub fn on(&mut self, delay: &mut impl DelayNs) {
        self.command(DISPON, &[]);
        delay.delay_ms(120);
    }

    /// Opens the window `x0..=x1`, `y0..=y1`: the pixels sent next fill it.
    fn window(&mut self, x0: u16, y0: u16, x1: u16, y1: u16) {
        self.open = None;
        let [a, b] = x0.to_be_bytes();
        let [c, d] = x1.to_be_bytes();
        self.command(CASET, &[a, b, c, d]);
        let [a, b] = y0.to_be_bytes();
        let [c, d] = y1.to_be_bytes();
        self.command(RASET, &[a, b, c, d]);
        self.command(RAMWR, &[]);
    }

    /// Sends `pixels` (from the line buffer `slot`) by DMA to columns `x0..` of row `y`,
    /// once the row before it has gone. A row that continues the open window (the same
    /// columns, the next row) follows the one before in the same RAMWR; another opens a
    /// window from its row to the panel's last (CASET, RASET, RAMWR: 11 bytes). Returns
    /// the slot of the row before, whose buffer is free again.
    pub fn send(
        &mut self,
        (x0, y): (u16, u16),
        slot: usize,
        pixels: &'static [u8],
    ) -> Option<usize> {
        self.send_rows((x0, y), (pixels.len() / 2) as u16, slot, pixels)
    }

    /// [`Panel::send`] for whole rows of `width` pixels from row `y` on (a band of rows
    /// in one transfer).
    pub fn send_rows(
        &mut self,
        (x0, y): (u16, u16),
        width: u16,
        slot: usize,
        pixels: &'static [u8],
    ) -> Option<usize> {
        let freed = self.finish();
        if width == 0 {
            return freed;
        }
        let x1 = x0 + width - 1;
        let rows = (pixels.len() / 2) as u16 / width;
        if self.open != Some((x0, x1, y)) {
            self.window(x0, y, x1, PANEL_HEIGHT - 1);
        }
        self.open = Some((x0, x1, y + rows));
        let (channel, bus, _) = self.idle();
        let sending = single_buffer::Config::new(channel, pixels, bus).start();
        self.link = Some(Link::Sending(sending, slot));
        freed
    }

    /// Waits until the last row has gone; returns its slot.
    pub fn finish(&mut self) -> Option<usize> {
        let (channel, bus, freed) = self.idle();
        self.link = Some(Link::Idle(channel, bus));
        freed
    }

    /// Fills the whole panel with one colour (big-endian RGB565), sent from `line`.
    pub fn fill(&mut self, colour: u16, line: &'static mut Line) {
        for pair in line.chunks_exact_mut(2) {
            pair.copy_from_slice(&colour.to_be_bytes());
        }
        let line: &'static [u8] = line;
        for y in 0..PANEL_HEIGHT {
            self.send((0, y), 0, line);
        }
        self.finish();
    }

    /// The channel and the bus, once nothing is in flight, and the slot that was.
    fn idle(&mut self) -> (Channel<CH0>, Bus, Option<usize>) {
        match self.link.take() {
            Some(Link::Idle(channel, bus)) => (channel, bus, None),
            Some(Link::Sending(sending, slot)) => {
                let (channel, _, bus) = sending.wait();
                (channel, bus, Some(slot))
            }
            // `link` is only ever empty inside this function and `send`.
            None => unreachable!("the panel's link is always put back"),
        }
    }

    /// Writes one command and its parameters with the CPU (DC low for the command).
    /// Called between frames only: no row is in flight, so no freed slot is lost.
    fn command(&mut self, command: u8, parameters: &[u8]) {
        let (channel, mut bus, freed) = self.idle();
        debug_assert!(freed.is_none(), "a command is written between frames");
        // The bus's last bytes shift out before DC changes; a DMA transfer leaves received
        // bytes behind, which the blocking writes below must not mistake for theirs.
        while bus.is_busy() {}
        drain_received();
        let Ok(()) = self.dc.set_low();
        let Ok(()) = bus.write(&[command]);
        let Ok(()) = bus.flush();
        let Ok(()) = self.dc.set_high();
        if !parameters.is_empty() {
            let Ok(()) = bus.write(parameters);
            let Ok(()) = bus.flush();
        }
        self.link = Some(Link::Idle(channel, bus));
    }
}

/// Empties SPI0's receive FIFO and clears its overrun flag (a send-only DMA transfer fills
/// both).
fn drain_received() {
    // SAFETY: reads of SPI0's data and status registers and a write-1-to-clear of its
    // overrun flag; the bus is idle (the caller waited) and owned by the caller.
    let spi0 = unsafe { &*pac::SPI0::ptr() };
    while spi0.sspsr().read().rne().bit_is_set() {
        let _ = spi0.sspdr().read();
    }
    spi0.sspicr().write(|w| w.roric().clear_bit_by_one());
}
