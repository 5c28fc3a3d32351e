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
    let message = plain_types(&message.join(" "));
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

/// [`clean_toml_error`] for an error in the scene file `text`: an unknown
/// key is located at its own line, where toml reports the table that holds
/// it (a misspelt key was once reported at its table's header).
pub fn clean_toml_error_in(e: &toml::de::Error, text: &str) -> String {
    let cleaned = clean_toml_error(e);
    let Some(span) = e.span() else {
        return cleaned;
    };
    let Some(unknown) = e
        .message()
        .split_once("unknown field `")
        .and_then(|(_, rest)| rest.split_once('`'))
        .map(|(name, _)| name)
    else {
        return cleaned;
    };
    // toml's span of a table may be its header alone: the table's keys
    // run from there to the next header.
    let Some(region) = text.get(span.start..) else {
        return cleaned;
    };
    let mut offset = span.start;
    for (k, line) in region.split_inclusive('\n').enumerate() {
        if k > 0 && offset >= span.end && line.trim_start().starts_with('[') {
            break;
        }
        let code = line.trim();
        let key = code
            .strip_prefix(unknown)
            .or_else(|| code.strip_prefix(&format!("\"{unknown}\"")));
        if key.is_some_and(|rest| rest.trim_start().starts_with(['=', '.'])) {
            let line_no = text[..offset].matches('\n').count() + 1;
            let column = line.len() - line.trim_start().len() + 1;
            let message = cleaned
                .split_once("): ")
                .filter(|(at, _)| at.starts_with("line "))
                .map_or(cleaned.as_str(), |(_, m)| m);
            return format!(
                "line {line_no}, column {column} (`{}`): {message}",
                shorten(code, 60)
            );
        }
        offset += line.len();
    }
    cleaned
}

/// serde's Rust type names in a message said in the scene file's words
/// (`k_e=abc` once said "expected f64").
fn plain_types(message: &str) -> String {
    let mut out = message.to_string();
    for (rust, plain) in [
        ("expected f64", "expected a number (e.g. 0.5)"),
        ("expected f32", "expected a number (e.g. 0.5)"),
        ("expected u32", "expected a whole number ≥ 0"),
        ("expected u64", "expected a whole number ≥ 0"),
        ("expected usize", "expected a whole number ≥ 0"),
        ("expected u8", "expected a whole number from 0 to 255"),
        ("expected i64", "expected a whole number"),
        ("expected a boolean", "expected true or false"),
        ("expected a sequence", "expected an array (e.g. [1, 2, 3])"),
    ] {
        if let Some(at) = out.find(rust) {
            let end = at + rust.len();
            // Only the whole word (`f64`, not `f64s`).
            if !out[end..].starts_with(|c: char| c.is_alphanumeric() || c == '_') {
                out.replace_range(at..end, plain);
            }
        }
    }
    out
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

pub(super) use crate::base::named::nearest_name;
