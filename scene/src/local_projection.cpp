#include "hexlod/scene/imported_footprints.h"

#include <cmath>

namespace hexlod::scene {
namespace {

constexpr double kSemiMajor = 6378137.0;            // WGS84 a
constexpr double kEccentricity2 = 6.69437999014e-3; // WGS84 e^2
constexpr double kPi = 3.14159265358979323846;

} // namespace

LocalProjection LocalProjection::about(double lon0, double lat0) {
    const double phi = lat0 * kPi / 180.0;
    const double s = std::sin(phi);
    const double w = 1.0 - kEccentricity2 * s * s;
    const double primeVertical = kSemiMajor / std::sqrt(w);
    const double meridional = kSemiMajor * (1.0 - kEccentricity2) / (w * std::sqrt(w));
    LocalProjection p;
    p.lon0 = lon0;
    p.lat0 = lat0;
    p.metresPerDegreeLon = primeVertical * std::cos(phi) * kPi / 180.0;
    p.metresPerDegreeLat = meridional * kPi / 180.0;
    return p;
}

void appendProjected(const std::vector<LonLatFootprint>& footprints, ImportedFootprints& out) {
    if (footprints.empty()) return;
    glm::dvec2 lo(1e9), hi(-1e9);
    for (const LonLatFootprint& f : footprints) {
        for (const glm::dvec2& q : f.outer) lo = glm::min(lo, q), hi = glm::max(hi, q);
    }
    const glm::dvec2 centre = 0.5 * (lo + hi);
    const LocalProjection projection = LocalProjection::about(centre.x, centre.y);
    out.originLon = centre.x;
    out.originLat = centre.y;
    for (const LonLatFootprint& f : footprints) {
        grammar::BuildingInput b;
        b.id = static_cast<uint32_t>(out.buildings.size());
        for (const glm::dvec2& q : f.outer) b.footprint.push_back(projection.project(q.x, q.y));
        out.buildings.push_back(std::move(b));
        out.heights.push_back(f.height);
        out.levels.push_back(f.levels);
    }
}

} // namespace hexlod::scene
