//! Small readers of the model files the crate writes, CPLEX LP and free MPS, as far as its models
//! use them: written here from the formats' definitions, not from the writers under test, so a
//! file is checked by reading it back. Both give an [`Lp`].

use std::collections::HashMap;

/// Terms `coefficient name` of a linear expression.
pub type Terms = Vec<(f64, String)>;

/// A CPLEX LP file as far as these models use it.
#[derive(Debug, Default)]
pub struct Lp {
    pub header: Vec<String>,
    pub maximise: bool,
    pub objective: Terms,
    /// (terms, operator, rhs)
    pub rows: Vec<(Terms, String, f64)>,
    /// name -> (lower, upper)
    pub bounds: HashMap<String, (f64, f64)>,
    pub generals: Vec<String>,
}

fn terms(tokens: &[&str]) -> Terms {
    assert!(tokens.len().is_multiple_of(2), "terms {tokens:?}");
    tokens
        .chunks(2)
        .map(|p| (p[0].parse().unwrap(), p[1].to_string()))
        .collect()
}

/// Reads a CPLEX LP file as `lp_solvers` writes it: `\ ` comment lines as the header, the
/// objective `obj:`, rows `cI: terms op rhs`, bounds and `Generals`.
pub fn read_lp(text: &str) -> Lp {
    let mut lp = Lp::default();
    let mut section = "";
    for line in text.lines() {
        let l = line.trim();
        if let Some(c) = line.strip_prefix("\\ ") {
            lp.header.push(c.to_string());
            continue;
        }
        match l {
            "" => continue,
            "Maximize" | "Minimize" => {
                lp.maximise = l == "Maximize";
                section = "obj";
                continue;
            }
            "Subject To" | "Bounds" | "Generals" | "End" => {
                section = l;
                continue;
            }
            _ => {}
        }
        let tokens: Vec<&str> = l.split_whitespace().collect();
        match section {
            "obj" => {
                assert_eq!(tokens[0], "obj:");
                lp.objective = terms(&tokens[1..]);
            }
            "Subject To" => {
                assert!(tokens[0].starts_with('c') && tokens[0].ends_with(':'));
                let n = tokens.len();
                lp.rows.push((
                    terms(&tokens[1..n - 2]),
                    tokens[n - 2].to_string(),
                    tokens[n - 1].parse().unwrap(),
                ));
            }
            "Bounds" => {
                let b = match tokens.as_slice() {
                    [lo, "<=", name, "<=", up] => (name, lo.parse().unwrap(), up.parse().unwrap()),
                    [lo, "<=", name] => (name, lo.parse().unwrap(), f64::INFINITY),
                    [name, "free"] => (name, f64::NEG_INFINITY, f64::INFINITY),
                    _ => panic!("bound line `{l}`"),
                };
                lp.bounds.insert(b.0.to_string(), (b.1, b.2));
            }
            "Generals" => lp.generals.push(l.to_string()),
            _ => panic!("line `{l}` outside a section"),
        }
    }
    lp
}

/// Reads a free MPS file: `* ` comment lines as the header, `OBJSENSE` `MAX`, the `N` row as the
/// objective, `L`/`E`/`G` rows (as `<=`, `=`, `>=`) in their order with their entries in the
/// order of the columns, `RHS` (0 when absent), `INTORG`/`INTEND` markers as the integer
/// columns, and `BOUNDS` (`LO`, `UP`, `FX`, `FR`, `MI`, `PL`, `BV`) over the default `[0, +inf)`.
pub fn read_mps(text: &str) -> Lp {
    let mut lp = Lp::default();
    let mut section = "";
    // Row name -> (position among the constraints, or None for the objective).
    let mut rows: HashMap<String, Option<usize>> = HashMap::new();
    let mut integer = false;
    let mut columns: Vec<String> = Vec::new();
    for line in text.lines() {
        if let Some(c) = line.strip_prefix("* ") {
            lp.header.push(c.to_string());
            continue;
        }
        let tokens: Vec<&str> = line.split_whitespace().collect();
        if tokens.is_empty() || line.starts_with('*') {
            continue;
        }
        if !line.starts_with(' ') {
            section = tokens[0];
            assert!(
                ["NAME", "OBJSENSE", "ROWS", "COLUMNS", "RHS", "BOUNDS", "ENDATA"]
                    .contains(&section),
                "unknown section `{line}`"
            );
            continue;
        }
        match (section, tokens.as_slice()) {
            ("OBJSENSE", [sense]) => lp.maximise = *sense == "MAX" || *sense == "MAXIMIZE",
            ("ROWS", ["N", name]) => {
                rows.insert(name.to_string(), None);
            }
            ("ROWS", [kind, name]) => {
                let op = match *kind {
                    "L" => "<=",
                    "E" => "=",
                    "G" => ">=",
                    _ => panic!("row kind `{line}`"),
                };
                rows.insert(name.to_string(), Some(lp.rows.len()));
                lp.rows.push((Vec::new(), op.to_string(), 0.0));
            }
            ("COLUMNS", [_, "'MARKER'", marker]) => integer = *marker == "'INTORG'",
            ("COLUMNS", [column, rest @ ..]) => {
                if columns.last().map(String::as_str) != Some(*column) {
                    columns.push(column.to_string());
                    lp.bounds.insert(column.to_string(), (0.0, f64::INFINITY));
                    if integer {
                        lp.generals.push(column.to_string());
                    }
                }
                assert!(rest.len() % 2 == 0, "column line `{line}`");
                for pair in rest.chunks(2) {
                    let c: f64 = pair[1].parse().unwrap();
                    match rows
                        .get(pair[0])
                        .unwrap_or_else(|| panic!("row of `{line}`"))
                    {
                        // A column in no row is listed with objective coefficient 0.
                        None if c == 0.0 => {}
                        None => lp.objective.push((c, column.to_string())),
                        Some(r) => lp.rows[*r].0.push((c, column.to_string())),
                    }
                }
            }
            ("RHS", [_, rest @ ..]) => {
                for pair in rest.chunks(2) {
                    let r = rows[pair[0]].expect("a constraint's right-hand side");
                    lp.rows[r].2 = pair[1].parse().unwrap();
                }
            }
            ("BOUNDS", [kind, _, column, value @ ..]) => {
                let b = lp
                    .bounds
                    .get_mut(*column)
                    .unwrap_or_else(|| panic!("bound on an unknown column `{line}`"));
                let x = || value[0].parse::<f64>().unwrap();
                match *kind {
                    "LO" => b.0 = x(),
                    "UP" => b.1 = x(),
                    "FX" => *b = (x(), x()),
                    "FR" => *b = (f64::NEG_INFINITY, f64::INFINITY),
                    "MI" => b.0 = f64::NEG_INFINITY,
                    "PL" => b.1 = f64::INFINITY,
                    "BV" => *b = (0.0, 1.0),
                    _ => panic!("bound kind `{line}`"),
                }
            }
            _ => panic!("line `{line}` in section {section}"),
        }
    }
    assert_eq!(section, "ENDATA", "the file does not end with ENDATA");
    lp
}
