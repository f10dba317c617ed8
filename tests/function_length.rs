//! Every function of the library and its front ends reads in one screen or so: at most
//! [`MAX_LINES`] lines of code (blank and comment-only lines not counted, as clippy's
//! `too_many_lines` counts them). A long driver is split into named phases instead. Exempt: a
//! function whose body is one `match` (dispatch) or one array literal (a table).
//! Read from the source with `syn`.

mod common;

use common::rust_files;
use proc_macro2::Span;
use std::path::Path;
use syn::spanned::Spanned;
use syn::visit::Visit;

/// The longest a function may be, in lines of code.
const MAX_LINES: usize = 120;

/// A function found in a file: its name, first line and lines of code.
#[derive(Debug, PartialEq)]
struct FnLength {
    name: String,
    line: usize,
    code_lines: usize,
}

/// Lines of code in `lines[first-1..last]`: neither blank nor only a comment.
fn code_lines(lines: &[&str], first: usize, last: usize) -> usize {
    let mut in_block_comment = false;
    let mut count = 0;
    for line in &lines[first - 1..last.min(lines.len())] {
        let t = line.trim();
        if in_block_comment {
            if t.contains("*/") {
                in_block_comment = false;
            }
            continue;
        }
        if t.is_empty() || t.starts_with("//") {
            continue;
        }
        if t.starts_with("/*") {
            in_block_comment = !t.contains("*/");
            continue;
        }
        count += 1;
    }
    count
}

/// A body that is one `match` (dispatch) or one array literal (a table).
fn exempt(block: &syn::Block) -> bool {
    let [stmt] = block.stmts.as_slice() else {
        return false;
    };
    let expr = match stmt {
        syn::Stmt::Expr(e, _) => e,
        _ => return false,
    };
    matches!(expr, syn::Expr::Match(_) | syn::Expr::Array(_))
}

struct Lengths<'a> {
    lines: Vec<&'a str>,
    found: Vec<FnLength>,
}

impl Lengths<'_> {
    fn record(&mut self, name: String, sig: Span, block: &syn::Block) {
        if exempt(block) {
            return;
        }
        let first = sig.start().line;
        let last = block.span().end().line;
        self.found.push(FnLength {
            name,
            line: first,
            code_lines: code_lines(&self.lines, first, last),
        });
    }
}

impl<'ast> Visit<'ast> for Lengths<'_> {
    fn visit_item_fn(&mut self, f: &'ast syn::ItemFn) {
        self.record(f.sig.ident.to_string(), f.sig.span(), &f.block);
        syn::visit::visit_item_fn(self, f);
    }
    fn visit_impl_item_fn(&mut self, f: &'ast syn::ImplItemFn) {
        self.record(f.sig.ident.to_string(), f.sig.span(), &f.block);
        syn::visit::visit_impl_item_fn(self, f);
    }
    fn visit_trait_item_fn(&mut self, f: &'ast syn::TraitItemFn) {
        if let Some(block) = &f.default {
            self.record(f.sig.ident.to_string(), f.sig.span(), block);
        }
        syn::visit::visit_trait_item_fn(self, f);
    }
}

/// Every function of a source text with its length.
fn lengths(text: &str) -> Vec<FnLength> {
    let file = syn::parse_file(text).expect("the library's source parses");
    let mut v = Lengths {
        lines: text.lines().collect(),
        found: Vec::new(),
    };
    v.visit_file(&file);
    v.found
}

#[test]
fn no_function_is_longer_than_the_limit() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    rust_files(&root.join("python").join("src"), &mut files);
    files.sort();
    let mut long = Vec::new();
    let mut counted = 0;
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap();
        for l in lengths(&text) {
            counted += 1;
            if l.code_lines > MAX_LINES {
                long.push(format!(
                    "{}:{} fn {} ({} lines of code)",
                    f.strip_prefix(root).unwrap().display(),
                    l.line,
                    l.name,
                    l.code_lines
                ));
            }
        }
    }
    // The scan saw the library: well over a thousand functions.
    assert!(counted > 1000, "only {counted} functions found");
    assert!(
        long.is_empty(),
        "functions over {MAX_LINES} lines of code (split them into named phases): {long:#?}"
    );
}

#[test]
fn the_length_scan_counts_code_lines_and_exempts_dispatch() {
    let text = "\
/// doc
fn short(x: u32) -> u32 {
    // a comment

    let y = x + 1;
    /* a block
       comment */
    y * 2
}

impl S {
    fn method(&self) {
        fn inner() {}
        inner();
    }
}

fn dispatch(k: K) -> u32 {
    match k {
        K::A => 1,
        K::B => 2,
    }
}
";
    let found = lengths(text);
    let summary: Vec<(&str, usize, usize)> = found
        .iter()
        .map(|l| (l.name.as_str(), l.line, l.code_lines))
        .collect();
    // short: the signature, `let`, `y * 2` and the closing brace; method: signature, inner's
    // line, the call and the brace; inner: one line; dispatch: exempt.
    assert_eq!(
        summary,
        [("short", 2, 4), ("method", 12, 4), ("inner", 13, 1)]
    );
}
