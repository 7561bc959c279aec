#include "hexlod/scene/osm_footprints.h"

// libosmium lives in a system include directory, so most of its warnings stay quiet, but GCC
// reports a -Wstringop-overread false positive in OSMObjectBuilder::set_user after inlining
// (the user name it reads is a terminated string in the buffer).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wstringop-overread"
#endif
#include <osmium/area/assembler.hpp>
#include <osmium/area/multipolygon_manager.hpp>
#include <osmium/area/problem_reporter.hpp>
#include <osmium/handler.hpp>
#include <osmium/handler/node_locations_for_ways.hpp>
#include <osmium/index/map/flex_mem.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/osm/area.hpp>
#include <osmium/relations/manager_util.hpp>
#include <osmium/tags/tags_filter.hpp>
#include <osmium/visitor.hpp>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <unordered_map>

namespace hexlod::scene {
namespace {

using Ring = std::vector<glm::dvec2>; // lon, lat
using LocationIndex = osmium::index::map::FlexMem<osmium::unsigned_object_id_type, osmium::Location>;
using LocationHandler = osmium::handler::NodeLocationsForWays<LocationIndex>;
using Manager = osmium::area::MultipolygonManager<osmium::area::Assembler>;

constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
constexpr double kMaxHeight = 2000.0; // metres, as for GeoJSON: taller is a tagging error
constexpr double kMaxLevels = 500.0;

bool isBuilding(const osmium::TagList& tags) {
    const char* value = tags["building"];
    return value != nullptr && std::strcmp(value, "no") != 0;
}

// Reads a number, optionally followed by `unit` (with or without a space); NaN unless the
// whole text is used. OSM heights are metres by default and often say so ("12 m", "12m");
// other units ("40'", "12 ft") are not guessed at.
double parseQuantity(const char* text, const char* unit) {
    char* end = nullptr;
    const double value = std::strtod(text, &end);
    if (end == text) return kUnknown;
    while (*end == ' ') ++end;
    if (unit != nullptr && std::strncmp(end, unit, std::strlen(unit)) == 0) end += std::strlen(unit);
    while (*end == ' ') ++end;
    return *end == '\0' ? value : kUnknown;
}

// Remembers the first problem the assembler reports for each object, so that an area it
// fails to build is counted under a reason. Problems of areas that were built anyway (the
// assembler repairs some) are dropped when the area arrives.
class FirstProblem : public osmium::area::ProblemReporter {
public:
    const char* take(osmium::object_id_type areaId) {
        const auto it = problems_.find(areaId);
        if (it == problems_.end()) return nullptr;
        const char* problem = it->second;
        problems_.erase(it);
        return problem;
    }
    const std::unordered_map<osmium::object_id_type, const char*>& remaining() const { return problems_; }

    void report_duplicate_segment(const osmium::NodeRef&, const osmium::NodeRef&) override {
        note("duplicate segment");
    }
    void report_overlapping_segment(const osmium::NodeRef&, const osmium::NodeRef&) override {
        note("overlapping segments");
    }
    void report_intersection(osmium::object_id_type, osmium::Location, osmium::Location,
                             osmium::object_id_type, osmium::Location, osmium::Location,
                             osmium::Location) override {
        note("self-intersection");
    }
    void report_ring_not_closed(const osmium::NodeRef&, const osmium::Way*) override {
        note("ring is not closed");
    }
    void report_touching_ring(osmium::object_id_type, osmium::Location) override { note("touching rings"); }
    void report_way_in_multiple_rings(const osmium::Way&) override { note("way in several rings"); }
    void report_invalid_location(osmium::object_id_type, osmium::object_id_type) override {
        note("member way references a missing or out-of-range node");
    }

private:
    void note(const char* problem) {
        problems_.emplace(osmium::object_id_to_area_id(m_object_id, m_object_type), problem);
    }

    std::unordered_map<osmium::object_id_type, const char*> problems_;
};

const char* readRing(const osmium::NodeRefList& ring, Ring& out) {
    if (ring.size() < 4) return "ring has fewer than 4 nodes";
    out.clear();
    for (const osmium::NodeRef& node : ring) {
        const osmium::Location location = node.location();
        if (!location.valid()) return "coordinate outside lon/lat range";
        out.push_back({location.lon_without_check(), location.lat_without_check()});
    }
    return nullptr;
}

// Second-pass handler, after the node locations: builds closed building ways itself, so that
// every one it drops is counted with a reason (the multipolygon manager drops unclosed ways
// and missing nodes silently), and receives the manager's relation areas in area().
class BuildingCollector : public osmium::handler::Handler {
public:
    BuildingCollector(ImportedFootprints& out, FirstProblem& problems, osmium::area::AssemblerConfig config)
        : out_(out), problems_(problems), config_(config) {}

    void way(const osmium::Way& way) {
        if (!isBuilding(way.tags())) return;
        ++out_.features;
        const osmium::WayNodeList& nodes = way.nodes();
        if (nodes.size() < 4) return skip("way has fewer than 4 nodes");
        for (const osmium::NodeRef& node : nodes) {
            if (!node.location()) return skip("way references a node missing from the file");
            if (!node.location().valid()) return skip("coordinate outside lon/lat range");
        }
        if (!way.ends_have_same_location()) return skip("way is not closed");
        osmium::area::Assembler assembler{config_};
        const bool built = assembler(way, buffer_);
        const char* problem = problems_.take(osmium::object_id_to_area_id(way.id(), osmium::item_type::way));
        if (!built)
            return skip(problem ? std::string("way area not assembled: ") + problem
                                : "way area not assembled");
        for (const osmium::Area& a : buffer_.select<osmium::Area>()) area(a);
        buffer_.clear();
    }

    void area(const osmium::Area& area) {
        if (!area.from_way()) {
            ++relationAreas_;
            problems_.take(area.id());
        }
        const osmium::TagList& tags = area.tags();
        const double height = tagValue(tags, "height", "m", kMaxHeight, "height is not a number of metres");
        const double levels = tagValue(tags, "building:levels", nullptr, kMaxLevels,
                                       "building:levels is not a positive number");
        for (const osmium::OuterRing& outer : area.outer_rings()) {
            const auto inner = area.inner_rings(outer);
            out_.holesIgnored += size_t(std::distance(inner.begin(), inner.end()));
            Ring ring;
            if (const char* reason = readRing(outer, ring)) {
                skip(reason);
                continue;
            }
            pending_.push_back({std::move(ring), height, levels});
        }
    }

    // Accounts for the multipolygon relations the manager took (`candidates`): those with
    // members missing from the file never complete; the others that gave no area failed in
    // the assembler, which mostly reported why.
    void countRelations(size_t candidates, size_t incomplete) {
        out_.features += candidates;
        if (incomplete > 0)
            out_.skipped["multipolygon relation has members missing from the file"] += incomplete;
        size_t unexplained = candidates - incomplete - std::min(candidates - incomplete, relationAreas_);
        for (const auto& [areaId, problem] : problems_.remaining()) {
            skip(std::string("multipolygon not assembled: ") + problem);
            unexplained -= std::min<size_t>(unexplained, 1);
        }
        if (unexplained > 0) out_.skipped["multipolygon not assembled"] += unexplained;
    }

    void finish() { appendProjected(pending_, out_); }

private:
    void skip(const std::string& reason) { ++out_.skipped[reason]; }

    // A positive quantity tag: absent is NaN quietly, unusable is NaN with a warning.
    double tagValue(const osmium::TagList& tags, const char* key, const char* unit, double limit,
                    const char* warning) {
        const char* text = tags[key];
        if (text == nullptr) return kUnknown;
        const double value = parseQuantity(text, unit);
        if (std::isfinite(value) && value > 0.0 && value < limit) return value;
        ++out_.warnings[warning];
        return kUnknown;
    }

    ImportedFootprints& out_;
    FirstProblem& problems_;
    const osmium::area::AssemblerConfig config_;
    osmium::memory::Buffer buffer_{4096, osmium::memory::Buffer::auto_grow::yes};
    std::vector<LonLatFootprint> pending_;
    size_t relationAreas_ = 0;
};

} // namespace

bool readOsmFootprints(const std::string& path, ImportedFootprints& out, std::string& error) {
    out = ImportedFootprints{};
    if (!std::ifstream(path, std::ios::binary)) {
        error = "cannot open '" + path + "'";
        return false;
    }
    try {
        const osmium::io::File file{path};
        FirstProblem problems;
        osmium::area::AssemblerConfig config;
        config.problem_reporter = &problems;
        config.create_empty_areas = false; // a failed area is counted, not kept
        BuildingCollector collector(out, problems, config);

        // The manager assembles only relations: the collector builds the ways.
        config.create_way_polygons = false;
        osmium::TagsFilter filter{false};
        filter.add_rule(false, osmium::TagMatcher{"building", "no"});
        filter.add_rule(true, osmium::TagMatcher{"building"});
        Manager manager{config, filter};
        osmium::relations::read_relations(file, manager);
        const size_t candidates = manager.relations_database().count_relations();

        LocationIndex index;
        LocationHandler locations{index};
        locations.ignore_errors(); // a missing node is the collector's to count, not fatal
        osmium::io::Reader reader{file, osmium::osm_entity_bits::node | osmium::osm_entity_bits::way};
        osmium::apply(reader, locations, collector, manager.handler([&](osmium::memory::Buffer&& areas) {
            osmium::apply(areas, collector);
        }));
        reader.close();
        collector.countRelations(candidates, manager.relations_database().count_relations());
        collector.finish();
    } catch (const std::exception& e) {
        out = ImportedFootprints{};
        error = path + ": " + e.what();
        return false;
    }
    out.attribution = "© OpenStreetMap contributors";
    return true;
}

} // namespace hexlod::scene
