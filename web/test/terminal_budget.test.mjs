// Which terminal sets the viewer admits within its cache budget (stream/terminal_budget.js).
import assert from 'node:assert/strict';
import test from 'node:test';

import { admitTerminalSets, bytesPerMember, DRAWN_PRIORITY_FACTOR } from '../src/stream/terminal_budget.js';

const set = (url, priority, bytes, drawn = false) => ({ url, priority, bytes, drawn });

test('sets are admitted highest priority first while their bytes fit', () => {
    const candidates = [set('far', 10, 40), set('near', 100, 50), set('mid', 50, 30)];
    assert.deepEqual([...admitTerminalSets(candidates, 80)], ['near', 'mid']);
    assert.deepEqual([...admitTerminalSets(candidates, 120)], ['near', 'mid', 'far']);
    assert.deepEqual([...admitTerminalSets(candidates, 29)], [], 'none fits');
});

test('a set that does not fit is passed over, and smaller ones after it take the room', () => {
    const candidates = [set('near', 100, 50), set('mid', 50, 60), set('far', 10, 40), set('farther', 5, 20)];
    assert.deepEqual([...admitTerminalSets(candidates, 100)], ['near', 'far']);
    assert.deepEqual([...admitTerminalSets([set('huge', 100, 500), set('small', 1, 5)], 100)], ['small']);
});

test('a set drawn now keeps its place against a slightly higher priority', () => {
    const drawn = set('drawn', 100, 50, true);
    assert.deepEqual([...admitTerminalSets([set('rival', 100 * DRAWN_PRIORITY_FACTOR * 0.99, 50), drawn], 60)], ['drawn']);
    assert.deepEqual([...admitTerminalSets([set('rival', 100 * DRAWN_PRIORITY_FACTOR * 1.01, 50), drawn], 60)], ['rival']);
});

test('extreme rooms and sizes: nothing fits in 0 or NaN, a NaN-sized set is never admitted, the same url once', () => {
    assert.equal(admitTerminalSets([set('a', 1, 1)], 0).size, 0);
    assert.equal(admitTerminalSets([set('a', 1, 1)], NaN).size, 0);
    assert.equal(admitTerminalSets([set('a', 1, 0)], 0).size, 1, 'an empty set fits anywhere');
    assert.deepEqual([...admitTerminalSets([set('a', 2, NaN), set('b', 1, 1)], 10)], ['b']);
    assert.deepEqual([...admitTerminalSets([set('a', 2, 5), set('a', 1, 5)], 6)], ['a']);
    assert.equal(admitTerminalSets([], 100).size, 0);
});

test('bytes per member come from the measured sets of the grammar, else 0', () => {
    const measured = [
        { grammar: 0, members: 10, bytes: 1000 },
        { grammar: 0, members: 30, bytes: 5000 },
        { grammar: 1, members: 0, bytes: 100 }, // no members: not counted
        { grammar: 1, members: NaN, bytes: 100 },
    ];
    const perMember = bytesPerMember(measured);
    assert.equal(perMember(0), 6000 / 40);
    assert.equal(perMember(1), 0, 'none of its own: free, so that its first set is fetched and measured');
    assert.equal(bytesPerMember(new Map([['u', { grammar: 2, members: 4, bytes: 8 }]]).values())(2), 2, 'any iterable');
});
