//! Tests of reading a class file (`input.rs`): pieces read as one pass, headers, keys.

use super::*;

#[test]
fn headers_ignore_case_spaces_and_a_byte_order_mark() {
    let t = parse(
        "\u{feff} Student ,PROBLEM, Part,Answer,extra\na,p,q,x,y\n".as_bytes(),
        &mut Default::default(),
    );
    let t = t.map_err(|e| e.0).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(t.format, Format::Long);
    assert_eq!(t.rows[0].line, 2);
    assert_eq!(t.answer(&t.rows[0]), "x");
    assert!(t.error(&t.rows[0]).is_none());
}

#[test]
fn wide_rows_are_the_non_empty_cells() {
    let t = parse(b"student,a/b,c/d\ns1,x,\ns2,,y\n", &mut Default::default()).map_err(|e| e.0);
    let t = t.unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(t.format, Format::Wide);
    let got: Vec<(u32, &str, &str)> = t
        .rows
        .iter()
        .map(|r| (r.line, t.student(r), t.part(r)))
        .collect();
    assert_eq!(got, [(2, "s1", "b"), (3, "s2", "d")]);
}

/// A file of several pieces (CRLF endings, quoted answers over two lines) reads as one
/// pass would: every record once, on its own line, text numbered in order of first
/// appearance, keys differing in case merged once.
#[test]
fn a_file_read_in_pieces_reads_as_one_pass() {
    let mut csv = String::from("student,problem,part,answer\r\n");
    let (mut line, mut want) = (2u32, Vec::new());
    for i in 0..100_000 {
        let student = if i == 30_000 {
            "S7".to_string()
        } else {
            format!("s{}", i % 97)
        };
        if i % 100 == 0 {
            csv.push_str(&format!("{student},p,q,\"x +\r\n{}\"\r\n", i % 13));
            want.push(line);
            line += 2;
        } else {
            csv.push_str(&format!("{student},p,q,answer number {}\r\n", i % 31));
            want.push(line);
            line += 1;
        }
    }
    assert!(csv.len() > 2 * super::super::decode::CUT_BYTES);
    let t = parse(csv.as_bytes(), &mut Default::default()).map_err(|e| e.0);
    let t = t.unwrap_or_else(|e| panic!("{e}"));
    let lines: Vec<u32> = t.rows.iter().map(|r| r.line).collect();
    assert_eq!(lines, want);
    let mut seen = 0;
    for r in &t.rows {
        assert!(r.answer <= seen, "first appearance order");
        seen = seen.max(r.answer + 1);
    }
    assert_eq!(t.students.len(), 97);
    assert_eq!(t.merged, [("s7".to_string(), "S7".to_string())]);
    assert!(t.rows.iter().all(|r| t.error(r).is_none()));
}

/// Everything a table holds, as text, row by row.
fn shown(t: &Table) -> Vec<String> {
    let mut out: Vec<String> = (t.rows.iter())
        .map(|r| {
            let e = t.error(r).unwrap_or("-");
            let ids = (r.student, r.problem, r.part, r.answer);
            let text = (t.student(r), t.problem(r), t.part(r), t.answer(r));
            format!("{} {ids:?} {text:?} {e}", r.line)
        })
        .collect();
    out.push(format!("{:?} {:?}", t.merged, t.students));
    out
}

/// Long and wide files with CR, LF and CRLF endings, quoted answers over several lines,
/// keys differing in case and bad rows, cut every few bytes: each reads as one pass.
#[test]
fn a_file_cut_anywhere_reads_as_one_pass() {
    let files = [
        "student,problem,part,answer\r\nA,p,q,x\r\na,p,q,\"y\r\nz\"\r\nb,p,q,\"\"\"w\"\"\"\rB,p,r,1\n,p,q,2\nc,p\nC,p,q,\"3\n\n4\"\r\n",
        "student,a/b,c/d\ns1,x,\"y\r\n1\"\rS1,,z\r\ns2,\"\",\",\"\n\ns3,1,2,3\n",
    ];
    for f in files {
        let whole = parse_cut(
            f.as_bytes().to_vec(),
            1 << 30,
            &mut Default::default(),
            |_| (),
        );
        let whole = (whole.map(|(t, ())| t).map_err(|e| e.0)).unwrap_or_else(|e| panic!("{e}"));
        for cut in 1..12 {
            let t = parse_cut(f.as_bytes().to_vec(), cut, &mut Default::default(), |_| ());
            let t = (t.map(|(t, ())| t).map_err(|e| e.0)).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(shown(&t), shown(&whole), "cut {cut}");
        }
    }
}

#[test]
fn a_header_of_neither_format_names_the_expected_columns() {
    let e = parse(b"name,score\n", &mut Default::default())
        .err()
        .map(|e| e.0)
        .unwrap_or_default();
    assert!(e.contains("student,problem,part,answer"), "{e}");
}
