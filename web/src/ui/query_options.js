// Options of the viewer's query string (?budget=MiB, ?concurrency=N, ?trees=..., ?mode=...,
// ?camera=...). A value the viewer cannot use is refused with a reason naming the option, and
// its default is used instead: `Number('x')` is NaN, and a budget of NaN evicted every payload
// on every update while a concurrency of NaN never started a fetch; a misspelt choice or
// camera fell back to the default without a word.

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

// One of `choices` (strings), or `fallback` when absent. Returns {value, problem}.
export function queryChoice(params, name, choices, fallback) {
    const text = params.get(name);
    if (text === null || choices.includes(text)) return { value: text ?? fallback, problem: null };
    return { value: fallback, problem: `?${name}=${text} refused: ${name} must be one of ${choices.join(', ')}; using ${fallback}` };
}

// ?camera=x,y,z,yaw,pitch: five finite numbers (metres, degrees), yaw and pitch in radians
// out; null when absent or refused (the caller's opening view). Returns {value, problem}.
export function queryCamera(params) {
    const text = params.get('camera');
    if (text === null) return { value: null, problem: null };
    const v = text.split(',').map((part) => (part.trim() === '' ? NaN : Number(part)));
    if (v.length !== 5 || !v.every(Number.isFinite) || Math.abs(v[4]) > 90)
        return { value: null, problem: `?camera=${text} refused: camera must be x,y,z,yaw,pitch (metres; degrees, pitch from -90 to 90); using the opening view` };
    return { value: { position: v.slice(0, 3), yaw: (v[3] * Math.PI) / 180, pitch: (v[4] * Math.PI) / 180 }, problem: null };
}
