//! Step 2 of loading, the diagnostics: toml's errors made into one
//! readable paragraph (location, the offending source line, the message
//! cut to a bounded length) with a suggestion when a key or value name is
//! misspelt; and the prefix that marks a note as a warning ([`WARNING`]).

/// Notes that begin with this are warnings: shown without `--verbose`.
pub const WARNING: &str = "warning: ";

/// Longest error message kept from toml (its messages quote the offending
/// value, which may be megabytes long).
const MAX_MESSAGE_CHARS: usize = 600;

/// Makes one paragraph of a toml error: `line L, column C (`source
/// line`): message`, without toml's caret diagram, cut to a readable
/// length, and with a suggestion when the problem is a misspelt key or
/// value name.
pub fn clean_toml_error(e: &impl std::fmt::Display) -> String {
    let text = e.to_string();
    let mut location = None;
    let mut source_line = None;
    let mut message = Vec::new();
    for line in text.lines().map(str::trim).filter(|l| !l.is_empty()) {
        if let Some(at) = line.strip_prefix("TOML parse error at ") {
            location = Some(at);
        } else if let Some(code) = snippet_code(line) {
            source_line = source_line.or(code);
        } else {
            message.push(line);
        }
    }
    let message = message.join(" ");
    let suggestion = unknown_name_suggestion(&message)
        .map(|name| format!("; did you mean `{name}`?"))
        .unwrap_or_default();
    let mut out = String::new();
    if let Some(at) = location {
        out += at;
        if let Some(code) = source_line {
            out += &format!(" (`{}`)", shorten(code, 60));
        }
        out += ": ";
    }
    out += &shorten(&message, MAX_MESSAGE_CHARS);
    out + &suggestion
}

/// A line of toml's caret diagram: `|`, `  |   ^^^` or `12 | code`. Returns
/// `Some(Some(code))` for a source line, `Some(None)` for the others.
fn snippet_code(line: &str) -> Option<Option<&str>> {
    if line.starts_with('|') {
        return Some(None);
    }
    let (number, code) = line.split_once(" |")?;
    (!number.is_empty() && number.bytes().all(|b| b.is_ascii_digit()))
        .then(|| Some(code.trim()).filter(|c| !c.is_empty()))
}

/// At most `max` characters of `text`, with `…` where it was cut.
fn shorten(text: &str, max: usize) -> String {
    match text.char_indices().nth(max) {
        Some((cut, _)) => format!("{}…", &text[..cut]),
        None => text.to_string(),
    }
}

/// For serde's `unknown field `x`, expected one of `a`, `b`` (and the same
/// for variants), the expected name nearest to `x`, if one is near enough
/// to be a likely misspelling.
fn unknown_name_suggestion(message: &str) -> Option<&str> {
    let rest = message
        .split_once("unknown field `")
        .or_else(|| message.split_once("unknown variant `"))?
        .1;
    let (unknown, rest) = rest.split_once('`')?;
    let expected = rest.split_once("expected")?.1;
    // Deserializing from a table appends the table's path: ` in `camera``.
    let expected = expected.split(" in `").next().unwrap_or_default();
    let candidates = expected.split('`').skip(1).step_by(2);
    nearest_name(unknown, candidates)
}

/// The candidate closest to `unknown` by edit distance (ignoring case), if
/// within a third of its length (at least 2 edits), or if one is a prefix
/// of the other (`fov` for `fov_y_deg`).
pub(super) fn nearest_name<'c>(
    unknown: &str,
    candidates: impl Iterator<Item = &'c str>,
) -> Option<&'c str> {
    // Keys are short; a long one is not a typo, and edit distance is
    // quadratic.
    if unknown.is_empty() || unknown.len() > 64 {
        return None;
    }
    let unknown = unknown.to_lowercase();
    let budget = (unknown.chars().count() / 3).max(2);
    candidates
        .filter(|c| !c.is_empty())
        .map(|c| {
            let lower = c.to_lowercase();
            let prefix = lower.starts_with(&unknown) || unknown.starts_with(&lower);
            (edit_distance(&unknown, &lower), prefix, c)
        })
        .filter(|&(distance, prefix, _)| distance <= budget || prefix)
        .min_by_key(|&(distance, _, _)| distance)
        .map(|(_, _, c)| c)
}

/// Levenshtein distance (insertions, deletions, substitutions), by chars.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut previous: Vec<usize> = (0..=b.len()).collect();
    let mut current = vec![0; b.len() + 1];
    for (i, ca) in a.chars().enumerate() {
        current[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitute = previous[j] + usize::from(ca != cb);
            current[j + 1] = substitute.min(previous[j + 1] + 1).min(current[j] + 1);
        }
        std::mem::swap(&mut previous, &mut current);
    }
    previous[b.len()]
}
