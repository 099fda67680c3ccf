//! The logical lines of an OBJ or MTL file: decoded (UTF-8, or UTF-16 with its BOM; a
//! UTF-8 BOM skipped; invalid bytes replaced), CR LF and CR-only endings accepted,
//! `\` continuations joined, comments and blank lines dropped.

use std::borrow::Cow;

/// The text of the file, decoded.
pub(crate) fn decode(bytes: &[u8]) -> Cow<'_, str> {
    let utf16 = |big: bool| -> Cow<'_, str> {
        let units = bytes[2..].chunks_exact(2).map(|c| {
            if big {
                u16::from_be_bytes([c[0], c[1]])
            } else {
                u16::from_le_bytes([c[0], c[1]])
            }
        });
        Cow::Owned(
            char::decode_utf16(units)
                .map(|c| c.unwrap_or(char::REPLACEMENT_CHARACTER))
                .collect(),
        )
    };
    match bytes {
        [0xEF, 0xBB, 0xBF, rest @ ..] => String::from_utf8_lossy(rest),
        [0xFE, 0xFF, ..] => utf16(true),
        [0xFF, 0xFE, ..] => utf16(false),
        _ => String::from_utf8_lossy(bytes),
    }
}

/// A logical line: its 1-based number (where it starts) and its text, comment removed
/// and trimmed; never empty.
pub(crate) struct Line<'a> {
    pub number: usize,
    pub text: Cow<'a, str>,
}

/// The physical lines of `text`, each ended by `\n`, `\r\n` or a lone `\r`.
fn physical(text: &str) -> impl Iterator<Item = &str> {
    let mut rest = text;
    std::iter::from_fn(move || {
        if rest.is_empty() {
            return None;
        }
        let end = rest.find(['\n', '\r']).unwrap_or(rest.len());
        let line = &rest[..end];
        let bytes = rest.as_bytes();
        let skip = match bytes.get(end) {
            Some(b'\r') if bytes.get(end + 1) == Some(&b'\n') => 2,
            Some(_) => 1,
            None => 0,
        };
        rest = &rest[end + skip..];
        Some(line)
    })
}

/// The logical lines of `text`.
pub(crate) fn lines(text: &str) -> impl Iterator<Item = Line<'_>> {
    let mut raw = physical(text).enumerate();
    std::iter::from_fn(move || {
        loop {
            let (index, first) = raw.next()?;
            let mut text = Cow::Borrowed(first);
            // A line ending in a backslash goes on on the next one.
            while let Some(stripped) = text.trim_end().strip_suffix('\\') {
                let mut joined = stripped.to_string();
                joined.push(' ');
                if let Some((_, next)) = raw.next() {
                    joined.push_str(next);
                }
                text = Cow::Owned(joined);
            }
            let cut = |t: &str| -> (usize, usize) {
                let body = t.find('#').map_or(t, |i| &t[..i]);
                let trimmed = body.trim();
                let start = trimmed.as_ptr() as usize - t.as_ptr() as usize;
                (start, start + trimmed.len())
            };
            let (a, b) = cut(&text);
            if a == b {
                continue;
            }
            let text = match text {
                Cow::Borrowed(t) => Cow::Borrowed(&t[a..b]),
                Cow::Owned(t) => Cow::Owned(t[a..b].to_string()),
            };
            return Some(Line {
                number: index + 1,
                text,
            });
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn collect(text: &str) -> Vec<(usize, String)> {
        lines(text)
            .map(|l| (l.number, l.text.into_owned()))
            .collect()
    }

    #[test]
    fn endings_continuations_and_comments() {
        let text = "v 1 2 3\r\n\r\n# comment\rf 1 \\\n 2 3 # tail\nvt 0 0";
        assert_eq!(
            collect(text),
            vec![
                (1, "v 1 2 3".to_string()),
                (4, "f 1   2 3".to_string()),
                (6, "vt 0 0".to_string())
            ]
        );
    }

    #[test]
    fn boms_and_utf16_are_decoded() {
        assert_eq!(decode(b"\xEF\xBB\xBFv 1"), "v 1");
        let utf16: Vec<u8> = [0xFE, 0xFF, 0, b'v', 0, b' ', 0, b'1'].to_vec();
        assert_eq!(decode(&utf16), "v 1");
        assert_eq!(decode(b"o caf\xE9"), "o caf\u{FFFD}");
    }
}
