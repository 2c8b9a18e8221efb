//! The report's "Fast lighting" section (issue 14): the firmware's instructions per pixel
//! and the share of pixels that differ from f64 on every shipped scene, before the issue
//! (recorded at commit 80ee0d2 in `docs/measured/issue14-before-*`, raw firmware output
//! and render tables, with the commands that produced them) and now (this run), the
//! goals of the issue against them, and the top of the Cortex-M0 profile of the default
//! scene before and after (`docs/measured/issue14-profile-*`, fwprof output).

use super::*;

/// The scenes the issue calls lit (every shipped scene with a light).
const LIT: [&str; 8] = [
    "default",
    "spheres",
    "specular",
    "spotlight",
    "mirror",
    "triangles",
    "course",
    "tiles",
];

/// The recorded files, relative to `docs/measured/`.
const BEFORE_M0: &str = "issue14-before-cortex-m0.txt";
const BEFORE_M4F: &str = "issue14-before-cortex-m4f.txt";
const BEFORE_ACCURACY: &str = "issue14-before-accuracy.txt";
const PROFILE_BEFORE: &str = "issue14-profile-before-cortex-m0-default-i16f16.txt";
const PROFILE_AFTER: &str = "issue14-profile-after-cortex-m0-default-i16f16.txt";

fn measured(name: &str) -> String {
    std::fs::read_to_string(crate::root().join("docs/measured").join(name)).unwrap_or_default()
}

/// `(format, scene) → instructions per pixel` from a firmware's output lines.
fn firmware_lines(text: &str) -> BTreeMap<(String, String), f64> {
    let mut out = BTreeMap::new();
    for line in text.lines().filter(|l| l.starts_with("format=")) {
        let field = |k: &str| {
            line.split_whitespace()
                .find_map(|w| w.strip_prefix(k).and_then(|v| v.strip_prefix('=')))
                .map(str::to_string)
        };
        if let (Some(f), Some(s), Some(p)) = (field("format"), field("scene"), field("per_pixel"))
            && let Ok(p) = p.parse::<f64>()
        {
            out.insert((f, s), p);
        }
    }
    out
}

/// `(scene, format) → percent` from the recorded render tables.
fn accuracy_lines(text: &str) -> BTreeMap<(String, String), f64> {
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .filter_map(|l| {
            let mut w = l.split_whitespace();
            let (s, f, p) = (w.next()?, w.next()?, w.next()?.parse().ok()?);
            Some(((s.to_string(), f.to_string()), p))
        })
        .collect()
}

fn cell(v: Option<f64>) -> String {
    v.map_or_else(|| "—".to_string(), |v| format!("{v:.0}"))
}

fn ratio(before: Option<f64>, after: Option<f64>) -> Option<f64> {
    Some(before? / after?)
}

fn ratio_cell(r: Option<f64>) -> String {
    r.map_or_else(|| "—".to_string(), |r| format!("{r:.2}×"))
}

fn verdict(ok: Option<bool>) -> &'static str {
    match ok {
        Some(true) => "met",
        Some(false) => "**not met**",
        None => "not measured",
    }
}

pub(super) fn lighting_section(accuracy: &AccuracyTable<'_>, fw: &FirmwareTable) -> String {
    let mut r = String::new();
    let before = [
        ("cortex-m0", firmware_lines(&measured(BEFORE_M0))),
        ("cortex-m4f", firmware_lines(&measured(BEFORE_M4F))),
    ];
    let now = |core: &str, format: &str, scene: &str| {
        fw.get(&(core.to_string(), format.to_string()))
            .and_then(|f| f.per_pixel.get(scene).copied())
    };
    let then = |core: &str, format: &str, scene: &str| {
        before
            .iter()
            .find(|(c, _)| *c == core)
            .and_then(|(_, t)| t.get(&(format.to_string(), scene.to_string())).copied())
    };
    let _ = writeln!(
        r,
        "\n## Fast lighting (issue 14): before and after\n\n\
         Firmware instructions per pixel (160×120, QEMU, deterministic) of every shipped \
         scene with a light, before the issue (commit 80ee0d2, recorded in \
         `docs/measured/{BEFORE_M0}` and `{BEFORE_M4F}`: the firmware's own output, built with \
         `FIXRAY_FW_SCENES=<all ten> FIXRAY_FW_FORMATS=i16f16,f32 cargo build --release \
         --example firmware --target <core>` and run under `qemu-system-arm … -icount \
         shift=0`) and now (this run's firmware table above). *tiles* has no light: it is \
         listed because its kernel changed too.\n\n\
         What changed, in the order measured (`git log`): I16F16 and I20F12 divide by a \
         table reciprocal corrected to `fixed`'s exact quotient on 32-bit targets (bit for \
         bit: hashes unchanged); diffuse light as `N·L/|L|²` (no square root, one division \
         per light); shadow segments decided by signs and exact product comparisons (planes: \
         the two ends' sides; spheres: the discriminant and the root interval); the fast \
         kernel keeps the planes' sides at the lights per frame and at the hit from its \
         primary terms (one product per plane), steps `N·D` along the scanline in the \
         unrounded double-width accumulator (`Scalar::Acc`: no products per pixel, bit for \
         bit the wide dot product), draws spheres (discriminant sign exact, one square root \
         per sphere met, the near root `c/q`) and every scene under the crate's rules (a \
         glint normalises the primary direction only where it shows); triangles keep their \
         edges' inward normals; `normalize` skips the scaling divisions for vectors that \
         square in range; the light loop is one copy in flash.\n"
    );
    let _ = writeln!(
        r,
        "| scene | M0 i16f16 before | now | fewer | M0 f32 before | now | M4F i16f16 before | now | fewer | M4F f32 before | now |\n\
         |---|---|---|---|---|---|---|---|---|---|---|"
    );
    for scene in LIT {
        let m0 = (
            then("cortex-m0", "i16f16", scene),
            now("cortex-m0", "i16f16", scene),
        );
        let m4 = (
            then("cortex-m4f", "i16f16", scene),
            now("cortex-m4f", "i16f16", scene),
        );
        let _ = writeln!(
            r,
            "| {scene} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            cell(m0.0),
            cell(m0.1),
            ratio_cell(ratio(m0.0, m0.1)),
            cell(then("cortex-m0", "f32", scene)),
            cell(now("cortex-m0", "f32", scene)),
            cell(m4.0),
            cell(m4.1),
            ratio_cell(ratio(m4.0, m4.1)),
            cell(then("cortex-m4f", "f32", scene)),
            cell(now("cortex-m4f", "f32", scene)),
        );
    }

    // The goals.
    let lit_ratios = |core: &str| -> Vec<(&str, Option<f64>)> {
        LIT.iter()
            .filter(|s| **s != "tiles")
            .map(|s| (*s, ratio(then(core, "i16f16", s), now(core, "i16f16", s))))
            .collect()
    };
    let all_at_least = |v: &[(&str, Option<f64>)], k: f64| -> Option<bool> {
        v.iter()
            .map(|(_, r)| r.map(|r| r >= k))
            .collect::<Option<Vec<_>>>()
            .map(|v| v.iter().all(|b| *b))
    };
    let worst = |v: &[(&str, Option<f64>)]| -> String {
        v.iter()
            .filter_map(|(s, r)| r.map(|r| (s, r)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map_or_else(|| "—".into(), |(s, r)| format!("worst {s} {r:.2}×"))
    };
    let m0_default = now("cortex-m0", "i16f16", "default");
    let m0_spheres = now("cortex-m0", "i16f16", "spheres");
    let soft = ratio(now("cortex-m0", "f32", "default"), m0_default);
    let fixed_best = ["i16f16", "i20f12", "i32f32"]
        .iter()
        .filter_map(|f| now("cortex-m4f", f, "default").map(|p| (*f, p)))
        .min_by(|a, b| a.1.total_cmp(&b.1));
    let hw = now("cortex-m4f", "f32", "default");
    let to_hw = fixed_best.and_then(|(_, p)| Some(p / hw?));
    let flash = fw
        .get(&("cortex-m0".to_string(), "i16f16".to_string()))
        .map(|f| f.flash);
    let (m0r, m4r) = (lit_ratios("cortex-m0"), lit_ratios("cortex-m4f"));
    let _ = writeln!(
        r,
        "\n| goal | now | |\n|---|---|---|\n\
         | M0 I16F16 default ≤ 2,000 instructions/pixel | {} | {} |\n\
         | M0 I16F16 spheres ≤ 3,000 | {} | {} |\n\
         | M0 I16F16 every lit scene ≥ 3× fewer than before | {} | {} |\n\
         | M0 I16F16 ≥ 10× fewer than soft-float f32 on default (same run) | {} | {} |\n\
         | M4F I16F16 every lit scene ≥ 2× fewer than before | {} | {} |\n\
         | M4F fastest fixed format within 1.2× of hardware f32 on default | {} | {} |\n\
         | M0 I16F16 firmware flash ≤ 64 KB (65,536 bytes; this run's build embeds all ten scenes' text) | {} | {} |",
        cell(m0_default),
        verdict(m0_default.map(|p| p <= 2000.0)),
        cell(m0_spheres),
        verdict(m0_spheres.map(|p| p <= 3000.0)),
        worst(&m0r),
        verdict(all_at_least(&m0r, 3.0)),
        ratio_cell(soft),
        verdict(soft.map(|s| s >= 10.0)),
        worst(&m4r),
        verdict(all_at_least(&m4r, 2.0)),
        match (fixed_best, to_hw) {
            (Some((f, _)), Some(x)) => format!("{f}: {x:.2}× of f32"),
            _ => "—".into(),
        },
        verdict(to_hw.map(|x| x <= 1.2)),
        flash.map_or_else(|| "—".into(), |f| f.to_string()),
        verdict(flash.map(|f| f <= 65_536)),
    );

    // Accuracy before and after.
    let before_acc = accuracy_lines(&measured(BEFORE_ACCURACY));
    let formats = ["i16f16", "i20f12", "i32f32", "f32"];
    let _ = writeln!(
        r,
        "\nShare of pixels that differ from f64, before (`docs/measured/{BEFORE_ACCURACY}`: \
         the render example's *differ* column at 80ee0d2) and now (this report's accuracy \
         table: the same `fixray::compare`); the goal is a rise of at most 0.5 percentage \
         points anywhere.\n\n\
         | scene | {} |\n|---|{}",
        formats
            .iter()
            .map(|f| format!("{f} before → now"))
            .collect::<Vec<_>>()
            .join(" | "),
        "---|".repeat(formats.len())
    );
    let mut worst_rise = f64::NEG_INFINITY;
    for (scene, _, _) in SCENES {
        let cells: Vec<String> = formats
            .iter()
            .map(|f| {
                let b = before_acc.get(&(scene.to_string(), f.to_string())).copied();
                let n = accuracy
                    .get(&(scene, *f))
                    .map(|a| 100.0 * a.cmp.differing_share());
                if let (Some(b), Some(n)) = (b, n) {
                    worst_rise = worst_rise.max(n - b);
                }
                match (b, n) {
                    (Some(b), Some(n)) => format!("{b:.3} → {n:.3} %"),
                    (_, Some(n)) => format!("— → {n:.3} %"),
                    _ => "—".into(),
                }
            })
            .collect();
        let _ = writeln!(r, "| {scene} | {} |", cells.join(" | "));
    }
    let _ = writeln!(
        r,
        "\nLargest rise: {worst_rise:+.3} percentage points ({}).\n",
        verdict(Some(worst_rise <= 0.5))
    );

    for (title, file) in [
        ("before", PROFILE_BEFORE),
        ("after (this issue's last step)", PROFILE_AFTER),
    ] {
        let text = measured(file);
        let top: Vec<&str> = text
            .lines()
            .filter(|l| !l.trim().is_empty())
            .take(22)
            .collect();
        let _ = writeln!(
            r,
            "Cortex-M0 profile of the default scene in I16F16, {title} \
             (`docs/measured/{file}`: `FIXRAY_FW_SCENES=default FIXRAY_FW_FORMATS=i16f16 cargo \
             build --release --example firmware --target thumbv6m-none-eabi` then \
             `../shared/tools/fwprof/fwprof target/thumbv6m-none-eabi/release/examples/firmware \
             --top 15 --merge`):\n\n```text\n{}\n```\n",
            top.join("\n")
        );
    }
    r
}
