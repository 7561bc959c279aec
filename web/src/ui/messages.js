// Messages to the user: errors (a malformed payload, a refused edit, an unreachable service)
// and notices, newest first, a few at a time; none of them stops the viewer.
export class Messages {
    constructor(element) {
        this.element = element;
        this.items = [];
    }

    add(text, kind = 'error') {
        this.items.unshift({ text, kind, at: new Date().toLocaleTimeString() });
        this.items.length = Math.min(this.items.length, 6);
        this.element.replaceChildren(
            ...this.items.map((m) => {
                const div = document.createElement('div');
                div.className = `message ${m.kind}`;
                div.textContent = `${m.at} ${m.text}`;
                return div;
            }),
        );
    }
}
