//! Thousands of deterministic truncations and byte mutations of valid OBJ and PLY files: every
//! one gives either valid meshes or a one-line error with a line or byte offset, never a panic.

use crate::common::{s, write_ply, El, Enc, Val};
use pathtrace_scene::mesh::parse_mesh;
use std::path::Path;

/// SplitMix64: a small deterministic generator.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

const OBJ: &str = "# seed\nmtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n\
                   vn 0 0 1\nvn 0 0 -1\ng g\nf 1/1/1 2/2/1 3/3/1 4/1/1\nusemtl red\nf -4//-1 -3//-1 -2//-2\n\
                   usemtl blue\nf 1/1 3/3 4/2\nf 1 2 \\\n 3\n";

fn ply(enc: Enc) -> Vec<u8> {
    let vertex = El {
        name: "vertex",
        props: &[
            "float x",
            "float y",
            "double z",
            "float nx",
            "float ny",
            "float nz",
            "list uchar short junk",
            "float u",
            "float v",
        ],
        records: (0..5)
            .map(|i| {
                let f = f64::from(i);
                let mut r = s(&[f, f * f, 1.0 - f, 0.0, 1.0, 0.0]);
                r.push(Val::L(vec![f; i as usize]));
                r.extend(s(&[f * 0.1, 0.5]));
                r
            })
            .collect(),
    };
    let other = El {
        name: "other",
        props: &["int a", "list uint uchar b"],
        records: vec![vec![Val::S(1.0), Val::L(vec![2.0])]],
    };
    let face = El {
        name: "face",
        props: &["list uchar int vertex_indices", "short flags"],
        records: vec![
            vec![Val::L(vec![0.0, 1.0, 2.0, 3.0]), Val::S(1.0)],
            vec![Val::L(vec![4.0, 3.0, 2.0]), Val::S(2.0)],
        ],
    };
    write_ply(enc, &[vertex, other, face])
}

/// Parses one input and checks the outcome; true when it loaded.
fn check(bytes: &[u8], name: &str) -> bool {
    match parse_mesh(bytes, Path::new(name)) {
        Ok(parts) => {
            assert!(!parts.is_empty());
            for (part, mesh) in parts {
                mesh.validate().unwrap_or_else(|e| panic!("{name} part {part}: invalid mesh {e}"));
                assert!(!mesh.indices.is_empty());
            }
            true
        }
        Err(e) => {
            assert!(e.line().is_some() || e.offset().is_some(), "no location: {e}");
            assert!(!e.to_string().contains('\n'), "not one line: {e}");
            false
        }
    }
}

/// Every truncation, then `mutations` random byte edits (replace, insert, delete, swap in
/// characters that matter to the parsers). Both outcomes must occur, or the corpus tests
/// little.
fn corpus(seed: &[u8], name: &str, mutations: usize, rng: &mut Rng) -> usize {
    assert!(check(seed, name), "the seed {name} must load");
    let mut loaded = 0;
    let mut cases = 0;
    for len in 0..seed.len() {
        loaded += usize::from(check(&seed[..len], name));
        cases += 1;
    }
    const SPECIAL: &[u8] = b" \n\r\t/-+.#\\0123456789eEnaif\xff\x00\x80";
    for _ in 0..mutations {
        let mut bytes = seed.to_vec();
        for _ in 0..1 + rng.below(3) {
            let at = rng.below(bytes.len());
            let byte = if rng.below(2) == 0 { SPECIAL[rng.below(SPECIAL.len())] } else { rng.next() as u8 };
            match rng.below(4) {
                0 => bytes.insert(at, byte),
                1 if !bytes.is_empty() => {
                    bytes.remove(at);
                }
                _ if !bytes.is_empty() => bytes[at] = byte,
                _ => {}
            }
        }
        if rng.below(4) == 0 {
            let len = rng.below(bytes.len() + 1);
            bytes.truncate(len);
        }
        loaded += usize::from(check(&bytes, name));
        cases += 1;
    }
    eprintln!("{name}: {cases} cases, {loaded} loaded, {} rejected with a location", cases - loaded);
    assert!(loaded > 0 && loaded < cases);
    cases
}

#[test]
fn mutated_obj_files_never_panic() {
    let mut rng = Rng(1);
    let cases = corpus(OBJ.as_bytes(), "fuzz.obj", 4000, &mut rng);
    assert!(cases > 4000);
}

#[test]
fn mutated_ply_files_never_panic() {
    let mut rng = Rng(2);
    let mut cases = 0;
    for (enc, name) in [(Enc::Ascii, "ascii.ply"), (Enc::Le, "le.ply"), (Enc::Be, "be.ply")] {
        cases += corpus(&ply(enc), name, 3000, &mut rng);
    }
    assert!(cases > 9000);
}

#[test]
fn mutated_real_meshes_never_panic() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes");
    let files = [
        "teapot-simple/meshes/teapot.ply",
        "veach-bidir-pbrt/models/Mesh003.ply",
        "cbox-classic/common/meshes/cbox/largebox.obj",
    ];
    let mut rng = Rng(3);
    for file in files {
        let Ok(seed) = std::fs::read(dir.join(file)) else {
            eprintln!("skipped: {file} is absent");
            continue;
        };
        for _ in 0..300 {
            let mut bytes = seed.clone();
            for _ in 0..1 + rng.below(4) {
                let at = rng.below(bytes.len());
                bytes[at] = rng.next() as u8;
            }
            let len = bytes.len() - rng.below(bytes.len() / 8 + 1);
            bytes.truncate(len);
            let _ = check(&bytes, file);
        }
    }
}
