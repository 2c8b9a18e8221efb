// Runs the board's firmware on an emulated RP2040 (rp2040js: one Cortex-M0+ core with its
// per-instruction cycle costs, SIO, SPI, DMA, UART, timer and clocks) and watches its two
// outputs: the UART0 lines, and the ST7789 panel rebuilt from the SPI0 byte stream (DC on
// GP16: CASET, RASET and RAMWR into a 240x320 controller memory).
//
//   node run.mjs ELF [--frames N] [--out DIR] [--instant-spi] [--patch OLD=NEW]...
//                    [--max-mcycles M] [--profile] [--profile-after K]
//                    [--callers NAME]
//
// The ELF's loadable segments go into the flash at their load addresses and the core starts
// at the second-stage bootloader (0x1000_0000) with LR = 0, as the boot ROM leaves it: boot2
// sets up execute-in-place and jumps through the vector table after it. The firmware must
// not call into the boot ROM (there is none here): build it with the `emulated` feature.
//
// Each SPI byte takes 8 SPI clocks at the rate the firmware configured (SSPCPSR and SCR
// from clk_peri), so the CPU waits on the display as it would on the board. --instant-spi
// completes every byte at once: the difference in cycles is the time spent waiting.
//
// A frame ends with the firmware's `frame=K ...` line. For each one the run prints a line
// `frame=K cycles=C clk_sys=HZ pixels=P draw_even=E draw_odd=O windows=W`: its emulated cycles (from
// the previous UART line), the pixels written, and the cycles spent drawing its rows on
// even and on odd panel rows (from the previous UART line or the previous row's first
// pixel to the row's first pixel: with the rows sent as they are drawn, a row's first
// pixel leaves when it is drawn), and the windows it opened (RAMWR commands). It
// also writes the panel (DIR/frame-K.rgb565, the
// panel's rows top to bottom, two big-endian bytes a pixel, 240 wide). DIR/run.json sums
// it up. --patch replaces bytes of the flash image (the scene text, say) before the run.
// --profile attributes the frames' cycles to the ELF's functions (from its symbol table)
// and prints the costliest; --profile-after K counts only the frames after frame K (the
// frames a loop repeats, without the first whole one); --callers NAME also counts the calls
// of the functions whose name holds NAME by calling function (from LR at their entry).

import { readFileSync, writeFileSync, mkdirSync } from 'node:fs';
import { RP2040 } from 'rp2040js';

const FLASH_BASE = 0x1000_0000;
const PANEL_COLUMNS = 240;
const PANEL_ROWS = 320;
const DC_PIN = 16;

function usage(message) {
  process.stderr.write(`error: ${message}\n`);
  process.stderr.write(
    'usage: node run.mjs ELF [--frames N] [--out DIR] [--instant-spi] [--patch OLD=NEW]... [--max-mcycles M] [--profile] [--profile-after K] [--callers NAME]\n',
  );
  process.exit(2);
}

function parseArgs(argv) {
  const args = {
    frames: 4,
    out: null,
    instantSpi: false,
    patches: [],
    maxCycles: 4e9,
    profile: false,
    profileAfter: -1,
    callers: null,
    elf: null,
  };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    const value = () => {
      if (i + 1 >= argv.length) usage(`${a} needs a value`);
      return argv[++i];
    };
    if (a === '--frames') args.frames = Number(value());
    else if (a === '--out') args.out = value();
    else if (a === '--instant-spi') args.instantSpi = true;
    else if (a === '--patch') {
      const p = value();
      const eq = p.indexOf('=');
      if (eq < 0) usage('--patch takes OLD=NEW');
      args.patches.push([p.slice(0, eq), p.slice(eq + 1)]);
    } else if (a === '--max-mcycles') args.maxCycles = Number(value()) * 1e6;
    else if (a === '--profile') args.profile = true;
    else if (a === '--profile-after') args.profileAfter = Number(argv[++i]);
    else if (a === '--callers') args.callers = argv[++i];
    else if (a.startsWith('--')) usage(`unknown option ${a}`);
    else if (args.elf === null) args.elf = a;
    else usage(`one ELF file, not ${a}`);
  }
  if (args.elf === null) usage('no ELF file');
  if (!(args.frames >= 1)) usage('--frames takes a number of frames, at least 1');
  return args;
}

/** Copies the ELF's PT_LOAD segments into `flash` at their physical (load) addresses. */
function loadElf(bytes, flash) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (view.getUint32(0, false) !== 0x7f454c46 || bytes[4] !== 1 || bytes[5] !== 1) {
    throw new Error('not a 32-bit little-endian ELF file');
  }
  const phoff = view.getUint32(28, true);
  const phentsize = view.getUint16(42, true);
  const phnum = view.getUint16(44, true);
  let loaded = 0;
  for (let i = 0; i < phnum; i++) {
    const h = phoff + i * phentsize;
    const type = view.getUint32(h, true);
    const offset = view.getUint32(h + 4, true);
    const paddr = view.getUint32(h + 12, true);
    const filesz = view.getUint32(h + 16, true);
    if (type !== 1 || filesz === 0) continue;
    if (paddr < FLASH_BASE || paddr + filesz > FLASH_BASE + flash.length) {
      throw new Error(`a loadable segment at 0x${paddr.toString(16)} lies outside the flash`);
    }
    flash.set(bytes.subarray(offset, offset + filesz), paddr - FLASH_BASE);
    loaded += filesz;
  }
  if (loaded === 0) throw new Error('the ELF file has nothing to load');
  return loaded;
}

/** The ELF's function symbols, sorted by address: [{ start, end, name }]. */
function functions(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const shoff = view.getUint32(32, true);
  const shentsize = view.getUint16(46, true);
  const shnum = view.getUint16(48, true);
  const section = (i) => {
    const h = shoff + i * shentsize;
    return {
      type: view.getUint32(h + 4, true),
      offset: view.getUint32(h + 16, true),
      size: view.getUint32(h + 20, true),
      link: view.getUint32(h + 24, true),
    };
  };
  const out = [];
  for (let i = 0; i < shnum; i++) {
    const symtab = section(i);
    if (symtab.type !== 2) continue; // SHT_SYMTAB
    const strtab = section(symtab.link);
    for (let at = symtab.offset; at < symtab.offset + symtab.size; at += 16) {
      const info = bytes[at + 12];
      const size = view.getUint32(at + 8, true);
      if ((info & 0xf) !== 2 || size === 0) continue; // STT_FUNC
      const start = view.getUint32(at + 4, true) & ~1;
      const nameAt = strtab.offset + view.getUint32(at, true);
      const name = Buffer.from(bytes.subarray(nameAt, bytes.indexOf(0, nameAt))).toString('latin1');
      out.push({ start, end: start + size, name: demangle(name) });
    }
  }
  return out.sort((a, b) => a.start - b.start);
}

/** A Rust symbol's path without its hash (`_ZN...17h...E`), or the name as it is. */
function demangle(name) {
  if (!name.startsWith('_ZN')) return name;
  const parts = [];
  let at = 3;
  while (at < name.length && name[at] !== 'E') {
    const digits = /^\d+/.exec(name.slice(at));
    if (!digits) return name;
    at += digits[0].length;
    parts.push(name.slice(at, at + Number(digits[0])));
    at += Number(digits[0]);
  }
  if (parts.length > 1 && /^h[0-9a-f]{16}$/.test(parts[parts.length - 1])) parts.pop();
  return parts
    .join('::')
    .replace(/\$LT\$/g, '<')
    .replace(/\$GT\$/g, '>')
    .replace(/\$u20\$/g, ' ')
    .replace(/\$C\$/g, ',')
    .replace(/\$RF\$/g, '&')
    .replace(/\$u7b\$/g, '{')
    .replace(/\$u7d\$/g, '}')
    .replace(/\.\./g, '::')
    .replace(/typenum::(uint|bit)::/g, '');
}

/** Cycles per function, looked up by PC (the last function found is tried first). */
class Profile {
  constructor(symbols) {
    this.symbols = symbols;
    this.cycles = new Map();
    this.calls = new Map();
    this.last = null;
    this.callers = null;
  }

  add(pc, cycles) {
    let f = this.last;
    if (f === null || pc < f.start || pc >= f.end) {
      let lo = 0;
      let hi = this.symbols.length - 1;
      f = null;
      while (lo <= hi) {
        const mid = (lo + hi) >> 1;
        const s = this.symbols[mid];
        if (pc < s.start) hi = mid - 1;
        else if (pc >= s.end) lo = mid + 1;
        else {
          f = s;
          break;
        }
      }
      f = f ?? { start: pc, end: pc + 2, name: `0x${pc.toString(16)}` };
      this.last = f;
    }
    this.cycles.set(f.name, (this.cycles.get(f.name) ?? 0) + cycles);
    // An instruction at a function's first address is a call (or a loop back to it).
    if (pc === f.start) {
      this.calls.set(f.name, (this.calls.get(f.name) ?? 0) + 1);
      if (this.callers !== null && f.name.includes(this.callers.of)) {
        const from = this.lookup((this.callers.lr() & ~1) - 2);
        const key = `${f.name} <- ${from}`;
        this.callers.counts.set(key, (this.callers.counts.get(key) ?? 0) + 1);
      }
    }
  }

  /** The name of the function holding `pc`. */
  lookup(pc) {
    let lo = 0;
    let hi = this.symbols.length - 1;
    while (lo <= hi) {
      const mid = (lo + hi) >> 1;
      const s = this.symbols[mid];
      if (pc < s.start) hi = mid - 1;
      else if (pc >= s.end) lo = mid + 1;
      else return s.name;
    }
    return `0x${pc.toString(16)}`;
  }

  print(total, top = 60) {
    const rows = [...this.cycles].sort((a, b) => b[1] - a[1]).slice(0, top);
    process.stdout.write(`profile: ${Math.round(total)} cycles after the start line (share, cycles, calls, function)\n`);
    for (const [name, c] of rows) {
      const calls = this.calls.get(name) ?? 0;
      process.stdout.write(
        `${((100 * c) / total).toFixed(2).padStart(6)} % ${String(Math.round(c)).padStart(11)} ${String(calls).padStart(9)}  ${name}\n`,
      );
    }
    if (this.callers !== null) {
      process.stdout.write(`callers of functions named *${this.callers.of}* (calls, callee <- caller)\n`);
      for (const [key, n] of [...this.callers.counts].sort((a, b) => b[1] - a[1]).slice(0, top)) {
        process.stdout.write(`${String(n).padStart(9)}  ${key}\n`);
      }
    }
  }
}

/** Replaces every occurrence of `from` in the flash image by `to` (the same length). */
function patchFlash(flash, from, to) {
  const a = Buffer.from(from, 'latin1');
  const b = Buffer.from(to, 'latin1');
  if (a.length !== b.length || a.length === 0) {
    throw new Error(`--patch ${from}=${to}: both sides must have the same, non-zero length`);
  }
  const image = Buffer.from(flash.buffer, flash.byteOffset, flash.byteLength);
  let count = 0;
  for (let at = image.indexOf(a); at >= 0; at = image.indexOf(a, at + 1)) {
    b.copy(image, at);
    count++;
  }
  if (count === 0) throw new Error(`--patch: "${from}" is not in the flash image`);
  return count;
}

/** The ST7789 as the firmware drives it: commands with DC low, their data with DC high. */
class Panel {
  constructor() {
    this.memory = new Uint16Array(PANEL_COLUMNS * PANEL_ROWS);
    this.command = null;
    this.args = [];
    this.window = { x0: 0, x1: PANEL_COLUMNS - 1, y0: 0, y1: PANEL_ROWS - 1 };
    this.x = 0;
    this.y = 0;
    this.high = null;
    this.pixels = 0;
    this.commands = 0;
    // Cycles spent drawing the rows, by the row's parity, since the last `take`.
    this.draw = [0, 0];
    this.mark = 0;
    // RAMWR commands since the last `take`.
    this.windows = 0;
  }

  byte(dc, value, now) {
    if (!dc) {
      this.command = value;
      this.args = [];
      this.high = null;
      this.commands++;
      if (value === 0x2c) {
        this.x = this.window.x0;
        this.y = this.window.y0;
        this.windows++;
      }
      return;
    }
    if (this.command === 0x2c) {
      if (this.high === null) {
        if (this.x === this.window.x0) {
          this.draw[this.y & 1] += now - this.mark;
          this.mark = now;
        }
        this.high = value;
        return;
      }
      const pixel = (this.high << 8) | value;
      this.high = null;
      if (this.x < PANEL_COLUMNS && this.y < PANEL_ROWS) {
        this.memory[this.y * PANEL_COLUMNS + this.x] = pixel;
      }
      this.pixels++;
      if (++this.x > this.window.x1) {
        this.x = this.window.x0;
        if (++this.y > this.window.y1) this.y = this.window.y0;
      }
      return;
    }
    this.args.push(value);
    if (this.args.length === 4 && (this.command === 0x2a || this.command === 0x2b)) {
      const lo = (this.args[0] << 8) | this.args[1];
      const hi = (this.args[2] << 8) | this.args[3];
      if (this.command === 0x2a) Object.assign(this.window, { x0: lo, x1: hi });
      else Object.assign(this.window, { y0: lo, y1: hi });
    }
  }

  /** The drawing cycles by row parity since the last call (at `now`). */
  take(now) {
    const draw = [...this.draw, this.windows];
    this.draw = [0, 0];
    this.windows = 0;
    this.mark = now;
    return draw;
  }

  /** The panel's rows as big-endian RGB565 bytes. */
  image(rows) {
    const out = Buffer.alloc(PANEL_COLUMNS * rows * 2);
    for (let i = 0; i < PANEL_COLUMNS * rows; i++) out.writeUInt16BE(this.memory[i], 2 * i);
    return out;
  }
}

function main() {
  const args = parseArgs(process.argv.slice(2));
  const mcu = new RP2040();
  mcu.logger = { debug() {}, info() {}, warn() {}, error: (c, m) => process.stderr.write(`${c}: ${m}\n`) };
  const elf = readFileSync(args.elf);
  const loaded = loadElf(elf, mcu.flash);
  const profile = args.profile ? new Profile(functions(elf)) : null;
  if (profile !== null && args.callers !== null) {
    profile.callers = { of: args.callers, lr: () => mcu.core.LR, counts: new Map() };
  }
  let profiling = false;
  let profiled = 0;
  for (const [from, to] of args.patches) patchFlash(mcu.flash, from, to);

  const panel = new Panel();
  const spi = mcu.spi[0];
  const done = mcu.clock.createAlarm(() => spi.completeTransmit(0));
  spi.onTransmit = (value) => {
    panel.byte(mcu.gpio[DC_PIN].outputValue, value, cycles);
    if (args.instantSpi) {
      spi.completeTransmit(0);
    } else {
      done.schedule((spi.dataBits * 1e9) / spi.clockFrequency);
    }
  };

  let cycles = 0;
  let lineStart = 0;
  let pixelsAtLine = 0;
  let line = '';
  const uart = [];
  const frames = [];
  let stop = null;
  mcu.uart[0].onByte = (b) => {
    if (b === 0x0a) {
      const text = line.replace(/\r$/, '');
      line = '';
      uart.push(text);
      const frameCycles = cycles - lineStart;
      const pixels = panel.pixels - pixelsAtLine;
      lineStart = cycles;
      pixelsAtLine = panel.pixels;
      const draw = panel.take(cycles);
      process.stdout.write(`uart: ${text}\n`);
      const m = /^frame=(\d+)\b/.exec(text);
      profiling = profile !== null && (m ? Number(m[1]) >= args.profileAfter : args.profileAfter < 0);
      if (m) {
        const [even, odd, windows] = draw;
        const frame = {
          index: Number(m[1]),
          cycles: frameCycles,
          pixels,
          clk_sys_hz: mcu.clkSys,
          draw_even: even,
          draw_odd: odd,
          windows,
        };
        if (args.out) {
          frame.file = `frame-${frames.length}.rgb565`;
          writeFileSync(`${args.out}/${frame.file}`, panel.image(PANEL_ROWS));
        }
        frames.push(frame);
        process.stdout.write(
          `frame=${frame.index} cycles=${Math.round(frameCycles)} clk_sys=${mcu.clkSys} pixels=${pixels}` +
            ` draw_even=${Math.round(even)} draw_odd=${Math.round(odd)} windows=${windows}\n`,
        );
        if (frames.length >= args.frames) stop = 'frames';
      } else if (text.startsWith('error:')) {
        stop = 'error';
      }
    } else {
      line += String.fromCharCode(b);
    }
  };

  if (args.out) mkdirSync(args.out, { recursive: true });
  mcu.core.SP = 0x2004_2000;
  mcu.core.LR = 0;
  mcu.core.PC = FLASH_BASE;
  const clock = mcu.clock;
  while (stop === null) {
    if (cycles > args.maxCycles) {
      stop = 'cycles';
      break;
    }
    if (mcu.core.waiting) {
      const nanos = clock.nanosToNextAlarm;
      if (!(nanos > 0) || !Number.isFinite(nanos)) {
        // Waiting for an interrupt that nothing will raise: the firmware has halted.
        stop = 'halted';
        break;
      }
      clock.tick(nanos);
      cycles += (nanos * mcu.clkSys) / 1e9;
      if (profiling) {
        profile.add(0xffff_fffe, (nanos * mcu.clkSys) / 1e9);
        profiled += (nanos * mcu.clkSys) / 1e9;
      }
    } else {
      const pc = mcu.core.PC;
      const c = mcu.core.executeInstruction();
      cycles += c;
      if (profiling) {
        profile.add(pc, c);
        profiled += c;
      }
      clock.tick((c * 1e9) / mcu.clkSys);
    }
  }
  if (profile !== null) profile.print(profiled);
  if (args.out) {
    // The panel as it is at the end (after an error, say).
    writeFileSync(`${args.out}/panel.rgb565`, panel.image(PANEL_ROWS));
  }
  const summary = {
    elf: args.elf,
    loaded_bytes: loaded,
    instant_spi: args.instantSpi,
    stop,
    cycles: Math.round(cycles),
    spi_hz: spi.clockFrequency,
    clk_sys_hz: mcu.clkSys,
    clk_peri_hz: mcu.clkPeri,
    panel: { columns: PANEL_COLUMNS, rows: PANEL_ROWS },
    uart,
    frames: frames.map((f) => ({
      ...f,
      cycles: Math.round(f.cycles),
      draw_even: Math.round(f.draw_even),
      draw_odd: Math.round(f.draw_odd),
    })),
  };
  if (args.out) writeFileSync(`${args.out}/run.json`, JSON.stringify(summary, null, 2) + '\n');
  process.stdout.write(`stop=${stop} cycles=${Math.round(cycles)} spi=${spi.clockFrequency}\n`);
  process.exit(stop === 'frames' || stop === 'error' ? 0 : 1);
}

main();
