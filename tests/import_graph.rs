//! The import graph of `src/`: no circle between files or between folders,
//! and the layers drawn in the README's architecture section hold.
//!
//! A circle makes a part impossible to read, test or replace without the
//! other: each file should be understandable from the files below it. This
//! test reads every `src/**/*.rs` reachable from `src/lib.rs` and
//! `src/main.rs` with a small Rust tokenizer (std only; well under a second),
//! leaves out test code (items under `#[cfg(test)]`, and so the files only
//! a `#[cfg(test)] mod x;` declares) and draws an edge from a file to every
//! file that *defines* an item it names:
//!
//! - `use` declarations of every form (`crate::`, `super::`, `self::`, a
//!   name in scope, grouped `{a::b, c}`, `as` renames, globs, `pub use`
//!   re-exports), wherever they stand;
//! - paths written inline in code (`crate::scene::mesh::bounds(…)`,
//!   `super::x::y`, or through an imported module, `mesh::bounds(…)`);
//! - re-exports are followed to the file that defines the item, so
//!   `use crate::material::Material` points at the file defining
//!   `Material`, not at `material/mod.rs`; a re-export is itself an edge
//!   from the re-exporting file to the definition;
//! - items count where they are written, also inside a macro invocation
//!   among the items (`named_enum!(ReflectanceModel, …)` defines
//!   `ReflectanceModel`).
//!
//! `mod x;` declarations are not edges: a parent declaring its children is
//! the tree itself. What a path cannot show is not seen: a method call
//! reaches the file of its `impl` block through the value's type, which a
//! tokenizer does not know, so an `impl` block may stand in a higher file
//! than its type (as `impl Material { fn new … }` does, above the table of
//! models it reads).
//!
//! From the file graph follow the folder graphs: at every folder, its
//! children (files and sub-folders; `x.rs` beside `x/` is one module, `x`)
//! with an edge A → B when a file under A uses a file under B. Both must be
//! free of circles; a failure prints each circle as a chain, each step with
//! the items that make it. The top-level folder graph must also follow the
//! layer map, the first fenced block of README.md's "Architecture"
//! section: modules separated by `→` from lower to higher layers, the
//! modules of one layer by `|`; a module may use only modules of lower
//! layers (not those of its own), and every top-level module of `src/`
//! must appear in it (the crate root `lib.rs` only declares them).

use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet, VecDeque};
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};

// ---------------------------------------------------------------- tokens

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    /// `::`
    PathSep,
    Punct(char),
    /// A string, character or number literal (contents dropped).
    Lit,
}

fn is_ident_start(c: char) -> bool {
    c.is_alphabetic() || c == '_'
}

fn is_ident_continue(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// Index just past the closing quote of a string whose body starts at `j`.
fn string_end(b: &[char], mut j: usize) -> usize {
    while j < b.len() {
        match b[j] {
            '\\' => j += 2,
            '"' => return j + 1,
            _ => j += 1,
        }
    }
    b.len()
}

/// Index just past a character literal whose body starts at `j`.
fn char_end(b: &[char], mut j: usize) -> usize {
    if b.get(j) == Some(&'\\') {
        j += 2;
    } else {
        j += 1;
    }
    while j < b.len() && b[j] != '\'' {
        j += 1;
    }
    j + 1
}

/// A prefixed or raw string literal at `i` (`r"…"`, `r#"…"#`, `b"…"`,
/// `b'…'`, `br"…"`, `c"…"`, `cr#"…"#`): the index past it.
fn prefixed_literal(b: &[char], i: usize) -> Option<usize> {
    let mut j = i;
    if b[j] == 'b' || b[j] == 'c' {
        j += 1;
    }
    if b.get(j) == Some(&'r') {
        j += 1;
        let mut hashes = 0;
        while b.get(j) == Some(&'#') {
            hashes += 1;
            j += 1;
        }
        if b.get(j) != Some(&'"') {
            return None;
        }
        j += 1;
        while j < b.len() {
            if b[j] == '"' && (0..hashes).all(|k| b.get(j + 1 + k) == Some(&'#')) {
                return Some(j + 1 + hashes);
            }
            j += 1;
        }
        return Some(b.len());
    }
    if j == i {
        return None;
    }
    match b.get(j) {
        Some('"') => Some(string_end(b, j + 1)),
        Some('\'') if b[i] == 'b' => Some(char_end(b, j + 1)),
        _ => None,
    }
}

/// Rust source to tokens, without comments (doc comments included) and
/// without the contents of literals.
fn lex(src: &str) -> Vec<Tok> {
    let b: Vec<char> = src.chars().collect();
    let mut out = Vec::with_capacity(b.len() / 4);
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if c.is_whitespace() {
            i += 1;
        } else if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if let Some(end) = (matches!(c, 'r' | 'b' | 'c'))
            .then(|| prefixed_literal(&b, i))
            .flatten()
        {
            out.push(Tok::Lit);
            i = end;
        } else if c == '"' {
            out.push(Tok::Lit);
            i = string_end(&b, i + 1);
        } else if c == '\'' {
            if next == Some('\\') || b.get(i + 2) == Some(&'\'') {
                out.push(Tok::Lit);
                i = char_end(&b, i + 1);
            } else {
                // A lifetime or a loop label.
                i += 1;
                while i < b.len() && is_ident_continue(b[i]) {
                    i += 1;
                }
            }
        } else if c.is_ascii_digit() {
            while i < b.len()
                && (is_ident_continue(b[i])
                    || (b[i] == '.' && b.get(i + 1).is_some_and(|d| d.is_ascii_digit())))
            {
                i += 1;
            }
            out.push(Tok::Lit);
        } else if is_ident_start(c) {
            let start = i;
            while i < b.len() && is_ident_continue(b[i]) {
                i += 1;
            }
            let mut word: String = b[start..i].iter().collect();
            if word == "r"
                && b.get(i) == Some(&'#')
                && b.get(i + 1).is_some_and(|&c| is_ident_start(c))
            {
                // A raw identifier, r#name.
                let s = i + 1;
                i = s;
                while i < b.len() && is_ident_continue(b[i]) {
                    i += 1;
                }
                word = b[s..i].iter().collect();
            }
            out.push(Tok::Ident(word));
        } else if c == ':' && next == Some(':') {
            out.push(Tok::PathSep);
            i += 2;
        } else {
            out.push(Tok::Punct(c));
            i += 1;
        }
    }
    out
}

fn is_punct(t: Option<&Tok>, c: char) -> bool {
    t == Some(&Tok::Punct(c))
}

fn is_ident(t: Option<&Tok>, s: &str) -> bool {
    matches!(t, Some(Tok::Ident(w)) if w == s)
}

/// The index past the bracket that closes the one at `open`.
fn close_of(toks: &[Tok], open: usize) -> usize {
    let mut depth = 0i32;
    let mut i = open;
    while i < toks.len() {
        match toks[i] {
            Tok::Punct('(' | '[' | '{') => depth += 1,
            Tok::Punct(')' | ']' | '}') => {
                depth -= 1;
                if depth == 0 {
                    return i + 1;
                }
            }
            _ => {}
        }
        i += 1;
    }
    toks.len()
}

// ------------------------------------------------------- test code away

/// Whether an attribute's tokens (between `[` and `]`) compile the item
/// only for tests: `cfg(test)` or `cfg(all(…, test, …))`.
fn is_test_cfg(attr: &[Tok]) -> bool {
    if !is_ident(attr.first(), "cfg") {
        return false;
    }
    let words: Vec<&str> = attr
        .iter()
        .filter_map(|t| match t {
            Tok::Ident(w) => Some(w.as_str()),
            _ => None,
        })
        .collect();
    words.contains(&"test")
        && !words.contains(&"not")
        && !words.contains(&"any")
        && (words.len() == 2 || words[1] == "all")
}

/// The tokens without the items compiled only for tests (a test module's
/// `#[cfg(test)] mod tests;` goes with them, so its file is never read);
/// whether the whole file is test-only (`#![cfg(test)]`).
fn strip_test_code(toks: &[Tok]) -> (Vec<Tok>, bool) {
    let mut out = Vec::with_capacity(toks.len());
    let mut i = 0;
    while i < toks.len() {
        let inner = is_punct(toks.get(i + 1), '!') && is_punct(toks.get(i + 2), '[');
        if is_punct(toks.get(i), '#') && (is_punct(toks.get(i + 1), '[') || inner) {
            let open = if inner { i + 2 } else { i + 1 };
            let end = close_of(toks, open);
            if is_test_cfg(&toks[open + 1..end - 1]) {
                if inner {
                    return (Vec::new(), true);
                }
                // Skip further attributes, then the item.
                let mut j = end;
                while is_punct(toks.get(j), '#') && is_punct(toks.get(j + 1), '[') {
                    j = close_of(toks, j + 1);
                }
                let mut depth = 0i32;
                while j < toks.len() {
                    match toks[j] {
                        Tok::Punct('(' | '[' | '{') => depth += 1,
                        Tok::Punct(')' | ']') => depth -= 1,
                        Tok::Punct('}') => {
                            depth -= 1;
                            if depth == 0 {
                                j += 1;
                                break;
                            }
                        }
                        Tok::Punct(';') if depth == 0 => {
                            j += 1;
                            break;
                        }
                        _ => {}
                    }
                    if depth < 0 {
                        // An attribute on the last field or statement of a block.
                        break;
                    }
                    j += 1;
                }
                i = j;
                continue;
            }
        }
        out.push(toks[i].clone());
        i += 1;
    }
    (out, false)
}

// ----------------------------------------------------------- module syntax

#[derive(Debug)]
struct Use {
    path: Vec<String>,
    /// The name it binds (`None` for `as _`).
    name: Option<String>,
    glob: bool,
}

#[derive(Debug, Default)]
struct ModSyntax {
    /// Names of the items defined here (functions, types, traits, constants,
    /// statics, macros).
    items: HashSet<String>,
    uses: Vec<Use>,
    /// `mod x;`
    file_children: Vec<String>,
    /// `mod x { … }`
    inline_children: Vec<(String, ModSyntax)>,
    /// Paths of two or more segments written in code.
    paths: Vec<Vec<String>>,
    /// Every single identifier in code (for names brought in by `*`).
    idents: HashSet<String>,
}

fn parse_use_tree(toks: &[Tok], pos: &mut usize, prefix: &[String], out: &mut Vec<Use>) {
    let mut path = prefix.to_vec();
    if toks.get(*pos) == Some(&Tok::PathSep) {
        *pos += 1;
    }
    loop {
        match toks.get(*pos) {
            Some(Tok::Ident(s)) => {
                path.push(s.clone());
                *pos += 1;
                if toks.get(*pos) == Some(&Tok::PathSep) {
                    *pos += 1;
                    continue;
                }
                break;
            }
            Some(Tok::Punct('*')) => {
                *pos += 1;
                out.push(Use {
                    path,
                    name: None,
                    glob: true,
                });
                return;
            }
            Some(Tok::Punct('{')) => {
                *pos += 1;
                while *pos < toks.len() && !is_punct(toks.get(*pos), '}') {
                    parse_use_tree(toks, pos, &path, out);
                    if is_punct(toks.get(*pos), ',') {
                        *pos += 1;
                    }
                }
                *pos += 1;
                return;
            }
            _ => return,
        }
    }
    if path.last().map(String::as_str) == Some("self") {
        path.pop();
    }
    let mut name = path.last().cloned();
    if is_ident(toks.get(*pos), "as") {
        name = match toks.get(*pos + 1) {
            Some(Tok::Ident(n)) if n != "_" => Some(n.clone()),
            _ => None,
        };
        *pos += 2;
    }
    out.push(Use {
        path,
        name,
        glob: false,
    });
}

fn parse_module(toks: &[Tok]) -> ModSyntax {
    let mut m = ModSyntax::default();
    let mut depth = 0i32;
    let mut i = 0;
    while i < toks.len() {
        match &toks[i] {
            Tok::Punct('{') => depth += 1,
            Tok::Punct('}') => depth -= 1,
            Tok::Ident(w) if w == "use" && !is_punct(toks.get(i + 1), '<') => {
                let mut pos = i + 1;
                parse_use_tree(toks, &mut pos, &[], &mut m.uses);
                while pos < toks.len() && !is_punct(toks.get(pos), ';') {
                    pos += 1;
                }
                i = pos + 1;
                continue;
            }
            Tok::Ident(w) if w == "mod" && depth == 0 => {
                if let Some(Tok::Ident(name)) = toks.get(i + 1) {
                    if is_punct(toks.get(i + 2), ';') {
                        m.file_children.push(name.clone());
                        i += 3;
                        continue;
                    }
                    if is_punct(toks.get(i + 2), '{') {
                        let end = close_of(toks, i + 2);
                        let inner = parse_module(&toks[i + 3..end - 1]);
                        m.inline_children.push((name.clone(), inner));
                        i = end;
                        continue;
                    }
                }
            }
            Tok::Ident(w)
                if depth == 0
                    && w != "macro_rules"
                    && is_punct(toks.get(i + 1), '!')
                    && matches!(toks.get(i + 2), Some(Tok::Punct('{' | '(' | '[')))
                    && toks.get(i.wrapping_sub(1)) != Some(&Tok::PathSep) =>
            {
                // A macro invocation among the items (`named_enum! { pub
                // enum … }`): the items written in it are this module's.
                let end = close_of(toks, i + 2);
                let body = &toks[i + 3..end - 1];
                let inner = parse_module(body);
                m.items.extend(inner.items);
                // A macro that defines a type takes its name first
                // (`named_enum!(ReflectanceModel, "…" { … })`).
                let mut k = 0;
                while is_punct(body.get(k), '#') {
                    k = close_of(body, k + 1);
                }
                if let Some(Tok::Ident(name)) = body.get(k)
                    && !is_item_keyword(name)
                    && name != "pub"
                {
                    m.items.insert(name.clone());
                }
                m.uses.extend(inner.uses);
                m.paths.extend(inner.paths);
                m.idents.extend(inner.idents);
                i = end;
                continue;
            }
            Tok::Ident(w) if depth == 0 && is_item_keyword(w) => {
                let mut k = i + 1;
                if w == "static" && is_ident(toks.get(k), "mut") {
                    k += 1;
                }
                if w == "macro_rules" && is_punct(toks.get(k), '!') {
                    k += 1;
                }
                if let Some(Tok::Ident(name)) = toks.get(k)
                    && !is_item_keyword(name)
                    && !matches!(name.as_str(), "unsafe" | "async" | "extern")
                {
                    m.items.insert(name.clone());
                }
            }
            Tok::Ident(first) if toks.get(i + 1) == Some(&Tok::PathSep) => {
                if i > 0 && toks[i - 1] == Tok::PathSep {
                    // The tail of `::extern_crate::…`: not ours.
                    i += 1;
                    continue;
                }
                let mut path = vec![first.clone()];
                let mut k = i + 1;
                while toks.get(k) == Some(&Tok::PathSep) {
                    match toks.get(k + 1) {
                        Some(Tok::Ident(s)) => {
                            path.push(s.clone());
                            k += 2;
                        }
                        _ => break,
                    }
                }
                m.paths.push(path);
                i = k;
                continue;
            }
            Tok::Ident(w) => {
                m.idents.insert(w.clone());
            }
            _ => {}
        }
        i += 1;
    }
    m
}

fn is_item_keyword(w: &str) -> bool {
    matches!(
        w,
        "fn" | "struct" | "enum" | "trait" | "type" | "union" | "const" | "static" | "macro_rules"
    )
}

// ----------------------------------------------------------------- crate

struct Module {
    file: usize,
    parent: Option<usize>,
    /// The crate root this module belongs to (lib or the binary).
    root: usize,
    syntax: ModSyntax,
    children: HashMap<String, usize>,
}

enum Res {
    Module(usize),
    Item(usize, String),
}

struct Crate {
    src: PathBuf,
    /// Paths relative to `src/`, with `/`.
    files: Vec<String>,
    modules: Vec<Module>,
    lib_root: usize,
}

impl Crate {
    fn load(src: &Path) -> Crate {
        let mut krate = Crate {
            src: src.to_path_buf(),
            files: Vec::new(),
            modules: Vec::new(),
            lib_root: 0,
        };
        krate.lib_root = krate.load_file(Path::new("lib.rs"), Path::new(""), None, None);
        krate.load_file(Path::new("main.rs"), Path::new(""), None, None);
        krate
    }

    /// Loads the module file `rel` (relative to src) whose `mod x;` children
    /// live in the folder `child_dir`.
    fn load_file(
        &mut self,
        rel: &Path,
        child_dir: &Path,
        parent: Option<usize>,
        root: Option<usize>,
    ) -> usize {
        let text = fs::read_to_string(self.src.join(rel))
            .unwrap_or_else(|e| panic!("{}: {e}", self.src.join(rel).display()));
        let (toks, test_only) = strip_test_code(&lex(&text));
        assert!(
            !test_only,
            "{}: a test-only file declared outside test code",
            rel.display()
        );
        let file = self.files.len();
        self.files.push(rel.to_string_lossy().replace('\\', "/"));
        let syntax = parse_module(&toks);
        self.add_module(file, syntax, child_dir, parent, root)
    }

    fn add_module(
        &mut self,
        file: usize,
        mut syntax: ModSyntax,
        child_dir: &Path,
        parent: Option<usize>,
        root: Option<usize>,
    ) -> usize {
        let id = self.modules.len();
        let root = root.unwrap_or(id);
        let file_children = std::mem::take(&mut syntax.file_children);
        let inline_children = std::mem::take(&mut syntax.inline_children);
        self.modules.push(Module {
            file,
            parent,
            root,
            syntax,
            children: HashMap::new(),
        });
        for name in file_children {
            let flat = child_dir.join(format!("{name}.rs"));
            let (rel, dir) = if self.src.join(&flat).is_file() {
                (flat, child_dir.join(&name))
            } else {
                (child_dir.join(&name).join("mod.rs"), child_dir.join(&name))
            };
            let child = self.load_file(&rel, &dir, Some(id), Some(root));
            self.modules[id].children.insert(name, child);
        }
        for (name, inner) in inline_children {
            let child = self.add_module(file, inner, &child_dir.join(&name), Some(id), Some(root));
            self.modules[id].children.insert(name, child);
        }
        id
    }

    fn resolve(&self, m: usize, path: &[String], depth: u32) -> Option<Res> {
        if depth > 40 || path.is_empty() {
            return None;
        }
        let module = &self.modules[m];
        let mut cur = match path[0].as_str() {
            "crate" => Res::Module(module.root),
            "self" => Res::Module(m),
            "super" => Res::Module(module.parent?),
            "gonio" if module.root != self.lib_root => Res::Module(self.lib_root),
            "Self" => return None,
            first => self.lookup(m, first, depth + 1)?,
        };
        for seg in &path[1..] {
            cur = match cur {
                Res::Item(..) => return Some(cur), // a variant or an associated item
                Res::Module(mm) => match seg.as_str() {
                    "super" => Res::Module(self.modules[mm].parent?),
                    "self" => Res::Module(mm),
                    _ => self.lookup(mm, seg, depth + 1)?,
                },
            };
        }
        Some(cur)
    }

    /// What `name` means inside module `m`.
    fn lookup(&self, m: usize, name: &str, depth: u32) -> Option<Res> {
        if depth > 40 {
            return None;
        }
        let module = &self.modules[m];
        if module.syntax.items.contains(name) {
            return Some(Res::Item(module.file, name.to_string()));
        }
        if let Some(&child) = module.children.get(name) {
            return Some(Res::Module(child));
        }
        for u in &module.syntax.uses {
            if !u.glob && u.name.as_deref() == Some(name) {
                return self.resolve(m, &u.path, depth + 1);
            }
        }
        for u in module.syntax.uses.iter().filter(|u| u.glob) {
            if let Some(Res::Module(g)) = self.resolve(m, &u.path, depth + 1)
                && let Some(r) = self.lookup(g, name, depth + 1)
            {
                return Some(r);
            }
        }
        None
    }

    /// Every edge file → file, with one item that causes it.
    fn edges(&self) -> BTreeMap<(usize, usize), String> {
        let mut items: BTreeMap<(usize, usize), BTreeSet<String>> = BTreeMap::new();
        let mut add = |from: usize, res: Option<Res>| {
            if let Some(Res::Item(to, name)) = res
                && to != from
            {
                items.entry((from, to)).or_default().insert(name);
            }
        };
        for (m, module) in self.modules.iter().enumerate() {
            let from = module.file;
            for u in &module.syntax.uses {
                let res = self.resolve(m, &u.path, 0);
                if u.glob
                    && let Some(Res::Module(g)) = res
                {
                    for ident in &module.syntax.idents {
                        add(from, self.lookup(g, ident, 0));
                    }
                    continue;
                }
                add(from, res);
            }
            for path in &module.syntax.paths {
                add(from, self.resolve(m, path, 0));
            }
        }
        items
            .into_iter()
            .map(|(edge, names)| (edge, names.into_iter().collect::<Vec<_>>().join(", ")))
            .collect()
    }
}

// ----------------------------------------------------------------- graphs

/// Strongly connected components with more than one node (Tarjan).
fn circles(n: usize, adj: &[Vec<usize>]) -> Vec<Vec<usize>> {
    struct State<'a> {
        adj: &'a [Vec<usize>],
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on_stack: Vec<bool>,
        stack: Vec<usize>,
        next: usize,
        out: Vec<Vec<usize>>,
    }
    fn visit(s: &mut State, v: usize) {
        s.index[v] = Some(s.next);
        s.low[v] = s.next;
        s.next += 1;
        s.stack.push(v);
        s.on_stack[v] = true;
        for &w in &s.adj[v] {
            match s.index[w] {
                None => {
                    visit(s, w);
                    s.low[v] = s.low[v].min(s.low[w]);
                }
                Some(iw) if s.on_stack[w] => s.low[v] = s.low[v].min(iw),
                _ => {}
            }
        }
        if Some(s.low[v]) == s.index[v] {
            let mut comp = Vec::new();
            loop {
                let w = s.stack.pop().unwrap();
                s.on_stack[w] = false;
                comp.push(w);
                if w == v {
                    break;
                }
            }
            if comp.len() > 1 {
                comp.sort_unstable();
                s.out.push(comp);
            }
        }
    }
    let mut s = State {
        adj,
        index: vec![None; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in 0..n {
        if s.index[v].is_none() {
            visit(&mut s, v);
        }
    }
    s.out.sort();
    s.out
}

/// A shortest circle through `start` inside `comp`.
fn shortest_circle(adj: &[Vec<usize>], comp: &[usize], start: usize) -> Vec<usize> {
    let inside: HashSet<usize> = comp.iter().copied().collect();
    let mut prev: HashMap<usize, usize> = HashMap::new();
    let mut queue = VecDeque::from([start]);
    while let Some(v) = queue.pop_front() {
        for &w in &adj[v] {
            if !inside.contains(&w) {
                continue;
            }
            if w == start {
                let mut chain = vec![v];
                let mut x = v;
                while x != start {
                    x = prev[&x];
                    chain.push(x);
                }
                chain.reverse();
                chain.push(start);
                return chain;
            }
            if let std::collections::hash_map::Entry::Vacant(e) = prev.entry(w) {
                e.insert(v);
                queue.push_back(w);
            }
        }
    }
    vec![start]
}

/// A readable account of the circles of one graph: for every tangle, the
/// shortest circles that together pass through all its members.
fn describe(
    title: &str,
    names: &[String],
    edges: &BTreeMap<(usize, usize), String>,
    report: &mut String,
) -> usize {
    let n = names.len();
    let mut adj = vec![Vec::new(); n];
    for &(a, b) in edges.keys() {
        adj[a].push(b);
    }
    let comps = circles(n, &adj);
    for comp in &comps {
        let _ = writeln!(
            report,
            "{title}: {} members tangled: {}",
            comp.len(),
            comp.iter()
                .map(|&v| names[v].as_str())
                .collect::<Vec<_>>()
                .join(", ")
        );
        let mut covered = HashSet::new();
        for &v in comp {
            if covered.contains(&v) {
                continue;
            }
            let chain = shortest_circle(&adj, comp, v);
            let mut line = String::from("    ");
            for pair in chain.windows(2) {
                covered.insert(pair[0]);
                let _ = write!(
                    line,
                    "{} →({}) ",
                    names[pair[0]],
                    edges[&(pair[0], pair[1])]
                );
            }
            let _ = writeln!(report, "{line}{}", names[v]);
        }
    }
    comps.len()
}

/// A file's path as module components: `x.rs` beside a folder `x/` is the
/// folder's `mod.rs`.
fn module_components(src: &Path, rel: &str) -> Vec<String> {
    let mut comps: Vec<String> = rel.split('/').map(str::to_string).collect();
    let last = comps.pop().unwrap();
    let dir: PathBuf = comps.iter().collect();
    if let Some(stem) = last.strip_suffix(".rs")
        && stem != "mod"
        && src.join(&dir).join(stem).is_dir()
    {
        comps.push(stem.to_string());
        comps.push("mod.rs".to_string());
    } else {
        comps.push(last);
    }
    comps
}

/// One graph's edges, each with what causes it.
type Edges = BTreeMap<(usize, usize), String>;
/// A folder's graph: its children's names and the edges between them.
type Graph = (Vec<String>, Edges);

struct Graphs {
    files: Vec<String>,
    file_edges: BTreeMap<(usize, usize), String>,
    /// Per folder (relative to src, "" for src itself): its children's names
    /// and the edges between them, each with one file edge that causes it.
    folders: BTreeMap<String, Graph>,
}

fn graphs(src: &Path) -> Graphs {
    let krate = Crate::load(src);
    let file_edges = krate.edges();
    let comps: Vec<Vec<String>> = krate
        .files
        .iter()
        .map(|f| module_components(src, f))
        .collect();
    let mut folders: BTreeMap<String, Graph> = BTreeMap::new();
    for ((a, b), item) in &file_edges {
        let (ca, cb) = (&comps[*a], &comps[*b]);
        let k = ca.iter().zip(cb).take_while(|(x, y)| x == y).count();
        let node = |c: &Vec<String>| {
            if k + 1 == c.len() {
                c[k].clone()
            } else {
                format!("{}/", c[k])
            }
        };
        let (na, nb) = (node(ca), node(cb));
        let (names, edges) = folders.entry(ca[..k].join("/")).or_default();
        let mut id = |name: String| match names.iter().position(|x| *x == name) {
            Some(i) => i,
            None => {
                names.push(name);
                names.len() - 1
            }
        };
        let (ia, ib) = (id(na), id(nb));
        edges
            .entry((ia, ib))
            .or_insert_with(|| format!("{} uses {item} of {}", krate.files[*a], krate.files[*b]));
    }
    Graphs {
        files: krate.files,
        file_edges,
        folders,
    }
}

// ----------------------------------------------------------------- layers

/// The layer map: the first fenced block of README.md's "## Architecture"
/// section, modules separated by `→` from lower to higher layers, peers of
/// one layer by `|` or `/`.
fn layer_map(readme: &str) -> Vec<Vec<String>> {
    let section = readme
        .split("\n## Architecture")
        .nth(1)
        .expect("README.md has an \"## Architecture\" section");
    let section = section.split("\n## ").next().unwrap();
    let block = section
        .split("```")
        .nth(1)
        .expect("the Architecture section starts with a fenced layer map");
    let block = block.split_once('\n').map_or("", |(_, body)| body);
    block
        .split('→')
        .map(|layer| {
            layer
                .split(['|', '/'])
                .map(str::trim)
                .filter(|s| !s.is_empty())
                .map(str::to_string)
                .collect::<Vec<_>>()
        })
        .filter(|l| !l.is_empty())
        .collect()
}

fn top_level_name(node: &str) -> &str {
    node.trim_end_matches('/').trim_end_matches(".rs")
}

// ------------------------------------------------------------------ tests

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn no_import_circle_between_files_or_folders() {
    let g = graphs(&root().join("src"));
    // `IMPORT_GRAPH_SHOW=gpu cargo test --test import_graph -- --nocapture`
    // prints a folder's graph (`""` for src/ itself): who uses whom, as
    // the maps in the module docs draw it.
    if let Ok(folder) = std::env::var("IMPORT_GRAPH_SHOW")
        && let Some((names, edges)) = g.folders.get(folder.trim_matches('/'))
    {
        let mut uses: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
        for (a, b) in edges.keys() {
            uses.entry(&names[*a]).or_default().push(&names[*b]);
        }
        for (a, bs) in uses {
            eprintln!("{a} -> {}", bs.join(" "));
        }
    }
    let mut report = String::new();
    let mut count = describe("files", &g.files, &g.file_edges, &mut report);
    for (folder, (names, edges)) in &g.folders {
        let title = if folder.is_empty() {
            "src/".to_string()
        } else {
            format!("src/{folder}/")
        };
        count += describe(&title, names, edges, &mut report);
    }
    eprintln!(
        "import graph: {} files, {} file edges, {} folders with edges",
        g.files.len(),
        g.file_edges.len(),
        g.folders.len()
    );
    assert!(
        count == 0,
        "{count} import circles (outside test code):\n{report}"
    );
}

#[test]
fn top_level_modules_follow_the_readme_layer_map() {
    let src = root().join("src");
    let readme = fs::read_to_string(root().join("README.md")).unwrap();
    let layers = layer_map(&readme);
    let mut layer_of = HashMap::new();
    for (i, layer) in layers.iter().enumerate() {
        for name in layer {
            assert!(
                layer_of.insert(name.clone(), i).is_none(),
                "README layer map names `{name}` twice"
            );
        }
    }
    // The top-level modules: every file and folder of src/ but the crate
    // root, which only declares them.
    let mut modules = BTreeSet::new();
    for entry in fs::read_dir(&src).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        if name != "lib.rs" {
            modules.insert(top_level_name(&name).to_string());
        }
    }
    let missing: Vec<_> = modules
        .iter()
        .filter(|m| !layer_of.contains_key(*m))
        .collect();
    let stale: Vec<_> = layer_of.keys().filter(|m| !modules.contains(*m)).collect();
    assert!(
        missing.is_empty(),
        "top-level modules missing from README's layer map: {missing:?}"
    );
    assert!(
        stale.is_empty(),
        "README's layer map names modules src/ does not have: {stale:?}"
    );

    let g = graphs(&src);
    let mut wrong = Vec::new();
    if let Some((names, edges)) = g.folders.get("") {
        for ((a, b), why) in edges {
            let (na, nb) = (top_level_name(&names[*a]), top_level_name(&names[*b]));
            let (Some(&la), Some(&lb)) = (layer_of.get(na), layer_of.get(nb)) else {
                continue; // the crate root
            };
            if la <= lb {
                wrong.push(format!("{na} (layer {la}) → {nb} (layer {lb}): {why}"));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "code edges that do not point to a lower layer of README's map:\n{}",
        wrong.join("\n")
    );
}
