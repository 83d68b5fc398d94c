//! `stopscan completions SHELL` and `stopscan man`: generated from the same clap definitions
//! as `--help`, so every command `--help` lists has its completion and its page.

use crate::common;

use common::{stopscan, temp};

/// The commands a `--help` text lists under "Commands:" (without `help`).
fn commands(args: &[&str]) -> Vec<String> {
    let mut all = args.to_vec();
    all.push("--help");
    let out = stopscan(&all);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    text.lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .map(String::from)
        .collect()
}

#[test]
fn completions_for_every_shell_name_every_command() {
    let top = commands(&[]);
    assert!(top.len() >= 10 && top.iter().any(|c| c == "serve"), "{top:?}");
    for (shell, opening) in [
        ("bash", "_stopscan()"),
        ("zsh", "#compdef stopscan"),
        ("fish", "complete -c stopscan"),
        ("elvish", "edit:completion"),
        ("powershell", "Register-ArgumentCompleter"),
    ] {
        let out = stopscan(&["completions", shell]);
        assert!(out.status.success(), "{shell}: {}", String::from_utf8_lossy(&out.stderr));
        let text = String::from_utf8(out.stdout).unwrap();
        assert!(text.contains(opening), "{shell}");
        for c in &top {
            assert!(text.contains(c.as_str()), "{shell} completions lack {c}");
        }
        // Options of a subcommand are completed too.
        assert!(text.contains("robot-radius"), "{shell}");
    }
    // To a file: the same bytes.
    let dir = temp("completions");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("stopscan.bash");
    let out = stopscan(&["completions", "bash", "--out", file.to_str().unwrap()]);
    assert!(out.status.success());
    assert_eq!(std::fs::read(&file).unwrap(), stopscan(&["completions", "bash"]).stdout);
    let bad = stopscan(&["completions", "tcsh"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("invalid value 'tcsh'"));
}

#[test]
fn man_pages_for_every_command() {
    let out = stopscan(&["man"]);
    assert!(out.status.success());
    let page = String::from_utf8(out.stdout).unwrap();
    assert!(page.contains(".TH stopscan 1"), "{page}");
    let dir = temp("man");
    let out = stopscan(&["man", "--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let mut expected = vec!["stopscan".to_string()];
    for c in commands(&[]) {
        let subs = commands(&[c.as_str()]);
        expected.extend(subs.iter().map(|s| format!("stopscan-{c}-{s}")));
        expected.push(format!("stopscan-{c}"));
    }
    let mut written: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().trim_end_matches(".1").to_string())
        .collect();
    written.sort();
    expected.sort();
    assert_eq!(written, expected);
    let explore = std::fs::read_to_string(dir.join("stopscan-explore.1")).unwrap();
    assert!(explore.contains(".TH stopscan-explore 1"));
    assert!(explore.contains("robot\\-radius"), "the page documents the options");
    // A directory whose parent is missing is refused before anything is written.
    let missing = dir.join("no/such");
    let out = stopscan(&["man", "--out", missing.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
}
