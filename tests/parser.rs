//! The scene parser: every error kind with its line and column, the lexical rules of
//! `scene-format.md`, and a seeded storm of mangled inputs that must never panic.

mod common;
use common::sampling;
use sampling::SplitMix;

use fixray::scene::Rules;
use fixray::scene::SceneErrorKind;
use fixray::{I16F16, I20F12, I32F32, Scalar, Scene, SceneError};

const CAMERA: &str = "camera cam { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }\n";

/// What these tests check is the format's `fixray` reading unless they say otherwise
/// (the course's reading has its own tests, at the end).
trait ParseFixray: Sized {
    fn parse_fixray(text: &str) -> Result<Self, SceneError>;
}
impl<S: Scalar> ParseFixray for Scene<S> {
    fn parse_fixray(text: &str) -> Result<Self, SceneError> {
        Scene::parse_as(text, Rules::Fixray)
    }
}

fn err<S: Scalar>(text: &str) -> SceneError {
    match Scene::<S>::parse_fixray(text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

/// Parses in I16F16 and checks position and kind (by the `Display` text, which also
/// checks the message a user reads).
fn check(text: &str, line: u32, column: u32, message: &str) {
    let e = err::<I16F16>(text);
    assert_eq!(
        (e.line, e.column),
        (line, column),
        "position of `{e}` in:\n{text}"
    );
    assert_eq!(e.to_string(), format!("{line}:{column}: {message}"));
    assert_one_line(&e);
}

/// An error's message is one line.
fn assert_one_line(e: &SceneError) {
    let text = e.to_string();
    assert!(!text.contains(['\n', '\r']), "{text:?}");
}

/// The main formats (`fixray::num::formats::MAIN`) that read `text`.
fn readers(text: &str) -> Vec<&'static str> {
    fn reads<S: Scalar>(text: &str) -> bool {
        Scene::<S>::parse_fixray(text).is_ok()
    }
    fixray::num::formats::MAIN
        .into_iter()
        .filter(|f| fixray::with_format!(f, reads(text)).unwrap())
        .collect()
}

#[test]
fn the_notes_scene_parses_with_every_feature_of_the_lexer() {
    let text = "# a comment line\n\
        camera cam{pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5}  # braces against words\n\
        material m { diffuse .25 0.5 1 ambient 1e-1 +0.2 0.3 specular 0 shininess 5 reflective 0 }\n\
        light l { emissivity 1 1 1 location -7 2.5E1 3 }\n\
        plane p { point 0 0 -7 normal 0 0 1 material m }\n\
        background 0 0 0.5 precision 0.001";
    let s = Scene::<I16F16>::parse_fixray(text).unwrap();
    assert_eq!(s.camera.width, 8);
    // Diffuse reflectances are plain reals; displayed colours are in channel units.
    assert_eq!(s.materials[0].diffuse[0].to_f64(), 0.25);
    assert_eq!(s.materials[0].ambient[0].to_f64(), 0.1 * 255.0);
    assert_eq!(s.lights[0].location.y.to_f64(), 25.0);
    assert_eq!(s.background[2].to_f64(), 127.5);
    assert_eq!(s.epsilon, I16F16::from_f64(0.001).unwrap());
    assert_eq!(s.objects.len(), 1);
    // Without `precision` the format's default applies.
    let s = Scene::<I32F32>::parse_fixray(CAMERA).unwrap();
    assert_eq!(s.epsilon, I32F32::DEFAULT_EPSILON);
}

#[test]
fn unknown_keyword() {
    check(
        "camer cam { }",
        1,
        1,
        "unknown keyword `camer` (expected camera, material, light, spotlight, plane, sphere, \
         tiled_plane, fplane, triangle, tri, texture, texplane, projector, revsurf, \
         background, precision or rules)",
    );
}

#[test]
fn unknown_attribute() {
    check(
        &format!("{CAMERA}material m {{\n  ambiant 1 1 1 }}"),
        3,
        3,
        "`ambiant` is not an attribute of material (did you mean `ambient`? material has: \
         ambient, diffuse, specular, shininess, reflective, transparency)",
    );
}

/// An unknown attribute lists the entity's attributes and names the nearest one: a
/// letter changed, dropped, added or two swapped, up to a third of the name's letters;
/// none when no attribute is that near.
#[test]
fn an_unknown_attribute_names_the_nearest_and_lists_the_attributes() {
    let sphere = |attribute: &str| {
        format!("{CAMERA}material m {{}}\nsphere s {{ material m {attribute} 0 0 -5 radius 1 }}")
    };
    let has = "sphere has: material, center, radius";
    check(
        &sphere("centre"),
        3,
        23,
        &format!("`centre` is not an attribute of sphere (did you mean `center`? {has})"),
    );
    for (typo, nearest) in [
        ("cnter", "center"),
        ("centerr", "center"),
        ("cetner", "center"),
        ("Center", "center"),
        ("materail", "material"),
        ("radious", "radius"),
    ] {
        let kind = err::<I16F16>(&sphere(typo)).kind;
        assert!(
            matches!(kind, SceneErrorKind::UnknownAttribute { .. }),
            "{kind:?}"
        );
        assert_eq!(kind.nearest(), Some(nearest), "{typo}");
    }
    // Too far from every attribute (three edits from `center`): no guess.
    check(
        &sphere("middle"),
        3,
        23,
        &format!("`middle` is not an attribute of sphere ({has})"),
    );
    check(
        &sphere("centroid"),
        3,
        23,
        &format!("`centroid` is not an attribute of sphere ({has})"),
    );
    // `v0` is one edit from `v1` and `v2` as well: the first of the nearest.
    check(
        &format!("{CAMERA}material m {{}}\ntri t {{ material m v3 0 0 0 }}"),
        3,
        20,
        "`v3` is not an attribute of tri (did you mean `v0`? tri has: material, v0, v1, v2)",
    );
}

#[test]
fn duplicate_attribute() {
    check(
        "camera c { pixeldim 8 6 pixeldim 8 6 }",
        1,
        25,
        "`pixeldim` given twice in one block",
    );
}

#[test]
fn missing_attribute() {
    check(
        "\n  camera c { pixeldim 8 6 worlddim 8 6 }",
        2,
        3,
        "camera is missing its `viewpoint`",
    );
    check(
        &format!("{CAMERA}material m {{}}\nplane p {{ material m normal 0 1 0 }}"),
        3,
        1,
        "plane is missing its `point`",
    );
}

#[test]
fn missing_open_brace() {
    check(
        "camera c pixeldim 8 6",
        1,
        10,
        "expected `{`, found `pixeldim`",
    );
}

#[test]
fn missing_close_brace_at_end_of_input() {
    check(
        "camera c { pixeldim 8 6\n worlddim 8 6",
        1,
        10,
        "`camera c` is not closed: missing `}`",
    );
    // In the middle of an attribute the missing number is the first problem.
    check(
        "camera c { pixeldim 8 6\n worlddim 8",
        2,
        12,
        "unexpected end of input: expected a number",
    );
}

/// A block whose `}` is missing is reported at its `{`, naming the block and the
/// statement that follows it, not as an unknown attribute at the next block's keyword.
#[test]
fn an_unclosed_block_is_reported_at_its_brace() {
    let red = "material red { ambient 1 0 0\n";
    // The next block's keyword at the start of a line.
    check(
        &format!("{CAMERA}{red}plane p {{ material red normal 0 1 0 point 0 0 0 }}"),
        2,
        14,
        "`material red` is not closed: missing `}` before `plane`",
    );
    // On the same line: an entity keyword followed by a name and `{`.
    check(
        &format!("{CAMERA}material red {{ ambient 1 0 0 sphere s {{ }}"),
        2,
        14,
        "`material red` is not closed: missing `}` before `sphere`",
    );
    // `material` is an attribute of a plane, but not when a name and `{` follow it.
    check(
        &format!(
            "{CAMERA}material m {{}}\nplane p {{ material m normal 0 1 0 point 0 0 0\n\
             material n {{ }}"
        ),
        3,
        9,
        "`plane p` is not closed: missing `}` before `material`",
    );
    // A statement keyword at the start of a line.
    check(
        &format!("{CAMERA}{red}background 0 0 0"),
        2,
        14,
        "`material red` is not closed: missing `}` before `background`",
    );
    // At the end of the input.
    check(
        &format!("{CAMERA}{red}"),
        2,
        14,
        "`material red` is not closed: missing `}`",
    );
    // An attribute at the start of a line is an attribute (`material` in a plane), and a
    // keyword that starts no block, inside a line, is an unknown attribute.
    assert!(
        Scene::<I16F16>::parse_fixray(&format!(
            "{CAMERA}material m {{}}\nplane p {{\nmaterial m\nnormal 0 1 0 point 0 0 0 }}"
        ))
        .is_ok()
    );
    check(
        &format!("{CAMERA}material m {{ ambient 1 1 1 sphere }}"),
        2,
        28,
        "`sphere` is not an attribute of material (material has: ambient, diffuse, \
         specular, shininess, reflective, transparency)",
    );
}

#[test]
fn bad_name() {
    // A name is any token that is not a brace, a keyword or a number (scene-format.md).
    check("camera 9 { }", 1, 8, "expected a name, found `9`");
    check("camera -0.5e2 { }", 1, 8, "expected a name, found `-0.5e2`");
    check("camera {", 1, 8, "expected a name, found `{`");
    check("camera plane { }", 1, 8, "expected a name, found `plane`");
    check(
        "camera c { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }\nmaterial sphere { }",
        2,
        10,
        "expected a name, found `sphere`",
    );
}

/// Names as real course files write them (Blender exports: `Sphere.060`,
/// `seg-your-fault.115`), and both spellings of a plane's dimensions.
#[test]
fn course_names_and_both_dimension_spellings_are_read() {
    let text = "camera Camera.001 { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }
        material Material.060 { ambient 0.5 0.5 0.5 }
        material seg-your-fault.115 { ambient 0 0 1 }
        tiled_plane Plane.002 { material Material.060 altmaterial seg-your-fault.115
            normal 0 1 0 point 0 0 0 xdir 1 0 0 dimensions 1 1 }
        fplane 9lives { material seg-your-fault.115 normal 0 0 1 point 0 0 -5 xdir 1 0 0
            dimension 2 1 }";
    let s = Scene::<I16F16>::parse_fixray(text).unwrap();
    assert_eq!((s.materials.len(), s.objects.len()), (2, 2));
    check(
        &format!(
            "{text}\nfplane f {{ material Material.060 normal 0 0 1 point 0 0 -5 xdir 1 0 0 dimension 2 1 dimensions 2 1 }}"
        ),
        8,
        85,
        "`dimensions` given twice in one block",
    );
}

/// What real course files have that fixray does not draw yet is refused at its position,
/// never silently ignored.
#[test]
fn course_entities_not_supported_yet_are_refused_where_they_are() {
    let cam = "camera c { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }\n";
    // revsurf: the course's profiles are 1, 2 and 3.
    check(
        &format!(
            "{cam}material m {{ }} revsurf r {{ material m surfer 4 base 0 0 0 \
             direction 0 1 0 height 6.28 }}"
        ),
        2,
        46,
        "`surfer` must be 1, 2 or 3 (the cone, the hourglass and the vase: the course's \
         profiles)",
    );
    check(
        &format!(
            "{cam}material m {{ }} revsurf r {{ material m surfer 1 base 0 0 0 \
             direction 0 0 0 height 6 }}"
        ),
        2,
        59,
        "`direction` must be a non-zero vector",
    );
    check(
        &format!("{cam}material glass {{ ambient 0 0 0 transparency 0.5 }}"),
        2,
        32,
        "`transparency` belongs to the course rules (write `rules course` to use it)",
    );
}

/// Textures: a file the parser cannot have, a malformed one, a name never defined, a
/// bad mode, each at its position and naming what is wrong; what `read_with` reads.
#[test]
fn texture_errors_name_the_file_and_the_position() {
    let cam = "rules course camera c { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }\n";
    let course = |text: &str, files: &mut dyn FnMut(&str) -> Option<&'static [u8]>| {
        let mut scene = Scene::<I16F16>::empty();
        scene.read_with(text, None, files).map(|_| scene)
    };
    let text = format!("{cam}texture t {{ filename ../img/a.ppm }}");
    let e = course(&text, &mut |_| None).unwrap_err();
    assert_eq!(
        e.to_string(),
        "2:22: texture file `../img/a.ppm` not found (`Scene::parse` reads no files: \
         `Scene::read_with` takes them)"
    );
    let e = course(&text, &mut |_| Some(b"P6 4 4 255\n\x00".as_slice())).unwrap_err();
    assert_eq!(
        e.to_string(),
        "2:22: texture file `../img/a.ppm`: the PPM is truncated: its header promises 48 \
         bytes of pixels, it holds 1"
    );
    static PIXEL: &[u8] = b"P6 1 1 255\n\x80\x40\x20";
    let named = |name: &str| (name == "../img/a.ppm").then_some(PIXEL);
    let plane = "material m { ambient 1 1 1 } texplane p { material m normal 0 0 1 \
                 point 0 0 -1 xdir 1 0 0 dimensions 8 6";
    let e = course(&format!("{text}\n{plane} texname b }}"), &mut { named }).unwrap_err();
    assert_eq!(
        e.to_string(),
        "3:114: unknown texture `b` (a texture must be defined before it is named)"
    );
    let e = course(&format!("{text}\n{plane} texname t mode 2 }}"), &mut {
        named
    })
    .unwrap_err();
    assert_eq!(e.to_string(), "3:121: `mode` must be 0 (fit) or 1 (tile)");
    let scene = course(&format!("{text}\n{plane} texname t mode 1 }}"), &mut {
        named
    })
    .unwrap();
    assert_eq!(scene.textures.len(), 1);
    assert_eq!(scene.textures[0].pixel(0, 0), Some([0x80, 0x40, 0x20]));
    // The texel multiplies the ambient (255 → 128, 64, 32), then the path length divides.
    use embedded_graphics::pixelcolor::RgbColor;
    let p = fixray::shade::pixel(&scene, 4, 3);
    assert!(p.r() > p.g() && p.g() > p.b() && p.b() > 0, "{p:?}");
    assert_eq!((p.r() / 2, p.g() / 2), (p.g(), p.b()), "{p:?}");
}

#[test]
fn bad_number() {
    check(
        "camera c { pixeldim 8 six }",
        1,
        23,
        "expected a number, found `six`",
    );
    check(
        "camera c { worlddim inf 1 }",
        1,
        21,
        "expected a number, found `inf`",
    );
    check(
        "camera c { worlddim 1 }",
        1,
        23,
        "expected a number, found `}`",
    );
}

#[test]
fn number_beyond_the_format() {
    check(
        &format!("{CAMERA}plane p {{ material m normal 0 1 0 point 0 40000 0 }}"),
        2,
        20,
        "unknown material `m` (a material must be defined before it is named)",
    );
    let text =
        format!("{CAMERA}material m {{}}\nplane p {{ material m normal 0 1 0 point 0 40000 0 }}");
    check(
        &text,
        3,
        43,
        "`40000` does not fit i16f16 (range ±32768); i20f12, i32f32, f32 \
         and f64 hold it",
    );
    // The same scene fits in I20F12 (±524288) and f32.
    assert!(Scene::<I20F12>::parse_fixray(&text).is_ok());
    assert!(Scene::<f32>::parse_fixray(&text).is_ok());
    // A colour must fit the format itself ...
    check(
        &format!("{CAMERA}background 40000 0 0"),
        2,
        12,
        "`40000` does not fit i16f16 (range ±32768); i20f12, i32f32, f32 \
         and f64 hold it",
    );
    // ... but its 255-fold (channel units) may saturate: 200 × 255 = 51000 > 32768 is
    // stored as I16F16::MAX, which displays as 255 exactly like 51000 would.
    let s = Scene::<I16F16>::parse_fixray(&format!("{CAMERA}background 200 0 0")).unwrap();
    assert_eq!(s.background[0], I16F16::MAX);
    // Beyond even f64.
    check(
        "precision 1e999",
        1,
        11,
        "`1e999` does not fit i16f16 (range ±32768); no number format \
         holds it",
    );
}

/// A number beyond the format gives the format's range and names exactly the main
/// formats that read the scene.
#[test]
fn a_number_beyond_the_format_names_the_formats_that_hold_it() {
    let scene = |x: &str| format!("{CAMERA}light l {{ location {x} 0 0 emissivity 1 1 1 }}");
    for (x, format, message) in [
        (
            "-32768.00001",
            "i16f16",
            "`-32768.00001` does not fit i16f16 (range ±32768); i20f12, \
             i32f32, f32 and f64 hold it",
        ),
        (
            "600000",
            "i20f12",
            "`600000` does not fit i20f12 (range ±524288); i32f32, f32 and \
             f64 hold it",
        ),
        (
            "3e9",
            "i32f32",
            "`3e9` does not fit i32f32 (range ±2147483648); f32 and \
             f64 hold it",
        ),
        (
            "1e39",
            "f32",
            "`1e39` does not fit f32 (range ±3.4e38); f64 holds it",
        ),
        (
            "2e308",
            "f64",
            "`2e308` does not fit f64 (range ±1.8e308); no number format holds it",
        ),
    ] {
        let text = scene(x);
        let e = fixray::with_format!(format, err(&text)).unwrap();
        assert_eq!(e.to_string(), format!("2:20: {message}"));
        assert!(matches!(e.kind, SceneErrorKind::DoesNotFit { .. }));
        // The formats named are the ones that read it.
        let named: Vec<&str> = readers(&text)
            .into_iter()
            .filter(|f| message.contains(&format!(" {f}")) && *f != format)
            .collect();
        assert_eq!(readers(&text), named, "{x}");
    }
    // At the edge: 32767.9999999 rounds to 32768, beyond I16F16; 32767.99999 to its
    // largest value.
    let e = err::<I16F16>(&scene("32767.9999999"));
    assert!(
        e.to_string()
            .ends_with("; i20f12, i32f32, f32 and f64 hold it"),
        "{e}"
    );
    assert_eq!(readers(&scene("32767.9999999"))[0], "i20f12");
    assert_eq!(readers(&scene("32767.99999"))[0], "i16f16");
}

#[test]
fn out_of_domain() {
    check(
        "camera c { pixeldim 8 6.5 worlddim 8 6 viewpoint 4 3 5 }",
        1,
        23,
        "`pixeldim` must be integers in 1..=4096",
    );
    check(
        "camera c { pixeldim 4097 6 worlddim 8 6 viewpoint 4 3 5 }",
        1,
        21,
        "`pixeldim` must be integers in 1..=4096",
    );
    check(
        "camera c { pixeldim 8 6 worlddim 8 0 viewpoint 4 3 5 }",
        1,
        36,
        "`worlddim` must be > 0",
    );
    check(
        "camera c { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 -5 }",
        1,
        52,
        "`viewpoint` must be at z > 0",
    );
    check(
        &format!("{CAMERA}material m {{ ambient 1 -0.5 0 }}"),
        2,
        24,
        "`ambient` must be >= 0",
    );
    check(
        &format!("{CAMERA}material m {{ shininess 0.5 }}"),
        2,
        24,
        "`shininess` must be >= 1",
    );
    check(
        &format!("{CAMERA}material m {{ reflective 1.5 }}"),
        2,
        25,
        "`reflective` must be in [0, 1]",
    );
    check("precision 0", 1, 11, "`precision` must be > 0");
    // Below I16F16's resolution: it would round to 0 and disable the test.
    check(
        "precision 1e-9",
        1,
        11,
        "`precision` must be at least the number format's resolution (it rounds to 0)",
    );
    assert!(Scene::<f64>::parse_fixray(&format!("{CAMERA}precision 1e-9")).is_ok());
}

#[test]
fn duplicate_names() {
    check(
        &format!("{CAMERA}material m {{}}\nmaterial m {{}}"),
        3,
        10,
        "material `m` is defined twice",
    );
    check(
        &format!(
            "{CAMERA}material m {{}}\nplane a {{ material m normal 0 1 0 point 0 0 0 }}\n\
             plane a {{ material m normal 1 0 0 point 0 0 0 }}"
        ),
        4,
        7,
        "plane `a` is defined twice",
    );
    // Names are unique per kind: a plane and a material may share one.
    assert!(
        Scene::<I16F16>::parse_fixray(&format!(
            "{CAMERA}material a {{}}\nplane a {{ material a normal 0 1 0 point 0 0 0 }}"
        ))
        .is_ok()
    );
}

#[test]
fn unknown_material_and_definition_order() {
    check(
        &format!("{CAMERA}plane p {{ material m normal 0 1 0 point 0 0 0 }}\nmaterial m {{}}"),
        2,
        20,
        "unknown material `m` (a material must be defined before it is named)",
    );
}

#[test]
fn zero_normal() {
    check(
        &format!("{CAMERA}material m {{}}\nplane p {{ material m normal 0 0 0 point 0 0 0 }}"),
        3,
        22,
        "the normal is zero",
    );
    // A normal that rounds to zero in the format is zero there.
    check(
        &format!("{CAMERA}material m {{}}\nplane p {{ material m normal 1e-7 0 0 point 0 0 0 }}"),
        3,
        22,
        "the normal is zero",
    );
}

#[test]
fn derived_value_beyond_the_format() {
    // N·point = 60000/√2 ≈ 42426 does not fit I16F16.
    check(
        &format!(
            "{CAMERA}material m {{}}\nplane p {{ material m normal 1 1 0 point 30000 30000 0 }}"
        ),
        3,
        1,
        "the plane's offset N·point does not fit in the i16f16 number format",
    );
}

#[test]
fn duplicates_of_singletons() {
    check(
        &format!("{CAMERA}{CAMERA}"),
        2,
        1,
        "a second `camera` (only one is allowed)",
    );
    check(
        &format!("{CAMERA}background 0 0 0\nbackground 1 1 1"),
        3,
        1,
        "a second `background` (only one is allowed)",
    );
    check(
        &format!("{CAMERA}precision 0.1\nprecision 0.2"),
        3,
        1,
        "a second `precision` (only one is allowed)",
    );
}

#[test]
fn missing_camera() {
    let message = "no camera: add one, such as `camera cam { pixeldim 160 120 worlddim 4 3 \
                   viewpoint 2 1.5 5 }`";
    check("material m {}\n", 2, 1, message);
    check("", 1, 1, message);
    // The suggested camera is one, in both rule sets and every main format.
    let suggested = message.split('`').nth(1).unwrap();
    assert!(suggested.starts_with("camera cam {"), "{suggested}");
    for rules in Rules::ALL {
        let s = Scene::<I16F16>::parse_as(suggested, rules).unwrap();
        assert_eq!((s.camera.width, s.camera.height), (160, 120));
    }
    assert_eq!(readers(suggested), fixray::num::formats::MAIN);
}

/// Control and invisible characters are shown escaped in quoted tokens; a byte order
/// mark at the very start of a file is skipped.
#[test]
fn invisible_characters_are_shown_escaped() {
    let keyword = |text: &str, line, column, token: &str| {
        let e = err::<I16F16>(text);
        assert_eq!((e.line, e.column), (line, column), "{e}");
        let message = format!("{line}:{column}: unknown keyword `{token}` (expected camera, ");
        assert!(e.to_string().starts_with(&message), "{e}");
    };
    // A byte order mark where two files were joined, a NUL, a no-break space.
    keyword(
        &format!("{CAMERA}\u{feff}camera c {{ }}"),
        2,
        1,
        "\\u{feff}camera",
    );
    keyword("\0camera", 1, 1, "\\u{0}camera");
    keyword("camera\u{a0}c { }", 1, 1, "camera\\u{a0}c");
    check(
        &format!("{CAMERA}material m {{ ambient\u{200b} 1 1 1 }}"),
        2,
        14,
        "`ambient\\u{200b}` is not an attribute of material (did you mean `ambient`? \
         material has: ambient, diffuse, specular, shininess, reflective, transparency)",
    );
    // A byte order mark that starts the file is skipped: columns count from the first
    // visible character.
    let s = Scene::<I16F16>::parse_fixray(&format!("\u{feff}{CAMERA}")).unwrap();
    assert_eq!(s.camera.width, 8);
    check(
        "\u{feff}camera c {",
        1,
        10,
        "`camera c` is not closed: missing `}`",
    );
}

/// Every error's message is one line: every kind this file produces, in every main
/// format, and a storm of mangled scenes ([`mangled_scenes_never_panic`] checks the same).
#[test]
fn every_message_is_one_line() {
    fn all<S: Scalar>(texts: &[String]) -> usize {
        texts
            .iter()
            .filter_map(|t| Scene::<S>::parse_fixray(t).err())
            .inspect(assert_one_line)
            .count()
    }
    let m = format!("{CAMERA}material m {{}}\n");
    let texts: Vec<String> = [
        "camer c { }".to_string(),
        format!("{m}sphere s {{ material m centre 0 0 0 radius 1 }}"),
        format!("{m}sphere s {{ material m center 0 0 0 radius 1"),
        format!("{m}sphere s {{ material m center 0 0 0 radius 1\nplane p {{ }}"),
        format!("{m}sphere s {{ material m center 0 0 0 radius 1e-9 }}"),
        format!("{m}sphere s {{ material m center 0 0 0 radius 1000 }}"),
        format!("{m}plane p {{ material m normal 0 0 0 point 0 0 0 }}"),
        format!("{m}plane p {{ material x normal 0 0 1 point 0 0 0 }}"),
        format!("{m}plane p {{ material m normal 1 1 0 point 3e4 3e4 0 }}"),
        format!("{m}light l {{ location 1e40 0 0 emissivity 1 1 1 }}"),
        format!("{m}material m {{}}"),
        format!("{CAMERA}{CAMERA}"),
        "camera c { pixeldim 160 120 worlddim 1e-5 1e-5 viewpoint 0 0 1 }".to_string(),
        "camera c { pixeldim 0 1 }".to_string(),
        "camera c pixeldim".to_string(),
        "camera 9 {".to_string(),
        "\u{feff}\u{85}\u{2028}\u{0}".to_string(),
        "rules mine".to_string(),
        format!("{m}texture t {{ filename a.ppm }}"),
        String::new(),
    ]
    .into();
    // Every text is an error in I16F16; most in the others.
    assert_eq!(all::<I16F16>(&texts), texts.len());
    let others = all::<I20F12>(&texts) + all::<I32F32>(&texts) + all::<f32>(&texts);
    assert!(others + all::<f64>(&texts) > 3 * texts.len(), "{others}");
}

#[test]
fn too_many() {
    let mut text = String::from(CAMERA);
    for i in 0..=fixray::scene::MAX_MATERIALS {
        text.push_str(&format!("material m{i} {{}}\n"));
    }
    let line = u32::try_from(fixray::scene::MAX_MATERIALS).unwrap() + 2;
    let raise = |what: &str, n: usize, p: &str| {
        format!(
            "too many {what}: the scene type holds {n} (raise its `{p}` parameter, e.g. \
             `fixray::scene::LargeScene`)"
        )
    };
    check(&text, line, 1, &raise("materials", 16, "MATERIALS"));
    // A scene type with room for them reads the same file, in both rule sets.
    for rules in Rules::ALL {
        let big = Scene::<I16F16, 32, 17>::parse_as(&text, rules).unwrap();
        assert_eq!(big.materials.len(), 17);
    }

    let mut text = format!("{CAMERA}material m {{}}\n");
    for i in 0..=fixray::scene::MAX_OBJECTS {
        text.push_str(&format!(
            "plane p{i} {{ material m normal 0 1 0 point 0 {i} 0 }}\n"
        ));
    }
    let line = u32::try_from(fixray::scene::MAX_OBJECTS).unwrap() + 3;
    check(&text, line, 1, &raise("objects", 32, "OBJECTS"));
    // The course rules (no name list) stop at the same place with the same error.
    let e = Scene::<I16F16>::parse_as(&text, Rules::Course).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!("{line}:1: {}", raise("objects", 32, "OBJECTS"))
    );
    let big = Scene::<f64, 33>::parse_as(&text, Rules::Fixray).unwrap();
    assert_eq!(big.objects.len(), 33);

    let mut text = String::from(CAMERA);
    for i in 0..=fixray::scene::MAX_LIGHTS {
        text.push_str(&format!(
            "light l{i} {{ location 0 0 0 emissivity 1 1 1 }}\n"
        ));
    }
    let line = u32::try_from(fixray::scene::MAX_LIGHTS).unwrap() + 2;
    check(&text, line, 1, &raise("lights", 8, "LIGHTS"));
    assert_eq!(
        fixray::scene::LargeScene::<I16F16>::parse(&text)
            .unwrap()
            .lights
            .len(),
        9
    );
}

#[test]
fn every_entity_of_the_format_is_read_and_checked() {
    let m = format!("{CAMERA}material m {{}}\nmaterial n {{}}\n");
    let ok = |text: &str| Scene::<I16F16>::parse_fixray(text).unwrap();
    let s = ok(&format!(
        "{m}sphere s {{ material m center 0 0 -5 radius 1 }}
         spotlight l {{ location 0 5 0 emissivity 1 1 1 point 0 0 -5 theta 30 }}
         tiled_plane t {{ material m altmaterial n normal 0 1 0 point 0 0 0 xdir 1 0 0 dimension 1 1 }}
         fplane f {{ material m normal 0 0 1 point 0 0 -9 xdir 1 0 0 dimensions 2 1 }}
         material shiny {{ specular 0.5 shininess 20 reflective 0.25 }}"
    ));
    assert_eq!(
        (s.objects.len(), s.lights.len(), s.materials.len()),
        (3, 1, 3)
    );
    // cos 30° = 0.866025…, from the Taylor series in I16F16.
    let cone = s.lights[0].cone().copied().unwrap();
    assert!((cone.cos_theta.to_f64() - 0.866_025_4).abs() < 4.0 * I16F16::DELTA.to_f64());
    assert_eq!(s.materials[2].shininess.to_f64(), 20.0);
    let plan = s.plan();
    assert!(plan.spheres && plan.tiles && plan.finite_planes && plan.spotlights);
    assert!(plan.lighting && plan.shadows && !plan.specular && !plan.reflection);

    check(
        &format!("{m}sphere s {{ material m center 0 0 -5 radius -1 }}"),
        4,
        44,
        "`radius` must be > 0",
    );
    check(
        &format!("{m}spotlight s {{ location 0 5 0 emissivity 1 1 1 point 0 0 -5 theta 95 }}"),
        4,
        66,
        "`theta` must be in (0, 90]",
    );
    check(
        &format!("{m}spotlight s {{ location 0 5 0 emissivity 1 1 1 point 0 5 0 theta 30 }}"),
        4,
        47,
        "`point` must be a point other than the spotlight's location",
    );
    check(
        &format!(
            "{m}tiled_plane t {{ material m altmaterial x normal 0 1 0 point 0 0 0 \
             xdir 1 0 0 dimension 1 1 }}"
        ),
        4,
        40,
        "unknown material `x` (a material must be defined before it is named)",
    );
    check(
        &format!("{m}fplane f {{ material m normal 0 1 0 point 0 0 0 xdir 1 0 0 dimensions 2 0 }}"),
        4,
        72,
        "`dimensions` must be > 0",
    );
    check(
        &format!("{m}fplane f {{ material m normal 0 1 0 point 0 0 0 xdir 0 2 0 dimensions 2 1 }}"),
        4,
        48,
        "`xdir` must be a direction with a component in the plane (not along the normal)",
    );
    check(
        &format!("{CAMERA}material m {{ specular -1 }}"),
        2,
        23,
        "`specular` must be >= 0",
    );
}

/// Mangles a valid scene in many ways (cut, duplicate, replace, insert tokens and bytes)
/// and parses each result in every format: each must end in a scene or an error whose
/// position lies inside the text, never a panic (this test runs with overflow checks).
#[test]
fn mangled_scenes_never_panic() {
    let base = include_str!("../scenes/default.scene");
    let pieces = [
        "{",
        "}",
        "#",
        "\n",
        " ",
        "-",
        ".",
        "e",
        "1e999",
        "-0",
        "40000",
        "plane",
        "camera",
        "material",
        "light",
        "sphere",
        "precision",
        "background",
        "é",
        "0.0000001",
        "9999999",
        "normal",
        "point",
        "pixeldim",
        "4097",
        "0",
        "NaN",
    ];
    let mut rng = SplitMix(0x5EED_F1C5);
    let mut errors = 0;
    for _ in 0..3000 {
        let mut text: String = base.into();
        for _ in 0..=rng.below(4) {
            let chars: Vec<char> = text.chars().collect();
            let at = rng.below(chars.len() + 1);
            let (head, tail) = chars.split_at(at);
            let head: String = head.iter().collect();
            let tail: String = tail.iter().collect();
            text = match rng.below(4) {
                0 => head + pieces[rng.below(pieces.len())] + &tail,
                1 => head + tail.get(rng.below(8).min(tail.len())..).unwrap_or(""),
                2 => head,
                _ => {
                    let byte = char::from(u8::try_from(rng.below(128)).unwrap());
                    head + &byte.to_string() + &tail
                }
            };
        }
        let lines = u32::try_from(text.lines().count().max(1)).unwrap() + 1;
        for result in [
            Scene::<I16F16>::parse(&text).err(),
            Scene::<I20F12>::parse(&text).err(),
            Scene::<I32F32>::parse(&text).err(),
            Scene::<f32>::parse(&text).err(),
            Scene::<f64>::parse(&text).err(),
        ]
        .into_iter()
        .flatten()
        {
            errors += 1;
            assert_one_line(&result);
            assert!(
                result.line >= 1 && result.line <= lines,
                "{result} in:\n{text}"
            );
            assert!(result.column >= 1, "{result}");
        }
    }
    // The storm must actually produce errors (it is not testing only valid scenes).
    assert!(errors > 3000, "only {errors} errors");
}

// The course's reading (`rules course`, or no `rules` statement): what real course files
// write and the crate's own rules refuse.

#[test]
fn the_rules_statement_chooses_the_reading_wherever_it_stands() {
    let body = "camera c { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }\n";
    assert_eq!(Scene::<I16F16>::parse(body).unwrap().rules(), Rules::Course);
    for (text, rules) in [
        (format!("rules fixray\n{body}"), Rules::Fixray),
        (format!("{body}rules fixray"), Rules::Fixray),
        (format!("{body}rules course"), Rules::Course),
    ] {
        assert_eq!(
            Scene::<I16F16>::parse(&text).unwrap().rules(),
            rules,
            "{text}"
        );
    }
    // parse_as overrides the file.
    let ours = format!("rules fixray\n{body}");
    assert_eq!(
        Scene::<I16F16>::parse_as(&ours, Rules::Course)
            .unwrap()
            .rules(),
        Rules::Course
    );
    let e = Scene::<I16F16>::parse(&format!("{body}rules mine")).unwrap_err();
    assert_eq!(
        e.to_string(),
        "2:7: unknown rule set `mine` (expected `course` or `fixray`)"
    );
    let e = Scene::<I16F16>::parse(&format!("rules course\n{body}rules fixray")).unwrap_err();
    assert_eq!(e.to_string(), "3:1: a second `rules` (only one is allowed)");
    let e = Scene::<I16F16>::parse(&format!("{body}rules")).unwrap_err();
    assert_eq!(
        e.to_string(),
        "2:6: unexpected end of input: expected a rule set"
    );
}

#[test]
fn the_course_reads_what_its_files_write() {
    let cam = "camera c { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }\n";
    // Duplicate names (the first material wins), a repeated attribute (the last wins),
    // `specular R G B` (read, unused), negative colours, a keyword as a name.
    let text = format!(
        "{cam}material m {{ ambient 0.5 0.5 0.5 ambient 0.2 -0.1 0 }}\n\
         material m {{ ambient 1 1 1 }}\n\
         material old {{ diffuse 1 1 1 specular 0.3 0.3 0.3 }}\n\
         light l {{ location 0 5 0 emissivity -1 2 3 }}\n\
         plane p {{ material m normal 0 1 0 point 0 0 0 }}\n\
         plane p {{ material old normal 0 1 0 point 0 -1 0 }}\n\
         triangle tri {{ material m vertex1 0 0 -2 vertex2 1 0 -2 vertex3 0 1 -2 }}"
    );
    let s = Scene::<I16F16>::parse(&text).unwrap();
    assert_eq!(s.materials.len(), 3);
    assert_eq!(s.objects[0].material, 0, "the first `m`");
    assert_eq!(s.materials[0].ambient[0].to_f64(), 0.2 * 255.0);
    assert_eq!(s.materials[0].ambient[1].to_f64(), -0.1 * 255.0);
    assert_eq!(
        s.materials[2].specular,
        I16F16::ZERO,
        "specular R G B is not used"
    );
    assert_eq!(s.lights[0].emissivity[0].to_f64(), -1.0);
    // The glint needs a `shininess` under the course rules: without one it is 0.
    assert_eq!(s.materials[0].shininess, I16F16::ZERO);
    // The crate's own rules refuse each of them, where it stands.
    let fixray = format!("rules fixray\n{text}");
    let e = Scene::<I16F16>::parse(&fixray).unwrap_err();
    assert_eq!(e.to_string(), "3:34: `ambient` given twice in one block");
    let e = Scene::<I16F16>::parse(&format!(
        "rules fixray\n{cam}material old {{ specular 0.3 0.3 0.3 }}"
    ))
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "3:29: `specular R G B` belongs to the course rules (write `rules course` to use it)"
    );
    // And the crate's `reflective` is refused under the course rules (its mirrors are
    // `specular`).
    let e =
        Scene::<I16F16>::parse(&format!("{cam}material glass {{ reflective 0.5 }}")).unwrap_err();
    assert_eq!(
        e.to_string(),
        "2:18: `reflective` belongs to the fixray rules (write `rules fixray` to use it)"
    );
}

#[test]
fn the_old_tiled_plane_tiles_world_x_and_z() {
    let text = "camera c { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }\n\
                material a { ambient 1 0 0 }\nmaterial b { ambient 0 0 1 }\n\
                tiled_plane t { material a normal 0 1 0 point 0 0 0 dimension 1 1 \
                altmaterial b }";
    for rules in Rules::ALL {
        let s = Scene::<I16F16>::parse_as(text, rules).unwrap();
        match s.objects[0].shape {
            fixray::geometry::Shape::Tiled { tiling, .. } => {
                assert_eq!(tiling, fixray::geometry::Tiling::WorldXz)
            }
            ref other => panic!("{other:?}"),
        }
    }
    // Without `xdir` a tiled plane is the old form; with it, the frame's form.
    let framed = text.replace("altmaterial b", "altmaterial b xdir 1 0 0");
    let s = Scene::<I16F16>::parse(&framed).unwrap();
    assert!(matches!(
        s.objects[0].shape,
        fixray::geometry::Shape::Tiled {
            tiling: fixray::geometry::Tiling::Frame,
            ..
        }
    ));
}
