// Numeric options of the viewer's query string (?budget=MiB, ?concurrency=N). A value that is
// not a number within its range is refused with a reason naming the option, and its default
// is used instead: `Number('x')` is NaN, and a budget of NaN evicted every payload on every
// update while a concurrency of NaN never started a fetch.

// `spec`: {fallback, min, max, integer}. Returns {value, problem}: problem is null when the
// option is absent or valid, else a sentence for the messages panel.
export function queryNumber(params, name, { fallback, min, max, integer = false }) {
    const text = params.get(name);
    if (text === null) return { value: fallback, problem: null };
    const value = text.trim() === '' ? NaN : Number(text);
    const kind = integer ? 'an integer' : 'a number';
    if (!Number.isFinite(value) || value < min || value > max || (integer && !Number.isInteger(value)))
        return { value: fallback, problem: `?${name}=${text} refused: ${name} must be ${kind} from ${min} to ${max}; using ${fallback}` };
    return { value, problem: null };
}
