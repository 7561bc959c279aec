// Vertex pulling for passes that draw one screen-facing or world rectangle per record: four
// vertices a record, fetched by gl_VertexID in one non-instanced indexed draw over a quad
// index buffer (quad_indices.h; base vertex 4 x the first record). A software rasteriser runs
// its whole vertex pipeline once per instance, and at a few pixels a record that overhead
// dominates (3.4 us an instance on llvmpipe); indexed, each corner is shaded once.

// The record this vertex belongs to.
uint pulledRecord() { return uint(gl_VertexID) / 4u; }

// The corner (0 to 3: bit 0 high x, bit 1 high y) of its rectangle this vertex is; the index
// buffer makes both triangles counter-clockwise.
int pulledCorner() { return int(uint(gl_VertexID) % 4u); }

// Where a vertex goes that draws nothing (outside the clip volume).
const vec4 kNoVertex = vec4(2.0, 2.0, 2.0, 1.0);
