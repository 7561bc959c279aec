// The viewer's HTTP client of the hexlod API (docs/protocol.md, "HTTP API, version 1"): JSON
// views, binary content by URL, edits. Every error reply of the service is a JSON object with
// a reason (and for edits the field at fault); ApiError carries them to the UI. Counts every
// byte it downloads, for the stats panel.
export class ApiError extends Error {
    constructor(status, reason, field, headers) {
        super(status ? `${status}: ${reason}` : reason);
        this.name = 'ApiError';
        this.status = status;
        this.reason = reason;
        this.field = field;
        this.headers = headers;
    }
}

export const traffic = { bytes: 0, requests: 0, errors: 0 };

async function failure(response) {
    let reason = response.statusText || 'request failed';
    let field;
    try {
        const body = await response.json();
        if (body && typeof body.error === 'string') reason = body.error;
        field = body?.field;
    } catch {
        // Not JSON (a proxy's page): keep the status text.
    }
    ++traffic.errors;
    return new ApiError(response.status, reason, field, response.headers);
}

async function request(url, init) {
    ++traffic.requests;
    let response;
    try {
        response = await fetch(url, init);
    } catch (e) {
        if (e.name === 'AbortError') throw e;
        ++traffic.errors;
        throw new ApiError(0, `${url}: ${e.message}`);
    }
    if (!response.ok) throw await failure(response);
    return response;
}

export async function getJson(url, init = {}) {
    const response = await request(url, init);
    const text = await response.text();
    traffic.bytes += text.length;
    try {
        return JSON.parse(text);
    } catch (e) {
        throw new ApiError(response.status, `${url}: not JSON (${e.message})`);
    }
}

export async function getBinary(url, init = {}) {
    const response = await request(url, init);
    const bytes = await response.arrayBuffer();
    traffic.bytes += bytes.byteLength;
    return { bytes, version: Number(response.headers.get('X-Hexlod-Version') ?? 0) };
}

export async function postJson(url, body) {
    const response = await request(url, {
        method: 'POST',
        headers: { 'Content-Type': 'application/json' },
        body: JSON.stringify(body),
    });
    const reply = await response.json();
    traffic.bytes += JSON.stringify(reply).length;
    return reply;
}
