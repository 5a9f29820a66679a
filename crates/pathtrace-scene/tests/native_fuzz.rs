//! Malformed-input corpus: thousands of truncated, mutated and random scene files through both
//! parsers and the build step. None may panic, and every error must carry a location inside
//! the file. The mutator is a small deterministic PCG-driven one, so failures reproduce.

use pathtrace_scene::native::{load_str, parse_str, to_string, Format};

const CORNELL: &str = include_str!("../../../scenes/cornell-box.toml");
const FEATURES: &str = include_str!("data/features.toml");

/// PCG32 (O'Neill, "PCG: A Family of Simple Fast Space-Efficient Statistically Good Algorithms
/// for Random Number Generation", 2014): 64-bit LCG state, XSH-RR output.
struct Pcg(u64);

impl Pcg {
    fn next(&mut self) -> u32 {
        let old = self.0;
        self.0 = old.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        xorshifted.rotate_right((old >> 59) as u32)
    }

    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            self.next() as usize % n
        }
    }
}

/// Fragments that stress the grammars and the schema.
const TOKENS: [&str; 34] = [
    "[",
    "]",
    "{",
    "}",
    "\"",
    "'",
    "=",
    ",",
    ":",
    "\n",
    "#",
    ".",
    "-",
    "nan",
    "inf",
    "-inf",
    "1e40",
    "-1e400",
    "0",
    "-1",
    "1.5",
    "true",
    "null",
    "é",
    "\\",
    "[[objects]]",
    "[render]",
    "type = \"box\"",
    "material = \"white\"",
    "transform = [{scale = 0}]",
    "\"materials\":",
    "4294967296",
    "radius = -1",
    "[[groups]]",
];

fn boundary(s: &str, mut i: usize) -> usize {
    i = i.min(s.len());
    while !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn mutate(seed: &str, rng: &mut Pcg) -> String {
    let mut s = seed.to_string();
    for _ in 0..1 + rng.below(4) {
        let at = boundary(&s, rng.below(s.len() + 1));
        match rng.below(6) {
            0 => s.truncate(at),
            1 => {
                let end = boundary(&s, at + rng.below(40));
                s.replace_range(at..end, "");
            }
            2 => s.insert_str(at, TOKENS[rng.below(TOKENS.len())]),
            3 => {
                let end = boundary(&s, at + 1 + rng.below(8));
                let token = TOKENS[rng.below(TOKENS.len())];
                s.replace_range(at..end.max(at), token);
            }
            4 => {
                let lines: Vec<&str> = s.lines().collect();
                let (a, b) = (rng.below(lines.len()), rng.below(lines.len()));
                let mut out: Vec<&str> = lines.clone();
                if !out.is_empty() {
                    out.swap(a, b);
                    out.insert(a, lines[b]);
                }
                s = out.join("\n");
            }
            _ => {
                // Replace a digit, so numbers change but the structure stays.
                if let Some(pos) = s[at..].find(|c: char| c.is_ascii_digit()) {
                    let p = at + pos;
                    let d = ["9", "0", "-", "e9", "e99", ".", "nan"][rng.below(7)];
                    s.replace_range(p..p + 1, d);
                }
            }
        }
    }
    s
}

fn random_text(rng: &mut Pcg) -> String {
    (0..rng.below(200)).map(|_| TOKENS[rng.below(TOKENS.len())]).collect::<Vec<_>>().join(["", " ", "\n"][rng.below(3)])
}

fn check(text: &str, format: Format, stats: &mut [usize; 2]) {
    let lines = text.lines().count() + 1;
    match load_str(text, format, "fuzz".as_ref()) {
        Ok(_) => stats[0] += 1,
        Err(e) => {
            stats[1] += 1;
            assert!(e.line >= 1 && e.column >= 1, "{e}\n--- input ---\n{text}");
            assert!(e.line <= lines, "line {} beyond the file ({lines} lines): {e}\n--- input ---\n{text}", e.line);
            assert!(!e.message.is_empty() && !e.message.contains('\n'), "{e:?}");
            assert!(e.to_string().starts_with(&format!("fuzz:{}:{}: ", e.line, e.column)));
        }
    }
}

fn run(seed_text: &str, format: Format, cases: usize, rng_seed: u64) -> [usize; 2] {
    let mut rng = Pcg(rng_seed);
    let mut stats = [0; 2];
    for len in (0..seed_text.len()).step_by(7) {
        check(&seed_text[..boundary(seed_text, len)], format, &mut stats);
    }
    for i in 0..cases {
        let text = if i % 10 == 9 { random_text(&mut rng) } else { mutate(seed_text, &mut rng) };
        check(&text, format, &mut stats);
    }
    stats
}

#[test]
fn mutated_toml_never_panics_and_errors_are_located() {
    for (i, seed) in [CORNELL, FEATURES].into_iter().enumerate() {
        let [ok, err] = run(seed, Format::Toml, 5000, 1 + i as u64);
        assert!(ok > 10 && err > 1000, "ok {ok}, errors {err}: the mutator should produce both");
    }
}

#[test]
fn mutated_json_never_panics_and_errors_are_located() {
    for (i, seed) in [CORNELL, FEATURES].into_iter().enumerate() {
        let file = parse_str(seed, Format::Toml, "seed.toml".as_ref()).unwrap();
        let json = to_string(&file, Format::Json).unwrap();
        let [ok, err] = run(&json, Format::Json, 5000, 10 + i as u64);
        assert!(ok > 10 && err > 1000, "ok {ok}, errors {err}: the mutator should produce both");
    }
}

/// Each number of the features scene replaced, one at a time, by a value at the edge of single
/// precision. The scene must load or give a located error that names the real problem: never a
/// whole-file 1:1 error, nor the symptoms of an overflow taken for something else ("no lights",
/// "must be non-zero", "singular", "the same point").
#[test]
fn extreme_numbers_in_every_field_give_located_errors_that_name_the_problem() {
    let numbers: Vec<(usize, usize)> = number_spans(FEATURES);
    assert!(numbers.len() > 80, "only {} numbers found", numbers.len());
    let mut outcomes = [0usize; 2];
    for &(start, end) in &numbers {
        for extreme in ["3e38", "-3e38", "1e30", "1e-30", "4294967296", "99999999999"] {
            let text = format!("{}{extreme}{}", &FEATURES[..start], &FEATURES[end..]);
            match load_str(&text, Format::Toml, "x.toml".as_ref()) {
                Ok(_) => outcomes[0] += 1,
                Err(e) => {
                    outcomes[1] += 1;
                    let at = format!("`{}` → {extreme}", &FEATURES[start..end]);
                    assert!((e.line, e.column) != (1, 1), "{at}: unlocated: {e}");
                    for symptom in ["no lights", "positive radiance", "non-zero", "singular", "same point"] {
                        assert!(!e.message.contains(symptom), "{at}: overflow reported as {symptom:?}: {e}");
                    }
                }
            }
        }
    }
    assert!(outcomes[0] > 0 && outcomes[1] > 0, "{outcomes:?}");
}

/// Byte ranges of the numeric literals outside comments and strings.
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let code = line.split('#').next().unwrap_or("");
        let bytes = code.as_bytes();
        let mut i = 0;
        let mut in_string = false;
        while i < bytes.len() {
            let c = bytes[i];
            if c == b'"' {
                in_string = !in_string;
            }
            let starts = !in_string
                && (c.is_ascii_digit() || c == b'-')
                && (i == 0 || !bytes[i - 1].is_ascii_alphanumeric() && bytes[i - 1] != b'_');
            if starts {
                let end = i + code[i..]
                    .find(|ch: char| !(ch.is_ascii_alphanumeric() || "+-.".contains(ch)))
                    .unwrap_or(code.len() - i);
                if code[i..end].parse::<f64>().is_ok() {
                    spans.push((offset + i, offset + end));
                }
                i = end;
            } else {
                i += 1;
            }
        }
        offset += line.len();
    }
    spans
}
