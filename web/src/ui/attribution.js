// Data attribution: whatever /api/v1/scene lists in `attributions` (imported OpenStreetMap data
// gives "© OpenStreetMap contributors"), always visible while the scene is shown.
export function showAttribution(element, scene) {
    const lines = [...(scene.attributions ?? [])];
    const osm = (scene.notes ?? []).some((n) => /openstreetmap|\.osm\b|osm\.pbf/i.test(n));
    if (osm && !lines.some((l) => /OpenStreetMap/.test(l))) lines.push('© OpenStreetMap contributors');
    element.textContent = lines.join(' · ');
    element.hidden = lines.length === 0;
}
