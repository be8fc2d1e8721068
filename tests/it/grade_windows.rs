//! `lagrange grade` checks the distinct answers a window at a time (issue 20 §5: memory that
//! does not grow with every verdict's scratch work). Every output must be byte-identical
//! whatever the window's size: a class where equal answers, equivalent spellings and one
//! student's parts fall in different windows, graded with follow-through and an LMS file at
//! window sizes 1, 7 and the default, with 1 and 2 threads.

use std::path::Path;
use std::process::Command;

/// A folder's files, by name, with their bytes.
type Files = Vec<(String, Vec<u8>)>;

/// Every file of a folder, by name, with its bytes.
fn outputs(dir: &Path) -> Files {
    let mut files: Files = std::fs::read_dir(dir)
        .expect("out dir")
        .map(|e| {
            let e = e.expect("entry");
            let name = e.file_name().to_string_lossy().into_owned();
            (name, std::fs::read(e.path()).expect("read"))
        })
        .collect();
    files.sort();
    files
}

/// The example class, then 24 students each giving a different multiple of the pendulum's
/// potential and EOM (all distinct), a right answer in two spellings and a repeat of an
/// earlier student's wrong answer (equal texts far apart).
fn class() -> String {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/class.csv");
    let mut csv = std::fs::read_to_string(example).expect("examples/class.csv");
    for i in 0..24 {
        let k = 1.0 + f64::from(i) / 8.0;
        let s = format!("w{i:02}@uni.example");
        let rows = [
            ("potential", format!("-{k}*m*g*l*cos(theta)")),
            (
                "lagrangian",
                format!("1/2*m*l^2*theta'^2 + {k}*m*g*l*cos(theta)"),
            ),
            ("eom", format!("m*l^2*theta'' + {k}*m*g*l*sin(theta) = 0")),
            ("potential", "-m g l cos(θ)".to_string()),
            (
                "frequencies",
                ["sqrt(g/l)", "√(g/l)", "g/l"][i as usize % 3].to_string(),
            ),
            ("eom", "m*l^2*theta'' - m*g*l*sin(theta) = 0".to_string()),
        ];
        for (part, answer) in rows {
            csv.push_str(&format!("{s},simple-pendulum,{part},\"{answer}\"\n"));
        }
    }
    csv
}

#[test]
fn outputs_do_not_depend_on_the_window_size() {
    let dir = crate::helpers::scratch("grade-windows");
    let input = dir.join("class.csv");
    std::fs::write(&input, class()).expect("write the class");
    let mut seen: Vec<(String, Files)> = Vec::new();
    for (window, threads) in [("", "2"), ("1", "2"), ("7", "1"), ("7", "2")] {
        let out = dir.join(format!("out-{window}-{threads}"));
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_lagrange"));
        cmd.arg("grade")
            .arg(&input)
            .arg("--out")
            .arg(&out)
            .args(["--follow-through", "--lms", "canvas"])
            .env("NO_COLOR", "1")
            .env("RAYON_NUM_THREADS", threads);
        if !window.is_empty() {
            cmd.env("LAGRANGE_GRADE_WINDOW", window);
        }
        let run = cmd.output().expect("the binary runs");
        assert_eq!(run.status.code(), Some(0), "{run:?}");
        seen.push((
            format!("window {window:?}, {threads} thread(s)"),
            outputs(&out),
        ));
    }
    let (first, want) = &seen[0];
    // results, gradebook, canvas, review, summary.md, summary.json.
    assert_eq!(want.len(), 6, "{first}");
    // 61 rows of the example and 6 per added student.
    let results = &want
        .iter()
        .find(|(n, _)| n == "results.csv")
        .expect("results")
        .1;
    assert_eq!(
        results.iter().filter(|&&b| b == b'\n').count(),
        1 + 61 + 24 * 6
    );
    for (label, got) in &seen[1..] {
        for ((name, a), (_, b)) in want.iter().zip(got) {
            assert!(a == b, "{name} differs: {first} vs {label}");
        }
    }
}
