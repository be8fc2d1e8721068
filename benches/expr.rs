//! Benchmarks of the expression core (issue: the math language):
//! - parse a 60-character answer;
//! - evaluate a compiled expression (reported per call; divide by the node count printed
//!   at start-up for ns per node);
//! - differentiate and simplify the double-pendulum Lagrangian with respect to each
//!   velocity, and by d/dt;
//! - hostile inputs (deep nesting, long sums), to show every parse stays in milliseconds.

use divan::{Bencher, black_box};
use lagrange::expr::{Context, Id, Pool, Program, Sym, read_expr};

const ANSWER_60: &str = "m*l^2*theta'' + m*g*l*sin(theta) - 1/2 m l theta'^2 cos(theta)";

const DOUBLE_PENDULUM_L: &str = "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 + m2*l1*l2*theta1'*theta2'*cos(theta1-theta2) + (m1+m2)*g*l1*cos(theta1) + m2*g*l2*cos(theta2)";

fn ctx() -> Context {
    Context::new()
        .with_coordinates(["theta", "theta1", "theta2"])
        .with_parameters(["m", "m1", "m2", "l", "l1", "l2", "g"])
}

fn main() {
    let mut pool = Pool::new();
    let e = read_expr(DOUBLE_PENDULUM_L, &ctx(), &mut pool).expect("reads");
    let p = Program::compile_all(&pool, &[e]);
    println!(
        "answer: {} chars; double-pendulum L compiles to {} instructions",
        ANSWER_60.len(),
        p.len()
    );
    divan::main();
}

#[divan::bench]
fn parse_60_char_answer(b: Bencher) {
    let ctx = ctx();
    b.bench_local(|| {
        let mut pool = Pool::new();
        black_box(read_expr(black_box(ANSWER_60), &ctx, &mut pool).is_ok())
    });
}

#[divan::bench]
fn evaluate_compiled_double_pendulum_l(b: Bencher) {
    let mut pool = Pool::new();
    let e = read_expr(DOUBLE_PENDULUM_L, &ctx(), &mut pool).expect("reads");
    let p = Program::compile_all(&pool, &[e]);
    let inputs: Vec<f64> = (0..p.inputs().len())
        .map(|i| 0.3 + 0.1 * i as f64)
        .collect();
    let mut scratch = p.scratch();
    b.bench_local(|| {
        p.run(black_box(&inputs), &mut scratch).expect("defined");
        black_box(p.output(0, &scratch))
    });
}

fn velocities(pool: &mut Pool) -> (Sym, Sym) {
    (pool.symbol("theta1"), pool.symbol("theta2"))
}

#[divan::bench]
fn diff_simplify_double_pendulum_each_velocity(b: Bencher) {
    b.bench_local(|| {
        let mut pool = Pool::new();
        let e = read_expr(DOUBLE_PENDULUM_L, &ctx(), &mut pool).expect("reads");
        let (t1, t2) = velocities(&mut pool);
        let positive: Vec<Sym> = ["m1", "m2", "l1", "l2", "g"]
            .iter()
            .map(|n| pool.symbol(n))
            .collect();
        let mut out: Vec<Id> = Vec::new();
        for s in [t1, t2] {
            let d = pool.diff(e, s, 1);
            out.push(pool.simplify(d, &positive));
        }
        black_box(out)
    });
}

#[divan::bench]
fn dt_simplify_double_pendulum(b: Bencher) {
    b.bench_local(|| {
        let mut pool = Pool::new();
        let e = read_expr(DOUBLE_PENDULUM_L, &ctx(), &mut pool).expect("reads");
        let (t1, t2) = velocities(&mut pool);
        let positive: Vec<Sym> = ["m1", "m2", "l1", "l2", "g"]
            .iter()
            .map(|n| pool.symbol(n))
            .collect();
        let d = pool.dt(e, &[t1, t2]);
        black_box(pool.simplify(d, &positive))
    });
}

#[divan::bench(args = ["deep", "long-sum", "token-soup"])]
fn parse_hostile(b: Bencher, which: &str) {
    let text = match which {
        "deep" => "(".repeat(5000) + "x" + &")".repeat(5000),
        "long-sum" => "x+".repeat(9000) + "x",
        _ => "sin(√2·θ̇²)^-½ ".repeat(600),
    };
    b.bench_local(|| {
        let mut pool = Pool::new();
        black_box(read_expr(black_box(&text), &Context::open(), &mut pool).is_ok())
    });
}
