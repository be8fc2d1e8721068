//! Numeric evaluation: an expression (or several sharing sub-expressions) is compiled once
//! into a flat program over f64 slots and then run at many points without allocating.
//!
//! Every instruction checks its result: a value that is not finite (log of a negative, 1/0,
//! overflow) stops the run with [`Undefined`] naming the node, instead of a silent NaN.
//!
//! sin and cos are computed by the same reduction and polynomials in [`Program::run`] and the
//! lane-parallel run (within a few ulp of libm, and faster: a quarter off a double-pendulum
//! right-hand side), so one trajectory and a batch of them agree to the bit.
//!
//! Numbers live in a prefix of the slots, copied in once per run rather than executed as
//! instructions, and [`Program::specialize`] folds inputs that stay fixed (a simulation's
//! parameters) into that prefix, so per-call work is only what depends on the state.

use num_traits::ToPrimitive;
use rustc_hash::FxHashMap;

use super::node::{Func, Id, Node, Sym};
use super::pool::Pool;

mod lanes;

/// The expression is not defined at the given point; `node` is where it first failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("undefined at this point")]
pub struct Undefined {
    pub(crate) node: Id,
}

/// A variable the program was not told about.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("`{name}` has no value")]
pub struct Unbound {
    pub(crate) name: String,
}

#[derive(Clone, Copy, Debug)]
enum Instr {
    Input(u32),
    Add(u32, u32),
    Mul(u32, u32),
    Recip(u32),
    Sqrt(u32),
    RecipSqrt(u32),
    PowI(u32, i32),
    PowF(u32, u32),
    // The common functions get their own instructions: one dispatch instead of two.
    Sin(u32),
    Cos(u32),
    Func(Func, u32),
}

impl Instr {
    /// The value of this instruction, given the values of its operand slots.
    #[inline(always)]
    fn apply(self, slot: impl Fn(u32) -> f64, inputs: &[f64]) -> f64 {
        match self {
            Instr::Input(k) => inputs.get(k as usize).copied().unwrap_or(f64::NAN),
            Instr::Add(a, b) => slot(a) + slot(b),
            Instr::Mul(a, b) => slot(a) * slot(b),
            Instr::Recip(a) => 1.0 / slot(a),
            Instr::Sqrt(a) => slot(a).sqrt(),
            Instr::RecipSqrt(a) => 1.0 / slot(a).sqrt(),
            Instr::PowI(a, k) => slot(a).powi(k),
            Instr::PowF(a, b) => slot(a).powf(slot(b)),
            Instr::Sin(a) => lanes::sin(slot(a)),
            Instr::Cos(a) => lanes::cos(slot(a)),
            Instr::Func(f, a) => f.apply(slot(a)),
        }
    }

    /// The slots this instruction reads.
    fn operands(self) -> [Option<u32>; 2] {
        match self {
            Instr::Input(_) => [None, None],
            Instr::Add(a, b) | Instr::Mul(a, b) | Instr::PowF(a, b) => [Some(a), Some(b)],
            Instr::Recip(a)
            | Instr::Sqrt(a)
            | Instr::RecipSqrt(a)
            | Instr::PowI(a, _)
            | Instr::Sin(a)
            | Instr::Cos(a)
            | Instr::Func(_, a) => [Some(a), None],
        }
    }

    /// The instruction reading `map[slot]` wherever it read `slot`.
    fn remap(self, map: &[u32]) -> Instr {
        let m = |a: u32| map[a as usize];
        match self {
            Instr::Input(k) => Instr::Input(k),
            Instr::Add(a, b) => Instr::Add(m(a), m(b)),
            Instr::Mul(a, b) => Instr::Mul(m(a), m(b)),
            Instr::PowF(a, b) => Instr::PowF(m(a), m(b)),
            Instr::Recip(a) => Instr::Recip(m(a)),
            Instr::Sqrt(a) => Instr::Sqrt(m(a)),
            Instr::RecipSqrt(a) => Instr::RecipSqrt(m(a)),
            Instr::PowI(a, k) => Instr::PowI(m(a), k),
            Instr::Sin(a) => Instr::Sin(m(a)),
            Instr::Cos(a) => Instr::Cos(m(a)),
            Instr::Func(f, a) => Instr::Func(f, m(a)),
        }
    }
}

/// A compiled program: inputs in a fixed order; slots are the constants (a prefix) then one
/// per instruction; some outputs.
#[derive(Clone, Debug)]
pub struct Program {
    inputs: Vec<(Sym, u8)>,
    consts: Vec<f64>,
    code: Vec<Instr>,
    origin: Vec<Id>,
    outputs: Vec<u32>,
}

impl Program {
    /// Compiles `roots` with inputs in the order of `inputs` (symbol, derivative order).
    pub fn compile(pool: &Pool, roots: &[Id], inputs: &[(Sym, u8)]) -> Result<Program, Unbound> {
        // Children have smaller ids than parents, so ascending id order is a valid schedule
        // and no recursion is needed.
        let mut reach: Vec<Id> = Vec::new();
        let mut seen = rustc_hash::FxHashSet::default();
        let mut stack: Vec<Id> = roots.to_vec();
        while let Some(n) = stack.pop() {
            if seen.insert(n) {
                reach.push(n);
                pool.push_children(n, &mut stack);
            }
        }
        crate::sort::sort_unstable(&mut reach);
        let mut prog = Program {
            inputs: inputs.to_vec(),
            consts: Vec::new(),
            code: Vec::with_capacity(reach.len() * 2),
            origin: Vec::with_capacity(reach.len() * 2),
            outputs: Vec::new(),
        };
        let mut slot: FxHashMap<Id, u32> = FxHashMap::default();
        for &n in &reach {
            let value = match pool.node(n) {
                Node::Num(v) => v.to_f64().unwrap_or(f64::NAN),
                Node::Pi => std::f64::consts::PI,
                _ => continue,
            };
            slot.insert(n, prog.consts.len() as u32);
            prog.consts.push(value);
        }
        for &n in &reach {
            if !slot.contains_key(&n) {
                let s = prog.node(pool, n, &slot)?;
                slot.insert(n, s);
            }
        }
        prog.outputs = roots.iter().map(|r| slot[r]).collect();
        Ok(prog)
    }

    /// Compiles `roots` with every variable they contain as an input, sorted.
    pub fn compile_all(pool: &Pool, roots: &[Id]) -> Program {
        let mut vars: Vec<(Sym, u8)> = roots.iter().flat_map(|&r| pool.variables(r)).collect();
        crate::sort::sort(&mut vars);
        vars.dedup();
        // Every variable is an input, so compiling cannot fail.
        Program::compile(pool, roots, &vars).unwrap_or_else(|_| Program {
            inputs: Vec::new(),
            consts: Vec::new(),
            code: Vec::new(),
            origin: Vec::new(),
            outputs: Vec::new(),
        })
    }

    fn emit(&mut self, i: Instr, from: Id) -> u32 {
        self.code.push(i);
        self.origin.push(from);
        (self.consts.len() + self.code.len() - 1) as u32
    }

    fn node(&mut self, pool: &Pool, n: Id, slot: &FxHashMap<Id, u32>) -> Result<u32, Unbound> {
        Ok(match pool.node(n) {
            // Numbers were given prefix slots before any instruction.
            Node::Num(_) | Node::Pi => slot[&n],
            Node::Var(s, o) => {
                let k = self
                    .inputs
                    .iter()
                    .position(|v| *v == (*s, *o))
                    .ok_or_else(|| Unbound {
                        name: format!("{}{}", pool.name(*s), "'".repeat(*o as usize)),
                    })?;
                self.emit(Instr::Input(k as u32), n)
            }
            Node::Add(ch) | Node::Mul(ch) => {
                let add = matches!(pool.node(n), Node::Add(_));
                let mut acc = slot[&ch[0]];
                for c in &ch[1..] {
                    let i = if add {
                        Instr::Add(acc, slot[c])
                    } else {
                        Instr::Mul(acc, slot[c])
                    };
                    acc = self.emit(i, n);
                }
                acc
            }
            Node::Pow(b, e) => {
                let bs = slot[b];
                match pool.as_num(*e) {
                    Some(v)
                        if v.is_integer() && v.to_integer().to_i32().is_some_and(|k| k == -1) =>
                    {
                        self.emit(Instr::Recip(bs), n)
                    }
                    Some(v) if v.is_integer() => match v.to_integer().to_i32() {
                        // x·x is exact and cheaper than powi's call.
                        Some(2) => self.emit(Instr::Mul(bs, bs), n),
                        Some(k) => self.emit(Instr::PowI(bs, k), n),
                        None => self.emit(Instr::PowF(bs, slot[e]), n),
                    },
                    Some(v) if *v.denom() == 2.into() && v.numer().to_i32() == Some(1) => {
                        self.emit(Instr::Sqrt(bs), n)
                    }
                    Some(v) if *v.denom() == 2.into() && v.numer().to_i32() == Some(-1) => {
                        self.emit(Instr::RecipSqrt(bs), n)
                    }
                    _ => self.emit(Instr::PowF(bs, slot[e]), n),
                }
            }
            Node::Func(Func::Sin, a) => self.emit(Instr::Sin(slot[a]), n),
            Node::Func(Func::Cos, a) => self.emit(Instr::Cos(slot[a]), n),
            Node::Func(f, a) => self.emit(Instr::Func(*f, slot[a]), n),
        })
    }

    /// The inputs, in the order `run` expects their values.
    pub fn inputs(&self) -> &[(Sym, u8)] {
        &self.inputs
    }

    /// Number of slots (constants and instructions).
    pub fn len(&self) -> usize {
        self.consts.len() + self.code.len()
    }

    /// Whether the program has no slots.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Number of instructions executed per run (constants are not).
    pub fn instructions(&self) -> usize {
        self.code.len()
    }

    /// A scratch buffer of the right size for [`run`](Self::run).
    pub fn scratch(&self) -> Vec<f64> {
        vec![0.0; self.len()]
    }

    /// Runs the program; afterwards [`output`](Self::output) reads the results from
    /// `scratch`. `inputs` must have one value per input, `scratch` one slot per instruction.
    pub fn run(&self, inputs: &[f64], scratch: &mut [f64]) -> Result<(), Undefined> {
        let nc = self.consts.len();
        let scratch = &mut scratch[..self.len()];
        scratch[..nc].copy_from_slice(&self.consts);
        // One flag instead of a branch per instruction; on failure the first slot that is
        // not finite is the instruction that failed (later ones only inherited it).
        let mut finite = true;
        for (i, ins) in self.code.iter().enumerate() {
            let v = ins.apply(|a| scratch[a as usize], inputs);
            finite &= v.is_finite();
            scratch[nc + i] = v;
        }
        if finite {
            return Ok(());
        }
        let i = scratch[nc..]
            .iter()
            .position(|v| !v.is_finite())
            .unwrap_or(0);
        Err(Undefined {
            node: self.origin[i],
        })
    }

    /// The same program with the inputs at `fixed` (input index, value) held at those values:
    /// every instruction depending only on numbers and fixed inputs is evaluated here, once,
    /// and becomes a constant; instructions no output needs are dropped. An instruction whose
    /// folded value is not finite is kept, so [`run`](Self::run) still fails there, naming it.
    /// The values `run` is given for fixed inputs are ignored.
    pub fn specialize(&self, fixed: &[(usize, f64)]) -> Program {
        let nc = self.consts.len();
        let mut known: Vec<Option<f64>> = self.consts.iter().map(|&c| Some(c)).collect();
        known.resize(self.len(), None);
        for (i, ins) in self.code.iter().enumerate() {
            let operands_known = ins
                .operands()
                .iter()
                .flatten()
                .all(|&a| known[a as usize].is_some());
            let v = match *ins {
                Instr::Input(k) => fixed.iter().find(|f| f.0 == k as usize).map(|f| f.1),
                _ if operands_known => {
                    Some(ins.apply(|a| known[a as usize].unwrap_or(f64::NAN), &[]))
                }
                _ => None,
            };
            known[nc + i] = v.filter(|v| v.is_finite());
        }
        // Which slots are needed: outputs, and operands of needed instructions (backwards).
        let mut needed = vec![false; self.len()];
        for &o in &self.outputs {
            needed[o as usize] = true;
        }
        for (i, ins) in self.code.iter().enumerate().rev() {
            if needed[nc + i] && known[nc + i].is_none() {
                for &a in ins.operands().iter().flatten() {
                    needed[a as usize] = true;
                }
            }
        }
        let mut out = Program {
            inputs: self.inputs.clone(),
            consts: Vec::new(),
            code: Vec::new(),
            origin: Vec::new(),
            outputs: Vec::new(),
        };
        let mut map = vec![u32::MAX; self.len()];
        for (s, v) in known.iter().enumerate() {
            if let (true, Some(v)) = (needed[s], v) {
                map[s] = out.consts.len() as u32;
                out.consts.push(*v);
            }
        }
        for (i, ins) in self.code.iter().enumerate() {
            if needed[nc + i] && known[nc + i].is_none() {
                map[nc + i] = out.emit(ins.remap(&map), self.origin[i]);
            }
        }
        out.outputs = self.outputs.iter().map(|&o| map[o as usize]).collect();
        out
    }

    /// Output `k` after a successful [`run`](Self::run).
    pub fn output(&self, k: usize, scratch: &[f64]) -> f64 {
        scratch[self.outputs[k] as usize]
    }

    /// Runs and returns every output (allocates; for convenience, not for hot loops).
    pub fn eval(&self, inputs: &[f64]) -> Result<Vec<f64>, Undefined> {
        let mut s = self.scratch();
        self.run(inputs, &mut s)?;
        Ok((0..self.outputs.len())
            .map(|k| self.output(k, &s))
            .collect())
    }
}

/// A slow, independent tree-walking evaluator, used as the reference the compiled programs
/// are tested against. `value` gives each variable's value. Returns NaN where undefined.
pub fn eval_tree(pool: &Pool, id: Id, value: &dyn Fn(Sym, u8) -> f64) -> f64 {
    match pool.node(id) {
        Node::Num(v) => v.to_f64().unwrap_or(f64::NAN),
        Node::Pi => std::f64::consts::PI,
        Node::Var(s, o) => value(*s, *o),
        Node::Add(ch) => ch.iter().map(|&c| eval_tree(pool, c, value)).sum(),
        Node::Mul(ch) => ch.iter().map(|&c| eval_tree(pool, c, value)).product(),
        Node::Pow(b, e) => eval_tree(pool, *b, value).powf(eval_tree(pool, *e, value)),
        Node::Func(f, a) => f.apply(eval_tree(pool, *a, value)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::{Context, read_expr};
    use lanes::sin_cos_lanes;

    fn at(src: &str, vals: &[(&str, f64)]) -> Result<f64, Undefined> {
        let mut pool = Pool::new();
        let e = read_expr(src, &Context::open(), &mut pool).unwrap();
        let inputs: Vec<(Sym, u8)> = vals.iter().map(|(n, _)| (pool.symbol(n), 0)).collect();
        let p = Program::compile(&pool, &[e], &inputs).unwrap();
        let v: Vec<f64> = vals.iter().map(|(_, v)| *v).collect();
        p.eval(&v).map(|o| o[0])
    }

    #[test]
    fn values() {
        type Row<'a> = (&'a str, &'a [(&'a str, f64)], f64);
        let cases: &[Row] = &[
            ("1/2*m*v^2", &[("m", 2.0), ("v", 3.0)], 9.0),
            ("sqrt(g/l)", &[("g", 9.0), ("l", 4.0)], 1.5),
            ("2^(1/2)", &[], std::f64::consts::SQRT_2),
            ("x^(-1/2)", &[("x", 4.0)], 0.5),
            ("cos(pi)", &[], -1.0),
            ("exp(log(x))", &[("x", 2.5)], 2.5),
            ("x^3 - 2x", &[("x", -2.0)], -4.0),
        ];
        for (src, vals, want) in cases {
            let got = at(src, vals).unwrap();
            assert!((got - want).abs() < 1e-12, "{src}: {got} != {want}");
        }
    }

    #[test]
    fn domain_errors_are_reported() {
        for (src, vals) in [
            ("log(x)", vec![("x", -1.0)]),
            ("sqrt(x)", vec![("x", -4.0)]),
            ("1/x", vec![("x", 0.0)]),
            ("exp(-1/x)", vec![("x", 0.0)]),
            ("exp(x)", vec![("x", 1e6)]),
            ("x^(1/3)", vec![("x", -8.0)]),
        ] {
            assert!(at(src, &vals).is_err(), "{src} should be undefined");
        }
    }

    #[test]
    fn lanes_equal_runs_lane_by_lane() {
        let sources = [
            "1/2*m*v^2 + sin(x)*exp(-x^2)",
            "log(x) + sqrt(v) + x^(1/3)",
            "1/x + v^(-1/2)",
            "exp(-1/x) + atan(1/v) + tanh(1/(x*v)) + (x*v)^0.5 + 1/(1/x)",
            "cos(x)^(-2) + sinh(1/x)*0 + exp(v^3)*x",
        ];
        for src in sources {
            let mut pool = Pool::new();
            let e = read_expr(src, &Context::open(), &mut pool).unwrap();
            let p = Program::compile_all(&pool, &[e]);
            let lanes: Vec<[f64; 8]> = (0..p.inputs().len())
                .map(|k| std::array::from_fn(|l| (l as f64 - 3.0) * (0.7 + k as f64)))
                .collect();
            let mut scratch = p.scratch_lanes::<8>();
            let bad = p.run_lanes(&lanes, &mut scratch);
            let out = p.output_lanes(0, &scratch);
            for l in 0..8 {
                let point: Vec<f64> = lanes.iter().map(|v| v[l]).collect();
                match p.eval(&point) {
                    Ok(v) => {
                        // The same operations in the same order, sin and cos included: equal
                        // to the bit.
                        assert_eq!(bad >> l & 1, 0, "{src} lane {l}");
                        assert_eq!(v[0].to_bits(), out[l].to_bits(), "{src} lane {l}");
                    }
                    Err(_) => assert_eq!(bad >> l & 1, 1, "{src} lane {l}"),
                }
            }
        }
    }

    #[test]
    fn lane_sine_and_cosine_are_libm_to_a_few_ulp() {
        let mut xs: Vec<f64> = (-40_000..=40_000)
            .map(|k| f64::from(k) * 0.25e-3 * 997.0)
            .collect();
        xs.extend((0..64).map(|k| f64::from(k) * std::f64::consts::FRAC_PI_4));
        xs.extend([0.0, -0.0, 1e-300, -1e-10, 3e5, -999_999.0, 2e6, -1e12]);
        for chunk in xs.chunks_exact(8) {
            let x: [f64; 8] = std::array::from_fn(|l| chunk[l]);
            let (mut s, mut c) = ([0.0; 8], [0.0; 8]);
            sin_cos_lanes(&x, 0, &mut s);
            sin_cos_lanes(&x, 1, &mut c);
            for l in 0..8 {
                let tol = 4.0 * f64::EPSILON * x[l].abs().max(1.0).log2().max(1.0);
                assert!((s[l] - x[l].sin()).abs() <= tol, "sin {}: {}", x[l], s[l]);
                assert!((c[l] - x[l].cos()).abs() <= tol, "cos {}: {}", x[l], c[l]);
            }
        }
        let (mut s, mut c) = ([0.0; 4], [0.0; 4]);
        let odd = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 0.5];
        sin_cos_lanes(&odd, 0, &mut s);
        sin_cos_lanes(&odd, 1, &mut c);
        assert!(s[..3].iter().chain(&c[..3]).all(|v| v.is_nan()));
        assert_eq!(s[3].to_bits(), 0.5f64.sin().to_bits());
    }

    #[test]
    fn unbound_variable() {
        let mut pool = Pool::new();
        let e = read_expr("a + b", &Context::open(), &mut pool).unwrap();
        let a = pool.symbol("a");
        let err = Program::compile(&pool, &[e], &[(a, 0)]).unwrap_err();
        assert_eq!(err.name, "b");
    }

    #[test]
    fn specializing_folds_fixed_inputs_and_keeps_values() {
        let mut pool = Pool::new();
        let src = "(m1 + m2)*l^2*cos(x - y) + g*sin(x)/l + sqrt(m1*g) - 2*pi";
        let e = read_expr(src, &Context::open(), &mut pool).unwrap();
        let names = ["x", "y", "m1", "m2", "l", "g"];
        let inputs: Vec<(Sym, u8)> = names.iter().map(|n| (pool.symbol(n), 0)).collect();
        let p = Program::compile(&pool, &[e], &inputs).unwrap();
        let params = [1.5, 0.5, 2.0, 9.81];
        let fixed: Vec<(usize, f64)> = params
            .iter()
            .enumerate()
            .map(|(j, &v)| (2 + j, v))
            .collect();
        let q = p.specialize(&fixed);
        assert!(
            q.instructions() < p.instructions(),
            "{} !< {}",
            q.instructions(),
            p.instructions()
        );
        for (x, y) in [(0.3, -1.2), (2.0, 2.0), (-3.0, 0.1)] {
            let full = p.eval(&[x, y, 1.5, 0.5, 2.0, 9.81]).unwrap()[0];
            // The values given for fixed inputs are ignored.
            let folded = q.eval(&[x, y, 0.0, 0.0, 0.0, 0.0]).unwrap()[0];
            assert!(
                (full - folded).abs() <= 1e-12 * full.abs().max(1.0),
                "{full} vs {folded}"
            );
        }
    }

    #[test]
    fn specializing_keeps_undefined_parts_failing() {
        let mut pool = Pool::new();
        let e = read_expr("x + 1/(a - 1)", &Context::open(), &mut pool).unwrap();
        let inputs = [(pool.symbol("x"), 0), (pool.symbol("a"), 0)];
        let p = Program::compile(&pool, &[e], &inputs)
            .unwrap()
            .specialize(&[(1, 1.0)]);
        assert!(p.eval(&[2.0, 7.0]).is_err());
        let q = Program::compile(&pool, &[e], &inputs)
            .unwrap()
            .specialize(&[(1, 3.0)]);
        assert_eq!(q.eval(&[2.0, 0.0]).unwrap(), vec![2.5]);
    }
}
