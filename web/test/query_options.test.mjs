// The viewer's query options: defaults, valid values, and malformed or extreme ones refused
// with a reason naming the option.
import assert from 'node:assert/strict';
import test from 'node:test';

import { queryCamera, queryChoice, queryNumber } from '../src/ui/query_options.js';

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

test('a choice is one of its values, else refused with them listed', () => {
    const trees = (query) => queryChoice(new URLSearchParams(query), 'trees', ['auto', 'terminals', 'billboards', 'none'], 'auto');
    assert.deepEqual(trees(''), { value: 'auto', problem: null });
    assert.deepEqual(trees('trees=none'), { value: 'none', problem: null });
    for (const query of ['trees=billbords', 'trees=', 'trees=NONE', 'trees=none%20']) {
        const { value, problem } = trees(query);
        assert.equal(value, 'auto', query);
        assert.match(problem, /refused: trees must be one of auto, terminals, billboards, none; using auto$/, query);
    }
});

test('a camera is five finite numbers with a pitch within a right angle, else refused', () => {
    const camera = (query) => queryCamera(new URLSearchParams(query));
    assert.deepEqual(camera(''), { value: null, problem: null });
    const { value, problem } = camera('camera=1,-2.5,1e7,90,-90');
    assert.equal(problem, null);
    assert.deepEqual(value.position, [1, -2.5, 1e7]);
    assert.equal(value.yaw, Math.PI / 2);
    assert.equal(value.pitch, -Math.PI / 2);
    for (const query of ['camera=1,2,3,4', 'camera=1,2,3,4,5,6', 'camera=1,2,,4,5', 'camera=a,2,3,4,5', 'camera=1,2,3,4,91', 'camera=1,2,3,Infinity,0', 'camera=', 'camera=1e400,0,0,0,0']) {
        const out = camera(query);
        assert.equal(out.value, null, query);
        assert.match(out.problem, /refused: camera must be x,y,z,yaw,pitch/, query);
    }
});
