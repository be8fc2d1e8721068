//! Input generators shared by the targets: grammar-generated expressions over a vocabulary,
//! token soups, byte mutations and blow-ups. Everything draws from one seeded ChaCha8 stream,
//! so an input is a pure function of (seed, target, index).

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The generator of every input.
pub type Rng = ChaCha8Rng;

/// The generator of input `index` of `target` in the run seeded `seed`: each input has its own
/// stream, so a run can resume at any index and a failure replays alone.
pub fn rng_for(seed: u64, target: &str, index: u64) -> Rng {
    let mut h = fnv1a(target.as_bytes()) ^ seed.rotate_left(17);
    h ^= index.wrapping_mul(0x9e37_79b9_7f4a_7c15);
    Rng::seed_from_u64(h)
}

/// FNV-1a, 64 bits: stable across Rust versions (unlike `DefaultHasher`), for seeds and for
/// the corpus file names.
pub fn fnv1a(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

/// Uniform in 0..n (n > 0).
pub fn below(r: &mut Rng, n: usize) -> usize {
    r.random_range(0..n.max(1))
}

/// One element of a nonempty slice.
pub fn pick<'a, T>(r: &mut Rng, xs: &'a [T]) -> &'a T {
    &xs[below(r, xs.len())]
}

/// True with probability p.
pub fn chance(r: &mut Rng, p: f64) -> bool {
    r.random_bool(p.clamp(0.0, 1.0))
}

/// The names an expression may use.
#[derive(Clone, Debug, Default)]
pub struct Vocab {
    /// Coordinates (their velocities and accelerations are generated too).
    pub coords: Vec<String>,
    /// Parameters.
    pub params: Vec<String>,
}

/// Numbers as people and hostile inputs write them.
const NUMBERS: &[&str] = &[
    "0",
    "1",
    "2",
    "3",
    "1/2",
    "0.5",
    "2.5",
    "1e-3",
    "1e3",
    "3.14159",
    "355/113",
    "1e-9",
    "1e9",
    "1e300",
    "1e-300",
    "1e301",
    "9.1e-31",
    "0.0",
    "1.0000001",
    "½",
    "¾",
    "10000000000",
    "123456789012345678901234567890",
];

/// Function names, including the rewritten ones.
const FUNCS: &[&str] = &[
    "sin", "cos", "tan", "sec", "csc", "cot", "asin", "acos", "atan", "sinh", "cosh", "tanh",
    "exp", "log", "ln", "sqrt", "abs",
];

/// A leaf: a coordinate in one of its spellings, a parameter, a number, π or t.
fn leaf(r: &mut Rng, v: &Vocab) -> String {
    match below(r, 10) {
        0..=3 if !v.coords.is_empty() => {
            let q = pick(r, &v.coords).clone();
            match below(r, 9) {
                0 | 1 => q,
                2 | 3 => format!("{q}'"),
                4 => format!("{q}''"),
                5 => format!("dot({q})"),
                6 => format!("{q}dot"),
                7 => format!("ddot({q})"),
                _ => format!("{q}(t)"),
            }
        }
        4..=6 if !v.params.is_empty() => pick(r, &v.params).clone(),
        7 => pick(r, &["pi", "π", "t"]).to_string(),
        _ => pick(r, NUMBERS).to_string(),
    }
}

/// A random expression over `v`, at most `depth` levels deep (text, with the language's
/// operators, implicit multiplication, Unicode forms and superscripts).
pub fn expr(r: &mut Rng, v: &Vocab, depth: u32) -> String {
    if depth == 0 || chance(r, 0.3) {
        return leaf(r, v);
    }
    let d = depth - 1;
    match below(r, 14) {
        0 | 1 => format!("{} + {}", expr(r, v, d), expr(r, v, d)),
        2 => format!("{} - {}", expr(r, v, d), expr(r, v, d)),
        3 | 4 => format!("{}*{}", expr(r, v, d), expr(r, v, d)),
        5 => format!("({})/({})", expr(r, v, d), expr(r, v, d)),
        6 => format!(
            "({})^{}",
            expr(r, v, d),
            pick(r, &["2", "3", "-1", "1/2", "-2", "0"])
        ),
        7 => format!("({})^({})", expr(r, v, d), expr(r, v, d)),
        8 => format!("-({})", expr(r, v, d)),
        9 | 10 => format!("{}({})", pick(r, FUNCS), expr(r, v, d)),
        11 => format!("{} {}", expr(r, v, d), expr(r, v, d)),
        12 => format!(
            "({})·({}) − {}",
            expr(r, v, d),
            expr(r, v, d),
            expr(r, v, d)
        ),
        _ => format!("({})²", expr(r, v, d)),
    }
}

/// Tokens for soups: every operator, mark and hostile character the reader may meet.
const TOKENS: &[&str] = &[
    "(",
    ")",
    "+",
    "-",
    "*",
    "/",
    "^",
    "**",
    "=",
    ",",
    ";",
    "'",
    "''",
    ".",
    " ",
    "  ",
    "x",
    "theta",
    "θ",
    "θ̇",
    "ẍ",
    "q",
    "m",
    "g",
    "l",
    "k",
    "m1",
    "m_1",
    "m₁",
    "sin",
    "cos",
    "sqrt",
    "√",
    "½",
    "²",
    "⁻",
    "¹",
    "·",
    "−",
    "×",
    "dot(",
    "ddot(",
    "_",
    "pi",
    "π",
    "t",
    "abs",
    "log",
    "exp",
    "0/0",
    "1/0",
    "0",
    "1",
    "2.5",
    "1e308",
    "1e-308",
    "9e99999",
    "\u{202e}",
    "\u{200b}",
    "\u{1b}[2J",
    "\u{0}",
    "\n",
    "\t",
    "é",
    "mgl",
    "x'",
    "x''",
    "x'''",
    "|",
    "[",
    "]",
    "{",
    "}",
    "\\frac",
    "<",
    ">",
    "!",
    "%",
    "e",
    "E",
    "inf",
    "nan",
    "NaN",
];

/// A soup of `n` tokens.
pub fn soup(r: &mut Rng, n: usize) -> String {
    (0..n).map(|_| *pick(r, TOKENS)).collect()
}

/// Random bytes (not necessarily UTF-8).
pub fn bytes(r: &mut Rng, n: usize) -> Vec<u8> {
    (0..n).map(|_| r.random::<u8>()).collect()
}

/// One to four mutations of `seed`: byte flips, deletions, insertions of tokens,
/// duplications, swaps of two chunks, a number made huge, truncation.
pub fn mutate(r: &mut Rng, seed: &[u8]) -> Vec<u8> {
    let mut s = seed.to_vec();
    for _ in 0..1 + below(r, 4) {
        let n = s.len();
        let i = below(r, n + 1).min(n);
        let j = (i + below(r, 8)).min(n);
        match below(r, 8) {
            0 if n > 0 => s[i.min(n - 1)] ^= 1 << below(r, 8),
            1 => {
                s.drain(i..j);
            }
            2 => {
                let t = pick(r, TOKENS).as_bytes().to_vec();
                s.splice(i..i, t);
            }
            3 => {
                let chunk = s[i..j].to_vec();
                s.splice(j..j, chunk);
            }
            4 if n > 2 => {
                let k = below(r, n);
                s.swap(i.min(n - 1), k);
            }
            5 => {
                let t = pick(
                    r,
                    &[
                        "1e300",
                        "1e-300",
                        "99999999999999999999",
                        "0",
                        "-0",
                        "1e309",
                    ],
                );
                s.splice(i..j, t.bytes());
            }
            6 => s.truncate(i),
            _ => {
                let t = pick(r, FUNCS);
                let mut wrapped = format!("{t}(").into_bytes();
                wrapped.extend_from_slice(&s[i..j]);
                wrapped.push(b')');
                s.splice(i..j, wrapped);
            }
        }
    }
    s
}

/// Inputs that have blown up time or memory before: towers of powers, long products of
/// cosines, deep parentheses and inputs near the length limit.
pub fn blowup(r: &mut Rng, v: &Vocab) -> String {
    let q = v.coords.first().cloned().unwrap_or_else(|| "x".into());
    let n = 1 + below(r, 60);
    match below(r, 6) {
        0 => {
            let tower = vec![format!("({q}'+2)"); n].join("^");
            format!("1/2 {q}'^2 + {tower}")
        }
        1 => (0..n)
            .map(|k| format!("cos({q} + {k})"))
            .collect::<Vec<_>>()
            .join("*"),
        2 => {
            let depth = 95 + below(r, 10);
            format!("{}{q}{}", "(".repeat(depth), ")".repeat(depth))
        }
        3 => {
            let len = 19_990 + below(r, 20);
            let mut s = format!("{q}'^2");
            while s.len() < len {
                s.push_str(" + x");
            }
            s.truncate(len);
            s
        }
        4 => (0..n * 20)
            .map(|k| format!("{k}*{q}^{}", k % 7))
            .collect::<Vec<_>>()
            .join(" + "),
        _ => format!(
            "({})^{}",
            expr(r, v, 3),
            pick(r, &["1000", "4096", "65536", "1e9"])
        ),
    }
}
