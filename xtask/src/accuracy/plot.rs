//! The report's picture: `docs/accuracy.png`, error against instructions per pixel.

use super::*;

/// Colour per format in the plot.
pub(super) fn format_color(format: &str) -> Rgb888 {
    match format {
        "i16f16" => Rgb888::new(0, 114, 178),
        "i16f16n" => Rgb888::new(86, 180, 233),
        "i16f16r" => Rgb888::new(120, 60, 160),
        "i20f12" => Rgb888::new(0, 158, 115),
        "i32f32" => Rgb888::new(213, 94, 0),
        "f32" => Rgb888::new(204, 121, 167),
        _ => Rgb888::new(230, 159, 0),
    }
}

pub(super) fn plot(
    accuracy: &AccuracyTable<'_>,
    host: &BTreeMap<(&str, &str), f64>,
    fw: &FirmwareTable,
    path: &Path,
) {
    // Points: (cost, label, core, format); errors looked up per panel.
    let mut points: Vec<(f64, String, &str, &str)> = Vec::new();
    let use_fw = !fw.is_empty();
    for (format, _) in FORMATS.iter().filter(|(f, _)| *f != "f64") {
        if use_fw {
            for (_, core) in qemu::CORES {
                if let Some(x) = fw
                    .get(&(core.to_string(), format.to_string()))
                    .and_then(|f| f.per_pixel.get("default"))
                {
                    points.push((*x, format.to_string(), core, format));
                }
            }
        } else if let Some(ns) = host.get(&("default", *format)) {
            points.push((ns / 19200.0, format.to_string(), "host", format));
        }
    }
    let (w, h) = (1200i32, 560i32);
    let mut d = SimulatorDisplay::<Rgb888>::new(Size::new(w as u32, h as u32));
    let _ = d.clear(Rgb888::WHITE);
    let text = MonoTextStyle::new(&FONT_6X10, Rgb888::BLACK);
    let title = if use_fw {
        "What accuracy costs (default scene). x: instructions per pixel under QEMU; circle: Cortex-M0, square: Cortex-M4F, triangle: RISC-V rv32imc; lines: Pareto fronts"
    } else {
        "What accuracy costs (default scene). x: host ns per pixel; lines: Pareto front"
    };
    let _ = Text::new(title, Point::new(20, 16), text).draw(&mut d);
    type Metric = fn(&Comparison) -> f64;
    let panels: [(&str, Metric); 2] = [
        (
            "mean hit-point error vs f64 (world units)",
            Comparison::mean_hit_error,
        ),
        (
            "share of pixels differing from f64",
            Comparison::differing_share,
        ),
    ];
    for (k, (label, metric)) in panels.into_iter().enumerate() {
        let series: Vec<(f64, f64, &str, &str, &str)> = points
            .iter()
            .map(|(x, l, core, f)| {
                (
                    *x,
                    metric(&accuracy[&("default", *f)].cmp),
                    l.as_str(),
                    *core,
                    *f,
                )
            })
            .filter(|p| p.1 > 0.0)
            .collect();
        let origin = Point::new(k as i32 * w / 2, 30);
        panel(
            &mut d,
            origin,
            Size::new((w / 2) as u32, (h - 30) as u32),
            label,
            &series,
            use_fw,
        );
    }
    let _ = d
        .to_rgb_output_image(&OutputSettings::default())
        .save_png(path);
}

/// One log-log panel: points (cost, error, label, core, format) and each core's Pareto front.
pub(super) fn panel(
    d: &mut SimulatorDisplay<Rgb888>,
    origin: Point,
    size: Size,
    ylabel: &str,
    points: &[(f64, f64, &str, &str, &str)],
    use_fw: bool,
) {
    let (w, h) = (size.width as i32, size.height as i32);
    let (left, right, top, bottom) = (70, 20, 30, 50);
    let text = MonoTextStyle::new(&FONT_6X10, Rgb888::BLACK);
    let grey = PrimitiveStyle::with_stroke(Rgb888::new(220, 220, 220), 1);
    let axis = PrimitiveStyle::with_stroke(Rgb888::BLACK, 1);
    let lg = |v: f64| v.log10();
    let (mut xmin, mut xmax, mut ymin, mut ymax) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for p in points {
        xmin = xmin.min(lg(p.0));
        xmax = xmax.max(lg(p.0));
        ymin = ymin.min(lg(p.1));
        ymax = ymax.max(lg(p.1));
    }
    if points.is_empty() {
        (xmin, xmax, ymin, ymax) = (0.0, 1.0, 0.0, 1.0);
    }
    let (xmin, xmax) = (xmin.floor(), xmax.ceil().max(xmin.floor() + 1.0));
    let (ymin, ymax) = (ymin.floor(), ymax.ceil().max(ymin.floor() + 1.0));
    let px = |x: f64| {
        origin.x + left + ((lg(x) - xmin) / (xmax - xmin) * f64::from(w - left - right)) as i32
    };
    let py = |y: f64| {
        origin.y + h
            - bottom
            - ((lg(y) - ymin) / (ymax - ymin) * f64::from(h - top - bottom)) as i32
    };
    for e in xmin as i32..=xmax as i32 {
        let x = px(10f64.powi(e));
        let _ = Line::new(
            Point::new(x, origin.y + top),
            Point::new(x, origin.y + h - bottom),
        )
        .into_styled(grey)
        .draw(d);
        let _ = Text::with_alignment(
            &format!("1e{e}"),
            Point::new(x, origin.y + h - bottom + 14),
            text,
            Alignment::Center,
        )
        .draw(d);
    }
    for e in ymin as i32..=ymax as i32 {
        let y = py(10f64.powi(e));
        let _ = Line::new(
            Point::new(origin.x + left, y),
            Point::new(origin.x + w - right, y),
        )
        .into_styled(grey)
        .draw(d);
        let _ = Text::with_alignment(
            &format!("1e{e}"),
            Point::new(origin.x + left - 6, y + 3),
            text,
            Alignment::Right,
        )
        .draw(d);
    }
    let _ = Rectangle::new(
        origin + Point::new(left, top),
        Size::new((w - left - right) as u32, (h - top - bottom) as u32),
    )
    .into_styled(axis)
    .draw(d);
    let xlabel = if use_fw {
        "instructions per pixel"
    } else {
        "host ns per pixel"
    };
    let _ = Text::with_alignment(
        xlabel,
        origin + Point::new((left + w - right) / 2, h - bottom + 30),
        text,
        Alignment::Center,
    )
    .draw(d);
    let _ = Text::new(ylabel, origin + Point::new(left, top - 8), text).draw(d);
    for core in ["cortex-m0", "cortex-m4f", "riscv32imc", "host"] {
        let mut pts: Vec<&(f64, f64, &str, &str, &str)> =
            points.iter().filter(|p| p.3 == core).collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut best = f64::MAX;
        let front: Vec<Point> = pts
            .iter()
            .filter(|p| {
                let keep = p.1 < best;
                best = best.min(p.1);
                keep
            })
            .map(|p| Point::new(px(p.0), py(p.1)))
            .collect();
        let colour = match core {
            "cortex-m0" => Rgb888::new(150, 150, 150),
            "riscv32imc" => Rgb888::new(90, 120, 200),
            _ => Rgb888::BLACK,
        };
        for pair in front.windows(2) {
            let _ = Line::new(pair[0], pair[1])
                .into_styled(PrimitiveStyle::with_stroke(colour, 2))
                .draw(d);
        }
    }
    for (x, y, label, core, format) in points {
        let c = Point::new(px(*x), py(*y));
        let style = PrimitiveStyle::with_fill(format_color(format));
        if *core == "cortex-m4f" {
            let _ = Rectangle::with_center(c, Size::new(11, 11))
                .into_styled(style)
                .draw(d);
        } else if *core == "riscv32imc" {
            let _ = Triangle::new(
                c + Point::new(0, -7),
                c + Point::new(-7, 6),
                c + Point::new(7, 6),
            )
            .into_styled(style)
            .draw(d);
        } else {
            let _ = Circle::with_center(c, 12).into_styled(style).draw(d);
        }
        let _ = Text::new(label, c + Point::new(8, -5), text).draw(d);
    }
}
