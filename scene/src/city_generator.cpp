#include "hexlod/scene/city_generator.h"

#include "city_lots.h"
#include "hexlod/grammar/position_hash.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace hexlod::scene {
namespace {

using detail::Lot;
using detail::Rect;
using grammar::combineKey;
using grammar::unitFloat;

constexpr uint64_t kGridTag = 0x971dull, kBlockTag = 0xb10cull, kParkTag = 0x9a4cull;
constexpr uint64_t kDistrictTag = 0xd157ull, kLotTag = 0x1075ull, kFloorsTag = 0xf100ull;
constexpr uint64_t kStreetTreeTag = 0x7ee5ull, kParkTreeTag = 0x7ee9ull, kTreeKeepTag = 0x4ee9ull;

// Natural tree spacing before the generator has to densify to reach the requested count.
constexpr double kStreetTreeSpacing = 12.5, kParkTreeSpacing = 12.0;

void require(bool ok, const std::string& option, const char* what) {
    if (!ok) throw std::invalid_argument("city option " + option + " " + what);
}

bool positiveFinite(double v) {
    return std::isfinite(v) && v > 0.0;
}

void validate(const CityOptions& o) {
    require(!o.districts.empty(), "districts", "must list at least one district");
    require(positiveFinite(o.blockSize), "blockSize", "must be a finite positive number");
    require(positiveFinite(o.streetWidth), "streetWidth", "must be a finite positive number");
    require(o.blockSize > o.streetWidth, "blockSize", "must exceed streetWidth");
    require(std::isfinite(o.parkShare) && o.parkShare >= 0.0 && o.parkShare <= 0.9, "parkShare",
            "must lie in [0, 0.9]");
    require(o.species > 0 || o.trees == 0, "species", "must be positive when trees are requested");
    double total = 0.0;
    for (size_t k = 0; k < o.districts.size(); ++k) {
        const DistrictSpec& d = o.districts[k];
        const std::string name = "districts[" + std::to_string(k) + "].";
        require(std::isfinite(d.share) && d.share >= 0.0, name + "share", "must be finite and non-negative");
        require(positiveFinite(d.lotWidth), name + "lotWidth", "must be a finite positive number");
        require(positiveFinite(d.lotDepth), name + "lotDepth", "must be a finite positive number");
        require(std::isfinite(d.minFloors), name + "minFloors", "must be finite");
        require(std::isfinite(d.maxFloors), name + "maxFloors", "must be finite");
        require(d.minFloors <= d.maxFloors, name + "minFloors", "must not exceed maxFloors");
        total += d.share;
    }
    require(total > 0.0, "districts[].share", "must sum to a positive number");
}

// Street centrelines: line i of either axis lies near i * blockSize. The jitter keeps every
// block at least 70% of its nominal width between the kerbs.
struct StreetGrid {
    uint64_t key;
    double spacing, jitter;
    double line(int axis, int64_t i) const {
        const float u =
            unitFloat(combineKey(combineKey(key, static_cast<uint64_t>(axis)), static_cast<uint64_t>(i)));
        return spacing * static_cast<double>(i) + jitter * (2.0 * u - 1.0);
    }
};

// Districts are rings of area proportional to their share, with wobbly boundaries: two
// low-frequency waves in the angle and a little per-block noise.
struct DistrictMap {
    std::vector<double> outer; // normalised outer radius of each ring
    double phase1 = 0.0, phase2 = 0.0;

    explicit DistrictMap(const CityOptions& options) {
        double total = 0.0, cumulative = 0.0;
        for (const DistrictSpec& d : options.districts) total += d.share;
        for (const DistrictSpec& d : options.districts) {
            cumulative += d.share;
            outer.push_back(std::sqrt(cumulative / total));
        }
        const uint64_t key = combineKey(options.seed, kDistrictTag);
        phase1 = 2.0 * M_PI * unitFloat(combineKey(key, 1));
        phase2 = 2.0 * M_PI * unitFloat(combineKey(key, 2));
    }

    // The district of a block centred at `centre`, and where it lies across that district's
    // ring: 0 at the inner boundary, 1 at the outer.
    std::pair<uint32_t, double> locate(glm::dvec2 centre, double radius, uint64_t blockKey) const {
        const double angle = std::atan2(centre.y, centre.x);
        const double wobble =
            1.0 + 0.07 * std::sin(3.0 * angle + phase1) + 0.04 * std::sin(5.0 * angle + phase2);
        const double noise = 0.03 * (2.0 * unitFloat(combineKey(blockKey, kDistrictTag)) - 1.0);
        const double t = std::max(0.0, glm::length(centre) / radius * wobble + noise);
        uint32_t k = 0;
        while (k + 1 < outer.size() && t > outer[k]) ++k;
        const double inner = k == 0 ? 0.0 : outer[k - 1];
        const double band = outer[k] > inner ? (t - inner) / (outer[k] - inner) : 0.0;
        return {k, std::clamp(band, 0.0, 1.0)};
    }
};

struct Block {
    int64_t i = 0, j = 0; // between street lines i, i+1 along x and j, j+1 along y
    Rect inner;           // kerb to kerb: the cell inset by half the street width
    double distance = 0.0;
    uint64_t key = 0;
    uint32_t district = 0;
    double band = 0.0;
    bool park = false;
    uint32_t lots = 0;
};

// Every block whose centre lies within `radius`, with its district and lot count.
std::vector<Block> blocksWithin(const CityOptions& options, const StreetGrid& grid,
                                const DistrictMap& districts, double radius, std::vector<Lot>& scratch) {
    const double minSpacing = grid.spacing - 2.0 * grid.jitter;
    const int64_t reach = static_cast<int64_t>(std::ceil(radius / minSpacing)) + 1;
    const double halfStreet = 0.5 * options.streetWidth;
    std::vector<Block> blocks;
    for (int64_t j = -reach; j < reach; ++j) {
        const double y0 = grid.line(1, j), y1 = grid.line(1, j + 1);
        for (int64_t i = -reach; i < reach; ++i) {
            const double x0 = grid.line(0, i), x1 = grid.line(0, i + 1);
            const glm::dvec2 centre(0.5 * (x0 + x1), 0.5 * (y0 + y1));
            Block b;
            b.distance = glm::length(centre);
            if (b.distance > radius) continue;
            b.i = i, b.j = j;
            b.inner = {{x0 + halfStreet, y0 + halfStreet}, {x1 - halfStreet, y1 - halfStreet}};
            b.key = combineKey(combineKey(combineKey(options.seed, kBlockTag), static_cast<uint64_t>(i)),
                               static_cast<uint64_t>(j));
            std::tie(b.district, b.band) = districts.locate(centre, radius, b.key);
            b.park = unitFloat(combineKey(b.key, kParkTag)) < options.parkShare;
            if (!b.park) {
                const DistrictSpec& spec = options.districts[b.district];
                scratch.clear();
                detail::subdivideBlock(b.inner, spec.lotWidth, spec.lotDepth, b.key, scratch);
                b.lots = static_cast<uint32_t>(scratch.size());
            }
            blocks.push_back(b);
        }
    }
    return blocks;
}

// Grows the city ring by ring until its blocks hold `target` lots, then keeps the blocks
// nearest the centre that are needed. Districts depend on the final radius, so each
// attempt lays out afresh.
std::vector<Block> growCity(const CityOptions& options, const StreetGrid& grid, uint64_t target) {
    const DistrictMap districts(options);
    double meanLotArea = 0.0, totalShare = 0.0;
    for (const DistrictSpec& d : options.districts) {
        meanLotArea += d.share * d.lotWidth * d.lotDepth;
        totalShare += d.share;
    }
    meanLotArea /= totalShare;
    // Lots cover a little over half of a block's cell, streets and courtyards the rest.
    double radius = std::max(0.75 * options.blockSize, std::sqrt(static_cast<double>(target) * meanLotArea *
                                                                 1.8 / (M_PI * (1.0 - options.parkShare))));
    std::vector<Lot> scratch;
    std::vector<Block> blocks;
    for (;;) {
        blocks = blocksWithin(options, grid, districts, radius, scratch);
        uint64_t lots = 0;
        for (const Block& b : blocks) lots += b.lots;
        if (lots >= target) break;
        radius *= lots == 0 ? 1.5 : std::max(1.05, 1.02 * std::sqrt(static_cast<double>(target) / lots));
    }
    std::sort(blocks.begin(), blocks.end(), [](const Block& a, const Block& b) {
        return std::tie(a.distance, a.j, a.i) < std::tie(b.distance, b.j, b.i);
    });
    uint64_t lots = 0;
    size_t kept = 0;
    while (lots < target) lots += blocks[kept++].lots;
    blocks.resize(kept);
    return blocks;
}

// Taller towards the centre of each district: the draw skews low towards its outer edge.
double drawFloors(const DistrictSpec& d, double band, uint64_t lotKey) {
    const double u = std::pow(unitFloat(combineKey(lotKey, kFloorsTag)), 1.0 + 2.0 * band);
    return std::clamp(std::round(d.minFloors + (d.maxFloors - d.minFloors) * u), d.minFloors, d.maxFloors);
}

std::vector<glm::dvec2> rectPolygon(const Rect& r) {
    return {r.lo, {r.hi.x, r.lo.y}, r.hi, {r.lo.x, r.hi.y}};
}

// The street segments around the kept blocks, merged into runs along each street line.
std::vector<RoadSegment> roadsAround(const std::vector<Block>& blocks, const StreetGrid& grid, double width) {
    std::vector<std::tuple<int, int64_t, int64_t>> spans; // axis, line, cell index along it
    spans.reserve(4 * blocks.size());
    for (const Block& b : blocks) {
        spans.emplace_back(0, b.i, b.j);
        spans.emplace_back(0, b.i + 1, b.j);
        spans.emplace_back(1, b.j, b.i);
        spans.emplace_back(1, b.j + 1, b.i);
    }
    std::sort(spans.begin(), spans.end());
    spans.erase(std::unique(spans.begin(), spans.end()), spans.end());
    std::vector<RoadSegment> roads;
    for (size_t s = 0; s < spans.size();) {
        const auto [axis, line, first] = spans[s];
        int64_t last = first;
        for (++s; s < spans.size() && std::get<0>(spans[s]) == axis && std::get<1>(spans[s]) == line &&
                  std::get<2>(spans[s]) == last + 1;
             ++s)
            ++last;
        const double across = grid.line(axis, line);
        const double from = grid.line(1 - axis, first), to = grid.line(1 - axis, last + 1);
        if (axis == 0)
            roads.push_back({{across, from}, {across, to}, width});
        else
            roads.push_back({{from, across}, {to, across}, width});
    }
    return roads;
}

struct TreeSpot {
    glm::dvec2 position;
    uint64_t key;
    bool inPark;
};

// Trees on the pavement of every block's four streets, so each street gets both sides.
void streetTrees(const Block& b, double spacing, double offset, std::vector<TreeSpot>& out) {
    const Rect& r = b.inner;
    const glm::dvec2 corners[4] = {r.lo, {r.hi.x, r.lo.y}, r.hi, {r.lo.x, r.hi.y}};
    const glm::dvec2 outward[4] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
    for (int e = 0; e < 4; ++e) {
        const glm::dvec2 from = corners[e], along = corners[(e + 1) % 4] - from;
        const double length = glm::length(along);
        const int64_t count = static_cast<int64_t>(length / spacing);
        const uint64_t edgeKey = combineKey(b.key, kStreetTreeTag + static_cast<uint64_t>(e));
        for (int64_t k = 0; k < count; ++k) {
            const uint64_t key = combineKey(edgeKey, static_cast<uint64_t>(k));
            const double t = (k + 0.5 + 0.4 * (unitFloat(key) - 0.5)) / count;
            out.push_back({from + t * along + offset * outward[e], key, false});
        }
    }
}

// A jittered grid of trees inside a park, at least one per park.
void parkTrees(const Block& b, double spacing, std::vector<TreeSpot>& out) {
    const glm::dvec2 size = b.inner.size();
    const double margin = std::min(2.0, 0.1 * std::min(size.x, size.y));
    const glm::dvec2 lo = b.inner.lo + margin, area = size - 2.0 * margin;
    const int64_t nx = std::max<int64_t>(1, static_cast<int64_t>(area.x / spacing));
    const int64_t ny = std::max<int64_t>(1, static_cast<int64_t>(area.y / spacing));
    const glm::dvec2 cell = area / glm::dvec2(nx, ny);
    const uint64_t parkKey = combineKey(b.key, kParkTreeTag);
    for (int64_t y = 0; y < ny; ++y) {
        for (int64_t x = 0; x < nx; ++x) {
            const uint64_t key = combineKey(parkKey, static_cast<uint64_t>(y * nx + x));
            const glm::dvec2 jitter(unitFloat(combineKey(key, 1)), unitFloat(combineKey(key, 2)));
            out.push_back({lo + cell * (glm::dvec2(x, y) + 0.2 + 0.6 * jitter), key, true});
        }
    }
}

// Exactly `options.trees` trees: natural spacing first, densified evenly when the city is
// short of spots, then thinned by a position-keyed priority when it has too many.
std::vector<TreeInstance> plantTrees(const CityOptions& options, const std::vector<Block>& blocks) {
    std::vector<TreeInstance> trees;
    if (options.trees == 0) return trees;
    const double offset = std::min(1.5, 0.25 * options.streetWidth);
    double streetSpacing = kStreetTreeSpacing, parkSpacing = kParkTreeSpacing;
    std::vector<TreeSpot> spots;
    for (;;) {
        spots.clear();
        for (const Block& b : blocks) {
            streetTrees(b, streetSpacing, offset, spots);
            if (b.park) parkTrees(b, parkSpacing, spots);
        }
        if (spots.size() >= options.trees) break;
        const double ratio = std::max(0.1, 0.97 * static_cast<double>(spots.size()) / options.trees);
        streetSpacing *= ratio;
        parkSpacing *= std::sqrt(ratio);
    }
    std::vector<bool> keep(spots.size(), true);
    if (spots.size() > options.trees) {
        std::vector<std::pair<uint64_t, uint32_t>> priority(spots.size());
        for (uint32_t s = 0; s < spots.size(); ++s) priority[s] = {combineKey(spots[s].key, kTreeKeepTag), s};
        std::nth_element(priority.begin(), priority.begin() + options.trees, priority.end());
        for (size_t s = options.trees; s < priority.size(); ++s) keep[priority[s].second] = false;
    }
    trees.reserve(options.trees);
    for (size_t s = 0; s < spots.size(); ++s) {
        if (!keep[s]) continue;
        const uint64_t key = spots[s].key;
        TreeInstance& tree = trees.emplace_back();
        tree.position = spots[s].position;
        tree.species = static_cast<uint32_t>(combineKey(key, 3) % options.species);
        tree.scale = 0.7f + 0.6f * unitFloat(combineKey(key, 4));
        tree.inPark = spots[s].inPark;
    }
    return trees;
}

} // namespace

GeneratedCity generateCity(const CityOptions& options) {
    validate(options);
    GeneratedCity city;
    if (options.buildings == 0 && options.trees == 0) return city;

    const StreetGrid grid{combineKey(options.seed, kGridTag), options.blockSize,
                          0.15 * (options.blockSize - options.streetWidth)};
    // Trees need streets even in a city without buildings, hence at least one lot.
    const std::vector<Block> blocks = growCity(options, grid, std::max<uint64_t>(options.buildings, 1));

    city.buildings.reserve(options.buildings);
    std::vector<Lot> lots;
    for (const Block& b : blocks) {
        if (b.park) {
            city.parks.push_back(rectPolygon(b.inner));
            continue;
        }
        const DistrictSpec& spec = options.districts[b.district];
        lots.clear();
        detail::subdivideBlock(b.inner, spec.lotWidth, spec.lotDepth, b.key, lots);
        for (uint64_t l = 0; l < lots.size() && city.buildings.size() < options.buildings; ++l) {
            const uint64_t lotKey = combineKey(combineKey(b.key, kLotTag), l);
            GeneratedBuilding& building = city.buildings.emplace_back();
            building.input.id = static_cast<uint32_t>(city.buildings.size() - 1);
            building.input.footprint = detail::makeFootprint(lots[l], lotKey);
            building.district = b.district;
            building.floors = drawFloors(spec, b.band, lotKey);
        }
    }
    city.roads = roadsAround(blocks, grid, options.streetWidth);
    city.trees = plantTrees(options, blocks);

    city.extentMin = city.extentMax = city.roads.front().a;
    for (const RoadSegment& road : city.roads) {
        city.extentMin = glm::min(city.extentMin, glm::min(road.a, road.b) - 0.5 * road.width);
        city.extentMax = glm::max(city.extentMax, glm::max(road.a, road.b) + 0.5 * road.width);
    }
    return city;
}

} // namespace hexlod::scene
