//! What a Rapier collider or body belongs to, packed into its `user_data`.

/// The kind of thing a collider belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// A fragment of a breakable object.
    Fragment,
    /// A projectile.
    Projectile,
    /// The ground.
    Ground,
}

/// Packs kind, owner (object id or projectile index) and index (fragment) into a `u128`.
pub(crate) fn tag(kind: Kind, owner: u32, index: u32) -> u128 {
    let k: u128 = match kind {
        Kind::Fragment => 1,
        Kind::Projectile => 2,
        Kind::Ground => 3,
    };
    (k << 64) | ((owner as u128) << 32) | index as u128
}

/// Unpacks a [`tag`].
pub(crate) fn untag(data: u128) -> Option<(Kind, u32, u32)> {
    let kind = match data >> 64 {
        1 => Kind::Fragment,
        2 => Kind::Projectile,
        3 => Kind::Ground,
        _ => return None,
    };
    Some((kind, (data >> 32) as u32, data as u32))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tags_round_trip() {
        for (k, o, i) in [
            (Kind::Fragment, 7, 1999),
            (Kind::Projectile, u32::MAX, 0),
            (Kind::Ground, 0, u32::MAX),
        ] {
            assert_eq!(untag(tag(k, o, i)), Some((k, o, i)));
        }
        assert_eq!(untag(0), None);
    }
}
