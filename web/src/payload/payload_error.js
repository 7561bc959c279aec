// The one error type of the payload decoders: a payload that is malformed, truncated, foreign
// or corrupt. Its message says why, in the words of the C++ decoder where it has one, so the
// viewer can show it and go on with the other cells.
export class PayloadError extends Error {
    constructor(message) {
        super(message);
        this.name = 'PayloadError';
    }
}
