//! A scene error as the example programs print it (`render`, `viewer`): `FILE:LINE:COL:
//! message`, naming the number format it concerns and the program's own capacities.

use fixray::SceneError;
use fixray::scene::SceneErrorKind;

/// A scene error as the program prints it, `FILE:LINE:COL: message`, for the scene read
/// in `format`. `reference` is the f64 reading's error (`None`: f64 read the scene): an
/// error f64 shares at the same place is the scene's, in every format; one it does not
/// share is `format`'s alone, and the message names it.
pub fn explain(file: &str, format: &str, e: &SceneError, reference: Option<&SceneError>) -> String {
    use SceneErrorKind as K;
    let shared = reference
        .filter(|r| (r.line, r.column) == (e.line, e.column))
        .map(|r| &r.kind);
    let message = match (&e.kind, shared) {
        // The capacities are this program's (`LargeScene`), in every format.
        (K::TooMany { what, capacity, .. }, _) => {
            format!("too many {what}: this program holds at most {capacity} {what}")
        }
        (K::DoesNotFit { value, .. }, Some(K::DoesNotFit { .. })) => {
            format!("`{value}` does not fit in any number format (not even f64)")
        }
        (K::DerivedDoesNotFit { what, .. }, Some(K::DerivedDoesNotFit { .. })) => {
            format!("{what} does not fit in any number format (not even f64)")
        }
        (kind, Some(_)) => kind.to_string(),
        // The format's own: say which, unless the message does.
        (kind, None) => {
            let message = kind.to_string();
            if message.contains(format) {
                message
            } else {
                format!("{message} (in the {format} number format)")
            }
        }
    };
    format!("{file}:{}:{}: {message}", e.line, e.column)
}
