//! The `[definitions]` table of a problem file: named quantities of the parameters
//! (`theta0 = "acos(g/(R*omega^2))"`, the side equilibrium of the rotating hoop) that a
//! statement names and an answer may use. Each is read in the problem's symbols when the
//! file is loaded; a name that is not one word, clashes with a symbol, or a value that does
//! not read, uses a coordinate or time, or adds unlike dimensions is a `bad-definition`
//! finding at its line.

use crate::expr::lexer::{Tok, lex};
use crate::expr::{Dimensions, read_expr};
use crate::mechanics::System;

use super::FindingCode;
use super::build_part::reserved;
use super::build_reader::Builder;
use super::finding::{Finding, line_of};
use super::schema::ProblemFile;

impl Builder<'_> {
    /// Reads the file's definitions into `system.definitions`, in the table's order.
    pub(super) fn definitions(
        &self,
        pf: &ProblemFile,
        system: &mut System,
        dims: &Dimensions,
    ) -> Result<(), Finding> {
        // The symbols alone: a definition may not use another one.
        let ctx = system.context();
        for (raw, value) in &pf.definitions {
            let line = line_of(self.text, value.span().start);
            let bad = |why: String| self.fail(line, FindingCode::BadDefinition, why);
            let name = crate::expr::names::normalize(raw.trim());
            let one_word = matches!(
                lex(raw.trim()).ok().as_deref(),
                Some([t]) if matches!(&t.tok, Tok::Name { dots: 0, .. })
            );
            if !one_word {
                return Err(bad(format!(
                    "definition `{raw}`: a defined name is one name, like `theta0`"
                )));
            }
            if let Some(why) = reserved(&name) {
                return Err(bad(format!("definition `{name}`: {why}")));
            }
            if ctx.is_coordinate(&name) || system.parameters.iter().any(|p| p.name == name) {
                return Err(bad(format!(
                    "definition `{name}` has the name of a coordinate or parameter"
                )));
            }
            let text = value.get_ref();
            let id = read_expr(text, &ctx, &mut system.pool)
                .map_err(|e| bad(format!("definition `{name}` = `{text}`: {e}")))?;
            let time = system.pool.time();
            if let Some((s, _)) = system
                .pool
                .variables(id)
                .into_iter()
                .find(|(s, _)| *s == time || system.coordinates.iter().any(|c| c.sym == *s))
            {
                return Err(bad(format!(
                    "definition `{name}` uses `{}`: a definition is a constant of the parameters",
                    system.pool.name(s)
                )));
            }
            if let Err(e) = system.pool.dimension(id, dims) {
                return Err(bad(format!("definition `{name}` = `{text}`: {e}")));
            }
            system.definitions.push((name, id));
        }
        Ok(())
    }
}
