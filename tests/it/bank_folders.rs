//! The instructor's folders beside the built-in bank: `--add-problems DIR` (merged, a built-in
//! id replaced with a note, two files of one id refused naming both), `--problems DIR` (only
//! the folder), and `problems export DIR` (the built-in files, verified as written, never
//! over an instructor's file without `--force`).

use std::path::Path;

use crate::helpers::{lagrange, scratch};

/// The built-in Atwood file with its title (and, with `id`, its id) changed.
fn atwood_as(title: &str, id: Option<&str>) -> String {
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("problems/atwood.toml"))
            .unwrap();
    let text = text.replacen(
        "title = \"Atwood machine\"",
        &format!("title = \"{title}\""),
        1,
    );
    match id {
        Some(id) => text.replacen("id = \"atwood\"", &format!("id = \"{id}\""), 1),
        None => text,
    }
}

#[test]
fn an_added_folder_is_merged_and_a_built_in_id_is_replaced_with_a_note() {
    let dir = scratch("add-problems");
    std::fs::write(dir.join("atwood.toml"), atwood_as("My Atwood", None)).unwrap();
    std::fs::write(dir.join("mine.toml"), atwood_as("Mine", Some("my-atwood"))).unwrap();
    let d = dir.display().to_string();
    let (code, out, err) = lagrange(&["--add-problems", &d, "problems", "list"]);
    assert_eq!(code, 0, "{err}");
    // Every built-in problem is still there, the replaced one once, and the new one added.
    for id in [
        "simple-pendulum",
        "double-pendulum",
        "rotating-hoop",
        "my-atwood",
    ] {
        assert!(out.contains(id), "{id} missing:\n{out}");
    }
    let atwood: Vec<&str> = out.lines().filter(|l| l.starts_with("atwood ")).collect();
    assert_eq!(atwood.len(), 1, "{out}");
    assert!(atwood[0].ends_with("My Atwood"), "{out}");
    let note = format!("note: {d}/atwood.toml replaces the built-in problem `atwood`");
    assert!(err.contains(&note), "{err}");

    // A command about one problem reads the folder's version, with the note.
    let (code, out, err) = lagrange(&["--add-problems", &d, "problems", "show", "atwood"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.starts_with("My Atwood"), "{out}");
    assert!(err.contains(&note), "{err}");
    // A built-in problem the folder does not have is the built-in one, without a note.
    let (code, _, err) = lagrange(&[
        "--add-problems",
        &d,
        "check",
        "simple-pendulum",
        "frequencies",
        "sqrt(g/l)",
    ]);
    assert_eq!((code, err.as_str()), (0, ""));
    // The folder's own problem is checked against its physics: (m1 + m2) x'' = (m1 − m2) g.
    let (code, out, err) = lagrange(&[
        "--add-problems",
        &d,
        "check",
        "my-atwood",
        "eom",
        "(m1+m2)*x'' = (m1-m2)*g",
    ]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("correct"), "{out}");

    // `--problems` keeps its meaning: only the folder.
    let (code, out, _) = lagrange(&["--problems", &d, "problems", "list"]);
    assert_eq!(code, 0);
    assert!(!out.contains("simple-pendulum"), "{out}");
    assert!(out.contains("my-atwood"), "{out}");
    // The two flags together are refused by the argument parser.
    let (code, _, err) = lagrange(&["--problems", &d, "--add-problems", &d, "problems", "list"]);
    assert_eq!(code, 2, "{err}");
}

#[test]
fn two_added_files_of_one_id_are_refused_naming_both() {
    let dir = scratch("add-problems-twin");
    let mine = atwood_as("Mine", Some("my-atwood"));
    std::fs::write(dir.join("a.toml"), &mine).unwrap();
    std::fs::write(dir.join("b.toml"), &mine).unwrap();
    let d = dir.display().to_string();
    for args in [
        vec!["--add-problems", &d, "problems", "list"],
        vec!["--add-problems", &d, "problems", "show", "my-atwood"],
        vec!["--add-problems", &d, "check", "my-atwood", "eom", "x''=0"],
    ] {
        let (code, _, err) = lagrange(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(
            err.contains("a.toml") && err.contains("b.toml") && err.contains("my-atwood"),
            "{args:?}: {err}"
        );
    }
    // A folder whose twin files reuse a built-in id refuses the bank too: neither the built-in
    // problem nor either file is judged by.
    let twin = scratch("add-problems-builtin-twin");
    let atwood = atwood_as("A", None);
    std::fs::write(twin.join("a.toml"), &atwood).unwrap();
    std::fs::write(twin.join("b.toml"), &atwood).unwrap();
    let t = twin.display().to_string();
    let (code, _, err) = lagrange(&["--add-problems", &t, "problems", "list"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("a.toml") && err.contains("b.toml"), "{err}");
}

#[test]
fn exported_problems_verify_as_written_and_an_edited_file_is_kept() {
    let dir = scratch("export");
    let out_dir = dir.join("mine");
    let d = out_dir.display().to_string();
    let (code, out, err) = lagrange(&["problems", "export", &d]);
    assert_eq!(code, 0, "{err}");
    let n = lagrange::bank::embedded::FILES.len();
    assert!(out.starts_with(&format!("{n} problems exported")), "{out}");
    let (code, out, err) = lagrange(&["problems", "verify", &d]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains(&format!("{n} problems, 0 failing")), "{out}");
    // Used as an added folder, every problem replaces its built-in twin (one note each).
    let (code, _, err) = lagrange(&["--add-problems", &d, "problems", "list"]);
    assert_eq!(code, 0);
    assert_eq!(
        err.matches("replaces the built-in problem").count(),
        n,
        "{err}"
    );

    // A second export leaves identical files alone.
    let (code, out, _) = lagrange(&["problems", "export", &d]);
    assert_eq!(code, 0);
    assert!(out.contains("(0 written"), "{out}");
    // An edited file is the instructor's: nothing is exported without --force.
    let atwood = out_dir.join("atwood.toml");
    let mut text = std::fs::read_to_string(&atwood).unwrap();
    text.push_str("# my note\n");
    std::fs::write(&atwood, &text).unwrap();
    std::fs::remove_file(out_dir.join("simple-pendulum.toml")).unwrap();
    let (code, _, err) = lagrange(&["problems", "export", &d]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("atwood.toml") && err.contains("--force"),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&atwood).unwrap(), text);
    assert!(
        !out_dir.join("simple-pendulum.toml").exists(),
        "all or nothing"
    );
    let (code, out, err) = lagrange(&["problems", "export", &d, "--force"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("(2 written"), "{out}");
    assert!(
        !std::fs::read_to_string(&atwood)
            .unwrap()
            .contains("# my note")
    );
}

#[cfg(unix)]
#[test]
fn export_never_writes_through_a_link() {
    let dir = scratch("export-link");
    let target = dir.join("precious.txt");
    std::fs::write(&target, "keep").unwrap();
    let out_dir = dir.join("out");
    std::fs::create_dir(&out_dir).unwrap();
    std::os::unix::fs::symlink(&target, out_dir.join("atwood.toml")).unwrap();
    let d = out_dir.display().to_string();
    let (code, _, err) = lagrange(&["problems", "export", &d, "--force"]);
    assert_ne!(code, 0);
    assert!(err.contains("symbolic link"), "{err}");
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep");
}
