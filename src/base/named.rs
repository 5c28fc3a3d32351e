//! [`named_enum!`]: a closed set of names (reflectance models, their terms,
//! shading modes) declared once, with its contract names, its parse (and
//! the error that lists what is accepted), `ALL` and `Display`.

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
                    format!("unknown {} `{s}`; expected one of {}", $what, known.join(", "))
                })
            }
        }
    };
}

pub(crate) use named_enum;
