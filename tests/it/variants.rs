//! Per-student variants: which numbers a student gets (pinned: the same on every machine and
//! release), answers judged against the student's own numbers (in symbols or with numbers),
//! verification of every variant and the refusals of declarations that would let a wrong
//! answer pass, and the instructor's commands (sheets, check, export, grade).

use lagrange::bank::load_str;
use lagrange::bank::verify::verify;
use lagrange::bank::verify_variants::coverage;
use lagrange::check::{Status, check};
use lagrange::problem::Problem;
use lagrange::problem::variant::pick;

use crate::helpers::{lagrange, scratch};

/// The variants example as first written (a fixture: the tests edit its text by line; the
/// bank's `pendulum-numbers` is its rewording): m ∈ {0.5, 1.5, 2, 2.5, 3} kg, l on the grid
/// 0.45 … 1.65 m by 0.3, g = 9.81 m/s².
fn example_text() -> String {
    std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/variants/pendulum-numbers.toml"),
    )
    .expect("the example problem")
}

fn example() -> Problem {
    load_str("pendulum-numbers.toml", &example_text()).expect("the example loads")
}

/// The example with `from` replaced by `to` (which must occur), loaded.
#[allow(clippy::result_large_err)] // a test helper: the finding is read once
fn edited(from: &str, to: &str) -> Result<Problem, lagrange::bank::Finding> {
    let text = example_text();
    assert!(text.contains(from), "the example has no `{from}`");
    load_str("edited.toml", &text.replacen(from, to, 1))
}

fn verdict(p: &Problem, part: &str, answer: &str) -> Status {
    check(p, p.part(part).expect("the part"), answer)
        .expect("checkable")
        .status
}

#[test]
fn three_students_get_these_numbers_forever() {
    let p = example();
    let values = |key: &str| pick(&p, 2026, key).expect("variants").values;
    let v = |g: f64, l: f64, m: f64| vec![("g".into(), g), ("l".into(), l), ("m".into(), m)];
    assert_eq!(values("ada@uni.example"), v(9.81, 1.65, 1.5));
    assert_eq!(values("ben@uni.example"), v(9.81, 0.45, 0.5));
    assert_eq!(values("cleo@uni.example"), v(9.81, 1.35, 3.0));
    // The key is normalised (trimmed, lower-cased); another seed gives other numbers.
    assert_eq!(values("  ADA@Uni.Example "), values("ada@uni.example"));
    assert_eq!(
        pick(&p, 0, "ada@uni.example").expect("variants").values,
        v(9.81, 1.35, 0.5)
    );
}

#[test]
fn every_variant_of_the_example_is_proved() {
    let p = example();
    assert_eq!(verify(&p), Vec::new());
    assert_eq!(
        coverage(&p).as_deref(),
        Some("answers proved for every one of the 25 variants")
    );
}

#[test]
fn a_student_answers_with_symbols_or_their_own_numbers() {
    let p = example();
    // ada: m = 1.5 kg, l = 1.65 m, g = 9.81 m/s²; ben: m = 0.5 kg, l = 0.45 m.
    let ada = p.pinned(&pick(&p, 2026, "ada@uni.example").expect("variants"));
    let ben = p.pinned(&pick(&p, 2026, "ben@uni.example").expect("variants"));
    // V = −m g l cos θ = −24.27975 cos θ for ada.
    assert_eq!(
        verdict(&ada, "potential", "-m*g*l*cos(theta)"),
        Status::Correct
    );
    assert_eq!(
        verdict(&ada, "potential", "-1.5*9.81*1.65*cos(theta)"),
        Status::Correct
    );
    assert_eq!(
        verdict(&ada, "potential", "-24.27975*cos(theta)"),
        Status::Correct
    );
    assert_eq!(
        verdict(&ben, "potential", "-1.5*9.81*1.65*cos(theta)"),
        Status::Incorrect
    );
    // The equation of motion scaled by any factor: l θ̈ + g sin θ = 0.
    assert_eq!(
        verdict(&ada, "eom", "1.65*theta'' + 9.81*sin(theta) = 0"),
        Status::Correct
    );
    assert_eq!(
        verdict(&ada, "eom", "theta'' + 9.81*sin(theta) = 0"),
        Status::Incorrect
    );
    // ω = √(g/l) = √(9.81/0.45) = 4.669 rad/s for ben; ω² is not ω.
    assert_eq!(
        verdict(&ben, "frequencies", "sqrt(9.81/0.45)"),
        Status::Correct
    );
    assert_eq!(verdict(&ben, "frequencies", "9.81/0.45"), Status::Incorrect);
    // A part without `numbers` is judged in symbols, against the problem itself: numbers
    // there are not an answer of the kind asked for (`numbers-for-symbols`).
    assert_eq!(
        verdict(&p, "kinetic", "1/2*0.5*0.45^2*theta'^2"),
        Status::Invalid
    );
    // Without the student's numbers, a number is no answer.
    assert_eq!(
        verdict(&p, "potential", "-1.5*9.81*1.65*cos(theta)"),
        Status::Incorrect
    );
}

#[test]
fn pinned_parameters_stay_at_the_students_value_at_wide_points() {
    // Regression: the checker also samples parameters far outside their range (×10, ÷10); a
    // pinned parameter must keep its one value there, or a numeric answer right at the
    // student's numbers would be refused at those points.
    let p = example();
    let ada = p.pinned(&pick(&p, 2026, "ada@uni.example").expect("variants"));
    let v = check(
        &ada,
        ada.part("eom").expect("eom"),
        "1.65*theta'' + 9.81*sin(theta) = 0",
    )
    .expect("checkable");
    assert_eq!(v.status, Status::Correct, "{v:?}");
}

fn codes(p: Result<Problem, lagrange::bank::Finding>) -> Vec<(&'static str, usize)> {
    match p {
        Err(f) => vec![(f.code.as_str(), f.line)],
        Ok(p) => verify(&p)
            .iter()
            .map(|f| (f.code.as_str(), f.line))
            .collect(),
    }
}

#[test]
fn a_varied_parameter_that_can_be_one_is_refused() {
    // m = 1 would let an answer missing the factor m pass.
    let found = codes(edited("values = [0.5, 1.5,", "values = [1, 1.5,"));
    assert_eq!(found, vec![("variant-trivial-value", 22)]);
}

#[test]
fn two_varied_parameters_that_can_be_equal_are_refused() {
    // l can be 1.05 m and m 1.05 kg: l written for m would pass for that student.
    let found = codes(edited("values = [0.5, 1.5,", "values = [0.5, 1.05,"));
    // Reported at the later declaration, in the order of the names (g, l, m).
    assert_eq!(found, vec![("variant-equal-values", 22)]);
}

#[test]
fn numbers_without_variants_are_refused() {
    let text = example_text();
    let start = text.find("\n[variants]").expect("variants");
    let end = text.find("[[bodies]]").expect("bodies");
    let without = format!("{}{}", &text[..start], &text[end..])
        .replace("{{", "")
        .replace("}}", "");
    let p = load_str("no-variants.toml", &without).expect("loads");
    let found: Vec<&str> = verify(&p).iter().map(|f| f.code.as_str()).collect();
    assert_eq!(
        found,
        vec![
            "numbers-without-variants",
            "numbers-without-variants",
            "numbers-without-variants"
        ]
    );
}

#[test]
fn a_variant_that_violates_an_assumption_is_refused_naming_it() {
    // l = 0.45 m breaks `l > 0.5`: for that student the problem means nothing.
    let p = edited("\n[parameters]", "assume = [\"l > 0.5\"]\n\n[parameters]").expect("loads");
    let found = verify(&p);
    assert_eq!(found.len(), 1, "{found:#?}");
    assert_eq!(found[0].code, "variant-fails");
    assert!(
        found[0].message.contains("l = 0.45 m"),
        "{}",
        found[0].message
    );
}

#[test]
fn a_variant_that_changes_the_physics_is_refused() {
    // A pendulum held up by a torsion spring κ: θ = 0 (upright) is stable only while
    // κ > m g l (and is then the only equilibrium). Over the sampled ranges κ ≥ 70 > m g l
    // always; with κ = 20 N m and m g l up to 3·9.81·1.65 = 48.6 J, not for some students.
    // The base problem is proved, but a variant fails.
    let text = example_text()
        .replace("-l*cos(theta)", "l*cos(theta)")
        .replace("periodic = true", "periodic = false, range = [-3, 3], dimension = \"1\"")
        .replace(
            "[[potentials]]\nkind = \"gravity\"",
            "[[potentials]]\nkind = \"explicit\"\nV = \"1/2*kappa*theta^2\"\n\n[[potentials]]\nkind = \"gravity\"",
        )
        .replace(
            "g = { dimension = \"L T^-2\", range = [5.0, 15.0], description = \"gravitational acceleration\" }",
            "g = { dimension = \"L T^-2\", range = [5.0, 15.0] }\nkappa = { dimension = \"M L^2 T^-2\", range = [70.0, 80.0] }",
        )
        .replace("g = { values = [9.81], unit = \"m/s²\" }", "g = { values = [9.81], unit = \"m/s²\" }\nkappa = { values = [20], unit = \"N m\" }");
    let text = format!(
        "{}\n[[parts]]\nid = \"equilibria\"\nkind = \"equilibria\"\nprompt = \"Is the upright position stable?\"\nanswer = [\"theta = 0\"]\nstability = [\"stable\"]\nrequire_stability = true\n",
        text.split("[[parts]]").next().expect("head")
    );
    let p = load_str("torsion.toml", &text).expect("loads");
    let found = verify(&p);
    assert_eq!(found.len(), 1, "{found:#?}");
    assert_eq!(found[0].code, "variant-fails", "{found:#?}");
}

#[test]
fn bad_declarations_are_findings_at_their_line() {
    let cases = [
        ("m = { values", "mu = { values", "is not a parameter"),
        (
            "step = 0.3,",
            "step = 0.3, values = [1.2],",
            "either `values",
        ),
        ("step = 0.3,", "", "exactly one of `step`"),
        (
            "values = [0.5, 1.5,",
            "values = [-0.5, 1.5,",
            "outside its domain",
        ),
        ("values = [0.5, 1.5,", "values = [0.5, 0.5,", "listed twice"),
        ("step = 0.3,", "step = 0.0,", "not a grid"),
    ];
    for (from, to, says) in cases {
        let f = edited(from, to).expect_err(to);
        assert_eq!(f.code, "bad-variant", "{to}: {f}");
        assert!(f.message.contains(says), "{to}: {}", f.message);
        assert!((21..=24).contains(&f.line), "{to}: line {}", f.line);
    }
    let f = edited("mass {{m}}", "mass {{M}}").expect_err("placeholder");
    assert_eq!((f.code.as_str(), f.line), ("bad-variant", 9));
}

#[test]
fn an_instructor_shows_sheets_checks_exports_and_grades() {
    let dir = scratch("variants");
    let bank = dir.join("bank");
    std::fs::create_dir_all(&bank).expect("bank folder");
    std::fs::write(bank.join("pendulum-numbers.toml"), example_text()).expect("copy");
    let bank = bank.to_string_lossy().to_string();
    let (code, out, _) = lagrange(&[
        "--problems",
        &bank,
        "problems",
        "show",
        "pendulum-numbers",
        "--student",
        "ben@uni.example",
        "--seed",
        "2026",
    ]);
    assert_eq!(code, 0);
    assert!(out.contains("a light, rigid rod of length 0.45 m"), "{out}");
    assert!(
        out.contains("numbers:     g = 9.81 m/s², l = 0.45 m, m = 0.5 kg"),
        "{out}"
    );
    let (code, out, _) = lagrange(&[
        "--problems",
        &bank,
        "check",
        "pendulum-numbers",
        "frequencies",
        "sqrt(9.81/0.45)",
        "--student",
        "ben@uni.example",
        "--seed",
        "2026",
    ]);
    assert_eq!(code, 0, "{out}");
    // export-sheets: a regression for its arguments, which once clashed with `--problems`.
    let list = dir.join("students.txt");
    std::fs::write(
        &list,
        "ada@uni.example\nben@uni.example\ncleo@uni.example\n",
    )
    .expect("list");
    let sheets = dir.join("sheets");
    let (code, out, err) = lagrange(&[
        "--problems",
        &bank,
        "problems",
        "export-sheets",
        "pendulum-numbers",
        "--students",
        &list.to_string_lossy(),
        "--seed",
        "2026",
        "--out",
        &sheets.to_string_lossy(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.starts_with("3 students: 7 files written"), "{out}");
    let md = std::fs::read_to_string(sheets.join("cleo@uni.example.md")).expect("markdown");
    assert!(
        md.contains("**Your numbers:** g = 9.81 m/s², l = 1.35 m, m = 3 kg."),
        "{md}"
    );
    let tex = std::fs::read_to_string(sheets.join("ada@uni.example.tex")).expect("latex");
    assert!(
        tex.contains("\\textbf{Your numbers:} g = 9.81 m/s², l = 1.65 m, m = 1.5 kg."),
        "{tex}"
    );
    // One text, two students: right for ada's numbers, wrong for ben's.
    let class = dir.join("class.csv");
    std::fs::write(
        &class,
        "student,problem,part,answer\n\
         ada@uni.example,pendulum-numbers,potential,-1.5*9.81*1.65*cos(theta)\n\
         ben@uni.example,pendulum-numbers,potential,-1.5*9.81*1.65*cos(theta)\n\
         cleo@uni.example,pendulum-numbers,potential,-m*g*l*cos(theta)\n",
    )
    .expect("class");
    let grades = dir.join("grades");
    let (code, _, err) = lagrange(&[
        "--problems",
        &bank,
        "grade",
        &class.to_string_lossy(),
        "--seed",
        "2026",
        "--out",
        &grades.to_string_lossy(),
    ]);
    assert_eq!(code, 0, "{err}");
    let results = std::fs::read_to_string(grades.join("results.csv")).expect("results");
    let status: Vec<&str> = results
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(5).unwrap_or(""))
        .collect();
    assert_eq!(status, ["correct", "incorrect", "correct"], "{results}");
    let book = std::fs::read_to_string(grades.join("gradebook.csv")).expect("gradebook");
    assert_eq!(
        book.lines().next(),
        Some("student,pendulum-numbers/potential,total,max,percent")
    );
}

#[test]
fn the_repl_practises_fresh_numbers_and_keeps_their_seed() {
    use lagrange::tutor::{Progress, Response, Session};
    let mut bank = lagrange::bank::Bank::default();
    bank.add(example(), "pendulum-numbers.toml".into());
    let mut s = Session::new(bank, Progress::new());
    s.handle(":open pendulum-numbers");
    let r = s.handle(":variant");
    let Some(Response::Statement(st)) = r.first() else {
        panic!("a statement: {r:?}");
    };
    // The numbers of the first seed after the problem id's: fixed, like every variant.
    let numbers = st.sheet.numbers.join(", ");
    let seed = s.progress().problems["pendulum-numbers"]
        .variant_seed
        .expect("the seed is kept");
    let p = example();
    let v = pick(&p, seed, "").expect("variants");
    assert_eq!(
        numbers,
        lagrange::report::sheets::numbers_of(&p, &v).join(", ")
    );
    let (l, m, g) = (
        v.get("l").unwrap(),
        v.get("m").unwrap(),
        v.get("g").unwrap(),
    );
    s.handle(":part potential");
    let r = s.handle(&format!("-{m}*{g}*{l}*cos(theta)"));
    assert!(
        matches!(&r[0], Response::Verdict(v) if v.verdict.status == Status::Correct),
        "{r:?}"
    );
    // A second `:variant` gives other numbers (the next seed of the sequence).
    s.handle(":variant");
    let next = s.progress().problems["pendulum-numbers"].variant_seed;
    assert_ne!(next, Some(seed));
    // A problem whose numbers do not vary says so.
    let mut plain = Session::new(lagrange::embedded::bank(), Progress::new());
    plain.handle(":open simple-pendulum");
    let r = plain.handle(":variant");
    assert!(
        matches!(&r[0], Response::Error(e) if e.code == "no-variants"),
        "{r:?}"
    );
}

/// The first three `:variant` numbers of `pendulum-numbers` for a progress with `learner`.
fn practised(learner: Option<u64>) -> Vec<String> {
    use lagrange::tutor::{Progress, Response, Session};
    let mut progress = Progress::new();
    progress.learner_seed = learner;
    let mut s = Session::new(lagrange::embedded::bank(), progress);
    s.handle(":open pendulum-numbers");
    (0..3)
        .map(|_| match s.handle(":variant").first() {
            Some(Response::Statement(st)) => st.sheet.numbers.join(", "),
            other => panic!("a statement: {other:?}"),
        })
        .collect()
}

/// Regression: `:variant` gave every learner the same sequence of numbers (it started from the
/// problem id alone). It now starts from the learner seed kept in the progress file: the same
/// file gives the same numbers, and the sequence goes on after a reload.
#[test]
fn each_learner_practises_their_own_numbers() {
    use lagrange::tutor::{Progress, Session};
    let ada = practised(Some(0x5eed_0001));
    assert_eq!(ada, practised(Some(0x5eed_0001)), "deterministic");
    assert_ne!(ada, practised(Some(0x5eed_0002)), "another learner");
    assert_ne!(ada, practised(None));
    // The seed and the sequence's state are saved; a reloaded progress continues it.
    let mut progress = Progress::new();
    progress.learner_seed = Some(0x5eed_0001);
    let mut s = Session::new(lagrange::embedded::bank(), progress);
    s.handle(":open pendulum-numbers");
    s.handle(":variant");
    s.handle(":variant");
    let saved = Progress::from_json(&s.progress().to_json()).expect("reads back");
    assert_eq!(saved.learner_seed, Some(0x5eed_0001));
    let mut again = Session::new(lagrange::embedded::bank(), saved);
    again.handle(":open pendulum-numbers");
    let third = match again.handle(":variant").first() {
        Some(lagrange::tutor::Response::Statement(st)) => st.sheet.numbers.join(", "),
        other => panic!("a statement: {other:?}"),
    };
    assert_eq!(third, ada[2]);
}

/// The bank's problem with variants works from a fresh clone, with no files: a student's sheet
/// with their numbers, and their answer checked with them.
#[test]
fn the_bank_problem_gives_a_students_sheet_and_checks_with_their_numbers() {
    let (code, out, err) = lagrange(&[
        "problems",
        "show",
        "pendulum-numbers",
        "--student",
        "ben@uni.example",
        "--seed",
        "2026",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("numbers:     g = 9.81 m/s², l = 0.45 m, m = 0.5 kg"),
        "{out}"
    );
    assert!(out.contains("A bob of mass 0.5 kg"), "{out}");
    // Regression: the sheet's check line left out the seed, so following it judged the
    // answer with another student's numbers.
    assert!(
        out.contains("--student ben@uni.example --seed 2026`"),
        "{out}"
    );
    // ω = √(g/l) = √(9.81/0.45) ≈ 4.669 rad/s for this student; √(9.81/1.65) is another's.
    let check = |answer: &str| {
        lagrange(&[
            "check",
            "pendulum-numbers",
            "frequencies",
            answer,
            "--student",
            "ben@uni.example",
            "--seed",
            "2026",
        ])
    };
    let (_, out, _) = check("sqrt(9.81/0.45)");
    assert!(
        out.contains("correct") && !out.contains("incorrect"),
        "{out}"
    );
    let (_, out, _) = check("sqrt(9.81/1.65)");
    assert!(out.contains("incorrect"), "{out}");
}
