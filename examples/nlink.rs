//! Profiling aid: derives the n-link pendulum's equations repeatedly
//! (`cargo run --release --example nlink -- 8 20`: n and the number of repetitions).

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
        let mut sys = lagrange::mechanics::fixtures::n_link_pendulum(n);
        std::hint::black_box(sys.derive().expect("derives"));
    }
    println!(
        "n = {n}: {:.3} ms per derivation",
        t0.elapsed().as_secs_f64() * 1e3 / reps as f64
    );
}
