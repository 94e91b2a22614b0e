//! The filters that derive text, as a page's templates see them: they return
//! plain text, which is escaped where it is shown, never markup.
//!
//! Minijinja keeps a filter's result markup (a "safe" string, written as it
//! is) when its input or one of its arguments is markup, and markup is easy
//! to come by: a `{% set %}` block, a macro's or `caller()`'s output are the
//! template's own output, captured. So `report.name|replace("&lt;", lt)`,
//! with `lt` a `{% set %}` block holding `<`, would turn the escaped
//! characters of a value back into markup, as would `format`, `join` or
//! `split` and `~`. Here those filters read markup as the text it is and
//! return plain text; the only markup left is the template's own output
//! captured whole, and `~` or `*` of it. `escape` is plain too: every value
//! is escaped where it is shown, once.
//!
//! The filters whose result can be larger than their input (`replace`,
//! `indent`, `format`) check its size first, against [`TEXT_LIMIT`] (and,
//! `replace` and `indent`, the page's fuel).

use minijinja::value::{FunctionArgs, Kwargs, Rest, StringInput, ValueKind, ValueOrKwargs};
use minijinja::{Environment, Error, ErrorKind, Output, State, Value, filters};

/// The largest text a filter may return, in bytes: far more than a page
/// shows (the bundled pages are at most 2.3 MB), and small enough that the
/// copies a page makes of it stay within its memory.
pub(super) const TEXT_LIMIT: usize = 16 << 20;

/// Replaces the builtin filters that derive text from markup with ones that
/// return plain text (see the module documentation).
pub(super) fn register(env: &mut Environment<'static>) {
    env.add_filter("escape", escape);
    env.add_filter("e", escape);
    env.add_filter("replace", replace);
    env.add_filter("indent", indent);
    env.add_filter("format", format);
    // The builtins, given plain text: their results are plain text too, and
    // bounded by their input (or, `join`, charged to the fuel).
    let builtins = [
        ("join", Value::from_function(filters::join)),
        ("upper", Value::from_function(filters::upper)),
        ("lower", Value::from_function(filters::lower)),
        ("capitalize", Value::from_function(filters::capitalize)),
        ("trim", Value::from_function(filters::trim)),
        ("split", Value::from_function(filters::split)),
        ("lines", Value::from_function(filters::lines)),
        ("first", Value::from_function(filters::first)),
        ("last", Value::from_function(filters::last)),
        ("reverse", Value::from_function(filters::reverse)),
    ];
    for (name, builtin) in builtins {
        env.add_filter(name, move |state: &mut State, args: Rest<ValueOrKwargs>| {
            builtin
                .call(state, &plain_args(args)?)
                .and_then(|result| plain_items(&result))
        });
    }
}

/// A filter's arguments, their markup read as text ([`plain_items`]).
fn plain_args(args: Rest<ValueOrKwargs>) -> Result<Vec<Value>, Error> {
    args.iter().map(|arg| plain_items(arg)).collect()
}

/// `value` with markup read as the text it is: a markup string as a plain
/// one, a sequence or keyword arguments with their markup items plain;
/// anything else as it is.
fn plain_items(value: &Value) -> Result<Value, Error> {
    Ok(match value.kind() {
        ValueKind::Seq => Value::from_iter(value.try_iter()?.map(|item| plain(&item))),
        ValueKind::Map => match Kwargs::try_from(value.clone()) {
            Ok(kwargs) => {
                let plain: Kwargs = kwargs
                    .args()
                    .map(|key| Ok((key, plain(&kwargs.peek::<Value>(key)?))))
                    .collect::<Result<_, Error>>()?;
                Value::from(plain)
            }
            Err(_) => value.clone(),
        },
        _ => plain(value),
    })
}

/// A markup string as plain text; anything else as it is.
fn plain(value: &Value) -> Value {
    match value.as_str() {
        Some(text) if value.is_safe() => Value::from(text),
        _ => value.clone(),
    }
}

/// `escape`, `e`: the value as plain text, escaped where it is shown.
fn escape(state: &State, value: &Value) -> Result<Value, Error> {
    Ok(Value::from(StringInput::new(state, value)?.as_str()))
}

/// `replace(from, to[, count])`: every occurrence of `from` (or the first
/// `count`) replaced by `to`, in plain text.
fn replace(state: &State, args: Rest<ValueOrKwargs>) -> Result<Value, Error> {
    let args = args.0.into_iter().map(Value::from).collect::<Vec<_>>();
    let (value, from, to, count, kwargs) =
        <(StringInput, StringInput, StringInput, Option<i64>, Kwargs)>::from_values(Some(state), &args)?;
    let count = match count {
        Some(count) => Some(count),
        None => kwargs.get::<Option<i64>>("count")?,
    };
    kwargs.assert_all_used()?;
    let count = count
        .and_then(|count| usize::try_from(count).ok())
        .unwrap_or(usize::MAX);
    let (value, from, to) = (value.as_str(), from.as_str(), to.as_str());
    if to.len() > from.len() {
        let matches = value.matches(from).take(count).count();
        charge(
            state,
            value
                .len()
                .saturating_add(matches.saturating_mul(to.len() - from.len())),
        )?;
    }
    Ok(Value::from(value.replacen(from, to, count)))
}

/// `indent(width=4, first=false, blank=false)`: each line but the first (or
/// every line) after `width` spaces, blank lines too with `blank`, in plain
/// text, as minijinja's.
fn indent(state: &State, args: Rest<ValueOrKwargs>) -> Result<Value, Error> {
    let args = args.0.into_iter().map(Value::from).collect::<Vec<_>>();
    let (value, width, first, blank, kwargs) =
        <(StringInput, Option<usize>, Option<bool>, Option<bool>, Kwargs)>::from_values(Some(state), &args)?;
    let width = match width {
        Some(width) => width,
        None => kwargs.get::<Option<usize>>("width")?.unwrap_or(4),
    };
    let first = first.map_or_else(|| kwargs.get::<Option<bool>>("first"), |f| Ok(Some(f)))?;
    let blank = blank.map_or_else(|| kwargs.get::<Option<bool>>("blank"), |b| Ok(Some(b)))?;
    kwargs.assert_all_used()?;
    let text = value.as_str();
    let text = text.strip_suffix('\n').unwrap_or(text);
    let text = text.strip_suffix('\r').unwrap_or(text);
    let lines = text.split('\n').count();
    charge(state, width.saturating_mul(lines).saturating_add(text.len()))?;
    let spaces = " ".repeat(width);
    let mut output = String::new();
    for (number, line) in text.split('\n').enumerate() {
        if number > 0 {
            output.push('\n');
        }
        let is_blank = line.is_empty() || line == "\r";
        if (number > 0 || first.unwrap_or(false)) && (!is_blank || blank.unwrap_or(false)) {
            output.push_str(&spaces);
        }
        output.push_str(line);
    }
    Ok(Value::from(output))
}

/// `format(args…)`: minijinja's printf-style `format`, given plain text, once
/// its widths and precisions are known to stay within [`TEXT_LIMIT`] (the
/// sum of every number in the format: `%1270000000s` is refused).
fn format(state: &mut State, args: Rest<ValueOrKwargs>) -> Result<Value, Error> {
    let args = plain_args(args)?;
    let format = args.first().and_then(Value::as_str).unwrap_or_default();
    let widths = format
        .split(|c: char| !c.is_ascii_digit())
        .filter(|digits| !digits.is_empty())
        .map(|digits| digits.parse::<usize>().unwrap_or(usize::MAX))
        .fold(format.len(), usize::saturating_add);
    check_size(widths)?;
    Value::from_function(filters::format).call(state, &args)
}

/// Writes `value` escaped, as minijinja does, once the page's fuel is known
/// to pay for it (64 bytes to the unit, each escaped character at most 6):
/// a value too large for what is left fails where it is shown, not after a
/// copy of it is made in the page, at the line of the block that showed it.
pub(super) fn affordable(out: &mut Output, state: &mut State, value: &Value) -> Result<(), Error> {
    if let (Some(text), Some((_, remaining))) = (value.as_str(), state.fuel_levels()) {
        let special = text.bytes().filter(|b| b"&<>\"'/".contains(b)).count();
        let bytes = text.len().saturating_add(special.saturating_mul(5));
        if bytes as u64 >= remaining.saturating_mul(64) {
            return Err(Error::from(ErrorKind::OutOfFuel));
        }
    }
    minijinja::escape_formatter(out, state, value)
}

/// Refuses a text of `bytes` bytes past [`TEXT_LIMIT`].
fn check_size(bytes: usize) -> Result<(), Error> {
    if bytes > TEXT_LIMIT {
        return Err(Error::new(
            ErrorKind::InvalidOperation,
            format!("the text would be {bytes} bytes, more than a filter may make ({TEXT_LIMIT})"),
        ));
    }
    Ok(())
}

/// Refuses a text of `bytes` bytes past [`TEXT_LIMIT`], and charges it to the
/// page's fuel (64 bytes to the unit) before it is made.
fn charge(state: &State, bytes: usize) -> Result<(), Error> {
    check_size(bytes)?;
    state.consume_fuel(bytes as u64 / 64)
}
