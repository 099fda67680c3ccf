//! The words users type: plain enums that name a choice (a fracture method, a seed
//! pattern, a shape, ...), each defined once with [`vocabulary!`](crate::vocabulary).
//!
//! Every vocabulary type has an `ALL` list (the order UIs show), `NAMES` (the same words
//! as strings), `name()`, [`Display`](std::fmt::Display) and
//! [`FromStr`](std::str::FromStr) with the same words; a bad word is an [`UnknownWord`]
//! that lists the valid ones. Behind the defining crate's cargo features, `serde`
//! (serialised as the same words) and `clap` (a `clap::ValueEnum` whose help is the
//! variant's doc comment).
//!
//! ```
//! use shatter_geom::fracture::Pattern;
//! let p: Pattern = "radial".parse().expect("a pattern");
//! assert_eq!(p.to_string(), "radial");
//! let err = "spiral".parse::<Pattern>().unwrap_err();
//! assert_eq!(
//!     err.to_string(),
//!     "unknown pattern `spiral` (expected one of: uniform, clustered, radial, splinter)"
//! );
//! ```

/// A word that is not in a vocabulary.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown {what} `{word}` (expected one of: {})", .valid.join(", "))]
pub struct UnknownWord {
    /// What the word should have named ("method", "pattern", ...).
    pub what: &'static str,
    /// The word given.
    pub word: String,
    /// The valid words.
    pub valid: &'static [&'static str],
}

/// The variant's doc comment as one line (for clap's help).
#[doc(hidden)]
pub fn one_line(doc: &str) -> String {
    doc.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Defines a vocabulary enum: the enum, `ALL`, `NAMES`, `name()`, `Display`, `FromStr`
/// (error: [`UnknownWord`]), `Default` when a `default Variant` follows the word, and, behind the calling crate's `serde` and `clap` features,
/// `Serialize`/`Deserialize` as the words and `clap::ValueEnum`.
///
/// The calling crate must declare the features `serde` and `clap` (with `serde` and
/// `clap` as dependencies when they are on).
///
/// ```ignore
/// shatter_geom::vocabulary! {
///     /// How fragments hold together.
///     pub enum BondModel: "bond model", default Clusters {
///         /// A fixed joint per bond.
///         Joints = "joints",
///         /// One body per connected cluster.
///         Clusters = "clusters",
///     }
/// }
/// ```
#[macro_export]
macro_rules! vocabulary {
    (
        $(#[$meta:meta])*
        $vis:vis enum $name:ident : $what:literal $(, default $default:ident)? {
            $( $(#[doc = $doc:literal])* $variant:ident = $word:literal ),+ $(,)?
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        $vis enum $name {
            $( $(#[doc = $doc])* $variant, )+
        }

        impl $name {
            /// Every value, in the order the user interfaces list them.
            pub const ALL: &'static [$name] = &[$($name::$variant),+];
            /// The words of [`Self::ALL`], in the same order.
            pub const NAMES: &'static [&'static str] = &[$($word),+];

            /// The word for this value (as parsed by `FromStr` and written by `Display`).
            pub fn name(self) -> &'static str {
                match self {
                    $( $name::$variant => $word, )+
                }
            }

            /// The variant's doc comment, on one line.
            pub fn help(self) -> String {
                match self {
                    $( $name::$variant => $crate::vocab::one_line(concat!($($doc, " "),*)), )+
                }
            }
        }

        $(
            impl Default for $name {
                fn default() -> Self {
                    $name::$default
                }
            }
        )?

        impl ::std::fmt::Display for $name {
            fn fmt(&self, f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl ::std::str::FromStr for $name {
            type Err = $crate::vocab::UnknownWord;
            fn from_str(s: &str) -> Result<Self, Self::Err> {
                match s {
                    $( $word => Ok($name::$variant), )+
                    _ => Err($crate::vocab::UnknownWord {
                        what: $what,
                        word: s.to_string(),
                        valid: Self::NAMES,
                    }),
                }
            }
        }

        #[cfg(feature = "serde")]
        impl ::serde::Serialize for $name {
            fn serialize<S: ::serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str(self.name())
            }
        }

        #[cfg(feature = "serde")]
        impl<'de> ::serde::Deserialize<'de> for $name {
            fn deserialize<D: ::serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                let word = <::std::string::String as ::serde::Deserialize>::deserialize(d)?;
                word.parse().map_err(::serde::de::Error::custom)
            }
        }

        #[cfg(feature = "clap")]
        impl ::clap::ValueEnum for $name {
            fn value_variants<'a>() -> &'a [Self] {
                Self::ALL
            }
            fn to_possible_value(&self) -> Option<::clap::builder::PossibleValue> {
                Some(::clap::builder::PossibleValue::new(self.name()).help(self.help()))
            }
        }
    };
}
