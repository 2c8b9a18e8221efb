//! [`Rules`]: which rule set draws a scene, the course tracer's or the crate's own.

use core::fmt;
use core::str::FromStr;

/// The rule set a scene is drawn by ([`crate::scene::language`], "Two rule sets"). A scene file
/// chooses it with `rules course` or `rules fixray`; a file without that statement is a
/// course file. A scene built in code ([`crate::Scene::new`]) follows the crate's own
/// rules. [`crate::Scene::set_rules`] overrides either.
///
/// ```
/// use fixray::{Scene, I16F16};
/// use fixray::scene::Rules;
///
/// let text = "camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }";
/// assert_eq!(Scene::<I16F16>::parse(text).unwrap().rules(), Rules::Course);
/// let ours = Scene::<I16F16>::parse(&format!("rules fixray {text}")).unwrap();
/// assert_eq!(ours.rules(), Rules::Fixray);
/// assert_eq!("course".parse::<Rules>(), Ok(Rules::Course));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Rules {
    /// The course tracer's rules (`course/COURSE-RULES.md`), which draw the instructor's
    /// pictures of real course files: pixels on the window's corners (`WX·i/(W−1)`),
    /// colours divided by the distance travelled from the eye and truncated, the normal as
    /// given, the screen rule (`z > 0.01`) for plane-type hits of every ray, secondary
    /// rays that skip the object they leave, the near sphere root only, `specular` as
    /// glint and mirror weight (`own + K·reflected`), glints without a light-distance
    /// division and only with `shininess`, checkerboards anchored at the world origin.
    Course,
    /// The crate's own rules (the rest of [`crate::scene::language`]): pixel centres, rounding,
    /// the normal facing the ray, `reflective` mirrors, glints divided by the light
    /// distance.
    Fixray,
}

impl Rules {
    /// Both rule sets.
    pub const ALL: [Rules; 2] = [Rules::Course, Rules::Fixray];

    /// The name a scene file writes (`rules course`).
    pub const fn name(self) -> &'static str {
        match self {
            Rules::Course => "course",
            Rules::Fixray => "fixray",
        }
    }
}

impl fmt::Display for Rules {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not a rule set's.
///
/// ```
/// use fixray::scene::{Rules, UnknownRules};
///
/// assert_eq!("fixray".parse::<Rules>(), Ok(Rules::Fixray));
/// assert_eq!("pbrt".parse::<Rules>(), Err(UnknownRules));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct UnknownRules;

impl fmt::Display for UnknownRules {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("unknown rule set (expected `course` or `fixray`)")
    }
}

impl FromStr for Rules {
    type Err = UnknownRules;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Rules::ALL
            .into_iter()
            .find(|r| r.name() == s)
            .ok_or(UnknownRules)
    }
}
