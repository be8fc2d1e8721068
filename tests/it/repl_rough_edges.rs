//! Issue 21 §3: the REPL's rough edges — Greek names in every flag, a did-you-mean shown
//! once, Unicode mathematics in statements, hints and derivations, parts revealed by the
//! analyses, and prompts that ask only what the part checks.

use crate::helpers::{lagrange, one, session};
use lagrange::tutor::Response;

#[test]
fn greek_names_work_in_flags() {
    let (code, out, err) = lagrange(&[
        "derive",
        "--lagrangian",
        "1/2 m l^2 θ'^2 + m g l cos θ",
        "--coords",
        "θ",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("Coordinate θ"), "{out}");
    let mut s = session();
    s.handle(":open double-pendulum");
    let r = one(&mut s, ":simulate --init \"θ₁=0.1, θ̇₂=0.2\" --t-end 1");
    assert!(matches!(r, Response::Analysis(_)), "{r:?}");
    let r = one(&mut s, ":derive 1/2 m x'^2 + 1/2 m φ'^2 --coords x, φ");
    assert!(matches!(r, Response::Analysis(_)), "{r:?}");
}

#[test]
fn a_suggestion_is_given_once_and_is_a_name() {
    let mut s = session();
    for line in [":open double-pendlum", ":hnt"] {
        let Response::Error(e) = one(&mut s, line) else {
            panic!("{line}: not an error");
        };
        assert!(!e.message.contains("did you mean"), "{}", e.message);
        assert!(e.suggestion.is_some(), "{line}");
    }
    s.handle(":open double-pendulum");
    for line in [":simulate --tend 3", ":simulate --init \"z=1\""] {
        let Response::Error(e) = one(&mut s, line) else {
            panic!("{line}: not an error");
        };
        assert_eq!(e.suggestion, None, "{line}: {e:?}");
    }
}

#[test]
fn inline_mathematics_is_unicode() {
    use lagrange::report::terminal_math;
    assert_eq!(terminal_math(r"$\omega_0 = \sqrt{k/m}$"), "ω₀ = √(k/m)");
    assert_eq!(
        terminal_math(r"$\sqrt{g}$, $\frac{1}{2} m v^2$"),
        "√g, 1/2 m v²"
    );
    assert_eq!(terminal_math(r"$\theta_{12}$"), "θ₁₂");
    let mut s = session();
    let Response::Statement(st) = &s.handle(":open rotating-trap")[0] else {
        panic!("no statement");
    };
    assert!(
        st.sheet.statement.contains("ω₀ = √(k/m)"),
        "{}",
        st.sheet.statement
    );
    assert!(!st.sheet.statement.contains('\\'), "{}", st.sheet.statement);
}

#[test]
fn the_worked_derivation_is_unicode() {
    let mut s = session();
    s.handle(":open simple-pendulum");
    s.handle(":part eom");
    let Response::Solution(sol) = one(&mut s, ":solution") else {
        panic!("no solution");
    };
    assert!(!sol.derivation.is_empty());
    for w in &sol.derivation {
        assert!(!w.unicode.is_empty(), "{w:?}");
        assert!(
            !w.unicode.contains('*') && !w.unicode.contains("theta"),
            "{w:?}"
        );
    }
}

#[test]
fn derive_and_modes_mark_the_parts_they_reveal() {
    let mut s = session();
    s.handle(":open simple-pendulum");
    let Response::Analysis(a) = one(&mut s, ":derive") else {
        panic!("no analysis");
    };
    let note = a.note.unwrap_or_default();
    assert!(note.contains("eom") && note.contains("revealed"), "{note}");
    let Response::Parts(p) = one(&mut s, ":parts") else {
        panic!("no parts");
    };
    let revealed = |id: &str| p.parts.iter().any(|e| e.id == id && e.revealed);
    assert!(revealed("eom") && !revealed("kinetic"), "{p:?}");
    let Response::Analysis(a) = one(&mut s, ":modes") else {
        panic!("no analysis");
    };
    assert!(a.note.unwrap_or_default().contains("revealed"));
}

#[test]
fn no_prompt_asks_a_yes_no_question() {
    for p in &lagrange::embedded::bank().problems {
        for q in &p.parts {
            let first = q.prompt.split_whitespace().next().unwrap_or("");
            let asks = q.prompt.contains("? ") || q.prompt.trim_end().ends_with('?');
            let yes_no = ["Is", "Are", "Does", "Do", "Can"]
                .iter()
                .any(|w| q.prompt.contains(&format!(". {w} ")) || first == *w);
            assert!(!(asks && yes_no), "{}/{}: {}", p.id, q.id, q.prompt);
        }
    }
}
