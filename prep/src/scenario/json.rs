//! JSON text to a `serde_json::Value`, with non-finite number tokens kept as marked strings so
//! that the field holding one can be named.

use super::error::{ErrorKind, ScenarioError};
use serde::de::{DeserializeSeed, Deserializer, Error as _, MapAccess, SeqAccess, Visitor};
use serde_json::Value;
use std::collections::HashSet;
use std::fmt;
use std::path::Path;

/// Marks a string that stood for a non-finite number token in the text.
pub(super) const NON_FINITE: &str = "\u{0}non-finite:";

/// Parses `text`, refusing an object with a key twice (see [`NoDuplicates`]).
pub(super) fn parse_json(text: &str, path: &Path) -> Result<Value, ScenarioError> {
    let parsed = match serde_json::from_str::<Value>(text) {
        Ok(v) => no_duplicates(text).map(|()| v),
        Err(e) => {
            // JSON has no NaN or infinities; Python writes NaN/Infinity, and 1e999 overflows.
            // Retry with such tokens turned into marked strings so that the field that holds
            // one is named. Any other error is reported as it was first found. (A duplicate key
            // is then found in the marked text: its column counts the marks on its line.)
            match mark_non_finite(text).and_then(|fixed| {
                serde_json::from_str::<Value>(&fixed)
                    .ok()
                    .map(|v| (fixed, v))
            }) {
                Some((fixed, v)) => no_duplicates(&fixed).map(|()| v),
                None => Err(e),
            }
        }
    };
    match parsed {
        Ok(v) => Ok(v),
        Err(e) => {
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

/// Reads `text` (already known to be JSON) once more and fails, with serde_json's line and
/// column, at the first object that has a key twice: `serde_json::Value` keeps the last value
/// silently.
fn no_duplicates(text: &str) -> Result<(), serde_json::Error> {
    let mut de = serde_json::Deserializer::from_str(text);
    NoDuplicates { path: "" }.deserialize(&mut de)?;
    de.end()
}

/// Visits a JSON value and its members, refusing a key that an object repeats. `path` names
/// the value as errors name fields (`features[3].properties`; empty: the top level). Nesting is
/// bounded by serde_json's recursion limit (128), as for the parse itself.
struct NoDuplicates<'p> {
    path: &'p str,
}

impl<'de> DeserializeSeed<'de> for NoDuplicates<'_> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for NoDuplicates<'_> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a JSON value")
    }

    fn visit_bool<E>(self, _: bool) -> Result<(), E> {
        Ok(())
    }

    fn visit_i64<E>(self, _: i64) -> Result<(), E> {
        Ok(())
    }

    fn visit_u64<E>(self, _: u64) -> Result<(), E> {
        Ok(())
    }

    fn visit_f64<E>(self, _: f64) -> Result<(), E> {
        Ok(())
    }

    fn visit_str<E>(self, _: &str) -> Result<(), E> {
        Ok(())
    }

    fn visit_unit<E>(self) -> Result<(), E> {
        Ok(())
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
        let mut i = 0usize;
        loop {
            let path = format!("{}[{i}]", self.path);
            if seq
                .next_element_seed(NoDuplicates { path: &path })?
                .is_none()
            {
                return Ok(());
            }
            i += 1;
        }
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        let mut keys = HashSet::new();
        while let Some(key) = map.next_key::<String>()? {
            if keys.contains(&key) {
                let within = if self.path.is_empty() {
                    "the top level"
                } else {
                    self.path
                };
                return Err(A::Error::custom(format!(
                    "duplicate key {key:?} in {within}"
                )));
            }
            let path = if self.path.is_empty() {
                key.clone()
            } else {
                format!("{}.{key}", self.path)
            };
            map.next_value_seed(NoDuplicates { path: &path })?;
            keys.insert(key);
        }
        Ok(())
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
