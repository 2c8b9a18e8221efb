//! The scale rule (`fixray::scene::MIN_SCALE_DELTAS`): a scene whose pixel pitch or sphere
//! radii the number format cannot resolve is refused at parse, at the number at fault, with
//! the formats that resolve it; the same scene is read in exactly those formats. Every
//! shipped and course scene is still read in every format.

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use fixray::num::formats::{FORMATS, MAIN};
use fixray::scene::{LargeScene, Quantity, Rules, SceneErrorKind};
use fixray::{I16F16, I20F12, I32F32, Scalar, Scene, SceneError, render_line};

/// A millimetre-scale scene: a window 1 mm wide at 160×120 pixels (a pitch of 6.25 µm),
/// a sphere of radius 0.5 mm on a floor, one light.
const MILLIMETRE: &str = "rules fixray
camera c { pixeldim 160 120 worlddim 0.001 0.00075 viewpoint 0.0005 0.0004 0.002 }
material floor { ambient 0.1 0.1 0.1 diffuse 0.7 0.7 0.7 }
material red { ambient 0.2 0.02 0.02 diffuse 0.9 0.1 0.1 }
light l { location 0.001 0.002 0.001 emissivity 1 1 1 }
plane p { material floor normal 0 1 0 point 0 0 0 }
sphere s { material red center 0.0005 0.0003 -0.001 radius 0.0005 }
";

fn err<S: Scalar>(text: &str) -> SceneError {
    match Scene::<S>::parse(text) {
        Ok(_) => panic!("{} accepted:\n{text}", S::NAME),
        Err(e) => e,
    }
}

/// The main formats that read `text`.
fn readers(text: &str) -> Vec<&'static str> {
    fn reads<S: Scalar>(text: &str) -> bool {
        Scene::<S>::parse(text).is_ok()
    }
    MAIN.into_iter()
        .filter(|f| fixray::with_format!(f, reads(text)).unwrap())
        .collect()
}

/// The main formats a message names, other than `format`.
fn named(message: &str, format: &str) -> Vec<&'static str> {
    let tail = message.rsplit("; ").next().unwrap();
    MAIN.into_iter()
        .filter(|f| *f != format && tail.split([' ', ',']).any(|w| w == *f))
        .collect()
}

fn picture<S: Scalar>(text: &str) -> Vec<Rgb888> {
    let scene = Scene::<S>::parse(text).unwrap();
    let (w, h) = (scene.camera.width, scene.camera.height);
    let mut pixels = vec![Rgb888::BLACK; usize::from(w) * usize::from(h)];
    for (row, line) in (0..h).zip(pixels.chunks_mut(usize::from(w))) {
        render_line(&scene, row, line);
    }
    pixels
}

/// The share of pixels more than 8 levels off f64's picture in some channel.
fn off_f64<S: Scalar>(text: &str) -> f64 {
    let (ours, truth) = (picture::<S>(text), picture::<f64>(text));
    let off = |p: &Rgb888, q: &Rgb888| {
        p.r().abs_diff(q.r()) > 8 || p.g().abs_diff(q.g()) > 8 || p.b().abs_diff(q.b()) > 8
    };
    let n = ours.iter().zip(&truth).filter(|(p, q)| off(p, q)).count();
    n as f64 / truth.len() as f64
}

/// The millimetre scene, of which I16F16 would draw 47 % of the pixels wrong without a
/// word, is refused at its `worlddim` in I16F16 and I20F12, naming the formats that read
/// it; f32 draws f64's picture of it.
#[test]
fn a_millimetre_scene_is_refused_where_the_format_cannot_resolve_it() {
    let e = err::<I16F16>(MILLIMETRE);
    assert_eq!(
        e.to_string(),
        "2:38: pixel pitch 6.25e-6 is below 4 DELTA of i16f16; i32f32, f32 or f64 resolve it"
    );
    assert!(matches!(
        e.kind,
        SceneErrorKind::BelowResolution {
            quantity: Quantity::PixelPitch,
            format: "i16f16",
            ..
        }
    ));
    let e = err::<I20F12>(MILLIMETRE);
    assert_eq!(
        e.to_string(),
        "2:38: pixel pitch 6.25e-6 is below 4 DELTA of i20f12; i32f32, f32 or f64 resolve it"
    );
    assert_eq!(readers(MILLIMETRE), ["i32f32", "f32", "f64"]);
    assert_eq!(named(&e.to_string(), "i20f12"), readers(MILLIMETRE));
    // f32 draws f64's picture. (I32F32 resolves the scale but, like I16F16, loses the
    // sphere's light at small radii: a shading matter, not the scale rule's.)
    assert_eq!(off_f64::<f32>(MILLIMETRE), 0.0);
    assert!(Scene::<I32F32>::parse(MILLIMETRE).is_ok());
}

/// A window 10 µm wide (its width a single DELTA of I16F16) is refused in I16F16 with the
/// formats that resolve it, and in I20F12 and f32 (whose resolution at 1 is 1.2e-7); it
/// is read in I32F32 and f64, and drawn there (not black).
#[test]
fn a_window_of_ten_micrometres_is_refused_where_it_draws_black() {
    let text = MILLIMETRE
        .replace("worlddim 0.001 0.00075", "worlddim 0.00001 0.0000075")
        .replace(
            "viewpoint 0.0005 0.0004 0.002",
            "viewpoint 0.000005 0.000004 0.00002",
        );
    let e = err::<I16F16>(&text);
    assert_eq!(
        e.to_string(),
        "2:38: pixel pitch 6.25e-8 is below 4 DELTA of i16f16; i32f32 or f64 resolve it"
    );
    assert_eq!(readers(&text), ["i32f32", "f64"]);
    assert_eq!(named(&e.to_string(), "i16f16"), readers(&text));
    let e = err::<f32>(&text);
    assert_eq!(
        e.to_string(),
        "2:38: pixel pitch 6.25e-8 is below 4 DELTA of f32; i32f32 or f64 resolve it"
    );
    // The picture is not black where it is read.
    assert!(picture::<I32F32>(&text).iter().any(|p| p.r() > 100));
}

/// A sphere too small for the format is refused at its radius: in a fixed format when
/// its square is below 4 DELTA, in a float when the radius is below 4 ulps of its centre.
#[test]
fn a_sphere_below_the_resolution_is_refused_at_its_radius() {
    let scene = |center: &str, radius: &str| {
        format!(
            "rules fixray camera c {{ pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }}\n\
             material m {{ ambient 1 0 0 }}\n\
             sphere s {{ material m center {center} radius {radius} }}"
        )
    };
    // 0.004² = 1.6e-5, 1.05 DELTA of I16F16 (radius 0.004 is 262 DELTA).
    let small = scene("4 3 -1", "0.004");
    let e = err::<I16F16>(&small);
    assert_eq!(
        e.to_string(),
        "3:44: radius² 1.6e-5 is below 4 DELTA of i16f16; i32f32, f32 or f64 resolve it"
    );
    assert_eq!(readers(&small), ["i32f32", "f32", "f64"]);
    // 0.008² = 6.4e-5 = 4.19 DELTA: read.
    assert!(Scene::<I16F16>::parse(&scene("4 3 -1", "0.008")).is_ok());
    // A radius that rounds to 0 is refused as one that is not > 0 in the format.
    let e = err::<I16F16>(&scene("4 3 -1", "0.000001"));
    assert!(
        e.to_string()
            .ends_with("(it rounds to 0 in this number format)"),
        "{e}"
    );
    // f32 at a million units from the origin resolves 0.125: a radius of 0.1 is below
    // 4 of its ulps there; I32F32 holds the centre and resolves the radius.
    let far = scene("1000000 3 -1", "0.1");
    let e = err::<f32>(&far);
    assert_eq!(
        e.to_string(),
        "3:50: radius 0.1 is below 4 DELTA of f32; i32f32 or f64 resolve it"
    );
    assert_eq!(readers(&far), ["i32f32", "f64"]);
}

/// A radius whose square is beyond the format's range is refused at the radius, naming
/// the formats that hold it.
#[test]
fn a_radius_whose_square_is_beyond_the_range_is_refused_at_the_radius() {
    let text = "camera c { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }\n\
                material m { ambient 1 0 0 }\n\
                sphere s { material m center 0 0 -500 radius 200 }";
    let e = err::<I16F16>(text);
    assert_eq!(
        e.to_string(),
        "3:46: radius² 40000 does not fit i16f16 (range ±32768); i20f12, \
         i32f32, f32 and f64 hold it"
    );
    assert!(matches!(
        e.kind,
        SceneErrorKind::BeyondRange {
            quantity: Quantity::RadiusSq,
            ..
        }
    ));
    assert_eq!(readers(text), ["i20f12", "i32f32", "f32", "f64"]);
}

/// The limit is 4 of the format's ulps at the scene's magnitude: in I16F16 a window of
/// 160 × 4 DELTA is read, one a little narrower refused; in f32 an eye a million units
/// to the side (ulp 0.0625) refuses a pitch of 0.05 that I32F32 and f64 resolve.
#[test]
fn the_limit_is_four_ulps_at_the_scene_magnitude() {
    let camera = |worlddim: &str, viewpoint: &str| {
        format!("camera c {{ pixeldim 160 120 worlddim {worlddim} viewpoint {viewpoint} }}")
    };
    let edge = 160.0 * 4.0 * I16F16::DELTA.to_f64();
    assert_eq!(edge, 0.009765625);
    assert!(Scene::<I16F16>::parse(&camera("0.009765625 1", "0 0 1")).is_ok());
    let e = err::<I16F16>(&camera("0.0097 1", "0 0 1"));
    assert_eq!(
        e.to_string(),
        "1:38: pixel pitch 6.062e-5 is below 4 DELTA of i16f16; i32f32, f32 or f64 resolve it"
    );
    // Along y too, at its own number.
    let e = err::<I16F16>(&camera("1 0.007", "0 0 1"));
    assert_eq!((e.line, e.column), (1, 40));
    let far = camera("8 6", "1000000 3 5");
    let e = err::<f32>(&far);
    assert_eq!(
        e.to_string(),
        "1:38: pixel pitch 0.05 is below 4 DELTA of f32; i32f32 or f64 resolve it"
    );
    assert_eq!(readers(&far), ["i32f32", "f64"]);
    // An eye far along z does not move the screen points' rounding: read.
    assert!(Scene::<f32>::parse(&camera("8 6", "4 3 1000000")).is_ok());
}

/// Every shipped scene (`scenes/`) and course scene (`course/scenes/`) is read in every
/// format of the one list: the rule refuses none of them.
#[test]
fn every_shipped_and_course_scene_is_read_in_every_format() {
    fn read<S: Scalar>(path: &std::path::Path, text: &str) -> Result<(), SceneError> {
        let mut scene = LargeScene::<S>::empty();
        scene.read_with(text, None, &mut fixray::scene::files::beside(path))
    }
    let root = env!("CARGO_MANIFEST_DIR");
    let mut count = 0;
    for dir in ["scenes", "course/scenes"] {
        for entry in std::fs::read_dir(format!("{root}/{dir}")).unwrap() {
            let path = entry.unwrap().path();
            let is_scene = path.extension().is_some_and(|e| e == "scene" || e == "txt");
            if !is_scene {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            for format in FORMATS {
                let result = fixray::with_format!(format, read(&path, &text)).unwrap();
                assert!(result.is_ok(), "{} in {format}: {result:?}", path.display());
            }
            count += 1;
        }
    }
    assert!(count >= 40, "{count} scenes");
    // Both rule sets read the millimetre scene's camera alike.
    for rules in Rules::ALL {
        let e = Scene::<I16F16>::parse_as(MILLIMETRE, rules).unwrap_err();
        assert!(e.to_string().contains("pixel pitch"), "{e}");
    }
}
