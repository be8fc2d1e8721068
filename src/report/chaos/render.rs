//! The text of a [`ChaosReport`]: the estimate, its convergence, the settings, the separation,
//! the section, and what the estimate suggests without claiming more than a finite run shows.

use std::fmt::Write as _;

use super::{ChaosReport, Verdict};
use crate::report::Paint;

/// Writes the summary.
pub(super) fn summary(r: &ChaosReport, paint: &dyn Paint, o: &mut String) -> std::fmt::Result {
    let (rate, time) = match r.time_unit.as_deref() {
        Some("s") => ("s⁻¹".to_string(), " s".to_string()),
        Some(u) => (format!("per {u}"), format!(" {u}")),
        None => ("per unit of t".to_string(), String::new()),
    };
    writeln!(
        o,
        "{} λ ≈ {:.4} {rate} (finite-time estimate at t = {}{time}, Benettin)",
        paint.heading("Largest Lyapunov exponent:"),
        r.exponent,
        r.t_end
    )?;
    let points: Vec<String> = r
        .checkpoints
        .iter()
        // Checkpoints are multiples of τ: rounding noise (3.5999999999999996) is not shown.
        .map(|(t, l)| format!("t = {}: {l:.4}", (t * 1e9).round() / 1e9))
        .collect();
    writeln!(
        o,
        "{} {}",
        paint.heading("Running estimate:"),
        points.join(", ")
    )?;
    let (lo, hi) = r.last_third;
    writeln!(
        o,
        "{} {lo:.4} … {hi:.4} (spread {:.4}); λ(t_end)/λ(t_end/3) = {:.3}",
        paint.heading("Over the last third:"),
        hi - lo,
        r.ratio_to_a_third
    )?;
    let n = r.names.len();
    writeln!(
        o,
        "{} delta = {:e} along (1, …, 1)/√{n} in the Euclidean norm of ({}), renormalised every τ = {}; dop853 rtol = {:e}, atol = {:e}; {} steps, {} right-hand-side evaluations",
        paint.heading("Settings:"),
        r.delta,
        r.names.join(", "),
        r.tau,
        r.rtol,
        r.atol,
        r.steps,
        r.rhs_evals
    )?;
    separation(r, paint, o)?;
    if let Some(s) = &r.section {
        let points: usize = s.orbits.iter().map(|o| o.points.len()).sum();
        writeln!(
            o,
            "{} {} = 0 with {}' > 0 at h = {:.10}: {} orbits, {points} points ({} starting values of {} refused: no velocity reaches that energy there)",
            paint.heading("Poincaré section:"),
            s.q1,
            s.q1,
            s.energy,
            s.orbits.len(),
            s.refused.len(),
            s.q2
        )?;
    }
    writeln!(o, "{} {}", paint.heading("Meaning:"), meaning(r, paint))
}

fn separation(r: &ChaosReport, paint: &dyn Paint, o: &mut String) -> std::fmt::Result {
    let Some(&(t_last, _)) = r.separation.last() else {
        return Ok(());
    };
    let (t_max, d_max) = r
        .separation
        .iter()
        .copied()
        .fold((0.0, 0.0), |a, p| if p.1 > a.1 { p } else { a });
    writeln!(
        o,
        "{} from {:e} at t = 0 to at most {d_max:.3e} (at t = {t_max:.3}) over t = 0 … {t_last} (never renormalised)",
        paint.heading("Separation:"),
        r.delta
    )
}

fn meaning(r: &ChaosReport, paint: &dyn Paint) -> String {
    match r.verdict {
        Verdict::Chaotic => paint.bad(
            "positive and steady over the last third: nearby motions separate exponentially, as in chaotic motion (a finite-time estimate: it suggests chaos, it does not prove it)",
        ),
        Verdict::Regular => paint.good(
            "falling towards 0 (like ln(t)/t when separations grow only as a power of t): consistent with regular motion (a finite run cannot exclude a small positive exponent)",
        ),
        Verdict::Unsettled => paint.warn(
            "not settled: the estimate neither holds steady nor falls like ln(t)/t over this run; lengthen --t-end before reading anything into it",
        ),
        Verdict::OneDegree => paint.warn(
            "nearby motions separate exponentially, but a system of one degree of freedom with a conserved h cannot be chaotic: the motion is at or near an unstable equilibrium or a separatrix, and λ is its instability rate",
        ),
        Verdict::AtEquilibrium => paint.warn(
            "the motion stays at rest on an unstable equilibrium: λ is that equilibrium's instability rate, not a sign of chaos",
        ),
        Verdict::Unstable => paint.warn(
            "nearby motions leave this one for good (their separation grows far beyond the motion's own size): it is an unstable motion, and λ its instability rate; chaos would keep them within the motion's range",
        ),
        Verdict::Runaway => paint.warn(
            "the motion keeps growing (it runs away): exponential separation of an unbounded motion is not chaos",
        ),
    }
}
