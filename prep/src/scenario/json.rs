//! JSON text to a `serde_json::Value`, with non-finite number tokens kept as marked strings so
//! that the field holding one can be named.

use super::error::{ErrorKind, ScenarioError};
use serde_json::Value;
use std::path::Path;

/// Marks a string that stood for a non-finite number token in the text.
pub(super) const NON_FINITE: &str = "\u{0}non-finite:";

pub(super) fn parse_json(text: &str, path: &Path) -> Result<Value, ScenarioError> {
    match serde_json::from_str::<Value>(text) {
        Ok(v) => Ok(v),
        Err(e) => {
            // JSON has no NaN or infinities; Python writes NaN/Infinity, and 1e999 overflows.
            // Retry with such tokens turned into marked strings so that the field that holds
            // one is named. Any other error is reported as it was first found.
            if let Some(fixed) = mark_non_finite(text) {
                if let Ok(v) = serde_json::from_str::<Value>(&fixed) {
                    return Ok(v);
                }
            }
            let message = e.to_string();
            let suffix = format!(" at line {} column {}", e.line(), e.column());
            let message = message
                .strip_suffix(&suffix)
                .unwrap_or(&message)
                .to_string();
            Err(ScenarioError::new(
                path,
                None,
                "",
                ErrorKind::Json {
                    line: e.line(),
                    column: e.column(),
                    message,
                },
            ))
        }
    }
}

/// `text` with every bare token outside strings that denotes a non-finite number (`NaN`,
/// `Infinity`, `-Infinity`, `inf`, …, or a numeral that overflows f64) replaced by a string
/// `"\u0000non-finite:<token>"`; `None` if there is none.
fn mark_non_finite(text: &str) -> Option<String> {
    let bytes = text.as_bytes();
    let mut out = String::with_capacity(text.len() + 16);
    let mut changed = false;
    let mut i = 0;
    let mut last = 0;
    while i < bytes.len() {
        let b = bytes[i];
        if b == b'"' {
            i += 1;
            while i < bytes.len() && bytes[i] != b'"' {
                i += if bytes[i] == b'\\' { 2 } else { 1 };
            }
            i += 1;
        } else if b.is_ascii_alphanumeric() || b == b'-' || b == b'+' || b == b'.' {
            let start = i;
            while i < bytes.len()
                && (bytes[i].is_ascii_alphanumeric() || matches!(bytes[i], b'-' | b'+' | b'.'))
            {
                i += 1;
            }
            let token = &text[start..i];
            let bare = token.trim_start_matches(['-', '+']).to_ascii_lowercase();
            let non_finite = matches!(bare.as_str(), "nan" | "inf" | "infinity")
                || (token.starts_with(|c: char| c.is_ascii_digit() || c == '-')
                    && token.parse::<f64>().is_ok_and(|v| !v.is_finite()));
            if non_finite {
                out.push_str(&text[last..start]);
                out.push_str("\"\\u0000non-finite:");
                out.push_str(token);
                out.push('"');
                last = i;
                changed = true;
            }
        } else {
            i += 1;
        }
    }
    if !changed {
        return None;
    }
    out.push_str(&text[last.min(text.len())..]);
    Some(out)
}

/// How a JSON value is named in errors.
pub(super) fn describe(v: &Value) -> String {
    match v {
        Value::Null => "null".into(),
        Value::Bool(b) => format!("the boolean {b}"),
        Value::Number(n) => format!("the number {n}"),
        Value::String(s) => match s.strip_prefix(NON_FINITE) {
            Some(t) => format!("the non-finite number {t}"),
            None => format!("the string {s:?}"),
        },
        Value::Array(a) => format!("an array of {}", a.len()),
        Value::Object(_) => "an object".into(),
    }
}
