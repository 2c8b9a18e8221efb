//! Cross-check of fixray's renders against an independent f64 reference written from
//! `docs/scene-format.md` alone (Geometry and Shading sections, ambient-only subset).
//!
//! The reference below does not share any code with fixray: it has its own parser for
//! the ambient-only subset (camera, material, plane, background, precision) and its own
//! plain-f64 plane caster. The f64 renders must match it away from boundaries; every
//! format of the one list (`fixray::num::formats::FORMATS`) must match it on all but 1 %
//! of the pixels.

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use fixray::num::formats::FORMATS;
use fixray::scene::Rules;
use fixray::{Scalar, Scene, render_line};
use std::collections::HashMap;

type V3 = [f64; 3];

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit(a: V3) -> V3 {
    let n = dot(a, a).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

struct RefPlane {
    normal: V3,
    point: V3,
    ambient: V3,
}

struct RefScene {
    w: u16,
    h: u16,
    wx: f64,
    wy: f64,
    eye: V3,
    background: V3,
    eps: f64,
    planes: Vec<RefPlane>,
}

/// One reference pixel: its colour, the index of the plane it sees (None for background)
/// and |N . d| of that hit (how grazing the ray is).
#[derive(Clone, Copy)]
struct RefPixel {
    rgb: [u8; 3],
    hit: Option<usize>,
    cos: f64,
}

fn tokenize(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for line in text.lines() {
        let line = line.split('#').next().unwrap_or("");
        let spaced = line.replace('{', " { ").replace('}', " } ");
        out.extend(spaced.split_whitespace().map(str::to_owned));
    }
    out
}

/// Parses `{ key values... key values... }` into a map from key to its values.
fn parse_block(toks: &[String], pos: &mut usize) -> HashMap<String, Vec<String>> {
    assert_eq!(toks[*pos], "{", "expected {{ at token {}", *pos);
    *pos += 1;
    let mut attrs: HashMap<String, Vec<String>> = HashMap::new();
    let mut key: Option<String> = None;
    while toks[*pos] != "}" {
        let t = toks[*pos].clone();
        let is_word = t.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_');
        // A word right after `material` is the material's name, not a new key.
        let takes_name = key.as_deref() == Some("material") && attrs["material"].is_empty();
        if is_word && !takes_name {
            attrs.insert(t.clone(), Vec::new());
            key = Some(t);
        } else {
            let k = key
                .as_ref()
                .unwrap_or_else(|| panic!("value {t} without attribute"));
            attrs.get_mut(k).unwrap().push(t);
        }
        *pos += 1;
    }
    *pos += 1;
    attrs
}

fn nums(attrs: &HashMap<String, Vec<String>>, key: &str) -> Vec<f64> {
    attrs[key]
        .iter()
        .map(|s| s.parse::<f64>().unwrap())
        .collect()
}

fn v3(v: &[f64]) -> V3 {
    [v[0], v[1], v[2]]
}

fn ref_parse(text: &str) -> RefScene {
    let toks = tokenize(text);
    let mut pos = 0;
    let mut materials: HashMap<String, V3> = HashMap::new();
    let mut scene = RefScene {
        w: 0,
        h: 0,
        wx: 0.0,
        wy: 0.0,
        eye: [0.0; 3],
        background: [0.0; 3],
        eps: 16.0 * f64::EPSILON, // fixray's documented f64 default
        planes: Vec::new(),
    };
    let num = |s: &String| s.parse::<f64>().unwrap();
    while pos < toks.len() {
        let kw = toks[pos].as_str();
        match kw {
            "background" => {
                scene.background = [
                    num(&toks[pos + 1]),
                    num(&toks[pos + 2]),
                    num(&toks[pos + 3]),
                ];
                pos += 4;
            }
            "precision" => {
                scene.eps = num(&toks[pos + 1]);
                pos += 2;
            }
            // The shipped scenes say `rules fixray`: the rules this reference implements.
            "rules" => {
                assert_eq!(
                    toks[pos + 1],
                    "fixray",
                    "reference parser: fixray rules only"
                );
                pos += 2;
            }
            "camera" | "material" | "plane" => {
                let name = toks[pos + 1].clone();
                pos += 2;
                let a = parse_block(&toks, &mut pos);
                match kw {
                    "camera" => {
                        let pd = nums(&a, "pixeldim");
                        let wd = nums(&a, "worlddim");
                        scene.w = pd[0] as u16;
                        scene.h = pd[1] as u16;
                        scene.wx = wd[0];
                        scene.wy = wd[1];
                        scene.eye = v3(&nums(&a, "viewpoint"));
                    }
                    "material" => {
                        let amb = if a.contains_key("ambient") {
                            v3(&nums(&a, "ambient"))
                        } else {
                            [0.0; 3]
                        };
                        materials.insert(name, amb);
                    }
                    _ => scene.planes.push(RefPlane {
                        normal: v3(&nums(&a, "normal")),
                        point: v3(&nums(&a, "point")),
                        ambient: materials[&a["material"][0]],
                    }),
                }
            }
            other => panic!("reference parser: unsupported keyword {other}"),
        }
    }
    assert!(scene.w > 0 && scene.h > 0, "no camera");
    scene
}

fn to_u8(c: f64) -> u8 {
    // 255 * c, clamped to [0, 255], ties away from zero (f64::round).
    (255.0 * c).clamp(0.0, 255.0).round() as u8
}

fn ref_render(s: &RefScene) -> Vec<Vec<RefPixel>> {
    let (w, h) = (f64::from(s.w), f64::from(s.h));
    (0..s.h)
        .map(|j| {
            (0..s.w)
                .map(|i| {
                    let screen = [
                        s.wx * (f64::from(i) + 0.5) / w,
                        s.wy * (1.0 - (f64::from(j) + 0.5) / h),
                        0.0,
                    ];
                    let b = s.eye;
                    let d = unit([screen[0] - b[0], screen[1] - b[1], screen[2] - b[2]]);
                    let mut best: Option<(f64, usize, f64)> = None;
                    for (k, p) in s.planes.iter().enumerate() {
                        let n = unit(p.normal);
                        let dp = dot(n, p.point);
                        let nd = dot(n, d);
                        if nd.abs() < s.eps {
                            continue;
                        }
                        let t = (dp - dot(n, b)) / nd;
                        if t < 0.0 {
                            continue;
                        }
                        if b[2] + t * d[2] > 0.0 {
                            continue;
                        }
                        if best.is_none_or(|(bt, _, _)| t < bt) {
                            best = Some((t, k, nd.abs()));
                        }
                    }
                    let (c, hit, cos) = match best {
                        Some((_, k, nd)) => (s.planes[k].ambient, Some(k), nd),
                        None => (s.background, None, 1.0),
                    };
                    RefPixel {
                        rgb: [to_u8(c[0]), to_u8(c[1]), to_u8(c[2])],
                        hit,
                        cos,
                    }
                })
                .collect()
        })
        .collect()
}

/// A scene's picture as rows of RGB triples.
fn render_all<S: Scalar>(scene: &Scene<S>) -> Vec<Vec<[u8; 3]>> {
    (0..scene.camera.height)
        .map(|row| {
            let mut line = vec![Rgb888::BLACK; usize::from(scene.camera.width)];
            render_line(scene, row, &mut line);
            line.iter().map(|p| [p.r(), p.g(), p.b()]).collect()
        })
        .collect()
}

/// The pixels of format `S`'s picture of `text` that differ from the reference's.
fn differing<S: Scalar>(text: &str, reference: &[Vec<RefPixel>]) -> usize {
    let scene = Scene::<S>::parse_as(text, Rules::Fixray).unwrap();
    let img = render_all(&scene);
    reference
        .iter()
        .zip(&img)
        .map(|(r, q)| r.iter().zip(q).filter(|(p, q)| p.rgb != **q).count())
        .sum()
}

/// |N . d| below this counts as grazing: there t = (D' - N.b) / (N.d) is huge and
/// ill-conditioned, so a last-bit difference in d (operation order, sqrt rounding)
/// moves the hit point far and can flip the z > 0 / t < 0 / EPS decisions. Two
/// correct f64 implementations need not agree there, so such pixels are not compared.
const GRAZING: f64 = 1e-3;

fn away_from_boundary(r: &[Vec<RefPixel>], i: usize, j: usize) -> bool {
    let p = r[j][i];
    if p.hit.is_some() && p.cos < GRAZING {
        return false;
    }
    // The 3×3 neighbourhood, cut at the image's edges.
    r.iter()
        .skip(j.saturating_sub(1))
        .take(if j == 0 { 2 } else { 3 })
        .all(|line| {
            line.iter()
                .skip(i.saturating_sub(1))
                .take(if i == 0 { 2 } else { 3 })
                .all(|q| q.hit == p.hit)
        })
}

fn check(name: &str, text: &str) {
    let reference = ref_render(&ref_parse(text));
    let f = Scene::<f64>::parse_as(text, Rules::Fixray).unwrap();
    assert_eq!(usize::from(f.camera.height), reference.len());
    assert_eq!(usize::from(f.camera.width), reference[0].len());
    let f_img = render_all(&f);

    let total = reference.len() * reference[0].len();
    let (mut compared, mut f_diff, mut f_diff_all) = (0usize, 0usize, 0usize);
    let mut first_bad = None;
    for (j, row) in reference.iter().enumerate() {
        for (i, p) in row.iter().enumerate() {
            if f_img[j][i] != p.rgb {
                f_diff_all += 1;
            }
            if away_from_boundary(&reference, i, j) {
                compared += 1;
                if f_img[j][i] != p.rgb {
                    f_diff += 1;
                    first_bad.get_or_insert((i, j, f_img[j][i], p.rgb));
                }
            }
        }
    }
    println!(
        "{name}: {total} px, f64 compared {compared} ({:.1} %), differing {f_diff} (all px: {f_diff_all})",
        100.0 * compared as f64 / total as f64,
    );
    assert_eq!(
        f_diff, 0,
        "{name}: f64 differs away from boundaries, first (i, j, fixray, ref) = {first_bad:?}"
    );
    assert!(
        compared * 10 > total * 8,
        "{name}: only {compared} of {total} pixels compared"
    );
    // Every format of the one list (`fixray::num::formats::FORMATS`) draws the
    // reference's picture but for fewer than 1 % of the pixels (the boundaries).
    for format in FORMATS {
        let q_diff = fixray::with_format!(format, differing(text, &reference)).unwrap();
        println!(
            "{name}: {format} differing {q_diff} ({:.2} %)",
            100.0 * q_diff as f64 / total as f64
        );
        assert!(
            q_diff * 100 < total,
            "{name}: {format} differs on {q_diff} of {total} pixels"
        );
    }
}

// Decimal colours 0.1, 0.3, 0.7, 0.9, 0.5 give exact .5 ties after * 255.
const CORRIDOR: &str = "
# five planes, tie colours
camera cam { pixeldim 160 120 worlddim 8 6 viewpoint 4 3 6 }
background 0.5 0.9 0.1
material a{ambient 0.1 0.3 0.7}
material b { ambient 0.7 0.1 0.3 }   # trailing comment
material c { ambient 0.3 0.7 0.1 diffuse 1 1 1 }
material d { ambient 0.9 0.5 0.1 }
material e { ambient 0.5 0.5 0.5 }
plane floor{ material a normal 0 1 0 point 0 0 0 }
plane ceiling { normal 0 -1 0 point 0 6 0 material b }
plane left { material c normal 1 0 0 point 0 0 0 }
plane right { material d normal -1 0 0 point 8 0 0 }
plane back { material e normal 0 0 1 point 0 0 -20 }
";

const FLOOR_HORIZON: &str = "
camera eye { pixeldim 160 120 worlddim 4 3 viewpoint 2 2 4 }
background 0.1 0.3 0.7
material grass { ambient 0.3 0.7 0.1 }
plane floor { material grass normal 0 1 0 point 0 -1 0 }
";

const TILTED: &str = "
camera eye { pixeldim 64 48 worlddim 4 3 viewpoint 2 1.5 5 }
background 0.9 0.9 0.1
material slant { ambient 0.7 0.3 0.1 }
material wall { ambient 0.1 0.5 0.9 }
plane slope { material slant normal 1 2 3 point 2 1.5 -6 }
plane back { material wall normal 0 0 2 point 0 0 -9 }
";

const PRECISION: &str = "
precision 0.01
camera eye { pixeldim 64 48 worlddim 4 3 viewpoint 2 3 4 }
background 0.3 0.1 0.5
material m { ambient 0.5 0.7 0.9 }
material n { ambient 0.9 0.1 0.3 }
plane floor { material m normal 0 1 0 point 0 -0.5 0 }
plane side { material n normal -1 0 0.05 point 3.5 0 0 }
";

#[test]
fn corridor() {
    check("corridor", CORRIDOR);
}

#[test]
fn floor_horizon() {
    check("floor_horizon", FLOOR_HORIZON);
}

#[test]
fn tilted_non_unit_normal() {
    check("tilted", TILTED);
}

#[test]
fn explicit_precision() {
    check("precision", PRECISION);
}

#[test]
fn repo_planes_scene() {
    check(
        "scenes/planes.scene",
        include_str!("../scenes/planes.scene"),
    );
}

#[test]
fn repo_horizon_scene() {
    check(
        "scenes/horizon.scene",
        include_str!("../scenes/horizon.scene"),
    );
}
