#include "footprint_shapes.h"

namespace hexlod::scene::detail {

Polygon box(double w, double d) {
    return {{0, 0}, {w, 0}, {w, d}, {0, d}};
}

Polygon lShape(double w, double d, double wing) {
    return {{0, 0}, {w, 0}, {w, wing}, {wing, wing}, {wing, d}, {0, d}};
}

Polygon uShape(double w, double d, double wing) {
    return {{0, 0}, {w, 0}, {w, d}, {w - wing, d}, {w - wing, wing}, {wing, wing}, {wing, d}, {0, d}};
}

Polygon tShape(double w, double d, double stem) {
    const double a = 0.5 * (w - stem), bar = 0.4 * d;
    return {{a, 0}, {a + stem, 0}, {a + stem, d - bar}, {w, d - bar},
            {w, d}, {0, d},        {0, d - bar},        {a, d - bar}};
}

} // namespace hexlod::scene::detail
