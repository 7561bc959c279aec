// Fly and walk cameras, z-up. Fly: W/S along the view, A/D sideways, E/Q (or Space/C) up and
// down, Shift ×4, the wheel or +/- scale the speed. Walk: the same keys on the ground, the eye
// kept 1.7 m above the ground of the cell it stands in. The mouse looks while a button is held
// (a click without a drag is left to the picker); F toggles the mode. The position is a triple
// of doubles: World renders everything relative to it.
export const EYE_HEIGHT = 1.7;

export class CameraControls {
    constructor(element, { position, yaw = 0, pitch = 0, groundAt = () => 0 }) {
        this.position = position.slice();
        this.yaw = yaw; // radians, 0 looks along +x, counter-clockwise from above
        this.pitch = pitch;
        this.mode = 'fly';
        this.speed = 40; // m/s
        this.fovY = Math.PI / 3;
        this.groundAt = groundAt;
        this.keys = new Set();
        this.dragged = 0;
        this.onModeChange = null;
        element.addEventListener('contextmenu', (e) => e.preventDefault());
        element.addEventListener('pointerdown', (e) => {
            this.looking = { x: e.clientX, y: e.clientY };
            this.dragged = 0;
        });
        window.addEventListener('pointerup', () => (this.looking = null));
        window.addEventListener('pointermove', (e) => {
            if (!this.looking) return;
            const dx = e.clientX - this.looking.x, dy = e.clientY - this.looking.y;
            this.looking = { x: e.clientX, y: e.clientY };
            this.dragged += Math.abs(dx) + Math.abs(dy);
            this.yaw -= dx * 0.004;
            this.pitch = Math.min(Math.max(this.pitch - dy * 0.004, -1.55), 1.55);
        });
        element.addEventListener('wheel', (e) => {
            e.preventDefault();
            this.scaleSpeed(e.deltaY < 0 ? 1.25 : 0.8);
        }, { passive: false });
        window.addEventListener('keydown', (e) => {
            if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement) return;
            const key = e.key.toLowerCase();
            if (key === 'f') this.setMode(this.mode === 'fly' ? 'walk' : 'fly');
            else if (key === '+' || key === '=') this.scaleSpeed(1.25);
            else if (key === '-') this.scaleSpeed(0.8);
            else this.keys.add(key);
        });
        window.addEventListener('keyup', (e) => this.keys.delete(e.key.toLowerCase()));
        window.addEventListener('blur', () => this.keys.clear());
    }

    scaleSpeed(factor) {
        this.speed = Math.min(Math.max(this.speed * factor, 0.5), 5000);
    }

    setMode(mode) {
        this.mode = mode;
        if (mode === 'walk') {
            this.speed = Math.min(this.speed, 6);
            this.position[2] = this.groundAt(this.position) + EYE_HEIGHT;
        }
        this.onModeChange?.(mode);
    }

    forward() {
        const c = Math.cos(this.pitch);
        return [c * Math.cos(this.yaw), c * Math.sin(this.yaw), Math.sin(this.pitch)];
    }

    set({ position, yaw, pitch }) {
        if (position) this.position = position.slice();
        if (yaw !== undefined) this.yaw = yaw;
        if (pitch !== undefined) this.pitch = pitch;
        if (this.mode === 'walk') this.position[2] = this.groundAt(this.position) + EYE_HEIGHT;
    }

    update(dt) {
        const k = this.keys;
        const step = this.speed * (k.has('shift') ? 4 : 1) * dt;
        const f = this.forward();
        const flat = [Math.cos(this.yaw), Math.sin(this.yaw), 0];
        const along = this.mode === 'walk' ? flat : f;
        const right = [Math.sin(this.yaw), -Math.cos(this.yaw), 0];
        let move = [0, 0, 0];
        const add = (v, s) => (move = move.map((m, i) => m + v[i] * s));
        if (k.has('w') || k.has('arrowup')) add(along, 1);
        if (k.has('s') || k.has('arrowdown')) add(along, -1);
        if (k.has('d') || k.has('arrowright')) add(right, 1);
        if (k.has('a') || k.has('arrowleft')) add(right, -1);
        if (this.mode === 'fly') {
            if (k.has('e') || k.has(' ')) add([0, 0, 1], 1);
            if (k.has('q') || k.has('c')) add([0, 0, 1], -1);
        }
        const length = Math.hypot(...move);
        if (length > 0) for (let i = 0; i < 3; ++i) this.position[i] += (move[i] / length) * step;
        if (this.mode === 'walk') this.position[2] = this.groundAt(this.position) + EYE_HEIGHT;
        return length > 0;
    }

    view(viewportHeight) {
        return {
            position: this.position,
            forward: this.forward(),
            fovY: this.fovY,
            near: this.mode === 'walk' ? 0.2 : 0.5,
            viewportHeight,
        };
    }
}
