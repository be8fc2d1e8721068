//! Lane-parallel evaluation of a compiled [`Program`]: the same instruction stream applied to
//! `K` points at once (structure of arrays), so the dispatch is paid once for `K` values and
//! the lane loops vectorize — many trajectories advanced together (the flip-time map).

use super::super::node::Func;
use super::{Instr, Program};

/// Lane-parallel evaluation: the same instruction stream applied to `K` points at once,
/// structure-of-arrays (one `[f64; K]` per input and per slot), so the per-instruction
/// dispatch is paid once for `K` values and the lane loops vectorize.
impl Program {
    /// A scratch buffer of the right size for [`run_lanes`](Self::run_lanes).
    pub fn scratch_lanes<const K: usize>(&self) -> Vec<[f64; K]> {
        vec![[0.0; K]; self.len()]
    }

    /// Runs the program on `K` points: `inputs[k][l]` is input `k` of lane `l`, `scratch`
    /// one `[f64; K]` per instruction (from [`scratch_lanes`](Self::scratch_lanes)); no
    /// allocation. Returns the bit mask of the lanes where some instruction was not finite
    /// (bit `l` for lane `l`; 0 when every lane is defined): exactly the lanes where
    /// [`run`](Self::run) would return `Undefined` (run that lane alone to learn the node).
    /// The other lanes' outputs are read with [`output_lanes`](Self::output_lanes).
    pub fn run_lanes<const K: usize>(&self, inputs: &[[f64; K]], scratch: &mut [[f64; K]]) -> u64 {
        const { assert!(K >= 1 && K <= 64, "1 to 64 lanes") };
        // v·0 is 0 for finite v and NaN for ±∞ or NaN: summing it per lane flags a
        // non-finite value without a branch per value. Only some values need it: a
        // non-finite value stays non-finite through +, ·, √, positive powers and the other
        // functions, so it shows at an output unless it meets an instruction that can make
        // it finite again (1/∞ = 0, exp(−∞) = 0, …): those instructions' operands are checked.
        let mut poison = [0.0f64; K];
        let taint = |x: &[f64; K], poison: &mut [f64; K]| {
            for l in 0..K {
                poison[l] += x[l] * 0.0;
            }
        };
        let missing = [f64::NAN; K];
        let nc = self.consts.len();
        for (slot, &c) in scratch.iter_mut().zip(&self.consts) {
            *slot = [c; K];
        }
        for (i, ins) in self.code.iter().enumerate() {
            let (done, rest) = scratch.split_at_mut(nc + i);
            let out = &mut rest[0];
            let un = |a: u32, out: &mut [f64; K], f: fn(f64) -> f64| {
                let x = &done[a as usize];
                for l in 0..K {
                    out[l] = f(x[l]);
                }
            };
            match *ins {
                Instr::Recip(a) | Instr::RecipSqrt(a) => taint(&done[a as usize], &mut poison),
                Instr::PowI(a, k) if k <= 0 => taint(&done[a as usize], &mut poison),
                Instr::PowF(a, b) => {
                    taint(&done[a as usize], &mut poison);
                    taint(&done[b as usize], &mut poison);
                }
                Instr::Func(Func::Exp | Func::Atan | Func::Tanh, a) => {
                    taint(&done[a as usize], &mut poison);
                }
                _ => {}
            }
            match *ins {
                Instr::Input(k) => *out = *inputs.get(k as usize).unwrap_or(&missing),
                Instr::Add(a, b) => {
                    let (x, y) = (&done[a as usize], &done[b as usize]);
                    for l in 0..K {
                        out[l] = x[l] + y[l];
                    }
                }
                Instr::Mul(a, b) => {
                    let (x, y) = (&done[a as usize], &done[b as usize]);
                    for l in 0..K {
                        out[l] = x[l] * y[l];
                    }
                }
                Instr::Recip(a) => {
                    let x = &done[a as usize];
                    for l in 0..K {
                        out[l] = 1.0 / x[l];
                    }
                }
                Instr::Sqrt(a) => un(a, out, f64::sqrt),
                Instr::RecipSqrt(a) => un(a, out, |v| 1.0 / v.sqrt()),
                Instr::PowI(a, k) => powi_lanes(&done[a as usize], k, out),
                Instr::PowF(a, b) => {
                    let (x, y) = (&done[a as usize], &done[b as usize]);
                    for l in 0..K {
                        out[l] = x[l].powf(y[l]);
                    }
                }
                Instr::Sin(a) | Instr::Func(Func::Sin, a) => {
                    sin_cos_lanes(&done[a as usize], 0, out)
                }
                Instr::Cos(a) | Instr::Func(Func::Cos, a) => {
                    sin_cos_lanes(&done[a as usize], 1, out)
                }
                Instr::Func(f, a) => un(a, out, f.as_fn()),
            }
        }
        for &o in &self.outputs {
            taint(&scratch[o as usize], &mut poison);
        }
        (0..K).fold(0u64, |m, l| if poison[l].is_nan() { m | 1 << l } else { m })
    }

    /// Output `k` of every lane after [`run_lanes`](Self::run_lanes).
    pub fn output_lanes<const K: usize>(&self, k: usize, scratch: &[[f64; K]]) -> [f64; K] {
        scratch[self.outputs[k] as usize]
    }
}

/// xᵏ on every lane by binary powering, the steps of compiler-rt's `__powidf2` (what
/// `f64::powi` calls) in the same order, so the values are the same, but vectorized.
fn powi_lanes<const K: usize>(x: &[f64; K], k: i32, out: &mut [f64; K]) {
    let mut a = *x;
    let mut r = [1.0; K];
    let mut n = k.unsigned_abs();
    loop {
        if n & 1 == 1 {
            for l in 0..K {
                r[l] *= a[l];
            }
        }
        n >>= 1;
        if n == 0 {
            break;
        }
        for v in &mut a {
            *v *= *v;
        }
    }
    if k < 0 {
        for v in &mut r {
            *v = 1.0 / *v;
        }
    }
    *out = r;
}

/// sin x for one value, as the lanes compute it.
#[inline]
pub(super) fn sin(x: f64) -> f64 {
    let mut o = [0.0];
    sin_cos_lanes(&[x], 0, &mut o);
    o[0]
}

/// cos x for one value, as the lanes compute it.
#[inline]
pub(super) fn cos(x: f64) -> f64 {
    let mut o = [0.0];
    sin_cos_lanes(&[x], 1, &mut o);
    o[0]
}

/// Lanes beyond this size go through libm: the reduction below is exact only while
/// y·DP1 is (y < 2²⁹), and this keeps a wide margin.
const TRIG_REDUCED: f64 = 1e6;

/// sin (`shift` 0) or cos (`shift` 1) of every lane, in a form the compiler vectorizes (the
/// scalar libm calls do not): x reduced modulo π/2 by Cody–Waite in three parts, then the
/// Cephes minimax polynomials on [−π/4, π/4] (as in Agner Fog's vector class library).
/// Within a few ulp of libm; lanes with |x| ≥ 1e6 or not finite are computed by libm.
// The coefficients are written as published (Cephes), digits past f64's included.
#[allow(clippy::excessive_precision)]
pub(super) fn sin_cos_lanes<const K: usize>(x: &[f64; K], shift: u64, out: &mut [f64; K]) {
    const S: [f64; 6] = [
        -1.666_666_666_666_663_1e-1,
        8.333_333_333_322_118_6e-3,
        -1.984_126_982_958_954e-4,
        2.755_731_362_138_572_5e-6,
        -2.505_074_776_285_780_7e-8,
        1.589_623_015_765_465_7e-10,
    ];
    const C: [f64; 6] = [
        4.166_666_666_666_659_3e-2,
        -1.388_888_888_887_305_6e-3,
        2.480_158_728_885_170_5e-5,
        -2.755_731_417_929_673_9e-7,
        2.087_570_084_197_473_2e-9,
        -1.135_853_652_138_768_2e-11,
    ];
    const DP1: f64 = 7.853_981_554_508_209_228_515_625e-1 * 2.0;
    const DP2: f64 = 7.946_627_356_147_928_367_14e-9 * 2.0;
    const DP3: f64 = 3.061_616_997_868_382_943_07e-17 * 2.0;
    // Adding 1.5·2⁵² rounds to an integer (ties to even) whose low bits are its last bits.
    const MAGIC: f64 = 6_755_399_441_055_744.0;
    let mut outside = false;
    for l in 0..K {
        let v = x[l];
        let xa = v.abs();
        outside |= xa.is_nan() | (xa >= TRIG_REDUCED);
        let t = xa * std::f64::consts::FRAC_2_PI + MAGIC;
        let q = t.to_bits().wrapping_add(shift);
        let y = t - MAGIC;
        let r = ((xa - y * DP1) - y * DP2) - y * DP3;
        let r2 = r * r;
        let ps = S[0] + r2 * (S[1] + r2 * (S[2] + r2 * (S[3] + r2 * (S[4] + r2 * S[5]))));
        let pc = C[0] + r2 * (C[1] + r2 * (C[2] + r2 * (C[3] + r2 * (C[4] + r2 * C[5]))));
        let sin_r = r + r * r2 * ps;
        let cos_r = (1.0 - 0.5 * r2) + r2 * r2 * pc;
        // Quadrant q: sin(r), cos(r), −sin(r), −cos(r) for sin; cos is sin a quadrant on.
        let value = if q & 1 == 0 { sin_r } else { cos_r };
        let negative = ((q >> 1) & 1) ^ ((shift ^ 1) & (v.to_bits() >> 63));
        out[l] = f64::from_bits(value.to_bits() ^ (negative << 63));
    }
    if outside {
        for l in 0..K {
            if x[l].is_nan() || x[l].abs() >= TRIG_REDUCED {
                out[l] = if shift == 0 { x[l].sin() } else { x[l].cos() };
            }
        }
    }
}
