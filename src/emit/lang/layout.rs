//! Lines of at most [`WIDTH`] columns: a pass over a rendered include that wraps comments at
//! word boundaries and breaks long code lines where a reader expects it, the way
//! rustfmt and clang-format do. It changes only whitespace: the printer writes every binary
//! operator between spaces and nothing else at the top level with one, so a line can be
//! broken at its loosest top-level operator, or else inside its longest bracket group, one
//! item per line.

use super::printer::{op_level as level, top_level_tokens};

/// The widest line an include has.
pub const WIDTH: usize = 100;

/// A comment's continuation lines start this far after the `//` and its space, so that a
/// paragraph reads as one: a line without it starts a new paragraph.
pub const HANG: &str = "  ";

/// `text` with every line of more than [`WIDTH`] columns wrapped or broken.
pub fn wrap(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + text.len() / 16);
    for line in text.split_inclusive('\n') {
        let (body, newline) = match line.strip_suffix('\n') {
            Some(b) => (b, "\n"),
            None => (line, ""),
        };
        if columns(body) <= WIDTH {
            out.push_str(line);
            continue;
        }
        let indent = body.len() - body.trim_start().len();
        let content = &body[indent..];
        let lines = match content.strip_prefix("//") {
            Some(c) => comment(&body[..indent], c.trim_start()),
            None => code(content, indent),
        };
        out.push_str(&lines.join("\n"));
        out.push_str(newline);
    }
    out
}

fn columns(s: &str) -> usize {
    s.chars().count()
}

/// A comment paragraph filled to [`WIDTH`], continuation lines indented by [`HANG`].
fn comment(pad: &str, text: &str) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = format!("{pad}// ");
    let mut empty = true;
    for word in text.split(' ').filter(|w| !w.is_empty()) {
        if !empty && columns(&line) + 1 + columns(word) > WIDTH {
            lines.push(line);
            line = format!("{pad}// {HANG}");
            empty = true;
        }
        if !empty {
            line.push(' ');
        }
        line.push_str(word);
        empty = false;
    }
    lines.push(line);
    lines
}

/// One code line broken into lines of at most [`WIDTH`] columns where it can be: at its
/// loosest top-level operator (continuations indented four more), or else inside its
/// longest top-level bracket group (one item per line, indented four more).
fn code(s: &str, indent: usize) -> Vec<String> {
    let pad = " ".repeat(indent);
    if indent + columns(s) <= WIDTH {
        return vec![format!("{pad}{s}")];
    }
    let tokens = top_level_tokens(s);
    // A continuation's leading operator is not a place to break.
    let loosest = tokens.iter().skip(1).filter_map(|(_, t)| level(t)).max();
    if let Some(l) = loosest {
        let mut pieces = Vec::new();
        let mut start = 0;
        for (pos, t) in tokens.iter().skip(1) {
            if level(t) == Some(l) {
                pieces.push(&s[start..pos - 1]);
                start = *pos;
            }
        }
        pieces.push(&s[start..]);
        let mut out = code(pieces[0], indent);
        for p in &pieces[1..] {
            out.extend(code(p, indent + 4));
        }
        return out;
    }
    let Some((open, close)) = longest_group(s) else {
        return vec![format!("{pad}{s}")];
    };
    let inner = &s[open + 1..close];
    let items = split_items(inner);
    let mut out = vec![format!("{pad}{}", &s[..=open])];
    for (k, item) in items.iter().enumerate() {
        let comma = if k + 1 < items.len() { "," } else { "" };
        out.extend(code(&format!("{}{comma}", item.trim()), indent + 4));
    }
    out.push(format!("{pad}{}", &s[close..]));
    out
}

/// The byte positions of the opening and closing bracket of the longest bracket group at
/// the top level of `s`.
fn longest_group(s: &str) -> Option<(usize, usize)> {
    let mut depth = 0i32;
    let mut open = 0;
    let mut best: Option<(usize, usize)> = None;
    for (i, c) in s.char_indices() {
        match c {
            '(' | '[' | '{' => {
                if depth == 0 {
                    open = i;
                }
                depth += 1;
            }
            ')' | ']' | '}' => {
                depth -= 1;
                if depth == 0 && best.is_none_or(|(o, c)| i - open > c - o) && i > open + 1 {
                    best = Some((open, i));
                }
            }
            _ => {}
        }
    }
    best
}

/// The comma-separated items of a bracket group's contents.
fn split_items(inner: &str) -> Vec<&str> {
    let mut items = Vec::new();
    let mut depth = 0i32;
    let mut start = 0;
    for (i, c) in inner.char_indices() {
        match c {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            ',' if depth == 0 => {
                items.push(&inner[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    items.push(&inner[start..]);
    items
}
