//! A small JSON Schema (2020-12) validator for the keywords
//! docs/shatter-fracture.schema.json uses: `$ref` (local), `type`, `required`,
//! `properties`, `additionalProperties`, `items`, `minItems`, `maxItems`, `minimum`,
//! `exclusiveMinimum`, `maximum`, `const`, `enum`, `minLength`. Any other keyword in the
//! schema is an error, so the schema cannot silently use one this check ignores.
//! (The `jsonschema` crate would pull in dozens of crates for this.)

use serde_json::Value;

const KNOWN: &[&str] = &[
    "$schema",
    "$id",
    "$defs",
    "$ref",
    "$comment",
    "title",
    "description",
    "type",
    "required",
    "properties",
    "additionalProperties",
    "items",
    "minItems",
    "maxItems",
    "minimum",
    "exclusiveMinimum",
    "maximum",
    "const",
    "enum",
    "minLength",
    "default",
    "examples",
];

/// Validates `value` against the schema at `pointer` (`#/$defs/root`) of `schema`.
pub fn validate(schema: &Value, pointer: &str, value: &Value) -> Result<(), String> {
    let sub = resolve(schema, pointer)?;
    check(schema, sub, value, "$")
}

fn resolve<'s>(schema: &'s Value, pointer: &str) -> Result<&'s Value, String> {
    let p = pointer
        .strip_prefix('#')
        .ok_or_else(|| format!("only local $refs: {pointer}"))?;
    schema
        .pointer(p)
        .ok_or_else(|| format!("$ref {pointer} does not resolve"))
}

fn type_ok(t: &str, v: &Value) -> bool {
    match t {
        "object" => v.is_object(),
        "array" => v.is_array(),
        "string" => v.is_string(),
        "boolean" => v.is_boolean(),
        "null" => v.is_null(),
        "number" => v.is_number(),
        "integer" => v.is_u64() || v.is_i64() || v.as_f64().is_some_and(|x| x.fract() == 0.0),
        _ => false,
    }
}

fn check(root: &Value, s: &Value, v: &Value, at: &str) -> Result<(), String> {
    let Some(obj) = s.as_object() else {
        return match s {
            Value::Bool(true) => Ok(()),
            Value::Bool(false) => Err(format!("{at}: not allowed")),
            _ => Err(format!("{at}: a schema that is not an object")),
        };
    };
    if let Some(k) = obj.keys().find(|k| !KNOWN.contains(&k.as_str())) {
        return Err(format!(
            "schema keyword `{k}` is not supported by this validator"
        ));
    }
    if let Some(r) = obj.get("$ref").and_then(Value::as_str) {
        check(root, resolve(root, r)?, v, at)?;
    }
    if let Some(t) = obj.get("type") {
        let ok = match t {
            Value::String(t) => type_ok(t, v),
            Value::Array(ts) => ts.iter().filter_map(Value::as_str).any(|t| type_ok(t, v)),
            _ => false,
        };
        if !ok {
            return Err(format!("{at}: {v} is not of type {t}"));
        }
    }
    if let Some(c) = obj.get("const")
        && c != v
    {
        return Err(format!("{at}: {v} is not {c}"));
    }
    if let Some(e) = obj.get("enum").and_then(Value::as_array)
        && !e.contains(v)
    {
        return Err(format!("{at}: {v} is not one of {e:?}"));
    }
    if let Some(x) = v.as_f64() {
        if let Some(m) = obj.get("minimum").and_then(Value::as_f64)
            && x < m
        {
            return Err(format!("{at}: {x} < minimum {m}"));
        }
        if let Some(m) = obj.get("exclusiveMinimum").and_then(Value::as_f64)
            && x <= m
        {
            return Err(format!("{at}: {x} <= exclusiveMinimum {m}"));
        }
        if let Some(m) = obj.get("maximum").and_then(Value::as_f64)
            && x > m
        {
            return Err(format!("{at}: {x} > maximum {m}"));
        }
    }
    if let (Some(s), Some(m)) = (v.as_str(), obj.get("minLength").and_then(Value::as_u64))
        && (s.chars().count() as u64) < m
    {
        return Err(format!("{at}: shorter than {m}"));
    }
    if let Some(items) = v.as_array() {
        let n = items.len() as u64;
        if let Some(m) = obj.get("minItems").and_then(Value::as_u64)
            && n < m
        {
            return Err(format!("{at}: {n} items, at least {m} required"));
        }
        if let Some(m) = obj.get("maxItems").and_then(Value::as_u64)
            && n > m
        {
            return Err(format!("{at}: {n} items, at most {m} allowed"));
        }
        if let Some(item) = obj.get("items") {
            for (i, x) in items.iter().enumerate() {
                check(root, item, x, &format!("{at}[{i}]"))?;
            }
        }
    }
    if let Some(map) = v.as_object() {
        if let Some(req) = obj.get("required").and_then(Value::as_array) {
            for r in req.iter().filter_map(Value::as_str) {
                if !map.contains_key(r) {
                    return Err(format!("{at}: missing required property `{r}`"));
                }
            }
        }
        let props = obj.get("properties").and_then(Value::as_object);
        for (k, x) in map {
            match props.and_then(|p| p.get(k)) {
                Some(p) => check(root, p, x, &format!("{at}.{k}"))?,
                None => {
                    if let Some(extra) = obj.get("additionalProperties") {
                        check(root, extra, x, &format!("{at}.{k}"))?;
                    }
                }
            }
        }
    }
    Ok(())
}
