//! Where each quantity sits in a state vector, defined once.
//!
//! A *sample point* (the input of every compiled program of a system) is
//! `[t, q₀, q₀', q₀'', q₁, q₁', q₁'', …, p₀, p₁, …]`: time, then each coordinate with its
//! velocity and acceleration, then the parameters. A *phase point* `y = (q, q')` (what an
//! ODE integrator advances) is `[q₀, …, q₍ₙ₋₁₎, q₀', …, q₍ₙ₋₁₎']`. [`Layout`] gives the index of
//! each; nothing else indexes these vectors by hand.

/// Slots per coordinate in a sample point: q, q', q''.
const SLOTS: usize = 3;

/// The layout of the states of a system with `n` coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layout {
    n: usize,
}

impl Layout {
    /// The layout for `n` coordinates.
    pub const fn new(n: usize) -> Self {
        Layout { n }
    }

    /// Number of coordinates.
    pub const fn coordinates(self) -> usize {
        self.n
    }

    /// Index of time t in a sample point.
    pub const fn time(self) -> usize {
        0
    }

    /// Index of coordinate `i` (its derivative of `order` 0, 1 or 2) in a sample point.
    pub const fn var(self, i: usize, order: usize) -> usize {
        1 + SLOTS * i + order
    }

    /// Index of qᵢ in a sample point.
    pub const fn q(self, i: usize) -> usize {
        self.var(i, 0)
    }

    /// Index of qᵢ' in a sample point.
    pub const fn qdot(self, i: usize) -> usize {
        self.var(i, 1)
    }

    /// Index of qᵢ'' in a sample point.
    pub const fn qddot(self, i: usize) -> usize {
        self.var(i, 2)
    }

    /// Index of the first parameter in a sample point (= the number of state slots).
    pub const fn params_start(self) -> usize {
        1 + SLOTS * self.n
    }

    /// Index of parameter `j` in a sample point.
    pub const fn param(self, j: usize) -> usize {
        self.params_start() + j
    }

    /// Length of a sample point with `n_params` parameters.
    pub const fn len(self, n_params: usize) -> usize {
        self.params_start() + n_params
    }

    /// The sample point at rest at `q` (t = 0, every velocity and acceleration 0) with
    /// parameter values `params`.
    pub fn at_rest(self, q: &[f64], params: &[f64]) -> Vec<f64> {
        let mut x = vec![0.0; self.params_start()];
        for (i, &v) in q.iter().enumerate().take(self.n) {
            x[self.q(i)] = v;
        }
        x.extend_from_slice(params);
        x
    }

    /// Index of qᵢ in a phase point `y = (q, q')`.
    pub const fn phase_q(self, i: usize) -> usize {
        i
    }

    /// Index of qᵢ' in a phase point `y = (q, q')`.
    pub const fn phase_qdot(self, i: usize) -> usize {
        self.n + i
    }

    /// Length of a phase point.
    pub const fn phase_len(self) -> usize {
        2 * self.n
    }

    /// Writes the phase point `y` and time `t` into the sample point `x` (accelerations
    /// and parameters untouched): the step from an integrator's state to a program input.
    pub fn load_phase(self, t: f64, y: &[f64], x: &mut [f64]) {
        x[self.time()] = t;
        for i in 0..self.n {
            x[self.q(i)] = y[self.phase_q(i)];
            x[self.qdot(i)] = y[self.phase_qdot(i)];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_follow_the_documented_order() {
        let l = Layout::new(2);
        assert_eq!(
            [l.time(), l.q(0), l.qdot(0), l.qddot(0), l.q(1), l.qddot(1)],
            [0, 1, 2, 3, 4, 6]
        );
        assert_eq!((l.params_start(), l.param(1), l.len(3)), (7, 8, 10));
        assert_eq!(
            l.at_rest(&[0.5, 1.5], &[9.0]),
            [0.0, 0.5, 0.0, 0.0, 1.5, 0.0, 0.0, 9.0]
        );
        let mut x = vec![0.0; l.len(0)];
        l.load_phase(1.0, &[1.0, 2.0, 3.0, 4.0], &mut x);
        assert_eq!(x, [1.0, 1.0, 3.0, 0.0, 2.0, 4.0, 0.0]);
    }
}
