//! The guide's error table (`docs/src/errors.md`) is complete: every error code the code can return
//! (`E` and four digits, and the checker's `C` and four digits, in the code of `src/` and
//! `python/src/`, comments aside) is covered by a row of the table under "| codes | what |" (a
//! code, a range `E0003–E0006` or a family `E39xx`), and every code the table names alone is one
//! the code returns. Likewise the plan checkers' rule codes (`P` and four digits) and the table of
//! `docs/src/checking.md` under "| code | rule |", one row per code.

mod common;

use common::rust_files;
use std::collections::BTreeSet;
use std::path::Path;

/// The letters of the codes the table lists: `E` (errors) and `C` (the hop checker's rules).
const LETTERS: [u8; 2] = [b'E', b'C'];

/// A code as a number: its letter times 10,000 plus its digits, so that `C3006` and `E3006`
/// differ and a range of one letter holds only that letter's codes.
fn code_number(letter: u8, digits: u32) -> u32 {
    u32::from(letter) * 10_000 + digits
}

/// A code number as written.
fn code_name(code: u32) -> String {
    format!("{}{:04}", char::from((code / 10_000) as u8), code % 10_000)
}

/// Every `E` or `C` followed by exactly four digits in `text`.
fn codes_in(text: &str) -> Vec<u32> {
    codes_of(text, &LETTERS)
}

/// Every code of one of `letters` (a letter followed by exactly four digits) in `text`.
fn codes_of(text: &str, letters: &[u8]) -> Vec<u32> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    for i in 0..b.len() {
        let digits = |k: usize| b.get(i + k).is_some_and(u8::is_ascii_digit);
        let before_ok = i == 0 || !b[i - 1].is_ascii_alphanumeric();
        if letters.contains(&b[i]) && before_ok && (1..=4).all(digits) && !digits(5) {
            out.push(code_number(b[i], text[i + 1..i + 5].parse().unwrap()));
        }
    }
    out
}

/// The codes the code returns: every `E####` and `C####` outside `//` comments.
fn codes_in_the_code() -> BTreeSet<u32> {
    codes_of_the_code(&LETTERS)
}

/// Every code of one of `letters` in the code of `src/` and `python/src/`, outside `//` comments.
fn codes_of_the_code(letters: &[u8]) -> BTreeSet<u32> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    rust_files(&root.join("python/src"), &mut files);
    let mut out = BTreeSet::new();
    for file in files {
        for line in std::fs::read_to_string(&file).unwrap().lines() {
            let code = line.split("//").next().unwrap_or("");
            out.extend(codes_of(code, letters));
        }
    }
    out
}

/// What the guide's table covers: single codes, ranges and families.
struct Table {
    single: BTreeSet<u32>,
    ranges: Vec<(u32, u32)>,
    families: Vec<u32>,
}

/// The rows of the table under `header` in the guide's page `page`, its header and rule left out.
fn table_rows(page: &str, header: &str) -> Vec<String> {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("docs/src")
            .join(page),
    )
    .unwrap();
    let mut lines = text.lines().skip_while(|l| !l.starts_with(header));
    lines
        .next()
        .unwrap_or_else(|| panic!("{page} has a table under {header}"));
    lines
        .skip(1)
        .take_while(|l| l.starts_with('|'))
        .map(str::to_string)
        .collect()
}

fn error_table() -> Table {
    let mut table = Table {
        single: BTreeSet::new(),
        ranges: Vec::new(),
        families: Vec::new(),
    };
    for line in table_rows("errors.md", "| codes | what |") {
        let cell = line.split('|').nth(1).unwrap().trim();
        for item in cell.split(',').map(str::trim) {
            if let Some((a, b)) = item.split_once('–') {
                let (a, b) = (codes_in(a), codes_in(b));
                table.ranges.push((a[0], b[0]));
            } else if let Some(prefix) = item.strip_prefix('E').and_then(|s| s.strip_suffix("xx")) {
                table
                    .families
                    .push(code_number(b'E', prefix.parse::<u32>().unwrap() * 100));
            } else {
                let found = codes_in(item);
                assert_eq!(
                    found.len(),
                    1,
                    "a table cell item reads as one code: {item}"
                );
                table.single.insert(found[0]);
            }
        }
    }
    table
}

impl Table {
    fn covers(&self, code: u32) -> bool {
        self.single.contains(&code)
            || self.ranges.iter().any(|&(a, b)| (a..=b).contains(&code))
            || self.families.iter().any(|&f| (f..f + 100).contains(&code))
    }
}

#[test]
fn every_error_code_is_in_the_guide_table_and_back() {
    let code = codes_in_the_code();
    let table = error_table();
    assert!(
        code.len() > 100,
        "the code's error codes are found: {}",
        code.len()
    );
    let missing: Vec<String> = code
        .iter()
        .filter(|&&c| !table.covers(c))
        .map(|&c| code_name(c))
        .collect();
    assert!(
        missing.is_empty(),
        "codes not in the table of docs/src/errors.md: {missing:?}"
    );
    let unknown: Vec<String> = table
        .single
        .iter()
        .chain(table.ranges.iter().flat_map(|(a, b)| [a, b]))
        .filter(|c| !code.contains(c))
        .map(|&c| code_name(c))
        .collect();
    assert!(
        unknown.is_empty(),
        "codes of docs/src/errors.md the code never returns: {unknown:?}"
    );
}

#[test]
fn every_plan_rule_code_is_in_the_guide_table_and_back() {
    let code = codes_of_the_code(b"P");
    assert!(
        code.len() > 50,
        "the checkers' codes are found: {}",
        code.len()
    );
    let mut table = BTreeSet::new();
    for row in table_rows("checking.md", "| code | rule |") {
        let cell = row.split('|').nth(1).unwrap().trim();
        let found = codes_of(cell, b"P");
        assert_eq!(found.len(), 1, "a row of one code: {row}");
        assert!(table.insert(found[0]), "a code with two rows: {cell}");
    }
    let missing: Vec<String> = code.difference(&table).map(|&c| code_name(c)).collect();
    assert!(
        missing.is_empty(),
        "rule codes not in the table of docs/src/checking.md: {missing:?}"
    );
    let unknown: Vec<String> = table.difference(&code).map(|&c| code_name(c)).collect();
    assert!(
        unknown.is_empty(),
        "codes of docs/src/checking.md no checker returns: {unknown:?}"
    );
}

#[test]
fn the_code_reader_finds_codes_and_only_codes() {
    assert_eq!(
        codes_in(r#"Error::invalid("E0123", x) [E4567] E12345 XE1111 E12 "C3006" P5001"#),
        vec![
            code_number(b'E', 123),
            code_number(b'E', 4567),
            code_number(b'C', 3006)
        ]
    );
    assert_eq!(code_name(code_number(b'C', 3006)), "C3006");
}
