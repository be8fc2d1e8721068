//! Profiling aid: derives the n-link pendulum's equations repeatedly (`cargo run --release
//! --example nlink -- 8`).

use lagrange::expr::{Context, Pool, read_expr};
use lagrange::mechanics::System;
use lagrange::mechanics::bodies::{Body, Potential};
use lagrange::mechanics::system::Coordinate;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(8);
    let reps: usize = std::env::args()
        .nth(2)
        .and_then(|a| a.parse().ok())
        .unwrap_or(20);
    let t0 = std::time::Instant::now();
    for _ in 0..reps {
        let mut pool = Pool::new();
        let names: Vec<String> = (1..=n).map(|i| format!("q{i}")).collect();
        let coordinates: Vec<Coordinate> = names
            .iter()
            .map(|q| Coordinate {
                name: q.clone(),
                sym: pool.symbol(q),
                periodic: true,
                range: (-3.2, 3.2),
            })
            .collect();
        let ctx = Context::open().with_coordinates(&names);
        let mut bodies = Vec::new();
        let (mut xs, mut ys) = (String::new(), String::new());
        for q in &names {
            xs.push_str(&format!(" + l*sin({q})"));
            ys.push_str(&format!(" - l*cos({q})"));
            let x = read_expr(&xs, &ctx, &mut pool).expect("x");
            let y = read_expr(&ys, &ctx, &mut pool).expect("y");
            let m = pool.sym("m");
            bodies.push(Body::Point {
                mass: m,
                position: vec![x, y],
            });
        }
        let g = pool.sym("g");
        let mut sys = System::from_bodies(
            pool,
            coordinates,
            &bodies,
            &[Potential::Gravity { g, axis: 1 }],
        );
        let d = sys.derive().expect("derives");
        std::hint::black_box(d);
    }
    println!(
        "n = {n}: {:.3} ms per derivation",
        t0.elapsed().as_secs_f64() * 1e3 / reps as f64
    );
}
