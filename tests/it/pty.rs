//! The REPL in a real pseudo-terminal, as a student types: Tab completion, recalling a line
//! with the Up arrow, editing it, submitting it, and reading the verdict from the screen.

#[cfg(unix)]
#[test]
fn a_student_types_in_a_terminal() {
    use rexpect::session::spawn_command;
    let home = std::env::temp_dir().join(format!("lagrange-pty-{}", std::process::id()));
    std::fs::create_dir_all(&home).unwrap();
    let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_lagrange"));
    cmd.args(["repl", "simple-pendulum"])
        .env("LAGRANGE_HOME", &home)
        .env("NO_COLOR", "1")
        .env("TERM", "xterm");
    let mut p = spawn_command(cmd, Some(10_000)).expect("the REPL starts in a pty");
    p.exp_string("kinetic>").expect("the first part is current");
    // Tab completes `th` to `theta`; a wrong answer first.
    p.send("1/2 m l^2 th").unwrap();
    p.send("\t").unwrap();
    p.send_line("'").unwrap();
    // (rexpect reads the screen byte by byte, so only ASCII is matched.)
    p.exp_string("1/2 m l^2 theta'")
        .expect("Tab completed th to theta");
    p.exp_string("read as:").expect("read back");
    p.exp_string("incorrect  score 0%").expect("a verdict");
    p.exp_string("[dimension]").expect("its reason");
    // Up recalls the line; `^2` is appended; Enter submits it.
    p.send("\x1b[A").unwrap();
    p.send_line("^2").unwrap();
    p.exp_string("1/2 m l^2 theta'^2")
        .expect("the recalled, edited line");
    p.exp_string("correct  score 100%").expect("accepted");
    p.exp_string("potential>")
        .expect("the next part is current");
    p.send_control('d').unwrap();
    p.exp_eof().expect("Ctrl-D ends the session");
    std::fs::remove_dir_all(&home).ok();
}
