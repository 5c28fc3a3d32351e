//! Conditional blocks in the WGSL sources.
//!
//! A directive is a line of its own (indentation allowed):
//!
//! ```text
//! #if shadows          (or `#if !shadows`, `#if mirror || cook-torrance`)
//! ...                  kept when the feature is on
//! #elif shadow_vertex  (optional, any number)
//! ...
//! #else                (optional)
//! ...
//! #endif
//! ```
//!
//! Blocks nest. Every name must be a [`Feature`]'s spelling, and every
//! block must be closed: anything else is an error naming the file and
//! line, never a line silently kept or dropped. The directive lines
//! themselves are not part of the output. WGSL has no `#`, so a directive
//! cannot be mistaken for code.

use super::features::Feature;

/// What one open `#if` block has decided so far.
struct Block {
    /// The lines around the block are kept.
    outer: bool,
    /// Some branch of the block was taken already.
    taken: bool,
    /// The current branch is kept.
    keeping: bool,
    /// `#else` was seen (no `#elif` or second `#else` may follow).
    in_else: bool,
}

/// `source` (the file `name`, for messages) with the blocks whose
/// condition fails for `features` removed.
pub fn preprocess(name: &str, source: &str, features: &[Feature]) -> Result<String, String> {
    let mut out = String::with_capacity(source.len());
    let mut blocks: Vec<Block> = Vec::new();
    let keeping = |blocks: &[Block]| blocks.last().is_none_or(|b| b.keeping);
    let error = |line: usize, message: String| format!("{name}:{}: {message}", line + 1);
    let term_holds = |line: usize, text: &str| -> Result<bool, String> {
        let (negated, spelling) = match text.trim().strip_prefix('!') {
            Some(rest) => (true, rest.trim()),
            None => (false, text.trim()),
        };
        let feature = Feature::parse(spelling).ok_or_else(|| {
            let known: Vec<_> = Feature::all().iter().map(|f| f.spelling()).collect();
            error(
                line,
                format!("unknown feature `{spelling}`; known: {}", known.join(", ")),
            )
        })?;
        Ok(features.contains(&feature) != negated)
    };
    // `a || b`: any of them; each `name` or `!name`.
    let condition = |line: usize, text: &str| -> Result<bool, String> {
        let mut any = false;
        for term in text.split("||") {
            any |= term_holds(line, term)?;
        }
        Ok(any)
    };
    for (number, line) in source.lines().enumerate() {
        let Some(directive) = line.trim_start().strip_prefix('#') else {
            if keeping(&blocks) {
                out.push_str(line);
                out.push('\n');
            }
            continue;
        };
        let (word, rest) = directive
            .split_once(char::is_whitespace)
            .unwrap_or((directive, ""));
        match word {
            "if" => {
                let outer = keeping(&blocks);
                let on = condition(number, rest)?;
                blocks.push(Block {
                    outer,
                    taken: on,
                    keeping: outer && on,
                    in_else: false,
                });
            }
            "elif" => {
                let on = condition(number, rest)?;
                let block = blocks
                    .last_mut()
                    .filter(|b| !b.in_else)
                    .ok_or_else(|| error(number, "`#elif` outside an `#if` block".into()))?;
                block.keeping = block.outer && !block.taken && on;
                block.taken |= on;
            }
            "else" if rest.trim().is_empty() => {
                let block = blocks
                    .last_mut()
                    .filter(|b| !b.in_else)
                    .ok_or_else(|| error(number, "`#else` outside an `#if` block".into()))?;
                block.keeping = block.outer && !block.taken;
                block.in_else = true;
            }
            "endif" if rest.trim().is_empty() => {
                blocks
                    .pop()
                    .ok_or_else(|| error(number, "`#endif` without an `#if`".into()))?;
            }
            _ => {
                return Err(error(
                    number,
                    format!("unknown directive `{}`", line.trim()),
                ));
            }
        }
    }
    if !blocks.is_empty() {
        return Err(format!(
            "{name}: {} `#if` block(s) not closed by `#endif`",
            blocks.len()
        ));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::shader_gen::sources;

    #[test]
    fn blocks_keep_their_lines_by_feature() {
        let any = "#if flat || !display\nx\n#endif\n";
        assert_eq!(preprocess("t", any, &[Feature::Display]).unwrap(), "");
        assert_eq!(
            preprocess("t", any, &[Feature::Flat, Feature::Display]).unwrap(),
            "x\n"
        );
        assert_eq!(preprocess("t", any, &[]).unwrap(), "x\n");
        let src = "a\n#if shadows\nb\n  #if !flat\n  c\n  #endif\n#elif display\nd\n#else\ne\n#endif\nf\n";
        let run = |features: &[Feature]| preprocess("t", src, features).unwrap();
        assert_eq!(run(&[Feature::Shadows]), "a\nb\n  c\nf\n");
        assert_eq!(run(&[Feature::Shadows, Feature::Flat]), "a\nb\nf\n");
        assert_eq!(run(&[Feature::Display]), "a\nd\nf\n");
        assert_eq!(run(&[Feature::Display, Feature::Shadows]), "a\nb\n  c\nf\n");
        assert_eq!(run(&[]), "a\ne\nf\n");
    }

    #[test]
    fn unknown_names_and_unbalanced_blocks_are_errors() {
        for (src, expected) in [
            ("#if shadow\nx\n#endif\n", "t:1: unknown feature `shadow`"),
            ("#if shadows\nx\n", "not closed"),
            ("x\n#endif\n", "t:2: `#endif` without"),
            ("#else\n", "t:1: `#else` outside"),
            ("#if flat\n#else\n#else\n#endif\n", "t:3: `#else` outside"),
            (
                "#if flat\n#else\n#elif display\n#endif\n",
                "t:3: `#elif` outside",
            ),
            ("#ifdef flat\n#endif\n", "t:1: unknown directive"),
        ] {
            let e = preprocess("t", src, &[]).unwrap_err();
            assert!(e.contains(expected), "{src:?}: {e}");
        }
    }

    /// Every marker under `shaders/` names a known feature, every block is
    /// closed, and no line-level `// #if` marker is left.
    #[test]
    fn every_shader_file_has_known_features_and_balanced_blocks() {
        let files = super::super::sources::tests::files_on_disk();
        assert!(files.len() >= sources::ALL.len());
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
        for path in files {
            let text = std::fs::read_to_string(root.join(&path)).unwrap();
            assert!(
                !text.contains("// #if"),
                "shaders/{path}: a line-level `// #if` marker; use `#if` blocks"
            );
            if let Err(e) = preprocess(&format!("shaders/{path}"), &text, &[]) {
                panic!("{e}");
            }
        }
    }
}
