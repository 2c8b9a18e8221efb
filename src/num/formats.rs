//! The one list of number formats: every tool (the build script, the firmware, the
//! accuracy report, the viewer, the `render` example and the tests) takes its format names
//! from here, and an unknown name is an error that lists the known ones.
//!
//! Adding a format touches two files: its [`Scalar`](crate::Scalar) implementation and
//! this one (a row of [`DESCRIBED`], an arm in [`with_format!`](crate::with_format); a
//! unit test keeps the two in step). `build.rs` reads the names from this file's text.
//!
//! ```
//! use fixray::num::formats::{self, UnknownFormat};
//! use fixray::{Scalar, with_format};
//!
//! fn name_of<S: Scalar>() -> &'static str {
//!     S::NAME
//! }
//! assert_eq!(with_format!("i20f12", name_of()), Ok("i20f12"));
//! let err = with_format!("q15", name_of()).unwrap_err();
//! assert_eq!(err, UnknownFormat::new("q15"));
//! assert!(err.to_string().starts_with("unknown number format `q15` (known: i16f16, "));
//! assert!(formats::MAIN.iter().all(|m| formats::FORMATS.contains(m)));
//! ```

use core::fmt;

/// Every number format with what it is, in the order the tools show them: the five main
/// formats and the variants of [`super::variants`] beside the format each varies. The one
/// list (`build.rs` reads the names from this table's text).
pub const DESCRIBED: [(&str, &str); 8] = [
    ("i16f16", "I16F16, wide dot products"),
    ("i16f16n", "I16F16, narrow dot products"),
    (
        "i16f16r",
        "I16F16, division by reciprocal (table + 2 Newton steps)",
    ),
    ("i20f12", "I20F12"),
    ("i32f32", "I32F32"),
    ("f32", "f32, correctly rounded libm sqrt"),
    ("f32m", "f32, micromath sqrt (≤ 6.1 % off)"),
    ("f64", "f64 (the reference)"),
];

/// The names of [`DESCRIBED`], in its order.
pub const FORMATS: [&str; 8] = {
    let mut names = [""; 8];
    let mut i = 0;
    while i < names.len() {
        names[i] = DESCRIBED[i].0;
        i += 1;
    }
    names
};

/// The main formats ([`for_each_format!`](crate::for_each_format) runs these): the
/// three fixed formats, `f32` and the `f64` reference.
pub const MAIN: [&str; 5] = ["i16f16", "i20f12", "i32f32", "f32", "f64"];

/// The reference every format is measured against.
pub const REFERENCE: &str = "f64";

/// A format name that is not in [`FORMATS`].
///
/// ```
/// use fixray::num::formats::{check, UnknownFormat};
///
/// assert_eq!(check("i16f16"), Ok("i16f16"));
/// let err = check("i8f8").unwrap_err();
/// assert_eq!(err, UnknownFormat::new("i8f8"));
/// assert!(err.to_string().starts_with("unknown number format `i8f8` (known: i16f16, "));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct UnknownFormat<'a> {
    name: &'a str,
}

impl<'a> UnknownFormat<'a> {
    /// The error for `name`.
    pub fn new(name: &'a str) -> Self {
        Self { name }
    }

    /// The name asked for.
    pub fn name(&self) -> &'a str {
        self.name
    }
}

impl fmt::Display for UnknownFormat<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "unknown number format `{}` (known: ", self.name)?;
        for (i, name) in FORMATS.iter().enumerate() {
            let sep = if i == 0 { "" } else { ", " };
            write!(f, "{sep}{name}")?;
        }
        write!(f, ")")
    }
}

impl core::error::Error for UnknownFormat<'_> {}

/// Whether `name` is a known format: the name itself, or the error naming the known ones.
///
/// # Errors
/// [`UnknownFormat`] when `name` is not in [`FORMATS`].
pub fn check(name: &str) -> Result<&'static str, UnknownFormat<'_>> {
    FORMATS
        .iter()
        .copied()
        .find(|f| *f == name)
        .ok_or(UnknownFormat::new(name))
}

/// Calls a generic function with the number format named at run time:
/// `with_format!(name, path::to::f(args…))` is `Ok(f::<Format>(args…))`, or
/// `Err(UnknownFormat)` naming the known formats. A function with more type parameters
/// after the format's is called as `with_format!(name, f::<_, More>(args…))`.
#[macro_export]
macro_rules! with_format {
    ($name:expr, $($f:ident)::+ ::<_ $(, $more:ty)*> ($($arg:expr),* $(,)?)) => {{
        let name: &str = $name;
        match name {
            "i16f16" => Ok($($f)::+::<$crate::I16F16 $(, $more)*>($($arg),*)),
            "i16f16n" => Ok($($f)::+::<$crate::num::variants::I16F16Narrow $(, $more)*>($($arg),*)),
            "i16f16r" => Ok($($f)::+::<$crate::num::variants::I16F16Recip $(, $more)*>($($arg),*)),
            "i20f12" => Ok($($f)::+::<$crate::I20F12 $(, $more)*>($($arg),*)),
            "i32f32" => Ok($($f)::+::<$crate::I32F32 $(, $more)*>($($arg),*)),
            "f32" => Ok($($f)::+::<f32 $(, $more)*>($($arg),*)),
            "f32m" => Ok($($f)::+::<$crate::num::variants::F32Micro $(, $more)*>($($arg),*)),
            "f64" => Ok($($f)::+::<f64 $(, $more)*>($($arg),*)),
            _ => Err($crate::num::formats::UnknownFormat::new(name)),
        }
    }};
    ($name:expr, $($f:ident)::+ ($($arg:expr),* $(,)?)) => {
        $crate::with_format!($name, $($f)::+::<_>($($arg),*))
    };
}

/// Calls `f::<Format>(args…)` for every main format ([`MAIN`], in its order), or with
/// `all:` first for every format of [`FORMATS`].
#[macro_export]
macro_rules! for_each_format {
    (all: $($f:ident)::+ ($($arg:expr),* $(,)?)) => {{
        for name in $crate::num::formats::FORMATS {
            let _ = $crate::with_format!(name, $($f)::+($($arg),*));
        }
    }};
    ($($f:ident)::+ ($($arg:expr),* $(,)?)) => {{
        for name in $crate::num::formats::MAIN {
            let _ = $crate::with_format!(name, $($f)::+($($arg),*));
        }
    }};
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scalar;

    fn name_of<S: Scalar>() -> &'static str {
        S::NAME
    }

    /// The names of the list and of the dispatch agree, one to one.
    #[test]
    fn every_listed_format_dispatches_to_itself() {
        for name in FORMATS {
            assert_eq!(crate::with_format!(name, name_of()), Ok(name));
            assert_eq!(check(name), Ok(name));
        }
        for name in MAIN {
            assert!(FORMATS.contains(&name), "{name}");
        }
        assert!(FORMATS.contains(&REFERENCE));
        let mut seen = std::vec::Vec::new();
        crate::for_each_format!(all: push_name(&mut seen));
        assert_eq!(seen, FORMATS);
    }

    fn push_name<S: Scalar>(seen: &mut std::vec::Vec<&'static str>) {
        seen.push(S::NAME);
    }

    /// An unknown name is an error, never a silent f64 in the tools.
    #[test]
    fn an_unknown_name_is_an_error_naming_the_known_ones() {
        let err = crate::with_format!("f16", name_of()).unwrap_err();
        assert_eq!(err.name(), "f16");
        let text = std::format!("{err}");
        for name in FORMATS {
            assert!(text.contains(name), "{text}");
        }
        assert_eq!(check("F64"), Err(UnknownFormat::new("F64")));
    }
}
