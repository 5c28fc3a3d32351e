//! `named_enum!`: a closed set of names (reflectance models, their terms,
//! shading modes) declared once, with its contract names, its parse (and
//! the error that lists what is accepted), `ALL` and `Display`; and
//! [`nearest_name`], the one "did you mean" of every name a user types
//! (models, fit models, measured materials, adapters, scene keys).

/// Declares a `Copy` enum whose variants each carry their contract name:
///
/// ```text
/// named_enum!(
///     /// doc
///     Shape, "shape" {
///         /// doc
///         Round = "round",
///         Square = "square",
///     }
/// );
/// ```
///
/// gives the array `Shape::ALL` (declaration order), `Shape::name`, `Display` and
/// `FromStr` whose error is ``unknown shape `x`; expected one of round,
/// square``. Extra derives (e.g. `Default`) follow the name as
/// `#[derive(..)]` attributes in the doc position.
macro_rules! named_enum {
    ($(#[$doc:meta])* $name:ident, $what:literal { $($(#[$vdoc:meta])* $variant:ident = $text:literal,)+ }) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum $name {
            $($(#[$vdoc])* $variant,)+
        }

        impl $name {
            /// Every value, in declaration order.
            pub const ALL: [$name; [$($text,)+].len()] = [$($name::$variant,)+];

            /// The contract's name.
            pub fn name(self) -> &'static str {
                match self {
                    $($name::$variant => $text,)+
                }
            }
        }

        impl ::std::fmt::Display for $name {
            fn fmt(&self, f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl ::std::str::FromStr for $name {
            type Err = String;
            fn from_str(s: &str) -> Result<Self, String> {
                Self::ALL.iter().copied().find(|v| v.name() == s).ok_or_else(|| {
                    let known: Vec<_> = Self::ALL.iter().map(|v| v.name()).collect();
                    format!(
                        "unknown {} `{s}`{}; expected one of {}",
                        $what,
                        $crate::base::named::did_you_mean(s, known.iter().copied()),
                        known.join(", ")
                    )
                })
            }
        }
    };
}

pub(crate) use named_enum;

/// The candidate closest to `unknown` by edit distance (ignoring case and
/// the difference between `-`, `_` and nothing, so `blinnphong` finds
/// `blinn-phong`), if within a third of its length (at least 2 edits), or
/// if one is a prefix of the other (`fov` for `fov_y_deg`).
pub fn nearest_name<'c>(
    unknown: &str,
    candidates: impl IntoIterator<Item = &'c str>,
) -> Option<&'c str> {
    // Names are short; a long one is not a typo, and edit distance is
    // quadratic.
    if unknown.is_empty() || unknown.len() > 64 {
        return None;
    }
    let fold = |s: &str| -> String {
        s.chars()
            .filter(|c| !matches!(c, '-' | '_' | ' '))
            .flat_map(char::to_lowercase)
            .collect()
    };
    let unknown = fold(unknown);
    if unknown.is_empty() {
        return None;
    }
    let budget = (unknown.chars().count() / 3).max(2);
    candidates
        .into_iter()
        .filter(|c| !c.is_empty())
        .map(|c| {
            let folded = fold(c);
            let prefix = folded.starts_with(&unknown) || unknown.starts_with(&folded);
            (edit_distance(&unknown, &folded), prefix, c)
        })
        .filter(|&(distance, prefix, _)| distance <= budget || prefix)
        .min_by_key(|&(distance, _, _)| distance)
        .map(|(_, _, c)| c)
}

/// `; did you mean `NAME`?` for the [`nearest_name`] of `unknown`, or
/// nothing when no candidate is near.
pub fn did_you_mean<'c>(unknown: &str, candidates: impl IntoIterator<Item = &'c str>) -> String {
    nearest_name(unknown, candidates)
        .map(|n| format!("; did you mean `{n}`?"))
        .unwrap_or_default()
}

/// Levenshtein distance (insertions, deletions, substitutions), by chars.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut previous: Vec<usize> = (0..=b.len()).collect();
    let mut current = vec![0; b.len() + 1];
    for (i, ca) in a.chars().enumerate() {
        current[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitute = previous[j] + usize::from(ca != cb);
            current[j + 1] = substitute.min(previous[j + 1] + 1).min(current[j] + 1);
        }
        std::mem::swap(&mut previous, &mut current);
    }
    previous[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_names_are_suggested_and_far_ones_not() {
        let models = ["lambert", "blinn-phong", "ward", "cook-torrance"];
        assert_eq!(nearest_name("blinnphong", models), Some("blinn-phong"));
        assert_eq!(nearest_name("wrd", models), Some("ward"));
        assert_eq!(nearest_name("Lambrt", models), Some("lambert"));
        assert_eq!(nearest_name("fov", ["fov_y_deg", "up"]), Some("fov_y_deg"));
        assert_eq!(nearest_name("zzzzzz", models), None);
        assert_eq!(
            did_you_mean("chromee", ["chrome", "gold"]),
            "; did you mean `chrome`?"
        );
        assert_eq!(did_you_mean("q", ["chrome"]), "");
    }
}
