// The viewer's numeric query options: defaults, valid values, and malformed or extreme ones
// refused with a reason naming the option.
import assert from 'node:assert/strict';
import test from 'node:test';

import { queryNumber } from '../src/ui/query_numbers.js';

const budget = { fallback: 384, min: 0, max: 65536 };
const concurrency = { fallback: 6, min: 1, max: 64, integer: true };
const parse = (query, name, spec) => queryNumber(new URLSearchParams(query), name, spec);

test('an absent option takes its default without a problem', () => {
    assert.deepEqual(parse('', 'budget', budget), { value: 384, problem: null });
});

test('values within range are taken, the bounds included', () => {
    for (const [query, value] of [['budget=0', 0], ['budget=65536', 65536], ['budget=12.5', 12.5], ['budget=%201e3', 1000]])
        assert.deepEqual(parse(query, 'budget', budget), { value, problem: null }, query);
    assert.deepEqual(parse('concurrency=1', 'concurrency', concurrency), { value: 1, problem: null });
});

test('malformed and extreme values are refused with the option named and the default used', () => {
    const bad = ['budget=', 'budget=abc', 'budget=NaN', 'budget=Infinity', 'budget=-1', 'budget=65537', 'budget=1e400', 'budget=0x', 'budget=%20'];
    for (const query of bad) {
        const { value, problem } = parse(query, 'budget', budget);
        assert.equal(value, 384, query);
        assert.match(problem, /^\?budget=.* refused: budget must be a number from 0 to 65536; using 384$/, query);
    }
    for (const query of ['concurrency=0', 'concurrency=2.5', 'concurrency=65', 'concurrency=six']) {
        const { value, problem } = parse(query, 'concurrency', concurrency);
        assert.equal(value, 6, query);
        assert.match(problem, /concurrency must be an integer from 1 to 64/, query);
    }
});
