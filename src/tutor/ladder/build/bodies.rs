//! The ladder's steps for one body: a point's (or a rigid body's centre of mass's) position
//! and speed squared, and a turning body's angular speed squared.

use super::Builder;
use crate::expr::Id;
use crate::mechanics::{Body, Orientation};
use crate::problem::PartKind;

impl Builder<'_> {
    /// The position and speed-squared steps of body `n` (1-based). A rotor has no position;
    /// its step is its angular speed squared. A rigid body's steps are those of its centre
    /// of mass, and a planar one's angular speed squared.
    pub(super) fn body(&mut self, n: usize, body: &Body) {
        match body {
            Body::Point { position, .. } => self.point_steps(n, position, ""),
            Body::Rigid(r) => {
                self.point_steps(n, &r.position, "the centre of mass of ");
                if let Orientation::Planar(angle) = r.orientation {
                    self.angular_step(
                        n,
                        angle,
                        "angular-speed-squared",
                        "is a rigid body turning in the plane",
                    );
                }
            }
            Body::Rotor { angle, .. } => {
                self.angular_step(n, *angle, "speed-squared", "turns about a fixed axis")
            }
        }
    }

    /// The Cartesian position and speed-squared steps of a point (`of`: "" for a point
    /// body, "the centre of mass of " for a rigid one).
    fn point_steps(&mut self, n: usize, position: &[Id], of: &str) {
        let coords = self.sys.coordinate_syms();
        let positive = self.sys.parameter_syms();
        let axes = ["x", "y", "z"];
        let names = axes[..position.len().min(3)].join(", ");
        let answers = position.iter().map(|&x| self.plain(x)).collect();
        // The axes, origin, sense and phase the reference uses: without them a right
        // position in other axes could not be told from a wrong one.
        let axes = match self.problem.axes.as_str() {
            "" => " Use the axes of the problem's statement.".to_string(),
            a => format!(" Axes: {}", sentence(a)),
        };
        let prompt = format!(
            "Write the Cartesian position of {of}body {n} (its {names} components, in that order) in terms of {}, separated by commas.{axes}",
            self.coordinate_list()
        );
        self.push(format!("position:{n}"), prompt, PartKind::Values, answers);
        let mut squares = Vec::new();
        for &x in position {
            let vx = self.sys.pool.dt(x, &coords);
            squares.push(self.sys.pool.powi(vx, 2));
        }
        let v2 = self.sys.pool.sum(squares);
        let v2 = self.sys.pool.simplify(v2, &positive);
        let answer = self.plain(v2);
        let prompt = format!(
            "Differentiate the position in time: write the square of {of}body {n}'s speed (the sum of the squares of its velocity components)."
        );
        self.push(
            format!("speed-squared:{n}"),
            prompt,
            PartKind::Expression,
            vec![answer],
        );
    }

    /// The step "write the square of body n's angular velocity" (`id`: the step's id prefix,
    /// `how`: how the body turns).
    fn angular_step(&mut self, n: usize, angle: Id, id: &str, how: &str) {
        let coords = self.sys.coordinate_syms();
        let positive = self.sys.parameter_syms();
        let w = self.sys.pool.dt(angle, &coords);
        let w2 = self.sys.pool.powi(w, 2);
        let w2 = self.sys.pool.simplify(w2, &positive);
        let answer = self.plain(w2);
        let prompt = format!("Body {n} {how}: write the square of its angular velocity.");
        self.push(
            format!("{id}:{n}"),
            prompt,
            PartKind::Expression,
            vec![answer],
        );
    }
}

/// `text` as a sentence: a full stop at its end unless it has one.
fn sentence(text: &str) -> String {
    let t = text.trim();
    if t.ends_with('.') {
        t.to_string()
    } else {
        format!("{t}.")
    }
}
