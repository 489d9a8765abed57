//! The crate's layers (the table under "Layers" in `src/lib.rs`) against
//! the imports in `src/`: every `crate::` path, grouped `crate::{..}`
//! paths and `super::` chains that reach the crate root, outside comments.
//! A module that imports one its table row does not list fails here, and
//! so does a table that lists a module below itself (a cycle) or leaves a
//! module out.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::Path;

/// The table of `src/lib.rs`: each module with the modules it may import,
/// in the table's order.
fn layers(lib: &str) -> Vec<(String, BTreeSet<String>)> {
    let mut rows: Vec<(String, BTreeSet<String>)> = Vec::new();
    let mut in_section = false;
    for line in lib.lines() {
        let Some(doc) = line.strip_prefix("//!") else {
            continue;
        };
        let doc = doc.trim();
        if doc.starts_with('#') {
            in_section = doc == "# Layers";
            continue;
        }
        if !in_section || !doc.starts_with('|') || doc.starts_with("|---") {
            continue;
        }
        let cells: Vec<&str> = doc.trim_matches('|').split('|').map(str::trim).collect();
        assert_eq!(cells.len(), 2, "a layer row has two cells: {doc}");
        if cells[0] == "module" {
            continue;
        }
        let name: String = cells[0]
            .split_whitespace()
            .next()
            .unwrap()
            .chars()
            .filter(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect();
        let allowed: BTreeSet<String> = match cells[1] {
            "nothing" => BTreeSet::new(),
            "every module above" => rows.iter().map(|(m, _)| m.clone()).collect(),
            list => list
                .split(',')
                .map(|m| m.trim().trim_matches('`').to_string())
                .collect(),
        };
        rows.push((name, allowed));
    }
    rows
}

/// `s` without its `//` and `/* */` comments (string literals are taken
/// as code: none of `src/` holds a module path in a string).
fn strip_comments(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let b = s.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i..].starts_with(b"//") {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if b[i..].starts_with(b"/*") {
            let mut depth = 0;
            while i < b.len() {
                if b[i..].starts_with(b"/*") {
                    depth += 1;
                    i += 2;
                } else if b[i..].starts_with(b"*/") {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else {
            out.push(b[i] as char);
            i += 1;
        }
    }
    out
}

fn ident_at(s: &str) -> String {
    s.chars()
        .skip_while(|c| c.is_whitespace())
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect()
}

/// The first path segments after the crate root in `code`, a file at
/// module depth `depth` (`src/a.rs` and `src/a/mod.rs`: 1, `src/a/b.rs`:
/// 2): `crate::x`, each `x` of `crate::{x::.., y}`, and `super::…::x` with
/// at least `depth` `super`s.
fn root_segments(code: &str, depth: usize) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    let bytes = code.as_bytes();
    let starts_word =
        |i: usize| i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_');
    let mut i = 0;
    while i < code.len() {
        let rest = &code[i..];
        if rest.starts_with("crate::") && starts_word(i) {
            let after = rest["crate::".len()..].trim_start();
            if let Some(group) = after.strip_prefix('{') {
                // Segments at the group's first level.
                let mut level = 1;
                let mut expect = true;
                for (k, c) in group.char_indices() {
                    match c {
                        '{' => level += 1,
                        '}' => {
                            level -= 1;
                            if level == 0 {
                                break;
                            }
                        }
                        ',' if level == 1 => expect = true,
                        c if expect && level == 1 && !c.is_whitespace() => {
                            found.insert(ident_at(&group[k..]));
                            expect = false;
                        }
                        _ => {}
                    }
                }
            } else {
                found.insert(ident_at(after));
            }
            i += "crate::".len();
        } else if rest.starts_with("super::") && starts_word(i) {
            let mut n = 0;
            let mut r = rest;
            while let Some(t) = r.strip_prefix("super::") {
                n += 1;
                r = t.trim_start();
            }
            if n >= depth {
                found.insert(ident_at(r));
            }
            i += rest.len() - r.len();
        } else {
            i += rest.chars().next().unwrap().len_utf8();
        }
    }
    found
}

/// Every `.rs` file under `dir`.
fn sources(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Module imports found in `src/`: importing module → imported module →
/// the files that do it.
fn imports(src: &Path, modules: &BTreeSet<String>) -> BTreeMap<(String, String), Vec<String>> {
    let mut files = Vec::new();
    sources(src, &mut files);
    let mut edges: BTreeMap<(String, String), Vec<String>> = BTreeMap::new();
    for path in files {
        let rel = path.strip_prefix(src).unwrap();
        let mut parts: Vec<String> = rel
            .iter()
            .map(|p| p.to_str().unwrap().trim_end_matches(".rs").to_string())
            .collect();
        if parts.last().is_some_and(|p| p == "mod") {
            parts.pop();
        }
        if parts == ["lib"] {
            continue;
        }
        let from = parts[0].clone();
        let code = strip_comments(&fs::read_to_string(&path).unwrap());
        for to in root_segments(&code, parts.len()) {
            if to != from && modules.contains(&to) {
                edges
                    .entry((from.clone(), to))
                    .or_default()
                    .push(rel.display().to_string());
            }
        }
    }
    edges
}

#[test]
fn imports_follow_the_layers_of_the_crate_docs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let lib = fs::read_to_string(root.join("src/lib.rs")).unwrap();
    let rows = layers(&lib);
    let names: Vec<&str> = rows.iter().map(|(m, _)| m.as_str()).collect();
    assert_eq!(
        names,
        ["num", "pixel", "geom", "mesh", "illum", "scene", "target", "raster", "render"]
    );

    // The table is a layering: each row lists only rows above it.
    for (k, (m, allowed)) in rows.iter().enumerate() {
        for a in allowed {
            assert!(
                names[..k].contains(&a.as_str()),
                "{m} may import {a}, which is not above it"
            );
        }
    }

    // Every module the crate root declares has a row.
    let declared: BTreeSet<String> = strip_comments(&lib)
        .lines()
        .filter_map(|l| {
            let l = l.trim().strip_prefix("pub ").unwrap_or(l.trim());
            l.strip_prefix("mod ")?
                .strip_suffix(';')
                .map(str::to_string)
        })
        .collect();
    let listed: BTreeSet<String> = names.iter().map(|n| n.to_string()).collect();
    assert_eq!(declared, listed);

    let edges = imports(&root.join("src"), &listed);
    // The scan finds imports (so an empty result cannot pass as clean).
    for edge in [
        ("render", "raster"),
        ("raster", "target"),
        ("mesh", "geom"),
        ("scene", "pixel"),
    ] {
        assert!(
            edges.contains_key(&(edge.0.to_string(), edge.1.to_string())),
            "{edge:?} not found"
        );
    }
    let allowed: BTreeMap<&str, &BTreeSet<String>> =
        rows.iter().map(|(m, a)| (m.as_str(), a)).collect();
    let wrong: Vec<String> = edges
        .iter()
        .filter(|((from, to), _)| !allowed[from.as_str()].contains(to))
        .map(|((from, to), files)| format!("{from} imports {to} in {files:?}"))
        .collect();
    assert!(wrong.is_empty(), "imports against the layers: {wrong:#?}");
}

#[test]
fn the_scan_reads_grouped_paths_and_super_chains() {
    let code = strip_comments(
        "use crate::{geom::Vec3, num::{Real, Q16}, self};\n\
         // use crate::scene::Scene;\n\
         /* crate::illum */ let x = crate::target::MAX_SCREEN;\n\
         use super::super::raster::Fill; use super::sibling;\n\
         fn f() { mycrate::mesh::X; }",
    );
    let found = |depth| root_segments(&code, depth).into_iter().collect::<Vec<_>>();
    assert_eq!(found(2), ["geom", "num", "raster", "self", "target"]);
    assert_eq!(found(3), ["geom", "num", "self", "target"]);
}
