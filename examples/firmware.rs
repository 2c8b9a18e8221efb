//! `firmware`: the ray caster on a microcontroller (Cortex-M0, Cortex-M4F, RISC-V rv32imc).
//! Parses the default scene and the boing
//! ball's scene at run time with the library's parser, renders them one scanline at a
//! time into a line buffer (no framebuffer) in every number format built in (the boing
//! ball 16 times, its sphere moved along its bounce by `fixray::anim::Bounce`), and
//! reports each frame over semihosting as one line (`frame=K` for the ball's frames):
//!
//! ```text
//! format=i16f16 size=160x120 hash=0x1a2b3c4d instructions=1234567 per_pixel=64.3 stack=2048 parse_instructions=… hash_instructions=…
//! ```
//!
//! `hash` is [`fixray::hash::FrameHash`] over every pixel (the host computes the same);
//! `instructions` counts the frame loop (`Frame::new`, `Frame::render_line` per row, and
//! hashing each pixel); the hashing
//! alone is measured too (`hash_instructions`), so the renderer's share is the difference.
//! `stack` is the deepest stack use seen during parse + frame (painted stack).
//!
//! Run it under QEMU (the runners are in `.cargo/config.toml`; needs `qemu-system-arm`, and
//! `qemu-system-misc` for RISC-V):
//! ```text
//! cargo run --release --example firmware --target thumbv6m-none-eabi      # Cortex-M0 (micro:bit)
//! cargo run --release --example firmware --target thumbv7em-none-eabihf  # Cortex-M4F (MPS2 AN386)
//! cargo run --release --example firmware --target riscv32imc-unknown-none-elf  # RISC-V (QEMU virt)
//! FIXRAY_FW_FORMATS=i16f16 cargo build ...   # only some formats (to measure flash per format)
//! FIXRAY_FW_SCENES=default,planes cargo ...  # which scenes/ to embed (default: default,boing)
//! FIXRAY_FW_SPANS=1 cargo run ...            # pure-geometry plane scenes in span mode
//! FIXRAY_FW_SAMPLING=8x8:8,4x4:1 cargo run --features sampling ...  # each frame also sampled in blocks
//! FIXRAY_FW_PPM=1 cargo run ...              # also write fixray-<core>-<scene>[NN]-<format>.ppm (Arm)
//! ```
//!
//! Counting: on the Arm boards QEMU does not model the cycle counter, but with
//! `-icount shift=0` each instruction advances virtual time by 1 ns, so SysTick (at the
//! board's 16 or 25 MHz) ticks once per 62.5 or 40 instructions: counts are deterministic,
//! their resolution one tick. On RISC-V the `minstret` counter counts retired instructions
//! exactly (with `-icount shift=0`). A calibration line at start-up checks the count with
//! 4000 instructions of `nop` loop.
//!
//! The boards (`board` below, one module per architecture, chosen by `target_arch`): how
//! instructions are counted, how a line reaches the host, how the program ends, the stack's
//! bounds. Everything else is the same code on every core.
//!
//! Off target (host builds, `cargo test`) this example compiles to an empty `main`.

#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[cfg(not(target_os = "none"))]
fn main() {
    // Firmware: build it for thumbv6m-none-eabi, thumbv7em-none-eabihf or
    // riscv32imc-unknown-none-elf (see above).
}

#[cfg(target_os = "none")]
mod firmware {
    use embedded_graphics::pixelcolor::Rgb888;
    use fixray::anim::Bounce;
    use fixray::hash::FrameHash;
    use fixray::{Frame, PlaneMode, Scalar, Scene};

    use board::{BOARD, instructions, say};

    // The scenes, as text (parsed on the chip): `SCENES`, chosen at build time by
    // FIXRAY_FW_SCENES (default: the default scene and the boing ball).
    include!(concat!(env!("OUT_DIR"), "/fw_scenes.rs"));

    /// The line buffer's capacity in pixels: a 240-pixel-wide panel (an ST7789 240×240),
    /// 720 bytes of the 16 KB (no more: the shipped scenes are at most 160 wide, and the
    /// deepest I32F32 frame needs the rest of its budget).
    const MAX_WIDTH: usize = 240;

    /// The painted stack's pattern.
    const PAINT: u32 = 0xC0DE_F00D;

    unsafe extern "C" {
        /// End of .bss (and of the heap, empty: both runtimes' `_heap_size` is 0 here):
        /// the lowest address the stack may grow to. cortex-m-rt and riscv-rt both
        /// define it.
        static mut __sheap: u32;
        /// Top of the stack (both runtimes).
        static _stack_start: u32;
    }

    /// Fills the free stack below the current stack pointer with `PAINT`.
    fn paint_stack() {
        let bottom = (&raw mut __sheap).cast::<u32>();
        // Leave 64 bytes under the current frame untouched.
        let top = (board::sp() - 64) as *mut u32;
        let mut p = bottom;
        while p < top {
            // SAFETY: [__sheap, sp − 64) is unused stack: nothing lives there now.
            unsafe { p.write_volatile(PAINT) };
            p = p.wrapping_add(1);
        }
    }

    /// Bytes of stack used since `paint_stack`: from the top down to the lowest word that
    /// no longer holds the pattern.
    fn stack_used() -> usize {
        let bottom = (&raw mut __sheap).cast::<u32>();
        let top = (&raw const _stack_start) as usize;
        let mut p = bottom;
        // SAFETY: reading the stack region between the end of .bss and its top.
        while (p as usize) < top && unsafe { p.read_volatile() } == PAINT {
            p = p.wrapping_add(1);
        }
        top - p as usize
    }

    /// The Arm boards under QEMU: BBC micro:bit (Cortex-M0) and MPS2 AN386 (Cortex-M4F).
    /// Instructions are counted by SysTick (`-icount shift=0`), lines and the exit go over
    /// semihosting.
    #[cfg(target_arch = "arm")]
    mod board {
        use core::sync::atomic::{AtomicU32, Ordering};

        use cortex_m::peripheral::SYST;
        use cortex_m::peripheral::syst::SystClkSource;
        use cortex_m_rt::exception;
        use cortex_m_semihosting::{debug, hprintln};
        use panic_semihosting as _;

        /// Board name and SysTick rate: instructions per tick × 2 (62.5 is not an integer).
        #[cfg(fw_microbit)]
        pub const BOARD: (&str, u64) = ("cortex-m0", 125);
        #[cfg(fw_mps2)]
        pub const BOARD: (&str, u64) = ("cortex-m4f", 80);

        static WRAPS: AtomicU32 = AtomicU32::new(0);

        #[exception]
        fn SysTick() {
            // Only this handler writes WRAPS: a load and a store are enough (the M0 has no
            // atomic read-modify-write).
            WRAPS.store(WRAPS.load(Ordering::Relaxed) + 1, Ordering::Relaxed);
        }

        /// Starts SysTick from a full period.
        pub fn start() {
            let Some(mut core) = cortex_m::Peripherals::take() else {
                say(format_args!("error=\"core peripherals taken\""));
                exit();
            };
            let syst = &mut core.SYST;
            syst.set_clock_source(SystClkSource::Core);
            syst.set_reload(0x00FF_FFFF);
            syst.clear_current();
            syst.enable_interrupt();
            syst.enable_counter();
            // The counter starts at 0 and loads the reload value on its first tick; wait
            // for that, so that counting starts from a full period.
            while SYST::get_current() == 0 {}
        }

        /// Executed instructions since SysTick was started (24-bit counter + wraps).
        pub fn instructions() -> u64 {
            loop {
                let wraps = WRAPS.load(Ordering::Relaxed);
                let current = SYST::get_current();
                if WRAPS.load(Ordering::Relaxed) == wraps {
                    let ticks = (u64::from(wraps) << 24) + u64::from(0x00FF_FFFF - current);
                    return ticks * BOARD.1 / 2;
                }
            }
        }

        /// One line to the host. Out of line: its own formatting state is not in the
        /// frames under the renderer (the stack figures are the renderer's).
        #[inline(never)]
        pub fn say(line: core::fmt::Arguments<'_>) {
            hprintln!("{}", line);
        }

        /// Ends the program (QEMU exits with status 0).
        pub fn exit() -> ! {
            debug::exit(debug::EXIT_SUCCESS);
            // Only reached without a semihosting host: sleep.
            loop {
                cortex_m::asm::wfi();
            }
        }

        /// The stack pointer (main stack).
        pub fn sp() -> usize {
            cortex_m::register::msp::read() as usize
        }

        /// Exactly 4000 instructions: 1000 rounds of two `nop`s, a subtract and a branch.
        #[inline(never)]
        pub fn nops() {
            // SAFETY: nops and a counted loop on a scratch register.
            unsafe {
                core::arch::asm!(
                    "2:", "nop", "nop", "subs {n}, #1", "bne 2b",
                    n = inout(reg) 1000u32 => _,
                    options(nomem, nostack),
                );
            }
        }

        #[cortex_m_rt::entry]
        fn main() -> ! {
            super::main()
        }
    }

    /// RISC-V (rv32imc, no FPU) on QEMU's `virt` board (`-bios none`; program at
    /// 0x8000_0000, `memory-riscv.x`): instructions are counted by `minstret` (exact with
    /// `-icount shift=0`), lines go to the 16550 UART at 0x1000_0000, the program ends by
    /// writing to the test device at 0x10_0000.
    #[cfg(target_arch = "riscv32")]
    mod board {
        use core::fmt::Write;

        /// Board name (the Arm boards' second field, their SysTick rate, has no use
        /// here: `minstret` counts instructions one by one).
        pub const BOARD: (&str, u64) = ("riscv32imc", 2);

        /// The 16550 UART's transmit register and line status register.
        const UART_THR: *mut u8 = 0x1000_0000 as *mut u8;
        const UART_LSR: *const u8 = 0x1000_0005 as *const u8;
        /// The `sifive_test` device: 0x5555 ends QEMU with status 0, `code << 16 | 0x3333`
        /// with status `code`.
        const FINISHER: *mut u32 = 0x0010_0000 as *mut u32;

        /// Nothing to start: `minstret` runs from reset.
        pub fn start() {}

        /// Instructions retired since reset.
        pub fn instructions() -> u64 {
            riscv::register::minstret::read64()
        }

        struct Uart;

        impl Write for Uart {
            fn write_str(&mut self, s: &str) -> core::fmt::Result {
                for b in s.bytes() {
                    // SAFETY: the virt board's UART registers; wait until the transmit
                    // holding register is empty (LSR bit 5), then write the byte.
                    unsafe {
                        while UART_LSR.read_volatile() & 0x20 == 0 {}
                        UART_THR.write_volatile(b);
                    }
                }
                Ok(())
            }
        }

        /// One line to the host (out of line, as on the Arm boards).
        #[inline(never)]
        pub fn say(line: core::fmt::Arguments<'_>) {
            let _ = Uart.write_fmt(line);
            let _ = Uart.write_str("\n");
        }

        /// Ends QEMU with `status`.
        fn finish(status: u32) -> ! {
            let word = if status == 0 {
                0x5555
            } else {
                (status << 16) | 0x3333
            };
            // SAFETY: the virt board's test device; the write ends the emulation.
            unsafe { FINISHER.write_volatile(word) };
            loop {
                riscv::asm::wfi();
            }
        }

        /// Ends the program (QEMU exits with status 0).
        pub fn exit() -> ! {
            finish(0)
        }

        #[panic_handler]
        fn panic(info: &core::panic::PanicInfo<'_>) -> ! {
            say(format_args!("panic: {info}"));
            finish(1)
        }

        /// Any exception (riscv-rt's default spins forever, until the runner's
        /// `timeout`): its cause and address, then QEMU ends with status 3.
        #[unsafe(export_name = "ExceptionHandler")]
        fn exception(_frame: &riscv_rt::TrapFrame) -> ! {
            let (cause, pc) = (
                riscv::register::mcause::read().bits(),
                riscv::register::mepc::read(),
            );
            say(format_args!("exception: mcause={cause:#x} mepc={pc:#x}"));
            finish(3)
        }

        /// The stack pointer.
        pub fn sp() -> usize {
            let sp: usize;
            // SAFETY: reads a register.
            unsafe { core::arch::asm!("mv {}, sp", out(reg) sp, options(nomem, nostack)) };
            sp
        }

        /// Exactly 4000 instructions: 1000 rounds of two `nop`s, a decrement and a branch.
        #[inline(never)]
        pub fn nops() {
            // SAFETY: nops and a counted loop on a scratch register.
            unsafe {
                core::arch::asm!(
                    "2:", "nop", "nop", "addi {n}, {n}, -1", "bnez {n}, 2b",
                    n = inout(reg) 1000u32 => _,
                    options(nomem, nostack),
                );
            }
        }

        #[riscv_rt::entry]
        fn main() -> ! {
            super::main()
        }
    }

    /// Writes one frame to the host as `fixray-<core>-<scene>[NN]-<format>.ppm` (`NN`:
    /// an animation's frame number, e.g. `fixray-cortex-m0-boing07-i16f16.ppm`; semihosting
    /// file I/O).
    #[cfg(all(fw_ppm, target_arch = "arm"))]
    fn write_ppm<S: Scalar>(
        name: &str,
        frame_no: Option<u16>,
        scene: &Scene<S>,
        line: &mut [Rgb888],
    ) {
        use core::fmt::Write;
        use cortex_m_semihosting::{nr, syscall};
        use embedded_graphics::pixelcolor::RgbColor;
        let scene_name = name;
        let mut name: heapless::String<64> = heapless::String::new();
        let _ = write!(name, "fixray-{}-{}", BOARD.0, scene_name);
        if let Some(k) = frame_no {
            let _ = write!(name, "{k:02}");
        }
        let _ = write!(name, "-{}.ppm\0", S::NAME);
        // SAFETY: semihosting OPEN with a NUL-terminated name and its length without NUL.
        let fd = unsafe {
            syscall!(
                OPEN,
                name.as_ptr(),
                nr::open::W_TRUNC_BINARY,
                name.len() - 1
            )
        };
        if fd as isize == -1 {
            say(format_args!("format={} ppm=failed", S::NAME));
            return;
        }
        let write = |bytes: &[u8]| {
            // SAFETY: semihosting WRITE of a live buffer.
            unsafe { syscall!(WRITE, fd, bytes.as_ptr(), bytes.len()) };
        };
        let mut header: heapless::String<32> = heapless::String::new();
        let _ = write!(
            header,
            "P6\n{} {}\n255\n",
            scene.camera.width, scene.camera.height
        );
        write(header.as_bytes());
        let w = usize::from(scene.camera.width);
        let frame = Frame::with_mode(scene, MODE);
        for row in 0..scene.camera.height {
            frame.render_line(row, &mut line[..w]);
            let mut bytes = [0u8; 3 * MAX_WIDTH];
            for (chunk, c) in bytes.chunks_mut(3).zip(&line[..w]) {
                chunk.copy_from_slice(&[c.r(), c.g(), c.b()]);
            }
            write(&bytes[..3 * w]);
        }
        // SAFETY: semihosting CLOSE of the descriptor opened above.
        unsafe { syscall!(CLOSE, fd) };
        say(format_args!(
            "format={} ppm={}",
            S::NAME,
            name.trim_end_matches('\0')
        ));
    }

    /// How pure-geometry plane scenes are drawn (`FIXRAY_FW_SPANS=1`: in spans).
    #[cfg(fw_spans)]
    const MODE: PlaneMode = PlaneMode::Spans;
    #[cfg(not(fw_spans))]
    const MODE: PlaneMode = PlaneMode::PerPixel;

    /// The formats this firmware renders (`FIXRAY_FW_FORMATS`, checked against
    /// `fixray::num::formats::FORMATS` by the build script).
    const FORMATS: &str = env!("FIXRAY_FW_FORMATS_BUILT");

    /// Whether `name` is one of the comma-separated names of [`FORMATS`] (at compile time:
    /// a format not asked for is not built in).
    const fn wanted(name: &str) -> bool {
        let (list, name) = (FORMATS.as_bytes(), name.as_bytes());
        let mut start = 0;
        while start <= list.len() {
            let mut end = start;
            while end < list.len() && list[end] != b',' {
                end += 1;
            }
            if end - start == name.len() {
                let mut i = 0;
                while i < name.len() && list[start + i] == name[i] {
                    i += 1;
                }
                if i == name.len() {
                    return true;
                }
            }
            start = end + 1;
        }
        false
    }

    /// Renders every scene in format `S`, if it is built in.
    fn frames<S: Scalar>(line: &mut [Rgb888; MAX_WIDTH]) {
        if !const { wanted(S::NAME) } {
            return;
        }
        for (name, text) in SCENES {
            frame::<S>(name, text, line);
        }
    }

    /// Parses one scene in format `S`, renders one frame and reports it.
    #[inline(never)]
    fn frame<S: Scalar>(name: &str, text: &str, line: &mut [Rgb888; MAX_WIDTH]) {
        paint_stack();
        let start = instructions();
        let mut scene = Scene::<S>::empty();
        let mut files = |name: &str| TEXTURES.iter().find(|t| t.0 == name).map(|t| t.1);
        if let Err(e) = scene.read_with(text, None, &mut files) {
            say(format_args!(
                "format={} scene={} error=\"scenes/{}.scene:{}\"",
                S::NAME,
                name,
                name,
                e
            ));
            return;
        }
        let parsed = instructions();
        let w = usize::from(scene.camera.width);
        if w > MAX_WIDTH {
            say(format_args!(
                "format={} scene={} error=\"width {} > line buffer {}\"",
                S::NAME,
                name,
                w,
                MAX_WIDTH
            ));
            return;
        }
        frames_of(name, &mut scene, parsed - start, line);
    }

    /// Renders the frames of a parsed scene and reports each: one, or the boing ball's 16
    /// (its sphere moved per frame, no re-parsing). Out of line, beside the parser (its
    /// frame and the parser's do not add up on the stack).
    #[inline(never)]
    fn frames_of<S: Scalar>(
        name: &str,
        scene: &mut Scene<S>,
        parse: u64,
        line: &mut [Rgb888; MAX_WIDTH],
    ) {
        let bounce = if name == ANIMATED {
            match Bounce::boing(&scene.objects) {
                Ok(b) => Some(b),
                Err(e) => {
                    say(format_args!(
                        "format={} scene={} error=\"{}\"",
                        S::NAME,
                        name,
                        e
                    ));
                    return;
                }
            }
        } else {
            None
        };
        for k in 0..bounce.map_or(1, |b| b.frames()) {
            if let Some(b) = bounce {
                if let Err(e) = b.apply(scene, k) {
                    say(format_args!(
                        "format={} scene={} error=\"{}\"",
                        S::NAME,
                        name,
                        e
                    ));
                    return;
                }
                if k > 0 {
                    // Each frame's stack on its own (the first's includes the parse).
                    paint_stack();
                }
            }
            draw(name, scene, bounce.map(|_| k), parse, line);
        }
    }

    /// The scene the firmware animates (`fixray::anim::Bounce::boing`), one report line
    /// per frame with `frame=K`.
    const ANIMATED: &str = "boing";

    /// Renders one frame of a parsed scene and reports it (`parse`: the parse's
    /// instructions, reported with every frame of the scene). Inlined (into
    /// `frames_of`): out of line, its frame made the deepest I32F32 stack deeper.
    #[inline(always)]
    fn draw<S: Scalar>(
        name: &str,
        scene: &Scene<S>,
        frame_no: Option<u16>,
        parse: u64,
        line: &mut [Rgb888; MAX_WIDTH],
    ) {
        let (w, h) = (usize::from(scene.camera.width), scene.camera.height);
        let mut hash = FrameHash::new();
        let before = instructions();
        // What is constant for the frame is computed once (`Frame`), then line by line.
        let frame = Frame::with_mode(scene, MODE);
        for row in 0..h {
            frame.render_line(row, &mut line[..w]);
            for c in &line[..w] {
                hash.push(*c);
            }
        }
        let after = instructions();
        let stack = stack_used();
        // The hashing alone, over the last line as many times: its share of `instructions`.
        let mut sink = FrameHash::new();
        let hash_start = instructions();
        for _ in 0..h {
            for c in &line[..w] {
                sink.push(*c);
            }
        }
        let hash_cost = instructions() - hash_start;
        core::hint::black_box(sink);
        let pixels = (w as u64) * u64::from(h);
        let frame = after - before;
        let tenths = frame * 10 / pixels;
        say(format_args!(
            "format={} size={}x{} hash=0x{:08x} instructions={} per_pixel={}.{} stack={} parse_instructions={} hash_instructions={} core={} scene={} mode={:?}{}",
            S::NAME,
            w,
            h,
            hash.value(),
            frame,
            tenths / 10,
            tenths % 10,
            stack,
            parse,
            hash_cost,
            BOARD.0,
            name,
            MODE,
            FrameNo(frame_no)
        ));
        #[cfg(all(fw_ppm, target_arch = "arm"))]
        write_ppm(name, frame_no, scene, line);
        #[cfg(fw_sampling)]
        sampled::frames(name, scene, frame_no);
    }

    /// The frame sampled in blocks (`FIXRAY_FW_SAMPLING`): one report line per mode,
    /// `sampling=8x8:8 filled=N` added, the frame drawn by `Frame::bands` a band of
    /// [`sampled::BAND`] rows at a time (the band's buffer is static: 5,760 bytes; each
    /// band's bottom corners are kept for the next).
    #[cfg(fw_sampling)]
    mod sampled {
        use embedded_graphics::pixelcolor::Rgb888;
        use fixray::hash::FrameHash;
        use fixray::{Frame, Sampling, Scalar, Scene};

        use super::board::{BOARD, instructions, say};
        use super::{FrameNo, MAX_WIDTH, MODE};

        /// Rows a band holds: the largest block's side.
        pub const BAND: usize = 8;

        /// The modes, as `FIXRAY_FW_SAMPLING` names them (checked by the build script).
        const MODES: &str = env!("FIXRAY_FW_SAMPLING_BUILT");

        /// The band's pixels.
        static mut PIXELS: [Rgb888; BAND * MAX_WIDTH] = [Rgb888::new(0, 0, 0); BAND * MAX_WIDTH];

        /// Draws and reports the frame in every mode of [`MODES`].
        #[inline(never)]
        pub fn frames<S: Scalar>(name: &str, scene: &Scene<S>, frame_no: Option<u16>) {
            // SAFETY: the firmware runs on one core without interrupts that touch the
            // band: this is its only reference.
            let band = unsafe { &mut *(&raw mut PIXELS) };
            let (w, h) = (usize::from(scene.camera.width), scene.camera.height);
            for text in MODES.split(',').filter(|m| !m.is_empty()) {
                let Ok(sampling) = text.parse::<Sampling>() else {
                    continue;
                };
                let mut hash = FrameHash::new();
                let before = instructions();
                let frame = Frame::with_mode(scene, MODE).with_sampling(sampling);
                let mut filled = 0;
                let mut top = 0;
                let mut bands = frame.bands();
                while top < h {
                    let rows = top..(top + BAND as u16).min(h);
                    let n = usize::from(rows.end - rows.start) * w;
                    filled += bands.render_rows(rows.clone(), &mut band[..n]);
                    for c in &band[..n] {
                        hash.push(*c);
                    }
                    top = rows.end;
                }
                let frame_instructions = instructions() - before;
                let pixels = (w as u64) * u64::from(h);
                let tenths = frame_instructions * 10 / pixels;
                say(format_args!(
                    "format={} size={}x{} hash=0x{:08x} instructions={} per_pixel={}.{} core={} scene={} sampling={} filled={}{}",
                    S::NAME,
                    w,
                    h,
                    hash.value(),
                    frame_instructions,
                    tenths / 10,
                    tenths % 10,
                    BOARD.0,
                    name,
                    text,
                    filled,
                    FrameNo(frame_no)
                ));
            }
        }
    }

    /// ` frame=K` for an animation's frame, nothing otherwise.
    struct FrameNo(Option<u16>);

    impl core::fmt::Display for FrameNo {
        fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
            match self.0 {
                Some(k) => write!(f, " frame={k}"),
                None => Ok(()),
            }
        }
    }

    /// Calibrates the count, then renders every scene in every format built in. Inlined
    /// into the board's entry: one frame under the renderer's, the board adding none.
    #[inline(always)]
    fn main() -> ! {
        board::start();
        // Calibration: 4000 instructions must count as 4000 (± one tick on the Arm
        // boards), plus the few instructions of the two reads.
        let a = instructions();
        board::nops();
        let b = instructions();
        say(format_args!(
            "calibration nops=4000 counted={} core={}",
            b - a,
            BOARD.0
        ));

        let mut line = [Rgb888::new(0, 0, 0); MAX_WIDTH];
        // Every format of the one list, in its order; `frames` skips those not built in.
        fixray::for_each_format!(all: frames(&mut line));
        board::exit()
    }
}
