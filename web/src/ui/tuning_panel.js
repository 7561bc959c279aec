// The selection and tuning panel: what is selected (building id, grammar, cell, and the current
// parameters from GET /api/v1/buildings/{id}), and one slider per parameter the grammar declares,
// its range the declared [min, max] (/api/v1/scene). Releasing a slider posts an edit for the
// chosen scope (the building, its cell, or its whole grammar); a refused edit shows the
// service's reason under the sliders. Undo posts /api/v1/edits/undo.
import { getJson } from '../api.js';

export class TuningPanel {
    constructor(element, { scene, edits, messages }) {
        this.element = element;
        this.scene = scene;
        this.edits = edits;
        this.messages = messages;
        this.selection = null;
    }

    grammar(index) {
        return this.scene.grammars.find((g) => g.index === index);
    }

    async select(selection) {
        this.selection = selection;
        if (!selection) return this.render(null, null);
        let building = null;
        if (selection.building !== undefined) {
            try {
                building = await getJson(`/api/v1/buildings/${selection.building}`);
            } catch (e) {
                this.messages.add(`building ${selection.building}: ${e.reason ?? e.message}`);
            }
        }
        if (this.selection !== selection) return; // another click meanwhile
        this.render(selection, building);
    }

    render(selection, building) {
        const root = this.element;
        root.replaceChildren();
        if (!selection) {
            root.append(text('h2', 'Selection'), text('p', 'Click a building or the ground to select it or its cell.'));
            return;
        }
        const grammarIndex = building?.grammar ?? selection.grammar;
        const grammar = grammarIndex !== undefined ? this.grammar(grammarIndex) : null;
        const cell = building?.cell ?? selection.cell;
        root.append(text('h2', building ? `Building ${building.id}` : `Cell ${cell?.join(', ')}`));
        const facts = [];
        if (building) facts.push(`grammar ${building.grammar_name} (${building.grammar})`, `cell ${building.cell.join(', ')}`, `batch v${building.batch.version} ${building.batch.key}`);
        else if (grammar) facts.push(`grammar ${grammar.label ?? grammar.name} (${grammar.index})`);
        root.append(text('p', facts.join(' · '), 'facts'));
        if (!grammar) return;

        const scope = document.createElement('select');
        scope.id = 'edit-scope';
        const scopes = building ? ['building', 'cell', 'grammar'] : ['cell', 'grammar'];
        for (const s of scopes) scope.append(new Option(`apply to: ${s}`, s));
        const undo = document.createElement('button');
        undo.textContent = 'Undo last edit';
        undo.onclick = () => this.run(() => this.edits.undo());
        const error = text('div', '', 'edit-error');
        error.id = 'edit-error';
        root.append(scope, undo, error);

        for (const p of grammar.parameters) {
            const value = building?.params?.[p.name] ?? p.default;
            const row = document.createElement('label');
            row.className = 'param';
            const slider = document.createElement('input');
            slider.type = 'range';
            slider.min = p.min;
            slider.max = p.max;
            slider.step = sliderStep(p);
            slider.value = value;
            slider.dataset.param = p.name;
            const shown = text('span', formatValue(value), 'value');
            slider.oninput = () => (shown.textContent = formatValue(Number(slider.value)));
            slider.onchange = () => {
                const selector =
                    scope.value === 'building' ? { buildings: [building.id] }
                    : scope.value === 'cell' ? { cell: cell }
                    : { grammar: grammar.index };
                this.post(selector, { [p.name]: Number(slider.value) });
            };
            row.append(text('span', p.name, 'name'), slider, shown);
            root.append(row);
        }
    }

    // What a slider does on release; a refused edit's reason goes under the sliders.
    post(selector, params) {
        const error = this.element.querySelector('#edit-error');
        if (error) error.textContent = '';
        return this.run(() => this.edits.edit(selector, params), error);
    }

    async run(action, errorElement) {
        try {
            const reply = await action();
            this.messages.add(`${reply.op} ${reply.seq}: ${reply.changed.length} batches changed`, 'notice');
            if (this.selection) this.select(this.selection); // current values and version
        } catch (e) {
            const reason = e.reason ?? e.message;
            if (errorElement) errorElement.textContent = reason;
            this.messages.add(`edit refused: ${reason}`);
        }
    }
}

function text(tag, content, className) {
    const element = document.createElement(tag);
    element.textContent = content;
    if (className) element.className = className;
    return element;
}

function sliderStep(p) {
    const whole = [p.min, p.max, p.default].every(Number.isInteger);
    return whole && p.max - p.min >= 4 ? 1 : (p.max - p.min) / 200;
}

function formatValue(v) {
    return Number.isInteger(v) ? String(v) : v.toFixed(3).replace(/0+$/, '').replace(/\.$/, '');
}
