//! The layering test: reads the `crate::…` and `super::…` paths of every file under `src/` and
//! fails when a lower layer of the library imports a higher one ([`crate::LAYERS`]), when a
//! face of the binary imports another face (they share only the face-support module), or when
//! the files of one folder import each other in a loop. The loop check runs in every folder,
//! library and faces alike, between the folder's entries (a sub-folder counts as one).
//! Test-only: the library itself reads no files.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A library file as the layering rules see it: its top-level module and, for a file inside a
/// module folder, its own name (`check/answer.rs` → `("check", Some("answer"))`).
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Unit {
    module: String,
    file: Option<String>,
}

impl std::fmt::Display for Unit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.file {
            Some(file) => write!(f, "{}/{}.rs", self.module, file),
            None => write!(f, "{}.rs", self.module),
        }
    }
}

/// The code of a file without comments and without its `#[cfg(test)]` tail (a test module's
/// `use super::*` names its own file, not a sibling).
fn code_of(text: &str) -> String {
    let text = match text.find("#[cfg(test)]") {
        Some(i) => &text[..i],
        None => text,
    };
    text.lines()
        .map(|l| match l.find("//") {
            Some(i) => &l[..i],
            None => l,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Expands one `use` tree (`a::{b, c::{d, e}}`) into its paths.
fn expand_use(tree: &str) -> Vec<String> {
    let tree: String = tree.chars().filter(|c| !c.is_whitespace()).collect();
    let Some(open) = tree.find('{') else {
        return vec![tree];
    };
    let prefix = &tree[..open];
    let inner = tree[open + 1..]
        .strip_suffix('}')
        .unwrap_or(&tree[open + 1..]);
    let mut items = Vec::new();
    let (mut depth, mut start) = (0usize, 0usize);
    for (i, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth = depth.saturating_sub(1),
            ',' if depth == 0 => {
                items.push(&inner[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    items.push(&inner[start..]);
    items
        .into_iter()
        .filter(|s| !s.is_empty())
        .flat_map(expand_use)
        .map(|s| format!("{prefix}{s}"))
        .collect()
}

/// Every `crate::…` or `super::…` path in `code`: from `use` statements (expanded) and from
/// paths written in place.
fn paths_in(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find("use ") {
        let before_ok = i == 0 || !rest.as_bytes()[i - 1].is_ascii_alphanumeric();
        let after = &rest[i + 4..];
        let end = after.find(';').unwrap_or(after.len());
        if before_ok {
            out.extend(expand_use(&after[..end]));
        }
        rest = &after[end.min(after.len())..];
    }
    for root in ["crate::", "super::"] {
        for (i, _) in code.match_indices(root) {
            let ok = i == 0 || !code.as_bytes()[i - 1].is_ascii_alphanumeric();
            let tail: String = code[i..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
                .collect();
            if ok && !tail.ends_with("::") {
                out.push(tail);
            }
        }
    }
    out.retain(|p| p.starts_with("crate::") || p.starts_with("super::"));
    out
}

/// What `path` (seen from `from`) names: a top-level module and maybe one of its files (the
/// longest known file path the path starts with: `crate::tutor::ladder::build::teach::x` →
/// `tutor/ladder/build/teach.rs`). `files` lists the files of each module folder; `reexports`
/// maps `module::Item` to the file whose `pub use` makes it visible at the module root.
fn target(
    from: &Unit,
    path: &str,
    files: &BTreeMap<String, BTreeSet<String>>,
    reexports: &BTreeMap<(String, String), String>,
) -> Option<Unit> {
    let segs: Vec<&str> = path.split("::").filter(|s| !s.is_empty()).collect();
    let (module, rest): (String, Vec<&str>) = match *segs.first()? {
        "crate" => (segs.get(1)?.to_string(), segs[2.min(segs.len())..].to_vec()),
        "super" => {
            // `super` is the parent of the file's own module path (`ladder/checker` → `ladder`);
            // from a module's root file it is the crate root, outside the module.
            let mut base: Vec<&str> = from
                .file
                .as_deref()
                .map_or(Vec::new(), |f| f.split('/').collect());
            let ups = segs.iter().take_while(|s| **s == "super").count();
            for _ in 0..ups {
                base.pop()?;
            }
            base.extend(&segs[ups..]);
            (from.module.clone(), base)
        }
        _ => return None,
    };
    let known = files.get(&module);
    let file = (1..=rest.len())
        .rev()
        .map(|n| rest[..n].join("/"))
        .find(|f| known.is_some_and(|k| k.contains(f)))
        .or_else(|| {
            let first = rest.first()?;
            reexports.get(&(module.clone(), first.to_string())).cloned()
        });
    Some(Unit { module, file })
}

/// The faces of the binary (`src/main.rs` declares them): each may use the library and the
/// shared face-support module [`FACE_SUPPORT`], never another face.
const FACES: &[&str] = &["cli", "repl", "grade"];

/// The one module the faces share (output files, the progress bar, pictures, the terminal):
/// it may use the library, never a face.
const FACE_SUPPORT: &str = "face";

/// The source files under `src/`: (unit, code), the library's modules and the binary's faces
/// and face support alike. `lib.rs`, `main.rs` (the binary's root, which dispatches to every
/// face) and this test are left out.
fn source_files(src: &Path) -> Vec<(Unit, String)> {
    let mut out = Vec::new();
    let Ok(entries) = std::fs::read_dir(src) else {
        return out;
    };
    let mut entries: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    entries.sort();
    for path in entries {
        let name = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("")
            .to_string();
        if path.is_dir() {
            for (file, text) in rs_files(&path) {
                let file = (file != "mod").then_some(file);
                out.push((
                    Unit {
                        module: name.clone(),
                        file,
                    },
                    code_of(&text),
                ));
            }
        } else if path.extension().is_some_and(|e| e == "rs")
            && !["lib", "main", "layers"].contains(&name.as_str())
        {
            let text = std::fs::read_to_string(&path).unwrap_or_default();
            out.push((
                Unit {
                    module: name,
                    file: None,
                },
                code_of(&text),
            ));
        }
    }
    out
}

/// The `.rs` files in `dir`, by stem; files of a folder below it (a file split by concept,
/// `session/answer.rs`) as `session/answer`, and its `mod.rs` as `session`.
fn rs_files(dir: &Path) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for p in std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
    {
        let stem = p
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("")
            .to_string();
        if p.is_dir() {
            for (file, text) in rs_files(&p) {
                let name = if file == "mod" {
                    stem.clone()
                } else {
                    format!("{stem}/{file}")
                };
                out.push((name, text));
            }
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push((stem, std::fs::read_to_string(&p).unwrap_or_default()));
        }
    }
    out.sort();
    out
}

/// Every violation of the rules in `units`, as sentences.
fn violations(units: &[(Unit, String)], layers: &[&str]) -> Vec<String> {
    let mut files: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (u, _) in units {
        if let Some(f) = &u.file {
            files.entry(u.module.clone()).or_default().insert(f.clone());
        }
    }
    // `pub use file::{A, B}` in a module root makes `module::A` an alias of that file.
    let mut reexports = BTreeMap::new();
    for (u, code) in units.iter().filter(|(u, _)| u.file.is_none()) {
        for line in code
            .split(';')
            .filter(|s| s.trim_start().starts_with("pub use "))
        {
            for p in expand_use(line.trim_start().trim_start_matches("pub use ")) {
                let segs: Vec<&str> = p.split("::").collect();
                let in_folder = files.get(&u.module).is_some_and(|f| f.contains(segs[0]));
                if segs.len() >= 2 && in_folder {
                    let item = segs[segs.len() - 1].split(" as ").last().unwrap_or("");
                    reexports.insert((u.module.clone(), item.to_string()), segs[0].to_string());
                }
            }
        }
    }
    let rank = |m: &str| layers.iter().position(|l| *l == m);
    let mut out = Vec::new();
    let mut edges: BTreeMap<Unit, BTreeSet<Unit>> = BTreeMap::new();
    for (from, code) in units {
        let from_face = FACES.contains(&from.module.as_str());
        let from_support = from.module == FACE_SUPPORT;
        let from_rank = rank(&from.module);
        if from_rank.is_none() && !from_face && !from_support {
            out.push(format!(
                "`{}` is in no layer: add it to LAYERS in src/lib.rs (or to FACES in src/layers.rs)",
                from.module
            ));
            continue;
        }
        for path in paths_in(code) {
            let Some(to) = target(from, &path, &files, &reexports) else {
                continue;
            };
            let to_face = FACES.contains(&to.module.as_str());
            if to.module != from.module && to_face && (from_face || from_support) {
                out.push(format!(
                    "{from} imports `{path}`: a face may use the library and `{FACE_SUPPORT}`, never another face"
                ));
            }
            if let (Some(from_rank), Some(r)) = (from_rank, rank(&to.module))
                && r > from_rank
            {
                out.push(format!(
                    "{from} imports `{path}`: `{}` is a higher layer than `{}`",
                    to.module, from.module
                ));
            }
            if to.module == from.module
                && let Some(edge) = sibling_edge(from, &to)
            {
                edges.entry(edge.0).or_default().insert(edge.1);
            }
        }
    }
    out.extend(cycles(&edges));
    out.sort();
    out.dedup();
    out
}

/// The import of `to` by `from` as an edge between two siblings of one folder: the two
/// entries (file or sub-folder, a sub-folder counting as one) below their deepest common
/// folder. `None` when one contains the other (a folder's `mod.rs` and its own files).
fn sibling_edge(from: &Unit, to: &Unit) -> Option<(Unit, Unit)> {
    let a: Vec<&str> = from.file.as_deref()?.split('/').collect();
    let b: Vec<&str> = to.file.as_deref()?.split('/').collect();
    let common = a.iter().zip(&b).take_while(|(x, y)| x == y).count();
    if common >= a.len() || common >= b.len() {
        return None;
    }
    let unit = |segs: &[&str]| Unit {
        module: from.module.clone(),
        file: Some(segs.join("/")),
    };
    Some((unit(&a[..=common]), unit(&b[..=common])))
}

/// One sentence per group of files that import each other in a loop (a strongly connected
/// component of the import graph with more than one file).
fn cycles(edges: &BTreeMap<Unit, BTreeSet<Unit>>) -> Vec<String> {
    let reach = |from: &Unit| {
        let mut seen = BTreeSet::new();
        let mut stack = vec![from.clone()];
        while let Some(u) = stack.pop() {
            for next in edges.get(&u).into_iter().flatten() {
                if seen.insert(next.clone()) {
                    stack.push(next.clone());
                }
            }
        }
        seen
    };
    let reachable: BTreeMap<&Unit, BTreeSet<Unit>> = edges.keys().map(|u| (u, reach(u))).collect();
    let mut groups = BTreeSet::new();
    for (u, from_u) in &reachable {
        let group: BTreeSet<&Unit> = from_u
            .iter()
            .filter(|v| reachable.get(v).is_some_and(|r| r.contains(*u)))
            .collect();
        if group.len() > 1 {
            groups.insert(group.iter().map(|g| g.to_string()).collect::<Vec<_>>());
        }
    }
    groups
        .into_iter()
        .map(|g| format!("import loop among {}", g.join(", ")))
        .collect()
}

#[test]
fn the_library_respects_its_layers() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let units = source_files(&src);
    assert!(
        units.len() > 20,
        "read only {} files under {}",
        units.len(),
        src.display()
    );
    let v = violations(&units, crate::LAYERS);
    assert!(v.is_empty(), "layering violations:\n{}", v.join("\n"));
}

fn unit(module: &str, file: Option<&str>, code: &str) -> (Unit, String) {
    let u = Unit {
        module: module.into(),
        file: file.map(String::from),
    };
    (u, code_of(code))
}

#[test]
fn an_upward_import_is_caught() {
    let layers = ["expr", "mechanics", "check"];
    let table: &[(&str, Option<&str>, &str, usize)] = &[
        ("mechanics", Some("system"), "use crate::expr::Pool;", 0),
        ("mechanics", Some("system"), "use crate::check::Verdict;", 1),
        (
            "mechanics",
            Some("system"),
            "use crate::{expr::Id, check::points::X};",
            1,
        ),
        (
            "expr",
            Some("pool"),
            "fn f() { crate::mechanics::System::new() }",
            1,
        ),
        ("expr", Some("pool"), "// use crate::check::Verdict;\n", 0),
        (
            "expr",
            Some("pool"),
            "#[cfg(test)]\nmod t { use crate::check::X; }",
            0,
        ),
        ("simulate", None, "use crate::expr::Pool;", 1),
    ];
    for (module, file, code, expected) in table {
        let v = violations(&[unit(module, *file, code)], &layers);
        assert_eq!(v.len(), *expected, "{module}/{file:?}: {code:?} gave {v:?}");
    }
}

#[test]
fn an_import_loop_between_files_is_caught() {
    let layers = ["check"];
    let looped = [
        unit("check", Some("answer"), "use super::lists::x;"),
        unit(
            "check",
            Some("lists"),
            "use super::{common::y, equations::z};",
        ),
        unit("check", Some("equations"), "use crate::check::answer::w;"),
        unit("check", Some("common"), ""),
    ];
    let v = violations(&looped, &layers);
    assert_eq!(v.len(), 1, "{v:?}");
    assert!(
        v[0].contains("check/answer.rs, check/equations.rs, check/lists.rs"),
        "{v:?}"
    );
    // A loop through a re-export at the module root is a loop too.
    let via_root = [
        unit("check", None, "pub use answer::{Checker, check};"),
        unit("check", Some("answer"), "use super::lists::x;"),
        unit("check", Some("lists"), "fn f(c: &crate::check::Checker) {}"),
    ];
    assert_eq!(violations(&via_root, &layers).len(), 1);
    let tree = [
        unit("check", Some("answer"), "use super::{lists::x, common::y};"),
        unit("check", Some("lists"), "use super::common::y;"),
        unit("check", Some("common"), ""),
    ];
    assert!(violations(&tree, &layers).is_empty());
}

#[test]
fn a_face_importing_another_face_is_caught() {
    let layers = ["expr"];
    let table: &[(&str, Option<&str>, &str, usize)] = &[
        ("repl", None, "use crate::face::Terminal;", 0),
        ("repl", Some("store"), "use lagrange::expr::Pool;", 0),
        ("repl", None, "use crate::cli::system_args::Terminal;", 1),
        ("grade", None, "fn f() { crate::cli::emit(\"\") }", 1),
        ("cli", Some("simulate"), "use crate::repl::Options;", 1),
        ("face", Some("plot"), "use crate::grade::Lms;", 1),
        ("face", Some("plot"), "use crate::face::outfile::check;", 0),
        ("gui", None, "use crate::face::Terminal;", 1),
    ];
    for (module, file, code, expected) in table {
        let v = violations(&[unit(module, *file, code)], &layers);
        assert_eq!(v.len(), *expected, "{module}/{file:?}: {code:?} gave {v:?}");
    }
}

#[test]
fn an_import_loop_inside_a_sub_folder_or_across_it_is_caught() {
    let layers = ["tutor"];
    // Inside `tutor/ladder/`: two of its files import each other.
    let inside = [
        unit("tutor", Some("ladder/build"), "use super::checker::x;"),
        unit(
            "tutor",
            Some("ladder/checker"),
            "use crate::tutor::ladder::build::y;",
        ),
    ];
    let v = violations(&inside, &layers);
    assert_eq!(v.len(), 1, "{v:?}");
    assert!(
        v[0].contains("tutor/ladder/build.rs, tutor/ladder/checker.rs"),
        "{v:?}"
    );
    // Across it: a file of the folder and a top-level file import each other.
    let across = [
        unit(
            "tutor",
            Some("ladder/build/teach"),
            "use crate::tutor::follow::z;",
        ),
        unit("tutor", Some("follow"), "use super::ladder::Step;"),
        unit("tutor", Some("ladder"), ""),
    ];
    let v = violations(&across, &layers);
    assert_eq!(v.len(), 1, "{v:?}");
    // A folder's root and its own files use each other freely.
    let own = [
        unit(
            "tutor",
            Some("ladder"),
            "use self::checker::x; fn f() { checker::y() }",
        ),
        unit("tutor", Some("ladder/checker"), "use super::Step;"),
    ];
    assert!(violations(&own, &layers).is_empty());
}
