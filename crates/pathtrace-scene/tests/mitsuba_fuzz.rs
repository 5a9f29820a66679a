//! The Mitsuba importer under extreme numbers: each number of a test scene replaced, one at a
//! time, by a value at the edge of single precision or of the integer types. Every result loads or
//! gives an error at the XML element concerned (never 1:1) that names the real problem, not an
//! overflow's symptom.

use pathtrace_scene::mitsuba::load_str;
use std::path::Path;

const SPOT: &str = include_str!("data/spot.xml");

/// Byte ranges of the numbers in attribute values (after `"`, `,` or a space), outside comments.
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let bytes = text.as_bytes();
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if text[i..].starts_with("<!--") {
            i += text[i..].find("-->").map_or(bytes.len(), |end| end + 3);
            continue;
        }
        let after_separator = i > 0 && matches!(bytes[i - 1], b'"' | b',' | b' ');
        if after_separator && (bytes[i].is_ascii_digit() || bytes[i] == b'-') {
            let len = text[i..].find(|c: char| !(c.is_ascii_alphanumeric() || "+-.".contains(c))).unwrap_or(0);
            if text[i..i + len].parse::<f64>().is_ok() {
                spans.push((i, i + len));
            }
            i += len.max(1);
        } else {
            i += 1;
        }
    }
    spans
}

#[test]
fn extreme_numbers_in_every_attribute_give_located_errors_that_name_the_problem() {
    let numbers = number_spans(SPOT);
    assert!(numbers.len() > 40, "only {} numbers found", numbers.len());
    let mut outcomes = [0usize; 2];
    for &(start, end) in &numbers {
        for extreme in ["3e38", "-3e38", "1e30", "1e-30", "4294967296", "99999999999"] {
            let text = format!("{}{extreme}{}", &SPOT[..start], &SPOT[end..]);
            match load_str(&text, Path::new("x.xml"), &[]) {
                Ok(_) => outcomes[0] += 1,
                Err(e) => {
                    outcomes[1] += 1;
                    let at = format!("`{}` at byte {start} → {extreme}", &SPOT[start..end]);
                    assert!((e.line, e.column) != (1, 1), "{at}: unlocated: {e}");
                    for symptom in
                        ["no lights", "positive radiance", "non-zero", "singular", "same point", "at least 1"]
                    {
                        assert!(!e.message.contains(symptom), "{at}: overflow reported as {symptom:?}: {e}");
                    }
                }
            }
        }
    }
    assert!(outcomes[0] > 0 && outcomes[1] > 0, "{outcomes:?}");
}
