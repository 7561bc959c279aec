// The bytes a three.js geometry holds in its attribute arrays and index: what the viewer's
// content cache counts for the GPU buffers built from them (the arrays stay on the JS side too).
export function geometryBytes(geometry) {
    let bytes = geometry.index?.array.byteLength ?? 0;
    for (const attribute of Object.values(geometry.attributes)) bytes += attribute.array.byteLength;
    return bytes;
}
