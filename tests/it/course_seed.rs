//! The course seed is never silently 0: a problem whose numbers vary needs `--seed` (or the
//! assignment's `seed`) to show, check, export or grade a student's numbers, and the sheet
//! tells the student the whole command. Found by an instructor whose correct answers were
//! graded wrong because the seed had been forgotten. Also the drafting rough edges they met.

use crate::helpers::{lagrange, scratch};

/// A pendulum whose mass and length vary, with one part that accepts numbers.
const VARIED: &str = r#"
id = "varied-pendulum"
title = "Pendulum with your numbers"
statement = "A bob of mass {{m}} on a rod of length {{l}} swings under gravity {{g}}."
coordinates = [{ name = "theta", periodic = true }]

[parameters]
m = { dimension = "M", range = [0.5, 2.0] }
l = { dimension = "L", range = [0.5, 2.0] }
g = { dimension = "L T^-2", range = [5.0, 15.0] }

[variants]
m = { values = [0.5, 1.5, 2.5], unit = "kg" }
l = { values = [0.4, 0.7, 1.3], unit = "m" }
g = { values = [9.81], unit = "m/s²" }

[[bodies]]
kind = "point"
mass = "m"
position = ["l*sin(theta)", "-l*cos(theta)"]

[[potentials]]
kind = "gravity"
g = "g"
axis = "y"

[[parts]]
id = "frequencies"
kind = "frequencies"
prompt = "The angular frequency of small oscillations about θ = 0, in rad/s."
answer = ["sqrt(g/l)"]
at = { theta = "0" }
numbers = true

[[parts]]
id = "potential"
kind = "expression"
prompt = "The potential energy V, zero at the pivot, with your numbers."
answer = "-m*g*l*cos(theta)"
numbers = true
"#;

fn bank(label: &str) -> (crate::helpers::Scratch, String) {
    let dir = scratch(label);
    let bank = dir.join("bank");
    std::fs::create_dir_all(&bank).expect("bank folder");
    std::fs::write(bank.join("varied-pendulum.toml"), VARIED).expect("problem");
    let path = bank.to_string_lossy().to_string();
    (dir, path)
}

#[test]
fn a_students_numbers_need_the_course_seed() {
    let (_dir, bank) = bank("seed-check");
    let key = "ben@uni.example";
    for args in [
        vec![
            "check",
            "varied-pendulum",
            "frequencies",
            "4.95",
            "--student",
            key,
        ],
        vec!["problems", "show", "varied-pendulum", "--student", key],
    ] {
        let mut all = vec!["--add-problems", &bank];
        all.extend(args);
        let (code, _, err) = lagrange(&all);
        assert_eq!(code, 2, "{all:?}: {err}");
        assert!(
            err.contains("`varied-pendulum`") && err.contains("--seed"),
            "{err}"
        );
    }
    // Without a student, nothing depends on the seed.
    let (code, _, err) = lagrange(&[
        "--add-problems",
        &bank,
        "problems",
        "show",
        "varied-pendulum",
    ]);
    assert_eq!(code, 0, "{err}");
}

#[test]
fn the_sheet_names_the_seed_that_finds_the_students_numbers() {
    let (_dir, bank) = bank("seed-sheet");
    let key = "ben@uni.example";
    // Seed 0 is a seed like any other: the sheet says it too.
    for seed in ["0", "2026"] {
        let (code, out, err) = lagrange(&[
            "--add-problems",
            &bank,
            "problems",
            "show",
            "varied-pendulum",
            "--student",
            key,
            "--seed",
            seed,
        ]);
        assert_eq!(code, 0, "{err}");
        let footer = format!("--student {key} --seed {seed}`");
        assert!(out.contains(&footer), "{out}");
        // The command the sheet gives, with this student's own ω = √(g/l), is accepted.
        let line = out
            .lines()
            .find(|l| l.contains("numbers:"))
            .expect("numbers line");
        let l: f64 = line
            .split("l = ")
            .nth(1)
            .and_then(|s| s.split(' ').next())
            .and_then(|s| s.parse().ok())
            .expect("l on the sheet");
        let omega = format!("{:.12}", (9.81 / l).sqrt());
        let (code, out, err) = lagrange(&[
            "--add-problems",
            &bank,
            "check",
            "varied-pendulum",
            "frequencies",
            &omega,
            "--student",
            key,
            "--seed",
            seed,
        ]);
        assert_eq!(code, 0, "ω = {omega} for l = {l}: {out}{err}");
    }
}

#[test]
fn grading_a_varied_problem_without_a_seed_is_refused_not_judged_with_seed_0() {
    let (dir, bank) = bank("seed-grade");
    let class = dir.join("class.csv");
    std::fs::write(
        &class,
        "student,problem,part,answer\nada@uni.example,varied-pendulum,frequencies,4.95\n",
    )
    .expect("class");
    let out = dir.join("out");
    let (class, out) = (class.to_string_lossy(), out.to_string_lossy());
    let (code, _, err) = lagrange(&["--add-problems", &bank, "grade", &class, "--out", &out]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("`varied-pendulum`") && err.contains("--seed"),
        "{err}"
    );
    assert!(
        !dir.join("out").join("results.csv").exists(),
        "nothing is written"
    );
    let (code, _, err) = lagrange(&[
        "--add-problems",
        &bank,
        "grade",
        &class,
        "--out",
        &out,
        "--seed",
        "7",
    ]);
    assert!(code == 0 || code == 1, "{err}");
    assert!(dir.join("out").join("results.csv").exists());
    // A class that answers only problems without variants needs no seed.
    let plain = dir.join("plain.csv");
    std::fs::write(
        &plain,
        "student,problem,part,answer\nada@uni.example,simple-pendulum,frequencies,sqrt(g/l)\n",
    )
    .expect("class");
    let (code, _, err) = lagrange(&["grade", &plain.to_string_lossy(), "--out", &out]);
    assert_eq!(code, 0, "{err}");
}

#[test]
fn a_coordinate_no_expression_uses_is_named_not_an_internal_error() {
    let (code, _, err) = lagrange(&[
        "problems",
        "new",
        "--id",
        "typo",
        "--coords",
        "r,th",
        "--point",
        "mass=m; position=r*sin(theta), -r*cos(theta)",
        "--gravity",
        "g",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("`th`") && err.contains("`theta`"), "{err}");
    assert!(!err.contains("lagrange's mistake"), "{err}");
}

#[test]
fn a_drafted_potential_hint_names_only_the_forces_present() {
    let draft = |extra: &[&str]| {
        let mut args = vec![
            "problems",
            "new",
            "--id",
            "p",
            "--coords",
            "theta",
            "--point",
            "mass=m; position=l*sin(theta), -l*cos(theta)",
            "--gravity",
            "g",
        ];
        args.extend(extra);
        let (code, out, err) = lagrange(&args);
        assert_eq!(code, 0, "{err}");
        out
    };
    let pendulum = draft(&[]);
    assert!(pendulum.contains("gravity contributes") || pendulum.contains("Gravity contributes"));
    assert!(!pendulum.contains("spring"), "{pendulum}");
    let sprung = draft(&["--spring", "k=k; from=1; to=l, 0"]);
    assert!(sprung.contains("a spring contributes"), "{sprung}");
}

/// A student's numbers as their sheet lists them (`g = 9.81 m/s², l = 0.4 m, m = 0.5 kg`)
/// and their l.
fn sheet_numbers(bank: &str, key: &str, seed: &str) -> (String, f64) {
    let (code, out, err) = lagrange(&[
        "--add-problems",
        bank,
        "problems",
        "show",
        "varied-pendulum",
        "--student",
        key,
        "--seed",
        seed,
    ]);
    assert_eq!(code, 0, "{err}");
    let line = out
        .lines()
        .find(|l| l.contains("numbers:"))
        .expect("numbers line");
    let numbers = line
        .split_once("numbers:")
        .expect("label")
        .1
        .trim()
        .to_string();
    let l = (numbers.split("l = ").nth(1))
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.parse().ok())
        .expect("l");
    (numbers, l)
}

/// Writes `rows` (after the long format's header) as `dir/class.csv` and grades it with the
/// problems of `bank`, course seed 7 and `extra` options, into `dir/out` (returned); the run
/// must grade (exit 0 or 1).
fn grade_at_seed_7(
    dir: &std::path::Path,
    bank: &str,
    rows: &str,
    extra: &[&str],
) -> std::path::PathBuf {
    let class = dir.join("class.csv");
    std::fs::write(&class, format!("student,problem,part,answer\n{rows}")).expect("class");
    let out = dir.join("out");
    let (class, out_text) = (class.to_string_lossy(), out.to_string_lossy());
    let mut args = vec![
        "--add-problems",
        bank,
        "grade",
        &class,
        "--out",
        &out_text,
        "--seed",
        "7",
    ];
    args.extend_from_slice(extra);
    let (code, _, err) = lagrange(&args);
    assert!(code == 0 || code == 1, "{err}");
    out
}

#[test]
fn an_override_on_one_students_numbers_leaves_another_variants_rows_alone() {
    let (dir, bank) = bank("seed-override");
    let (ada, (ada_numbers, ada_l)) = (
        "ada@uni.example",
        sheet_numbers(&bank, "ada@uni.example", "7"),
    );
    // Another student with another length: the same number is right for one, wrong for the other.
    let (ben, (ben_numbers, _)) = [
        "ben@uni.example",
        "cleo@uni.example",
        "dan@uni.example",
        "eve@uni.example",
    ]
    .into_iter()
    .map(|k| (k, sheet_numbers(&bank, k, "7")))
    .find(|(_, (_, l))| *l != ada_l)
    .expect("two lengths among four students");
    assert_ne!(ada_numbers, ben_numbers);
    let text = format!("{:.12}", (9.81 / ada_l).sqrt());
    let decisions = dir.join("decisions.csv");
    std::fs::write(
        &decisions,
        format!("problem,part,variant,answer,decision\nvaried-pendulum,frequencies,\"{ben_numbers}\",{text},0.5\n"),
    )
    .expect("decisions");
    let rows = format!(
        "{ada},varied-pendulum,frequencies,{text}\n{ben},varied-pendulum,frequencies,{text}\n"
    );
    let decisions = decisions.to_string_lossy();
    let out = grade_at_seed_7(
        &dir,
        &bank,
        &rows,
        &["--overrides", &decisions, "--feedback"],
    );
    let results = std::fs::read_to_string(out.join("results.csv")).expect("results");
    let row = |key: &str| {
        results
            .lines()
            .find(|l| l.contains(key))
            .unwrap_or_else(|| panic!("{key} in {results}"))
            .to_string()
    };
    // Ada's answer is her own ω = √(g/l): correct, untouched by a decision about Ben's numbers.
    assert!(
        row(ada).contains(",correct,") && !row(ada).contains("instructor"),
        "{}",
        row(ada)
    );
    // Ben's is decided for his numbers.
    assert!(row(ben).contains("instructor's decision"), "{}", row(ben));
    // review.csv names each listed answer's variant.
    let review = std::fs::read_to_string(out.join("review.csv")).expect("review");
    assert!(
        review.starts_with("problem,part,variant,answer,"),
        "{review}"
    );
    assert!(review.contains(&ben_numbers), "{review}");
    // Each student's feedback names the numbers their answer was judged with.
    let feedback =
        std::fs::read_to_string(out.join("feedback").join(format!("{ada}.md"))).expect("feedback");
    assert!(
        feedback.contains(&format!("Your numbers: {ada_numbers}")),
        "{feedback}"
    );
}

#[test]
fn the_summary_never_groups_one_number_told_differently_to_different_students() {
    let (dir, bank) = bank("seed-summary");
    let (_, ada_l) = sheet_numbers(&bank, "ada@uni.example", "7");
    let ben = [
        "ben@uni.example",
        "cleo@uni.example",
        "dan@uni.example",
        "eve@uni.example",
    ]
    .into_iter()
    .find(|k| sheet_numbers(&bank, k, "7").1 != ada_l)
    .expect("two lengths among four students");
    // m g l = 9.81 J is nobody's (m l is never 1 here): wrong for both, by different factors.
    let wrong = "-1*9.81*1*cos(theta)";
    let rows = format!(
        "ada@uni.example,varied-pendulum,potential,{wrong}\n{ben},varied-pendulum,potential,{wrong}\n"
    );
    let out = grade_at_seed_7(&dir, &bank, &rows, &[]);
    let mut results = csv::Reader::from_path(out.join("results.csv")).expect("results");
    let messages: Vec<String> = (results.records())
        .map(|r| r.expect("a record")[8].to_string())
        .collect();
    assert_eq!(messages.len(), 2);
    assert_ne!(messages[0], messages[1]);
    let summary = std::fs::read_to_string(out.join("summary.md")).expect("summary");
    let groups = summary.lines().filter(|l| l.contains(wrong)).count();
    assert_eq!(groups, 2, "one group per thing told: {summary}");
}

/// A learner practising alone gets the empty key's numbers: `pick_own` (which the page and
/// the REPL call, without the Unicode case tables) is `pick` with `""` or blanks, for every
/// varied problem of the bank and many seeds; a real key gives other numbers.
#[test]
fn practising_alone_is_the_empty_key() {
    use lagrange::problem::variant::{pick, pick_own};
    let bank = lagrange::bank::embedded::bank();
    let varied: Vec<_> = (bank.problems.iter())
        .filter(|p| !p.variants.is_empty())
        .collect();
    assert!(!varied.is_empty(), "the bank has a problem with variants");
    for p in varied {
        let mut differs = false;
        for seed in 0..64 {
            let own = pick_own(p, seed);
            assert!(own.is_some(), "{}", p.id);
            assert_eq!(own, pick(p, seed, ""), "{} seed {seed}", p.id);
            assert_eq!(own, pick(p, seed, "  "), "{} seed {seed}", p.id);
            differs |= own != pick(p, seed, "Ada@uni.example");
        }
        assert!(differs, "{}: a key changes the numbers", p.id);
    }
}
