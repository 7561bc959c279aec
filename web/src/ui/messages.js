// Messages to the user: errors (a malformed payload, a refused edit, an unreachable service)
// and notices, newest first, a few at a time; none of them stops the viewer. Notices fade
// after a while, errors stay until newer messages push them out.
export class Messages {
    constructor(element) {
        this.element = element;
        this.items = [];
    }

    add(text, kind = 'error') {
        const item = { text, kind, at: new Date().toLocaleTimeString() };
        this.items.unshift(item);
        this.items.length = Math.min(this.items.length, 6);
        if (kind === 'notice') setTimeout(() => this.drop(item), 8000);
        this.render();
    }

    drop(item) {
        this.items = this.items.filter((m) => m !== item);
        this.render();
    }

    render() {
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
