//! Keeping error lines short: a value echoed in a message (a material name, a number, a file name)
//! can be megabytes long in a broken or hostile file, and a 10 MB error line helps no one.

/// The longest run of non-space characters a message keeps whole.
const MAX_RUN: usize = 120;

/// `text` with every run of non-whitespace characters longer than [`MAX_RUN`] shortened to its
/// start and end around a note of how long it was: enough to recognise the value.
pub fn elide_long_runs(text: &str) -> String {
    let mut out = String::with_capacity(text.len().min(4 * MAX_RUN));
    let mut rest = text;
    while !rest.is_empty() {
        let run_end = rest.find(char::is_whitespace).unwrap_or(rest.len());
        let (run, after) = rest.split_at(run_end);
        if run.chars().count() > MAX_RUN {
            let head: String = run.chars().take(60).collect();
            let tail: String = run.chars().rev().take(20).collect::<Vec<_>>().into_iter().rev().collect();
            out.push_str(&format!("{head}…[{} bytes]…{tail}", run.len()));
        } else {
            out.push_str(run);
        }
        let space_end = after.find(|c: char| !c.is_whitespace()).unwrap_or(after.len());
        out.push_str(&after[..space_end]);
        rest = &after[space_end..];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_values_are_shortened_and_short_text_kept() {
        assert_eq!(elide_long_runs("unknown material `white`"), "unknown material `white`");
        let name = "x".repeat(10_000_000);
        let line = elide_long_runs(&format!("unknown material `{name}` — in  `a`"));
        assert!(line.len() < 200, "{}", line.len());
        assert!(line.starts_with("unknown material `xxx") && line.contains("[10000002 bytes]"), "{line}");
        assert!(line.ends_with("xx` — in  `a`"), "{line}");
        assert_eq!(elide_long_runs(&"é".repeat(121)).chars().filter(|&c| c == 'é').count(), 80);
    }
}
