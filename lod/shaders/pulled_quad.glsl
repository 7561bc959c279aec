// Vertex pulling for passes that draw one screen-facing or world rectangle per record: six
// vertices (two triangles) a record, fetched by gl_VertexID in one non-instanced draw. A
// software rasteriser runs its whole vertex pipeline once per instance, and at a few pixels a
// record that overhead dominates (3.4 us an instance on llvmpipe).

// The record this vertex belongs to.
uint pulledRecord() { return uint(gl_VertexID) / 6u; }

// The corner (0 to 3: bit 0 high x, bit 1 high y) of its rectangle this vertex is,
// counter-clockwise.
int pulledCorner() {
    const int corners[6] = int[](0, 1, 2, 2, 1, 3);
    return corners[uint(gl_VertexID) % 6u];
}

// Where a vertex goes that draws nothing (outside the clip volume).
const vec4 kNoVertex = vec4(2.0, 2.0, 2.0, 1.0);
